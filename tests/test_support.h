// Small helpers the test suites share: scratch folders and the message of an expected error.
#pragma once
#include <bmfr/error.h>
#include <filesystem>
#include <functional>
#include <string>
#include <unistd.h>

namespace bmfr::testing {

/// An empty folder under the system's temporary directory, unique to this process.
inline std::filesystem::path freshDir(const std::string& suite, const std::string& name) {
    const std::filesystem::path p =
        std::filesystem::temp_directory_path() /
        ("bmfr_" + suite + "_" + name + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(p);
    std::filesystem::create_directories(p);
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
