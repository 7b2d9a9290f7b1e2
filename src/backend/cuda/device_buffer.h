// Device memory for the CUDA backend's passes: error checks that throw bmfr::Error, and owning
// arrays and images that allocate only when their size changes (so never after the first frame
// of a sequence). Host code; the kernels see raw pointers.
#pragma once
#include "core/image.h"
#include <cstddef>
#include <cuda_runtime_api.h>
#include <utility>

namespace bmfr::cuda {

/// Throws bmfr::Error "CUDA error in <what>: <message>" unless `e` is cudaSuccess.
void check(cudaError_t e, const char* what);

/// Whether the current device has stream-ordered allocation (memory pools); without them the
/// arrays fall back to cudaMalloc and cudaFree, which wait for the device.
bool streamOrderedAllocation();

/// Orders the device allocations made in its scope, on this thread, on `stream`:
/// DeviceArray::resize frees, allocates and zeroes in that stream's order (cudaMallocAsync), so
/// the work queued there after it sees zeroed memory, and no other stream or the host waits.
class AllocationStream {
  public:
    explicit AllocationStream(cudaStream_t stream);
    ~AllocationStream();
    AllocationStream(const AllocationStream&) = delete;
    AllocationStream& operator=(const AllocationStream&) = delete;
    /// The innermost scope's stream; throws bmfr::Error outside any scope.
    static cudaStream_t current();

  private:
    const AllocationStream* outer_;
    cudaStream_t stream_;
};

/// An owning device array of T, zeroed when (re)allocated, in the order of the current
/// AllocationStream. Freed with cudaFree: its owner destroys it after the GPU's last use.
template <typename T> class DeviceArray {
  public:
    DeviceArray() = default;
    DeviceArray(const DeviceArray&) = delete;
    DeviceArray& operator=(const DeviceArray&) = delete;
    DeviceArray(DeviceArray&& o) noexcept : p_(std::exchange(o.p_, nullptr)), n_(o.n_) {}
    ~DeviceArray() { cudaFree(p_); }
    void resize(size_t n) {
        if (n == n_ && p_) return;
        const cudaStream_t s = AllocationStream::current();
        const size_t bytes = (n ? n : 1) * sizeof(T);
        void* p = nullptr;
        if (streamOrderedAllocation()) {
            if (p_) check(cudaFreeAsync(p_, s), "cudaFreeAsync");
            p_ = nullptr, n_ = 0;
            check(cudaMallocAsync(&p, bytes, s), "cudaMallocAsync");
        } else { // cudaFree waits for the device
            if (p_) check(cudaFree(p_), "cudaFree");
            p_ = nullptr, n_ = 0;
            check(cudaMalloc(&p, bytes), "cudaMalloc");
        }
        p_ = static_cast<T*>(p);
        check(cudaMemsetAsync(p_, 0, bytes, s), "cudaMemsetAsync");
        n_ = n;
    }
    T* data() { return p_; }
    const T* data() const { return p_; }
    size_t size() const { return n_; }
    size_t bytes() const { return n_ * sizeof(T); }

  private:
    T* p_ = nullptr;
    size_t n_ = 0;
};

/// An interleaved device image, the device twin of Image<T> (same resize and data()).
template <typename T> struct DeviceImage {
    int width = 0, height = 0, channels = 0;
    DeviceArray<T> pixels;
    /// `padding` elements follow the last pixel, as Image<T> (kept for a like layout).
    void resize(int w, int h, int c, int padding = 0) {
        width = w, height = h, channels = c;
        pixels.resize(size_t(w) * size_t(h) * size_t(c) + size_t(padding));
    }
    long pixelCount() const { return long(width) * height; }
    T* data() { return pixels.data(); }
    const T* data() const { return pixels.data(); }
    /// Copies the pixels into `host` (resized on size change), ordered on `stream`.
    void download(Image<T>& host, cudaStream_t stream) const {
        if (host.width != width || host.height != height || host.channels != channels)
            host.resize(width, height, channels);
        check(cudaMemcpyAsync(host.data(), data(), size_t(pixelCount()) * channels * sizeof(T),
                              cudaMemcpyDeviceToHost, stream),
              "download");
    }
};

using DeviceImageF = DeviceImage<float>;
/// A view of a device image for the caller (Memory::Cuda).
inline ImageView deviceView(const DeviceImage<float>& img) {
    return ImageView{img.data(), img.width, img.height, img.channels, 0, Memory::Cuda};
}
using DeviceImageU8 = DeviceImage<uint8_t>;

/// A non-blocking stream owned by one filter's passes.
class Stream {
  public:
    Stream();
    ~Stream();
    Stream(const Stream&) = delete;
    Stream& operator=(const Stream&) = delete;
    cudaStream_t get() const { return s_; }
    void synchronize() const;

  private:
    cudaStream_t s_ = nullptr;
};

} // namespace bmfr::cuda
