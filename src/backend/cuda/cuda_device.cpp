#include "backend/cuda/cuda_device.h"
#include "backend/cuda/device_buffer.h"
#include "backend/cuda/image_copy.h"
#include "temporal/input_staging.h"
#include <algorithm>
#include <atomic>
#include <bmfr/error.h>
#include <cstdio>
#include <dlfcn.h>
#include <mutex>
#include <string>
#include <vector>

namespace bmfr::cuda {

void check(cudaError_t e, const char* what) {
    if (e != cudaSuccess)
        throw Error(std::string("CUDA error in ") + what + ": " + cudaGetErrorString(e) + " (" +
                    cudaGetErrorName(e) + ")");
}

Stream::Stream() {
    check(cudaStreamCreateWithFlags(&s_, cudaStreamNonBlocking), "cudaStreamCreate");
}
Stream::~Stream() {
    cudaStreamDestroy(s_);
}
void Stream::synchronize() const {
    check(cudaStreamSynchronize(s_), "cudaStreamSynchronize");
}

namespace {
thread_local const AllocationStream* tAllocation = nullptr;
} // namespace

AllocationStream::AllocationStream(cudaStream_t stream) : outer_(tAllocation), stream_(stream) {
    tAllocation = this;
}
AllocationStream::~AllocationStream() {
    tAllocation = outer_;
}
cudaStream_t AllocationStream::current() {
    if (!tAllocation)
        throw Error("internal error: a device allocation outside an AllocationStream");
    return tAllocation->stream_;
}

bool streamOrderedAllocation() {
    // One answer per device, asked once; 64 devices is more than any machine has.
    static std::atomic<int> known[64] = {}; // 0 unknown, 1 no, 2 yes
    int device = 0;
    check(cudaGetDevice(&device), "cudaGetDevice");
    if (device < 0 || device >= 64) return false;
    if (const int k = known[device].load(std::memory_order_relaxed)) return k == 2;
    int pools = 0;
    check(cudaDeviceGetAttribute(&pools, cudaDevAttrMemoryPoolsSupported, device),
          "cudaDeviceGetAttribute");
    known[device].store(pools ? 2 : 1, std::memory_order_relaxed);
    return pools != 0;
}

bool built() {
    return true;
}

namespace {
/// The runtime reports a missing driver as an old one; tell the two apart.
bool driverInstalled() {
    void* lib = dlopen("libcuda.so.1", RTLD_LAZY | RTLD_LOCAL);
    if (lib) dlclose(lib);
    return lib != nullptr;
}
} // namespace

void requireDevice(int device) {
    // The driver's answer cannot change within a process; ask it once.
    static std::once_flag once;
    static std::string why;
    static int count = 0;
    std::call_once(once, [] {
        const cudaError_t e = cudaGetDeviceCount(&count);
        if (e == cudaErrorInsufficientDriver && !driverInstalled())
            why = "no NVIDIA driver is installed (libcuda.so.1 cannot be loaded)";
        else if (e != cudaSuccess)
            why = std::string(cudaGetErrorString(e)) + " (" + cudaGetErrorName(e) + ")";
        else if (count == 0)
            why = "the driver reports no CUDA-capable device";
    });
    if (!why.empty()) throw Error("no CUDA device: " + why + " (use --backend cpu or reference)");
    if (device < 0 || device >= count)
        throw Error("no CUDA device " + std::to_string(device) + ": the driver reports " +
                    std::to_string(count) + " (numbered from 0)");
}

int deviceCount() {
    requireDevice();
    int count = 0;
    check(cudaGetDeviceCount(&count), "cudaGetDeviceCount");
    return count;
}
int currentDevice() {
    int device = 0;
    check(cudaGetDevice(&device), "cudaGetDevice");
    return device;
}

DeviceScope::DeviceScope(int device) {
    int current = 0;
    check(cudaGetDevice(&current), "cudaGetDevice");
    if (current == device) return;
    check(cudaSetDevice(device), "cudaSetDevice");
    previous_ = current;
}
DeviceScope::~DeviceScope() {
    if (previous_ >= 0) cudaSetDevice(previous_);
}

std::string deviceName(int device) {
    requireDevice(device);
    cudaDeviceProp p{};
    check(cudaGetDeviceProperties(&p, device), "cudaGetDeviceProperties");
    char buf[384];
    std::snprintf(buf, sizeof buf, "%s (sm_%d%d, %d SMs, %.1f GiB)", p.name, p.major, p.minor,
                  p.multiProcessorCount, double(p.totalGlobalMem) / (1024.0 * 1024.0 * 1024.0));
    return buf;
}

double copyFloorMs(double bytes, int repeats) {
    requireDevice();
    // A copy reads and writes: half the bytes each way moves `bytes` in all.
    const size_t n = std::max<size_t>(size_t(bytes / 2.0), 1);
    Stream stream;
    DeviceArray<unsigned char> a, b;
    {
        const AllocationStream on(stream.get());
        a.resize(n), b.resize(n);
    }
    cudaEvent_t start, stop;
    check(cudaEventCreate(&start), "cudaEventCreate");
    check(cudaEventCreate(&stop), "cudaEventCreate");
    std::vector<float> ms;
    for (int r = 0; r <= repeats; ++r) {
        check(cudaEventRecord(start, stream.get()), "cudaEventRecord");
        check(cudaMemcpyAsync(b.data(), a.data(), n, cudaMemcpyDeviceToDevice, stream.get()),
              "cudaMemcpyAsync");
        check(cudaEventRecord(stop, stream.get()), "cudaEventRecord");
        check(cudaEventSynchronize(stop), "cudaEventSynchronize");
        float t = 0;
        check(cudaEventElapsedTime(&t, start, stop), "cudaEventElapsedTime");
        if (r > 0) ms.push_back(t); // the first copy warms up
    }
    cudaEventDestroy(start);
    cudaEventDestroy(stop);
    std::nth_element(ms.begin(), ms.begin() + long(ms.size() / 2), ms.end());
    return double(ms[ms.size() / 2]);
}

void copyOutput(const ImageView& from, const MutableImageView& to, void* stream) {
    const cudaStream_t s = static_cast<cudaStream_t>(stream);
    launchUnpackRgb(from.data, from.width, from.height, to.data, to.channels, to.stride(), s);
    if (!stream) check(cudaStreamSynchronize(s), "cudaStreamSynchronize");
}

ImageView downloadRgb(const ImageView& from, void* stream) {
    const cudaStream_t s = static_cast<cudaStream_t>(stream);
    thread_local std::vector<float> packed;
    packed.resize(size_t(from.width) * size_t(from.height) * 3);
    check(cudaMemcpyAsync(packed.data(), from.data, packed.size() * sizeof(float),
                          cudaMemcpyDeviceToHost, s),
          "output download");
    check(cudaStreamSynchronize(s), "cudaStreamSynchronize");
    return ImageView{packed.data(), from.width, from.height, 3};
}

void writeResult(const ImageView& from, const MutableImageView& to, void* stream) {
    if (from.memory == Memory::Cuda && to.memory == Memory::Cuda)
        return copyOutput(from, to, stream);
    if (from.memory == Memory::Cuda) return writeOutput(downloadRgb(from, stream), to);
    writeOutput(from, to);
}

DeviceImageCopy::DeviceImageCopy(const ImageView& host) : view_(host) {
    view_.memory = Memory::Cuda;
    if (!host.data) return;
    requireDevice();
    const size_t row = size_t(host.width) * size_t(host.channels) * sizeof(float);
    const size_t pitch = size_t(host.stride()) * sizeof(float);
    check(cudaMalloc(&data_, pitch * size_t(host.height)), "cudaMalloc");
    check(cudaMemcpy2D(data_, pitch, host.data, pitch, row, size_t(host.height),
                       cudaMemcpyHostToDevice),
          "device copy");
    // A pageable copy may still be on its way; the filters' streams do not wait for it.
    check(cudaDeviceSynchronize(), "device copy");
    view_.data = static_cast<const float*>(data_);
}
DeviceImageCopy::~DeviceImageCopy() {
    cudaFree(data_);
}

CallerStream::CallerStream() {
    requireDevice();
    cudaStream_t s = nullptr;
    check(cudaStreamCreateWithFlags(&s, cudaStreamNonBlocking), "cudaStreamCreate");
    stream_ = s;
}
CallerStream::~CallerStream() {
    cudaStreamDestroy(static_cast<cudaStream_t>(stream_));
}
void CallerStream::synchronize() const {
    check(cudaStreamSynchronize(static_cast<cudaStream_t>(stream_)), "cudaStreamSynchronize");
}

} // namespace bmfr::cuda
