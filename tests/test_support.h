// Small helpers the test suites share: scratch folders and the message of an expected error.
#pragma once
#include "core/hash.h"
#include "synth/procedural_scene.h"
#include <bmfr/error.h>
#include <filesystem>
#include <fstream>
#include <functional>
#include <gtest/gtest.h>
#include <iterator>
#include <string>
#include <unistd.h>
#include <vector>

namespace bmfr::testing {

/// The scratch folders this process made: removed at exit when every test passed, kept for a
/// look when one failed (ctest runs each test in its own process).
class ScratchFolders {
  public:
    void add(const std::filesystem::path& p) { folders_.push_back(p); }
    ~ScratchFolders() {
        const ::testing::UnitTest* run = ::testing::UnitTest::GetInstance();
        if (run->failed_test_count() > 0) return;
        std::error_code ignored;
        for (const std::filesystem::path& p : folders_) std::filesystem::remove_all(p, ignored);
    }

  private:
    std::vector<std::filesystem::path> folders_;
};

/// A path under the system's temporary directory, unique to this process and not there: for
/// the folders that a command under test makes itself. Removed at exit as freshDir's.
inline std::filesystem::path scratchPath(const std::string& suite, const std::string& name) {
    static ScratchFolders made;
    const std::filesystem::path p =
        std::filesystem::temp_directory_path() /
        ("bmfr_" + suite + "_" + name + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(p);
    made.add(p);
    return p;
}

/// An empty folder under the system's temporary directory, unique to this process.
inline std::filesystem::path freshDir(const std::string& suite, const std::string& name) {
    const std::filesystem::path p = scratchPath(suite, name);
    std::filesystem::create_directories(p);
    return p;
}

/// A file's bytes.
inline std::string slurp(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

/// A number in [0, 1) that depends only on three keys: repeatable test data.
inline float uniform(uint32_t a, uint32_t b, uint32_t c) {
    return unitFloat(hashKeys(a, b, c));
}

/// The procedural scene's first `n` frames at w x h.
inline std::vector<FrameData> proceduralFrames(int w, int h, int n) {
    ProceduralSceneOptions o;
    o.width = w, o.height = h, o.frames = n;
    ProceduralScene scene(o);
    std::vector<FrameData> frames(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) scene.render(i, frames[size_t(i)]);
    return frames;
}

/// What `f` throws as bmfr::Error, or "(no error)".
inline std::string errorOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "(no error)";
}

} // namespace bmfr::testing
