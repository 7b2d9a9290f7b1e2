/* bmfr's C API (C99), in Open Image Denoise's shape: devices and filters as reference-counted
 * handles, images shared by pointer with a format and byte strides, settings by key, an error
 * code and message per device. No exception crosses it. Compiled as C++, this header also gives
 * the C++ API (<bmfr/bmfr.hpp>). Every name, setting and convention: docs/c-api.md. */
#ifndef BMFR_BMFR_H
#define BMFR_BMFR_H

#include <bmfr/api.h>
#include <stdbool.h>
#include <stddef.h>

#ifdef __cplusplus
#define BMFR_NOEXCEPT noexcept
extern "C" {
#else
#define BMFR_NOEXCEPT
#endif

/* Where filters run (as bmfr::Backend); DEFAULT is CPU. */
typedef enum BMFRDeviceType {
    BMFR_DEVICE_TYPE_DEFAULT = 0,
    BMFR_DEVICE_TYPE_CPU = 1,
    BMFR_DEVICE_TYPE_REFERENCE = 2,
    BMFR_DEVICE_TYPE_CUDA = 3
} BMFRDeviceType;

/* Error codes, OIDN's values. */
typedef enum BMFRError {
    BMFR_ERROR_NONE = 0,
    BMFR_ERROR_UNKNOWN = 1,
    BMFR_ERROR_INVALID_ARGUMENT = 2,  /* a bad value, image, matrix or name */
    BMFR_ERROR_INVALID_OPERATION = 3, /* a call out of order (execute before commit...) */
    BMFR_ERROR_OUT_OF_MEMORY = 4,
    BMFR_ERROR_UNSUPPORTED_HARDWARE = 5 /* the device type is not built in or has no device */
} BMFRError;

/* Called on every error, on the thread that made the call, before the call returns. */
typedef void (*BMFRErrorFunction)(void* userPtr, BMFRError code, const char* message);

/* Pixel formats, OIDN's values: 1 to 4 channels of 32-bit or 16-bit (IEEE half) floats. */
typedef enum BMFRFormat {
    BMFR_FORMAT_UNDEFINED = 0,
    BMFR_FORMAT_FLOAT = 1,
    BMFR_FORMAT_FLOAT2 = 2,
    BMFR_FORMAT_FLOAT3 = 3,
    BMFR_FORMAT_FLOAT4 = 4,
    BMFR_FORMAT_HALF = 257,
    BMFR_FORMAT_HALF2 = 258,
    BMFR_FORMAT_HALF3 = 259,
    BMFR_FORMAT_HALF4 = 260
} BMFRFormat;

/* The filter int "accumulationMode", set per frame (NRD's AccumulationMode). */
typedef enum BMFRAccumulationMode {
    BMFR_ACCUMULATION_MODE_CONTINUE = 0,         /* use the history */
    BMFR_ACCUMULATION_MODE_RESTART = 1,          /* drop it: a camera cut */
    BMFR_ACCUMULATION_MODE_CLEAR_AND_RESTART = 2 /* as RESTART: no history is read after one */
} BMFRAccumulationMode;

typedef struct BMFRDeviceImpl* BMFRDevice;
typedef struct BMFRFilterImpl* BMFRFilter;

/* Devices. A new device takes settings until committed: int "threads" (worker threads, 0 = all
 * cores, [0, 1024], default 0) and, for BMFR_DEVICE_TYPE_CUDA, int "cudaDevice" (the GPU, as
 * cudaSetDevice numbers them, default 0; current only while the library works, the caller's
 * restored after). Read-only ints: "type", "threads", "cudaDevice", "versionMajor",
 * "versionMinor", "versionPatch". A NULL device in any call is an error reported to the thread's
 * own slot, which bmfrGetDeviceError(NULL, ...) reads. */
BMFR_API BMFRDevice bmfrNewDevice(BMFRDeviceType type) BMFR_NOEXCEPT;
BMFR_API void bmfrRetainDevice(BMFRDevice device) BMFR_NOEXCEPT;
BMFR_API void bmfrReleaseDevice(BMFRDevice device) BMFR_NOEXCEPT;
BMFR_API void bmfrSetDeviceInt(BMFRDevice device, const char* name, int value) BMFR_NOEXCEPT;
BMFR_API int bmfrGetDeviceInt(BMFRDevice device, const char* name) BMFR_NOEXCEPT;
BMFR_API void bmfrSetDeviceErrorFunction(BMFRDevice device, BMFRErrorFunction func,
                                         void* userPtr) BMFR_NOEXCEPT;
/* Returns the first error since the last call and clears it; *outMessage (when not NULL) points
 * to its message, valid until the next call on this device, or to NULL without an error. */
BMFR_API BMFRError bmfrGetDeviceError(BMFRDevice device, const char** outMessage) BMFR_NOEXCEPT;
BMFR_API void bmfrCommitDevice(BMFRDevice device) BMFR_NOEXCEPT;
/* Waits for the device's queued work (bmfrExecuteFilterAsync). */
BMFR_API void bmfrSyncDevice(BMFRDevice device) BMFR_NOEXCEPT;

/* Filters: "bmfr", "svgf", "walr" or "mara2017". A filter keeps its history between executes,
 * so one filter serves one view. */
BMFR_API BMFRFilter bmfrNewFilter(BMFRDevice device, const char* type) BMFR_NOEXCEPT;
BMFR_API void bmfrRetainFilter(BMFRFilter filter) BMFR_NOEXCEPT;
BMFR_API void bmfrReleaseFilter(BMFRFilter filter) BMFR_NOEXCEPT;

/* Shares an image in host memory: not copied, but read (or, for "output", written) at every
 * execute until it is unset or set again, so it must stay valid that long.
 * Inputs: "color", "albedo", "normal", "position", "depth", "motion", "emission", and every
 * other buffer of docs/c-api.md's table; the output: "output". byteOffset is added to ptr;
 * bytePixelStride 0 = packed, byteRowStride 0 = packed rows. A NULL ptr unsets the image. */
BMFR_API void bmfrSetFilterImage(BMFRFilter filter, const char* name, void* ptr, BMFRFormat format,
                                 size_t width, size_t height, size_t byteOffset,
                                 size_t bytePixelStride, size_t byteRowStride) BMFR_NOEXCEPT;
BMFR_API void bmfrUnsetFilterImage(BMFRFilter filter, const char* name) BMFR_NOEXCEPT;
/* A 4x4 matrix, 16 floats, row-major, acting on column vectors: "viewProjection" (this frame's
 * world-to-clip, as bmfr::FrameInput's). */
BMFR_API void bmfrSetFilterMatrix(BMFRFilter filter, const char* name,
                                  const float* rowMajor4x4) BMFR_NOEXCEPT;

/* Settings by key: every key of `bmfr settings FILTER` (the filter's own and the shared ones),
 * "preset" (string: "quality", the default, or "faithful", the papers' settings alone; applied
 * before the other keys), and the per-frame conventions of docs/c-api.md ("accumulationMode",
 * "frameIndex", "jitterX", "jitterY", "motionScaleX", "motionScaleY", "motionYUp",
 * "motionIncludesJitter", "normalOctUnorm"). A
 * setting of the filter's table takes effect at the next bmfrCommitFilter, which starts a new
 * history; the per-frame ones at the next execute. */
BMFR_API void bmfrSetFilterBool(BMFRFilter filter, const char* name, bool value) BMFR_NOEXCEPT;
BMFR_API void bmfrSetFilterInt(BMFRFilter filter, const char* name, int value) BMFR_NOEXCEPT;
BMFR_API void bmfrSetFilterFloat(BMFRFilter filter, const char* name, float value) BMFR_NOEXCEPT;
BMFR_API void bmfrSetFilterString(BMFRFilter filter, const char* name,
                                  const char* value) BMFR_NOEXCEPT;
BMFR_API bool bmfrGetFilterBool(BMFRFilter filter, const char* name) BMFR_NOEXCEPT;
BMFR_API int bmfrGetFilterInt(BMFRFilter filter, const char* name) BMFR_NOEXCEPT;
BMFR_API float bmfrGetFilterFloat(BMFRFilter filter, const char* name) BMFR_NOEXCEPT;

/* Makes the filter with its settings. With "maxWidth" and "maxHeight" set, sizes every buffer
 * for frames that large (and each image's conversion buffer when the image is first set), so
 * that no execute up to that size allocates (docs/c-api.md says the one exception). */
BMFR_API void bmfrCommitFilter(BMFRFilter filter) BMFR_NOEXCEPT;
/* Denoises the frame set on the filter into "output". */
BMFR_API void bmfrExecuteFilter(BMFRFilter filter) BMFR_NOEXCEPT;
/* The same, queued on the device: host devices finish before returning; see docs/c-api.md. */
BMFR_API void bmfrExecuteFilterAsync(BMFRFilter filter) BMFR_NOEXCEPT;
/* Host bytes the filter's buffers take for frames of width x height with its committed
 * settings: its own buffers and the input conversions the C API makes (docs/c-api.md). */
BMFR_API size_t bmfrGetFilterMemoryBytes(BMFRFilter filter, int width, int height) BMFR_NOEXCEPT;

#ifdef __cplusplus
} /* extern "C" */
#include <bmfr/bmfr.hpp>
#endif

#endif /* BMFR_BMFR_H */
