// The CUDA backend's BMFR fit as a launch host C++ can call: the block-cooperative fit
// (cooperative_fit.h), one CUDA block per regression block, over the history as float or,
// under halfHistory, as Half (H). The per-pixel stages run on the CUDA executor.
#pragma once
#include "core/half.h"
#include "filters/bmfr/fitting_kernel.h"
#include <cstddef>
#include <cuda_runtime_api.h>

namespace bmfr::cuda {

/// How the fit runs on this device for M features and B x B blocks.
struct FitPlan {
    int threads = 256;      ///< team size, a power of two
    size_t sharedBytes = 0; ///< dynamic shared memory per block
    size_t maskBytes = 0;   ///< the emitter mask (and again its stage bits): B^2 bytes, to 16
    bool matrixInShared = true;
    size_t matrixFloats = 0; ///< (M + 3) x B^2: per block, in global scratch when not shared
};
FitPlan planFit(int featureCount, int blockSize);
/// Fits every block of a.grid; `scratch` holds matrixFloats per block when !matrixInShared.
/// With `poorOnly` (history lengths), only the blocks owning a history-poor pixel.
template <class H>
void launchFitBlocks(const BlockFitOf<H>& a, const FitPlan& plan, float* scratch,
                     cudaStream_t stream, const uint8_t* poorOnly = nullptr);

} // namespace bmfr::cuda
