// The C API's devices and error slots.
#include "capi/api_objects.h"
#include <bmfr/bmfr.hpp>
#include <cstring>

namespace bmfr::capi {

namespace {

/// The error slot of calls made without a device (a null handle, a failed bmfrNewDevice).
struct ThreadSlot {
    BMFRError error = BMFR_ERROR_NONE;
    std::string message, returned;
};
thread_local ThreadSlot tSlot;

BMFRDeviceImpl* requireDevice(BMFRDevice device) {
    if (!device) throw BMFRApiError{BMFR_ERROR_INVALID_ARGUMENT, "the device handle is NULL"};
    return device;
}

void requireName(const char* name) {
    if (!name) throw BMFRApiError{BMFR_ERROR_INVALID_ARGUMENT, "the parameter name is NULL"};
}

} // namespace

void reportError(BMFRDeviceImpl* device, BMFRError code, const char* message) {
    if (!device) {
        if (tSlot.error == BMFR_ERROR_NONE) {
            tSlot.error = code;
            tSlot.message = message;
        }
        return;
    }
    device->report(code, message);
}

void reportCurrentException(BMFRDeviceImpl* device) noexcept {
    try {
        try {
            throw;
        } catch (const BMFRApiError& e) {
            reportError(device, e.code, e.message.c_str());
        } catch (const std::bad_alloc&) {
            reportError(device, BMFR_ERROR_OUT_OF_MEMORY, "out of memory");
        } catch (const bmfr::Error& e) {
            reportError(device, BMFR_ERROR_INVALID_ARGUMENT, e.what());
        } catch (const std::exception& e) {
            reportError(device, BMFR_ERROR_UNKNOWN, e.what());
        } catch (...) {
            reportError(device, BMFR_ERROR_UNKNOWN, "unknown error");
        }
    } catch (...) {
        // No memory left for the message: the code alone (the slot's message stays empty).
        if (!device) {
            if (tSlot.error == BMFR_ERROR_NONE) tSlot.error = BMFR_ERROR_OUT_OF_MEMORY;
        } else if (device->error == BMFR_ERROR_NONE) {
            device->error = BMFR_ERROR_OUT_OF_MEMORY;
        }
    }
}

} // namespace bmfr::capi

using namespace bmfr::capi;

void BMFRDeviceImpl::report(BMFRError code, const char* what) {
    BMFRErrorFunction function;
    void* user;
    {
        std::lock_guard<std::mutex> lock(errorMutex);
        if (error == BMFR_ERROR_NONE) {
            error = code;
            message = what;
        }
        function = errorFunction;
        user = errorUserPtr;
    }
    if (!function) return;
    try {
        function(user, code, what);
    } catch (...) {
        // An error function of C++ that throws: nothing may cross back into a C caller.
    }
}

