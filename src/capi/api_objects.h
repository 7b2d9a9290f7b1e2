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
    std::optional<bmfr::Device> device; ///< made at commit

    std::mutex errorMutex;
    BMFRErrorFunction errorFunction = nullptr;
    void* errorUserPtr = nullptr;
    BMFRError error = BMFR_ERROR_NONE; ///< the first since the last bmfrGetDeviceError
    std::string message;
    std::string returnedMessage; ///< what the last bmfrGetDeviceError pointed to

    /// Keeps the first error and calls the error function.
    void report(BMFRError code, const std::string& what);
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

    std::string preset = "faithful";
    bmfr::SettingValues values; ///< the filter table's keys as set, one entry per key
    int maxWidth = 0, maxHeight = 0;
    bool changed = true; ///< settings changed since the last commit
    std::unique_ptr<bmfr::Filter> filter;

    std::map<std::string, bmfr::capi::SharedImage> images;
    FrameConventions frame;
    /// The previous execute's jitter and frame index (for motion without jitter and restarts).
    float previousJitter[2] = {0.0f, 0.0f};
    long previousFrameIndex = -1;

    /// Buffers of the converted inputs, by image name; kept between frames.
    std::map<std::string, std::vector<float>> converted;
};

namespace bmfr::capi {

/// Keeps the error on `device`, or on the calling thread's slot when null.
void reportError(BMFRDeviceImpl* device, BMFRError code, const std::string& message);

/// Runs `body`, turning every exception into an error on `device`; returns `fallback` after one.
template <class T, class F> T guard(BMFRDeviceImpl* device, T fallback, F&& body) {
    try {
        return body();
    } catch (const BMFRApiError& e) {
        reportError(device, e.code, e.message);
    } catch (const std::bad_alloc&) {
        reportError(device, BMFR_ERROR_OUT_OF_MEMORY, "out of memory");
    } catch (const bmfr::Error& e) {
        reportError(device, BMFR_ERROR_INVALID_ARGUMENT, e.what());
    } catch (const std::exception& e) {
        reportError(device, BMFR_ERROR_UNKNOWN, e.what());
    } catch (...) {
        reportError(device, BMFR_ERROR_UNKNOWN, "unknown error");
    }
    return fallback;
}

/// The settings every execute reads rather than the filter's table (docs/c-api.md).
bool isFrameConvention(const std::string& key);

/// The filter's commit and execute (c_filter.cpp).
void commitFilter(BMFRFilterImpl& f);
void executeFilter(BMFRFilterImpl& f);
size_t filterMemoryBytes(BMFRFilterImpl& f, int width, int height);

} // namespace bmfr::capi
