// Where a stage's per-pixel loop runs. A stage is written once, as e.forEachPixel(...) over
// BMFR_HD kernels, and runs on the host's threads (HostExecutor) or as one CUDA kernel
// (CudaExecutor, backend/cuda/cuda_executor.h): pbrt-v4's ParallelFor and GPUParallelFor.
#pragma once
#include "core/host_device.h"
#include "core/parallel.h"
#include <cstdint>

/// A lambda for an executor: by value, and on the device too where nvcc compiles it
/// (pbrt-v4's PBRT_CPU_GPU_LAMBDA; needs nvcc's --extended-lambda).
#if defined(__CUDACC__)
#define BMFR_LAMBDA(...) [=] __host__ __device__(__VA_ARGS__)
#else
#define BMFR_LAMBDA(...) [=](__VA_ARGS__)
#endif

namespace bmfr {

/// A frame's count that any thread adds to (non-finite inputs, lost histories): an integer, so
/// the total does not depend on the order.
struct FrameCounter {
    unsigned long long* value;
    BMFR_HD void add(int64_t n) const {
        if (!n) return; // rare: no traffic on the counter for most pixels
#if defined(__CUDA_ARCH__)
        atomicAdd(value, static_cast<unsigned long long>(n));
#else
        __atomic_fetch_add(value, static_cast<unsigned long long>(n), __ATOMIC_RELAXED);
#endif
    }
};

/// The host's worker threads.
struct HostExecutor {
    ThreadPool& pool;
    /// f(i) for i in [0, n).
    template <class F> void forEachIndex(long n, const F& f) const {
        pool.parallelFor(n, 4096, [&](long i0, long i1) {
            for (long i = i0; i < i1; ++i) f(i);
        });
    }
    /// f(x, y) for every pixel of a w x h image, `grainRows` rows at least per task.
    template <class F> void forEachPixel(int w, int h, const F& f, long grainRows = 4) const {
        pool.forEachPixel(w, h, grainRows, f);
    }
};

} // namespace bmfr
