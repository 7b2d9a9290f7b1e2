#include "peers/oidn_library.h"
#include <bmfr/error.h>
#include <cstdlib>
#include <dlfcn.h>
#include <fmt/core.h>
#include <map>
#include <memory>
#include <mutex>

namespace bmfr::oidn {

namespace {

/// Set by CMake from the pyoidn wheel that scripts/install-oidn.sh installs into .venv/.
#ifdef BMFR_OIDN_DEFAULT_LIBRARY
constexpr const char* kInstalled = BMFR_OIDN_DEFAULT_LIBRARY;
#else
constexpr const char* kInstalled = "";
#endif

constexpr const char* kHowToInstall =
    "install it with `bash scripts/install-oidn.sh` (PyPI's pyoidn 2.5.1.0, which carries OIDN "
    "2.5.1, into .venv/; then build again), or give --oidn-library PATH or BMFR_OIDN_LIBRARY "
    "naming libOpenImageDenoise.so.2 of OIDN 2";

template <class F> void resolve(void* handle, const char* name, F& fn) {
    fn = reinterpret_cast<F>(dlsym(handle, name));
    if (!fn) throw Error(fmt::format("it has no {} (not OIDN 2)", name));
}

/// The Api of the library at `path`; throws bmfr::Error with the reason alone.
Api open(const std::string& path) {
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
        const char* why = dlerror();
        throw Error(why ? why : "dlopen failed");
    }
    Api a;
    try {
        resolve(handle, "oidnNewDevice", a.newDevice);
        resolve(handle, "oidnCommitDevice", a.commitDevice);
        resolve(handle, "oidnReleaseDevice", a.releaseDevice);
        resolve(handle, "oidnSetDeviceInt", a.setDeviceInt);
        resolve(handle, "oidnGetDeviceInt", a.getDeviceInt);
        resolve(handle, "oidnGetDeviceError", a.getDeviceError);
        resolve(handle, "oidnNewFilter", a.newFilter);
        resolve(handle, "oidnSetSharedFilterImage", a.setSharedFilterImage);
        resolve(handle, "oidnSetFilterBool", a.setFilterBool);
        resolve(handle, "oidnSetFilterInt", a.setFilterInt);
        resolve(handle, "oidnCommitFilter", a.commitFilter);
        resolve(handle, "oidnExecuteFilter", a.executeFilter);
        resolve(handle, "oidnReleaseFilter", a.releaseFilter);
    } catch (const Error&) {
        dlclose(handle);
        throw;
    }
    a.path = path;
    return a; // the handle stays open: the Api's pointers live as long as the process
}

} // namespace

std::vector<std::string> libraryCandidates(const std::string& explicitPath) {
    if (!explicitPath.empty()) return {explicitPath};
    std::vector<std::string> c;
    if (const char* env = std::getenv("BMFR_OIDN_LIBRARY"); env && *env) c.push_back(env);
    if (*kInstalled) c.push_back(kInstalled);
    c.push_back("libOpenImageDenoise.so.2");
    return c;
}

/// AddressSanitizer aborts the process when OIDN's TBB loads tbbbind with RTLD_DEEPBIND
/// (google/sanitizers issue 611): such a build says so instead of running it.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kSanitizerBuild = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kSanitizerBuild = true;
#else
constexpr bool kSanitizerBuild = false;
#endif
#else
constexpr bool kSanitizerBuild = false;
#endif

bool sanitizerBuild() {
    return kSanitizerBuild;
}

void checkCanRun() {
    if (kSanitizerBuild)
        throw Error("this bmfr is built with AddressSanitizer, under which OIDN cannot run (its "
                    "TBB loads libraries with RTLD_DEEPBIND, which the sanitizer aborts on); use "
                    "a build without sanitizers");
}

const Api& loadApi(const std::string& explicitPath) {
    static std::mutex mutex;
    static std::map<std::string, std::unique_ptr<Api>> loaded; // by the path asked for
    const std::lock_guard<std::mutex> lock(mutex);
    if (auto it = loaded.find(explicitPath); it != loaded.end()) return *it->second;
    std::string tried;
    for (const std::string& path : libraryCandidates(explicitPath)) {
        try {
            auto api = std::make_unique<Api>(open(path));
            return *loaded.emplace(explicitPath, std::move(api)).first->second;
        } catch (const Error& e) {
            tried += fmt::format("\n  {}: {}", path, e.what());
        }
    }
    throw Error(fmt::format("Intel Open Image Denoise (OIDN) was not found; tried:{}\n{}", tried,
                            kHowToInstall));
}

std::string whyUnavailable(const std::string& explicitPath) {
    try {
        checkCanRun();
        loadApi(explicitPath);
        return "";
    } catch (const Error& e) {
        return e.what();
    }
}

bool available(const std::string& explicitPath) {
    return whyUnavailable(explicitPath).empty();
}

} // namespace bmfr::oidn
