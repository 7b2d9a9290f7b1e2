// Parts of one render (`bmfr render --frame-range`), rendered at once into one folder, make the
// sequence a single render makes, bit for bit; the manifest appears only once all parts are in.
#include "io/sequence.h"
#include "render/scene_description.h"
#include "render/sequence_renderer.h"
#include "test_support.h"
#include <filesystem>
#include <gtest/gtest.h>
#include <thread>

namespace bmfr {
namespace {

namespace fs = std::filesystem;
using testing::slurp;

render::SceneDescription smallScene() {
    render::SceneDescription d = render::loadSceneDescription("cornell-moving", ".");
    d.width = 16, d.height = 12, d.frames = 5, d.referenceSpp = 4;
    return d;
}

render::SequenceRenderReport renderPart(const fs::path& dir, int first, int end,
                                        bool overwrite = false,
                                        const render::SceneDescription& d = smallScene()) {
    render::SequenceRenderOptions o{dir.string(), "manifest", true, overwrite};
    o.firstFrame = first;
    o.endFrame = end;
    return render::renderSequence(
        d, o, nullptr, [](int, int) {}, [](const std::string&) {});
}

/// Every file of `a` (but the lock and fingerprint records) has the same bytes in `b`.
void expectSameFiles(const fs::path& a, const fs::path& b) {
    int files = 0;
    for (const fs::directory_entry& e : fs::directory_iterator(a)) {
        const std::string name = e.path().filename().string();
        if (!e.is_regular_file() || name[0] == '.') continue;
        ++files;
        ASSERT_TRUE(fs::exists(b / name)) << name;
        EXPECT_TRUE(slurp(e.path()) == slurp(b / name)) << name << " differs";
    }
    EXPECT_GT(files, 5 * 4);
}

TEST(RenderParts, PartsRenderedAtOnceMakeTheSequenceOfOneRender) {
    const fs::path whole = testing::freshDir("parts", "whole");
    const fs::path parts = testing::scratchPath("parts", "parts"); // the parts make it
    const render::SequenceRenderReport all = renderPart(whole, 0, 5);
    EXPECT_TRUE(all.complete);
    render::SequenceRenderReport a, b;
    std::thread first([&] { a = renderPart(parts, 0, 2); });
    std::thread second([&] { b = renderPart(parts, 2, 5); });
    first.join();
    second.join();
    EXPECT_EQ(a.rendered + b.rendered, 5);
    EXPECT_TRUE(a.complete || b.complete); // the one that finished last wrote the manifest
    expectSameFiles(whole, parts);
    expectSameFiles(parts, whole);
    fs::remove_all(whole);
    fs::remove_all(parts);
}

TEST(RenderParts, TheManifestWaitsForEveryPartAndAWholeRenderResumesThem) {
    const fs::path dir = testing::freshDir("parts", "waits");
    const render::SequenceRenderReport late = renderPart(dir, 3, 5);
    EXPECT_EQ(late.rendered, 2);
    EXPECT_EQ(late.framesIn, 2);
    EXPECT_FALSE(late.complete);
    EXPECT_FALSE(fs::exists(dir / "sequence.json")); // no readable sequence with holes
    EXPECT_EQ(renderPart(dir, 3, 5).skipped, 2);     // a part run again renders nothing
    // A whole render renders only what the parts left, and writes the manifest.
    render::SequenceRenderReport rest = render::renderSequence(
        smallScene(), {dir.string(), "manifest", true}, nullptr, [](int, int) {},
        [](const std::string&) {});
    EXPECT_EQ(rest.rendered, 3);
    EXPECT_EQ(rest.skipped, 2);
    EXPECT_TRUE(rest.complete);
    const auto sequence = SequenceReader::open(dir.string());
    EXPECT_EQ(sequence->info().frameCount, 5);
    fs::remove_all(dir);
}

TEST(RenderParts, AReplacedFolderForgetsTheOldSequenceWholeAndInParts) {
    const fs::path dir = testing::freshDir("parts", "replaced");
    EXPECT_TRUE(renderPart(dir, 0, 5).complete); // another seed's sequence, whole
    render::SceneDescription other = smallScene();
    other.seed = 7;
    EXPECT_THROW(renderPart(dir, 2, 5, false, other), Error);
    const render::SequenceRenderReport late = renderPart(dir, 2, 5, true, other);
    EXPECT_EQ(late.rendered, 3);
    EXPECT_EQ(late.framesIn, 3); // frames 0 and 1 on disk are the other seed's
    EXPECT_FALSE(fs::exists(dir / "sequence.json"));
    const render::SequenceRenderReport early = renderPart(dir, 0, 2, false, other);
    EXPECT_EQ(early.rendered, 2);
    EXPECT_TRUE(early.complete);
    const fs::path fresh = testing::scratchPath("parts", "fresh");
    renderPart(fresh, 0, 5, false, other);
    expectSameFiles(fresh, dir);
    fs::remove_all(dir);
    EXPECT_THROW(renderPart(dir, 4, 9), Error); // past the end: refused before the folder is made
    EXPECT_FALSE(fs::exists(dir));
    fs::remove_all(fresh);
}

} // namespace
} // namespace bmfr
