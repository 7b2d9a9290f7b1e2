// A thread team: the threads of one CUDA block (DeviceTeam), or the host running the same
// code one thread after another (HostTeam). Team code is a sequence of phases: every thread runs
// a phase's body with its index, and no thread starts the next phase before all have finished
// this one. State that outlives a phase lives in the team's shared memory, never in a thread, so
// the host runs the very code, in the very order of operations, that the GPU runs; the tests
// hold the GPU's algorithms to the reference that way on machines without a GPU.
#pragma once
#include "core/host_device.h"

namespace bmfr::cuda {

/// The host's team of `size` threads, run in index order.
struct HostTeam {
    static constexpr bool kWarps = false; ///< no warp shuffles: every step is a phase
    int threads = 256;
    int size() const { return threads; }
    /// body(t) for every thread t, then a barrier.
    template <class Body> void parallel(Body&& body) const {
        for (int t = 0; t < threads; ++t) body(t);
    }
    /// body() on one thread, then a barrier.
    template <class Body> void single(Body&& body) const { body(); }
};

#if defined(__CUDACC__)
/// The threads of this CUDA block (one-dimensional).
struct DeviceTeam {
    static constexpr bool kWarps = true; ///< team code may use the first warp's shuffles
    BMFR_HD int size() const {
#if defined(__CUDA_ARCH__)
        return int(blockDim.x);
#else
        return 0;
#endif
    }
    template <class Body> BMFR_HD void parallel(Body&& body) const {
#if defined(__CUDA_ARCH__)
        body(int(threadIdx.x));
        __syncthreads();
#endif
    }
    template <class Body> BMFR_HD void single(Body&& body) const {
#if defined(__CUDA_ARCH__)
        if (threadIdx.x == 0) body();
        __syncthreads();
#endif
    }
};
#endif

} // namespace bmfr::cuda
