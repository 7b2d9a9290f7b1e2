// What the C API's handles are: a device (the C++ Device, its error slot and callback) and a
// filter (its settings as text, the caller's images, the per-frame conventions and the C++
// filter made at commit). Every entry point runs through guard(), so no exception crosses the C
// boundary and every error reaches the device's slot and callback with the C++ API's message.
#pragma once
#include "capi/shared_image.h"
#include <atomic>
#include <bmfr/bmfr.h>
#include <map>
#include <memory>
#include <mutex>
#include <new>
#include <optional>
#include <string>
#include <string_view>

/// A failure the C layer itself detects, with its code (the C++ API's bmfr::Error is
/// BMFR_ERROR_INVALID_ARGUMENT).
struct BMFRApiError {
    BMFRError code;
    std::string message;
};

struct BMFRDeviceImpl {
    std::atomic<int> references{1};
    bmfr::Backend backend = bmfr::Backend::Cpu;
    int threads = 0;
    int cudaDevice = 0;                 ///< the cuda type's GPU
    std::optional<bmfr::Device> device; ///< made at commit

    std::mutex errorMutex;
    BMFRErrorFunction errorFunction = nullptr;
    void* errorUserPtr = nullptr;
    BMFRError error = BMFR_ERROR_NONE; ///< the first since the last bmfrGetDeviceError
    std::string message;
    std::string returnedMessage; ///< what the last bmfrGetDeviceError pointed to

    /// Keeps the first error and calls the error function.
    void report(BMFRError code, const char* what);
};

/// The per-frame conventions of docs/c-api.md, read at each execute.
struct FrameConventions {
    int accumulationMode = BMFR_ACCUMULATION_MODE_CONTINUE; ///< for the next execute only
    long frameIndex = -1;                                   ///< -1: not given
    float jitter[2] = {0.0f, 0.0f};
    bmfr::capi::MotionConvention motion;
    bool normalOctUnorm = false;
    bmfr::Mat4 viewProjection;
    bool hasViewProjection = false;
};

struct BMFRFilterImpl {
    std::atomic<int> references{1};
    BMFRDeviceImpl* device = nullptr; ///< retained
    std::string type;

    std::string preset = "quality";
    bmfr::SettingValues values;          ///< the filter table's keys as set, one entry per key
    bmfr::SettingValues committedValues; ///< the preset's and these, as the last commit made it
    int maxWidth = 0, maxHeight = 0;
    bool changed = true; ///< settings changed since the last commit
    std::unique_ptr<bmfr::Filter> filter;

    std::map<std::string, bmfr::capi::SharedImage, std::less<>> images;
    FrameConventions frame;
    /// The previous execute's jitter and frame index (for motion without jitter and restarts).
    float previousJitter[2] = {0.0f, 0.0f};
    long previousFrameIndex = -1;

    /// Buffers of the converted inputs, by image name; kept between frames.
    std::map<std::string, std::vector<float>, std::less<>> converted;
    /// The frame handed to the C++ filter, kept so that its extras keep their capacity.
    bmfr::FrameInput frameInput;

    BMFRFilterImpl() { frameInput.extras.reserve(16); }
};

namespace bmfr::capi {

/// Keeps the error on `device`, or on the calling thread's slot when null.
void reportError(BMFRDeviceImpl* device, BMFRError code, const char* message);

/// Reports the exception being handled (in a catch block) on `device`, mapped to its code.
void reportCurrentException(BMFRDeviceImpl* device) noexcept;

/// Runs `body`, turning every exception into an error on `device`; returns `fallback` after one.
template <class T, class F> T guard(BMFRDeviceImpl* device, T fallback, F&& body) noexcept {
    try {
        return body();
    } catch (...) {
        reportCurrentException(device);
    }
    return fallback;
}

/// The settings every execute reads rather than the filter's table (docs/c-api.md).
bool isFrameConvention(std::string_view key);

/// The filter's commit and execute (c_filter.cpp).
void commitFilter(BMFRFilterImpl& f);
void executeFilter(BMFRFilterImpl& f);
size_t filterMemoryBytes(BMFRFilterImpl& f, int width, int height);

} // namespace bmfr::capi
