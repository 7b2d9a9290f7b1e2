// Compile-only check that the per-pixel and per-block kernels are device code: every BMFR_HD
// kernel of src/temporal and src/filters called from CUDA kernels. Built by nvcc (ctest
// Kernels.CompileForCuda) where the toolkit exists; needs no GPU. The CUDA backend itself is
// src/backend/cuda/; this keeps the filters it does not run yet (WALR, Mara) device-ready.
#include "filters/bmfr/accumulation_kernels.h"
#include "filters/bmfr/fitting_kernel.h"
#include "filters/mara2017/mara_stages.h"
#include "filters/svgf/svgf_kernels.h"
#include "filters/walr/refwlr.h"
#include "filters/walr/walr_temporal_kernels.h"
#include "temporal/taa.h"

namespace bmfr {
/// Stands in for a device QR: only the shared back substitution, to instantiate fitBlock.
struct DeviceSolve {
    __device__ int operator()(float*, int m, int, float* coeffs) const {
        HouseholderSteps q;
        return q.solve(m, coeffs);
    }
};
__global__ void phase1(NoisyAccumulation a, long n, unsigned long long* lost) {
    long i = blockIdx.x * long(blockDim.x) + threadIdx.x;
    if (i >= n) return;
    int64_t bad = 0;
    if (accumulateNoisyPixel(a, i, bad)) atomicAdd(lost, 1ull);
}
__global__ void phase3(FittedAccumulation a, float* out, long n) {
    long i = blockIdx.x * long(blockDim.x) + threadIdx.x;
    if (i < n) store3(out, i, accumulateFittedPixel(a, i));
}
__global__ void taa(TaaInputs a, float* out) {
    int x = threadIdx.x, y = blockIdx.x;
    if (x < a.width && y < a.height) store3(out, long(y) * a.width + x, taaPixel(a, x, y));
}
__global__ void fit(BlockFit a, BlockFitScratch sc) {
    fitBlock(a, blockIdx.x, blockIdx.y, sc, DeviceSolve{});
}
__global__ void svgf(SvgfFrame f, AtrousLevel l, SvgfSettings s, float* filtered, float* var) {
    int64_t bad = 0;
    svgfAccumulatePixel(f, threadIdx.x, bad);
    svgfDepthGradientPixel(f, threadIdx.x, 0);
    svgfVariancePixel(f, s, threadIdx.x, 0, filtered, var);
    svgfAtrousPixel(l, s, threadIdx.x, 0);
}
__global__ void walr(WalrFrame f, EdgeGuide g, WalrLevel l, WalrPost p, float* out) {
    int64_t bad = 0;
    const int x = threadIdx.x, y = blockIdx.x;
    walrInputPixel(f, long(y) * f.width + x, bad);
    walrAccumulatePixel(f, x, y, out, l.layout);
    walrAtrousPixel(g, l, x, y);
    store3(out, x, walrSolvePixel(l.out, l.layout, x, {0.5f, 0.5f}, 1e-4f));
    store3(out, x, refwlrPixel(g, out, out, 4, 1e-4, x, y));
    walrPostPixel(p, x, y);
}
__global__ void mara(MaraFrame f) {
    int64_t bad = 0;
    const int x = threadIdx.x, y = blockIdx.x;
    const long i = long(y) * f.width + x;
    maraInputPixel(f, i, bad);
    maraMatteTemporalPixel(f, x, y);
    maraPreBilateralPixel(f, x, y);
    maraRowMinPixel(f, x, y);
    maraColumnMinPixel(f, x, y);
    maraMedianPixel(f, x, y);
    maraFinalBilateralPixel(f, f.median, x, y);
    maraGlossyTemporalPixel(f, x, y);
    maraGlossyPassPixel(f, f.glossyTemporal, f.glossyRow, x, y, 1, 0);
    maraComposePixel(f, i);
}
} // namespace bmfr
