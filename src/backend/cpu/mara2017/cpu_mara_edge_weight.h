// maraEdgeWeight (filters/mara2017/mara_kernels.h) for eight or sixteen taps, shared by the CPU
// backend's sparse and glossy bilaterals.
#pragma once
#include "backend/cpu/simd.h"
#include "filters/mara2017/mara_kernels.h"

namespace bmfr::cpu {

/// maraEdgeWeight for eight or sixteen taps (V), operation for operation. The clamps at 0 are
/// maxOn and the absolute values a mask: the same values (an along of -0 or +0 gives a wp of
/// exactly 1 either way, and a NaN wp is clamped to 0 either way).
template <Isa kIsa, class V>
BMFR_SIMD_INLINE V edgeWeightOf(const V nc[3], const V pc[3], const V nq[3], const V pq[3],
                                const MaraEdgeWeights& k) {
    const V cn = simd::maxOn<kIsa>(V{}, nc[0] * nq[0] + nc[1] * nq[1] + nc[2] * nq[2]);
    const V c2 = cn * cn;
    const V w = simd::maxOn<kIsa>(V{}, 1.0f - k.normal * (1.0f - c2 * c2));
    const V dp[3] = {pq[0] - pc[0], pq[1] - pc[1], pq[2] - pc[2]};
    const V d2 = dp[0] * dp[0] + dp[1] * dp[1] + dp[2] * dp[2];
    const V a = simd::absOf(dp[0] * nq[0] + dp[1] * nq[1] + dp[2] * nq[2]);
    const V b = simd::absOf(dp[0] * nc[0] + dp[1] * nc[1] + dp[2] * nc[2]);
    const V along = simd::maxOn<kIsa>(a, b);
    V root = d2;
    for (int l = 0; l < simd::kLanesOf<V>; ++l) root[l] = __builtin_sqrtf(root[l]);
    const V wp = simd::maxOn<kIsa>(V{}, 1.0f - 2.0f * k.plane * along / root);
    return d2 >= k.planeNearSquared ? w * (wp * wp) : w;
}

} // namespace bmfr::cpu