extern "C" {

BMFRDevice bmfrNewDevice(BMFRDeviceType type) noexcept {
    return guard<BMFRDevice>(nullptr, nullptr, [&] {
        auto device = std::make_unique<BMFRDeviceImpl>();
        switch (type) {
        case BMFR_DEVICE_TYPE_DEFAULT:
        case BMFR_DEVICE_TYPE_CPU:
            device->backend = bmfr::Backend::Cpu;
            break;
        case BMFR_DEVICE_TYPE_REFERENCE:
            device->backend = bmfr::Backend::Reference;
            break;
        case BMFR_DEVICE_TYPE_CUDA:
            device->backend = bmfr::Backend::Cuda;
            break;
        default:
            throw BMFRApiError{BMFR_ERROR_INVALID_ARGUMENT,
                               "unknown device type " + std::to_string(int(type)) +
                                   " (expected a BMFR_DEVICE_TYPE_ value)"};
        }
        return device.release();
    });
}

void bmfrRetainDevice(BMFRDevice device) noexcept {
    guard(nullptr, 0, [&] {
        requireDevice(device)->references.fetch_add(1);
        return 0;
    });
}

void bmfrReleaseDevice(BMFRDevice device) noexcept {
    guard(nullptr, 0, [&] {
        if (requireDevice(device)->references.fetch_sub(1) == 1) delete device;
        return 0;
    });
}

void bmfrSetDeviceInt(BMFRDevice device, const char* name, int value) noexcept {
    guard(device, 0, [&] {
        requireDevice(device);
        requireName(name);
        const std::string key = name;
        if (key != "threads" && key != "cudaDevice")
            throw BMFRApiError{BMFR_ERROR_INVALID_ARGUMENT,
                               "unknown device setting '" + key +
                                   "' (the device takes 'threads' and 'cudaDevice')"};
        if (device->device)
            throw BMFRApiError{BMFR_ERROR_INVALID_OPERATION,
                               "'" + key + "' is set before bmfrCommitDevice, not after"};
        if (key == "cudaDevice") {
            if (device->backend != bmfr::Backend::Cuda)
                throw BMFRApiError{BMFR_ERROR_INVALID_ARGUMENT,
                                   "'cudaDevice' is for a BMFR_DEVICE_TYPE_CUDA device"};
            if (value < 0)
                throw BMFRApiError{BMFR_ERROR_INVALID_ARGUMENT,
                                   "cudaDevice " + std::to_string(value) + " is below 0"};
            device->cudaDevice = value;
            return 0;
        }
        if (value < 0 || value > 1024)
            throw BMFRApiError{BMFR_ERROR_INVALID_ARGUMENT,
                               "threads " + std::to_string(value) + " is outside [0, 1024]"};
        device->threads = value;
        return 0;
    });
}

int bmfrGetDeviceInt(BMFRDevice device, const char* name) noexcept {
    return guard(device, 0, [&] {
        requireDevice(device);
        requireName(name);
        const std::string key = name;
        if (key == "type") {
            switch (device->backend) {
            case bmfr::Backend::Reference:
                return int(BMFR_DEVICE_TYPE_REFERENCE);
            case bmfr::Backend::Cuda:
                return int(BMFR_DEVICE_TYPE_CUDA);
            default:
                return int(BMFR_DEVICE_TYPE_CPU);
            }
        }
        if (key == "threads")
            return device->device ? device->device->threadCount() : device->threads;
        if (key == "cudaDevice") return device->cudaDevice;
        if (key == "versionMajor") return BMFR_VERSION_MAJOR;
        if (key == "versionMinor") return BMFR_VERSION_MINOR;
        if (key == "versionPatch") return BMFR_VERSION_PATCH;
        throw BMFRApiError{BMFR_ERROR_INVALID_ARGUMENT,
                           "unknown device parameter '" + key +
                               "' (expected type, threads, cudaDevice, versionMajor, "
                               "versionMinor or versionPatch)"};
    });
}

void bmfrSetDeviceErrorFunction(BMFRDevice device, BMFRErrorFunction function,
                                void* userPtr) noexcept {
    guard(device, 0, [&] {
        std::lock_guard<std::mutex> lock(requireDevice(device)->errorMutex);
        device->errorFunction = function;
        device->errorUserPtr = userPtr;
        return 0;
    });
}

BMFRError bmfrGetDeviceError(BMFRDevice device, const char** outMessage) noexcept {
    BMFRError code;
    const char* text = nullptr;
    if (!device) {
        code = tSlot.error;
        tSlot.returned.swap(tSlot.message); // no allocation: nothing here can throw
        tSlot.error = BMFR_ERROR_NONE;
        tSlot.message.clear();
        if (code != BMFR_ERROR_NONE) text = tSlot.returned.c_str();
    } else {
        std::lock_guard<std::mutex> lock(device->errorMutex);
        code = device->error;
        device->returnedMessage.swap(device->message);
        device->error = BMFR_ERROR_NONE;
        device->message.clear();
        if (code != BMFR_ERROR_NONE) text = device->returnedMessage.c_str();
    }
    if (outMessage) *outMessage = text;
    return code;
}

void bmfrCommitDevice(BMFRDevice device) noexcept {
    guard(device, 0, [&] {
        requireDevice(device);
        if (device->device) return 0; // committed already: nothing changed since
        try {
            device->device.emplace(device->backend, device->threads, device->cudaDevice);
        } catch (const bmfr::Error& e) {
            throw BMFRApiError{BMFR_ERROR_UNSUPPORTED_HARDWARE, e.what()};
        }
        return 0;
    });
}

void bmfrSyncDevice(BMFRDevice device) noexcept {
    // Every execute has finished when it returns: the images are in host memory (c-api.md).
    guard(device, 0, [&] {
        requireDevice(device);
        return 0;
    });
}

} // extern "C"
