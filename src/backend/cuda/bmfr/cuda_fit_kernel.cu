// The BMFR fitting kernel on the GPU: one CUDA block per regression block running
// fitBlockTeam (cooperative_fit.h) with the matrix in shared memory, or in global scratch when
// the block is too large for this device's shared memory.
#include "backend/cuda/bmfr/cooperative_fit.h"
#include "backend/cuda/bmfr/cuda_bmfr_kernels.h"
#include "backend/cuda/device_buffer.h"
#include "filters/bmfr/second_grid.h"

namespace bmfr::cuda {

namespace {
/// The fixed part of the team's memory, rounded to keep the float arrays 16-byte aligned.
constexpr size_t kStateBytes = (sizeof(TeamFitState) + 15) / 16 * 16;

template <class H>
__global__ void fitKernel(BlockFitOf<H> a, int matrixFloats, bool matrixInShared, int maskBytes,
                          float* scratch, const uint8_t* poorOnly) {
    extern __shared__ float4 shared[];
    if (poorOnly) {
        // Only a history-poor pixel reads this fit (blendSecondFit): a block owning none is
        // left unfitted. __syncthreads_or gives every thread the same answer.
        int any = 0;
        const int W = a.grid.blockSize * a.grid.blockSize;
        for (int k = int(threadIdx.x); k < W && !any; k += int(blockDim.x)) {
            bool owned;
            const long idx = blockPixel(a.grid, int(blockIdx.x), int(blockIdx.y), k, owned);
            any = owned && historyPoor(poorOnly[idx]);
        }
        if (!__syncthreads_or(any)) return;
    }
    char* base = reinterpret_cast<char*>(shared);
    const DeviceTeam team;
    float* partial = reinterpret_cast<float*>(base + kStateBytes);
    // The mask and its stage bits (maskBytes each, a multiple of 16) between the partial sums
    // and the matrix.
    uint8_t* mask =
        reinterpret_cast<uint8_t*>(partial + size_t(teamFitPartials(a.featureCount)) * blockDim.x);
    float* matrix = reinterpret_cast<float*>(mask + 2 * maskBytes);
    if (!matrixInShared)
        matrix = scratch + size_t(blockIdx.y * gridDim.x + blockIdx.x) * size_t(matrixFloats);
    const TeamFitMemory mem{reinterpret_cast<TeamFitState*>(base), partial, matrix, mask,
                            mask + maskBytes};
    fitBlockTeam(team, a, int(blockIdx.x), int(blockIdx.y), mem);
}
} // namespace

FitPlan planFit(int featureCount, int blockSize) {
    FitPlan p;
    const int W = blockSize * blockSize;
    // Two of the block's pixels per thread, 256 threads at most, a warp at least. Measured on
    // an H200, 720p: 16x16 blocks fit in 0.68 ms with 128 threads, 0.74 with 64, 0.84 with
    // 256 and 0.90 with 32 (the fit is latency-bound: more threads hide more of it, until
    // the reductions' extra levels and the shared memory they take cost more).
    p.threads = 32;
    while (p.threads < 256 && p.threads * 2 < W) p.threads *= 2;
    p.matrixFloats = size_t(featureCount + 3) * size_t(W);
    p.maskBytes = (size_t(W) + 15) / 16 * 16;
    const size_t fixed = kStateBytes +
                         size_t(teamFitPartials(featureCount)) * size_t(p.threads) * sizeof(float) +
                         2 * p.maskBytes;
    int device = 0, optin = 0;
    check(cudaGetDevice(&device), "cudaGetDevice");
    check(cudaDeviceGetAttribute(&optin, cudaDevAttrMaxSharedMemoryPerBlockOptin, device),
          "cudaDeviceGetAttribute");
    cudaFuncAttributes kernel{};
    check(cudaFuncGetAttributes(&kernel, fitKernel<float>), "cudaFuncGetAttributes");
    const int most = optin - int(kernel.sharedSizeBytes); // dynamic shared memory, at most
    p.matrixInShared = fixed + p.matrixFloats * sizeof(float) <= size_t(most);
    p.sharedBytes = fixed + (p.matrixInShared ? p.matrixFloats * sizeof(float) : 0);
    // The attribute is the kernel's on this device, for the whole process, not this filter's:
    // set to one plan's need, it would fail the launches of another filter that needs more.
    // The device's largest fits every plan, and it only permits, so all set the same value.
    for (const void* kernel : {reinterpret_cast<const void*>(fitKernel<float>),
                               reinterpret_cast<const void*>(fitKernel<Half>)})
        check(cudaFuncSetAttribute(kernel, cudaFuncAttributeMaxDynamicSharedMemorySize, most),
              "cudaFuncSetAttribute");
    return p;
}

template <class H>
void launchFitBlocks(const BlockFitOf<H>& a, const FitPlan& plan, float* scratch,
                     cudaStream_t stream, const uint8_t* poorOnly) {
    const dim3 grid(unsigned(a.grid.blocksX), unsigned(a.grid.blocksY));
    fitKernel<H><<<grid, unsigned(plan.threads), plan.sharedBytes, stream>>>(
        a, int(plan.matrixFloats), plan.matrixInShared, int(plan.maskBytes), scratch, poorOnly);
    check(cudaGetLastError(), "fit kernel");
}

template void launchFitBlocks(const BlockFitOf<float>&, const FitPlan&, float*, cudaStream_t,
                              const uint8_t*);
template void launchFitBlocks(const BlockFitOf<Half>&, const FitPlan&, float*, cudaStream_t,
                              const uint8_t*);

} // namespace bmfr::cuda
