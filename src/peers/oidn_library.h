// Intel Open Image Denoise's C API, loaded at run time: bmfr neither builds nor links against
// OIDN, so the same binary runs the peer wherever the library is (pyoidn's wheel carries it,
// scripts/install-oidn.sh puts that in .venv/) and runs everything else where it is not.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

namespace bmfr::oidn {

// The few types and values of OIDN 2's oidn.h that the peer uses, with OIDN's numbering.
using Device = struct DeviceImpl*;
using FilterHandle = struct FilterImpl*;
enum DeviceType { kDeviceDefault = 0, kDeviceCpu = 1 };
enum Format { kFormatFloat3 = 3 };
enum Quality { kQualityFast = 4, kQualityBalanced = 5, kQualityHigh = 6 };

/// OIDN's entry points, resolved from one shared library that stays loaded for the process.
struct Api {
    Device (*newDevice)(int type);
    void (*commitDevice)(Device);
    void (*releaseDevice)(Device);
    void (*setDeviceInt)(Device, const char*, int);
    int (*getDeviceInt)(Device, const char*);
    int (*getDeviceError)(Device, const char** message);
    FilterHandle (*newFilter)(Device, const char* type);
    void (*setSharedFilterImage)(FilterHandle, const char* name, void* ptr, int format,
                                 size_t width, size_t height, size_t byteOffset,
                                 size_t pixelByteStride, size_t rowByteStride);
    void (*setFilterBool)(FilterHandle, const char*, bool);
    void (*setFilterInt)(FilterHandle, const char*, int);
    void (*commitFilter)(FilterHandle);
    void (*executeFilter)(FilterHandle);
    void (*releaseFilter)(FilterHandle);
    std::string path; ///< the file it was loaded from
};

/// The files tried, in order: `explicitPath` alone when given; else $BMFR_OIDN_LIBRARY, the
/// library scripts/install-oidn.sh installed when bmfr was configured (if any), and
/// libOpenImageDenoise.so.2 on the system's library path.
std::vector<std::string> libraryCandidates(const std::string& explicitPath);

/// Loads the first candidate that is OIDN 2 (once per path; later calls return the same Api).
/// Throws bmfr::Error naming each file tried and why it failed, and how to install OIDN.
const Api& loadApi(const std::string& explicitPath = "");

/// True in a build with AddressSanitizer, where OIDN cannot run: OIDN's TBB loads libraries
/// with RTLD_DEEPBIND, on which the sanitizer aborts the process.
bool sanitizerBuild();

/// Throws bmfr::Error, saying why, in a build where OIDN cannot run (sanitizerBuild()).
void checkCanRun();

/// Why OIDN cannot run here: "" when loadApi(explicitPath) succeeds and this build can run it
/// (for "include OIDN when it is installed"), else the reason, with how to install it.
std::string whyUnavailable(const std::string& explicitPath = "");

/// whyUnavailable(explicitPath).empty().
bool available(const std::string& explicitPath = "");

} // namespace bmfr::oidn
