// Small helpers the test suites share: scratch folders and the message of an expected error.
#pragma once
#include <bmfr/error.h>
#include <filesystem>
#include <functional>
#include <gtest/gtest.h>
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

/// An empty folder under the system's temporary directory, unique to this process.
inline std::filesystem::path freshDir(const std::string& suite, const std::string& name) {
    static ScratchFolders made;
    const std::filesystem::path p =
        std::filesystem::temp_directory_path() /
        ("bmfr_" + suite + "_" + name + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(p);
    std::filesystem::create_directories(p);
    made.add(p);
    return p;
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
