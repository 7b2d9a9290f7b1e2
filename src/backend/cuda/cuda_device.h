// What the rest of bmfr (the registry, bench, tests) asks of CUDA without including its
// headers: whether the backend is built, whether a device is there, which one, and how fast it
// copies. In a build without CUDA every call but built() throws bmfr::Error saying so.
#pragma once
#include <bmfr/frame.h>
#include <string>

namespace bmfr::cuda {

/// True when this library was built with the CUDA backend.
bool built();
/// Throws bmfr::Error "no CUDA device: ..." unless device `device` (as cudaSetDevice counts)
/// exists and is usable. Leaves the current device as it was. Cheap after the first call.
void requireDevice(int device = 0);
/// Device `device`, as "NVIDIA H200 (sm_90, 132 SMs, 140.4 GiB)".
std::string deviceName(int device = 0);

/// The devices the driver reports, and the calling thread's current one (for the tests).
int deviceCount();
int currentDevice();

/// Makes device `device` current for the scope's life and then restores the caller's, so that
/// the library never leaves an engine's thread on another device (rmm's cuda_set_device_raii).
class DeviceScope {
  public:
    explicit DeviceScope(int device);
    ~DeviceScope();
    DeviceScope(const DeviceScope&) = delete;
    DeviceScope& operator=(const DeviceScope&) = delete;

  private:
    int previous_ = -1; ///< the caller's device, or -1 when it was already `device`
};
/// The memory floor of `bytes` on the current GPU: milliseconds a device-to-device copy of that
/// many bytes takes (median of `repeats` timed copies after one warm-up, CUDA events).
double copyFloorMs(double bytes, int repeats = 9);
/// Writes the packed RGB device image `from` into the device image `to` (3 or 4 channels, any
/// row stride; a fourth channel is left as it was), ordered on `stream` (a cudaStream_t, or null
/// for the default stream, then waited for).
void copyOutput(const ImageView& from, const MutableImageView& to, void* stream);
/// The packed RGB device image `from` brought to the host after the work queued on `stream`
/// (waited for); the view is valid until this thread's next call.
ImageView downloadRgb(const ImageView& from, void* stream);

/// Writes an output of the CUDA passes (`from`, packed RGB in device or host memory) into the
/// caller's view in device or host memory, ordered on `stream`.
void writeResult(const ImageView& from, const MutableImageView& to, void* stream);

/// A host image copied once into device memory (same channels and row stride), for callers
/// that hand a filter device buffers: the bench and the tests, as an engine would.
class DeviceImageCopy {
  public:
    explicit DeviceImageCopy(const ImageView& host);
    ~DeviceImageCopy();
    DeviceImageCopy(const DeviceImageCopy&) = delete;
    DeviceImageCopy& operator=(const DeviceImageCopy&) = delete;
    /// The copy, as a view in device memory (null data for a null host view).
    ImageView view() const { return view_; }

  private:
    void* data_ = nullptr;
    ImageView view_;
};

/// A CUDA stream of the caller's (FrameInput::cudaStream), for the bench and the tests.
class CallerStream {
  public:
    CallerStream();
    ~CallerStream();
    CallerStream(const CallerStream&) = delete;
    CallerStream& operator=(const CallerStream&) = delete;
    void* get() const { return stream_; }
    void synchronize() const;

  private:
    void* stream_ = nullptr;
};

} // namespace bmfr::cuda
