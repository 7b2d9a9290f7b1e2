// The frame's buffer table (temporal/frame_buffers.h) holds every image buffer of FrameInput,
// once, and the readers, the staging and the checks follow it.
#include "io/sequence.h"
#include "temporal/frame_checks.h"
#include "temporal/input_staging.h"
#include "test_support.h"
#include <gtest/gtest.h>
#include <set>
#include <string>
#include <utility>

namespace bmfr {
namespace {

/// Converts to any member type: FrameInput{AnyField{}, ...} compiles for as many initialisers
/// as it has fields (an array of n counts n).
struct AnyField {
    template <class T> operator T() const;
};
template <class T, size_t... I> constexpr bool initialisesWith(std::index_sequence<I...>) {
    return requires {
        T{(void(I), AnyField{})...};
    };
}
template <class T, size_t N = 0> constexpr size_t fieldCount() {
    if constexpr (initialisesWith<T>(std::make_index_sequence<N + 1>{}))
        return fieldCount<T, N + 1>();
    else
        return N;
}

TEST(FrameBuffers, EveryImageBufferOfFrameInputIsInTheTable) {
    // The fields that are not image buffers: extras, viewProjection, jitter[2], reset and
    // cudaStream. A new ImageView member of FrameInput must join BMFR_FRAME_BUFFERS.
    EXPECT_EQ(fieldCount<FrameInput>(), size_t(kFrameBufferCount) + 6)
        << "FrameInput has a field that temporal/frame_buffers.h does not list";
    std::set<std::string> members, files;
    FrameInput in;
    float pixel[4] = {};
    for (const FrameBuffer& b : kFrameBuffers) {
        members.insert(b.member);
        files.insert(b.file);
        EXPECT_EQ((in.*b.view).data, nullptr) << b.member << " is listed twice";
        (in.*b.view).data = pixel;
    }
    EXPECT_EQ(members.size(), size_t(kFrameBufferCount));
    EXPECT_EQ(files.size(), size_t(kFrameBufferCount));
}

TEST(FrameBuffers, StagingGivesEveryBufferItsOwnPlane) {
    const int w = 3, h = 2;
    FrameInput in;
    std::vector<std::vector<float>> images;
    images.reserve(kFrameBufferCount);
    for (const FrameBuffer& b : kFrameBuffers) {
        const int c = b.channels.hi;
        images.emplace_back(size_t(w * h * c), float(images.size()));
        in.*b.view = ImageView{images.back().data(), w, h, c};
    }
    std::set<int> slots;
    std::set<const float*> planes;
    const InputPlanes p = stagePlanes(in, [&](const ImageView& v, int channels, int slot, int) {
        EXPECT_TRUE(slots.insert(slot).second) << "slot " << slot << " used twice";
        EXPECT_LT(slot, kStagedPlanes);
        EXPECT_LE(channels, v.channels);
        planes.insert(v.data);
        return v.data;
    });
    EXPECT_EQ(planes.size(), size_t(kFrameBufferCount)); // motion's depth offset reuses motion's
    EXPECT_EQ(p.sampleMask, in.sampleMask.data);
    EXPECT_EQ(p.glossyHitDistance, in.glossyHitDistance.data);
    EXPECT_NE(p.motionDepth, nullptr);
    ASSERT_EQ(p.extraCount, 1); // the visibility, after the frame's (no) extras
    EXPECT_EQ(p.extras[0], in.visibility.data);
}

TEST(FrameBuffers, EveryBufferIsCheckedWithItsName) {
    const std::vector<FrameData> frames = testing::proceduralFrames(6, 4, 1);
    for (const FrameBuffer& b : kFrameBuffers) {
        if (b.view == &FrameInput::color) continue; // the size the others are held to
        FrameInput in = frames[0].input();
        ImageF wrong(5, 4, b.channels.lo);
        in.*b.view = view(wrong);
        EXPECT_EQ(testing::errorOf([&] { checkFrameInput(in, 0, "cpu", false); }),
                  std::string("input buffer '") + b.member + "' is 5x4, colour is 6x4")
            << b.member;
    }
}

TEST(FrameBuffers, SequencesWriteAndReadEveryBuffer) {
    std::vector<FrameData> frames = testing::proceduralFrames(6, 4, 1);
    FrameData& f = frames[0];
    f.extras.clear(); // the procedural scene's extras need names; not what this is about
    float value = 0.25f;
    f.forEachBuffer([&](const FrameBuffer& b, ImageF& image) {
        if (image.width) return;
        const int c = b.channels.lo == kMotion.lo ? 3 : b.staged;
        image.resize(6, 4, c);
        for (float& x : image.pixels) x = value;
        value += 0.25f;
    });
    const std::filesystem::path dir = testing::freshDir("FrameBuffers", "round_trip");
    {
        SequenceInfo info;
        info.width = 6, info.height = 4, info.frameCount = 1;
        ManifestWriter writer(dir.string(), info);
        writer.addFrame(0, f);
    }
    std::unique_ptr<SequenceReader> reader = SequenceReader::open(dir.string());
    FrameData back;
    reader->load(0, back);
    std::vector<const ImageF*> written, read;
    f.forEachBuffer([&](const FrameBuffer&, const ImageF& image) { written.push_back(&image); });
    back.forEachBuffer([&](const FrameBuffer&, const ImageF& image) { read.push_back(&image); });
    for (int k = 0; k < kFrameBufferCount; ++k) {
        EXPECT_EQ(read[size_t(k)]->channels, written[size_t(k)]->channels) << kFrameBuffers[k].file;
        EXPECT_EQ(read[size_t(k)]->pixels, written[size_t(k)]->pixels) << kFrameBuffers[k].file;
    }
}

} // namespace
} // namespace bmfr
