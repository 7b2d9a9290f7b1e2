#include "backend/cuda/cuda_device.h"
#include "backend/cuda/device_buffer.h"
#include <algorithm>
#include <bmfr/error.h>
#include <cstdio>
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

bool built() {
    return true;
}

void requireDevice() {
    // The answer cannot change within a process; ask the driver once.
    static std::once_flag once;
    static std::string why;
    std::call_once(once, [] {
        int count = 0;
        const cudaError_t e = cudaGetDeviceCount(&count);
        if (e != cudaSuccess)
            why = std::string(cudaGetErrorString(e)) + " (" + cudaGetErrorName(e) + ")";
        else if (count == 0)
            why = "the driver reports no CUDA-capable device";
        else {
            const cudaError_t s = cudaSetDevice(0);
            if (s != cudaSuccess)
                why = std::string("device 0 is unusable: ") + cudaGetErrorString(s);
        }
    });
    if (!why.empty()) throw Error("no CUDA device: " + why + " (use --backend cpu or reference)");
    check(cudaSetDevice(0), "cudaSetDevice");
}

std::string deviceName() {
    requireDevice();
    cudaDeviceProp p{};
    check(cudaGetDeviceProperties(&p, 0), "cudaGetDeviceProperties");
    char buf[384];
    std::snprintf(buf, sizeof buf, "%s (sm_%d%d, %d SMs, %.1f GiB)", p.name, p.major, p.minor,
                  p.multiProcessorCount, double(p.totalGlobalMem) / (1024.0 * 1024.0 * 1024.0));
    return buf;
}

double copyFloorMs(double bytes, int repeats) {
    requireDevice();
    // A copy reads and writes: half the bytes each way moves `bytes` in all.
    const size_t n = std::max<size_t>(size_t(bytes / 2.0), 1);
    DeviceArray<unsigned char> a, b;
    a.resize(n), b.resize(n);
    check(cudaDeviceSynchronize(), "allocation");
    Stream stream;
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

} // namespace bmfr::cuda
