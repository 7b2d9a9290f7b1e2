// maraEdgeWeight (filters/mara2017/mara_kernels.h) for eight or sixteen taps, shared by the CPU
// backend's sparse and glossy bilaterals.
#pragma once
#include "backend/cpu/simd.h"
#include "filters/mara2017/mara_kernels.h"

namespace bmfr::cpu {

/// maraEdgeWeight for eight or sixteen taps (V), operation for operation.
template <class V>
BMFR_SIMD_INLINE V edgeWeightOf(const V nc[3], const V pc[3], const V nq[3], const V pq[3],
                                const MaraEdgeWeights& k) {
    V cn = nc[0] * nq[0] + nc[1] * nq[1] + nc[2] * nq[2];
    cn = cn > 0.0f ? cn : V{};
    const V c2 = cn * cn;
    V w = 1.0f - k.normal * (1.0f - c2 * c2);
    w = w > 0.0f ? w : V{};
    const V dp[3] = {pq[0] - pc[0], pq[1] - pc[1], pq[2] - pc[2]};
    const V d2 = dp[0] * dp[0] + dp[1] * dp[1] + dp[2] * dp[2];
    V a = dp[0] * nq[0] + dp[1] * nq[1] + dp[2] * nq[2];
    V b = dp[0] * nc[0] + dp[1] * nc[1] + dp[2] * nc[2];
    a = a < 0.0f ? -a : a, b = b < 0.0f ? -b : b;
    const V along = a < b ? b : a;
    V root = d2;
    for (int l = 0; l < simd::kLanesOf<V>; ++l) root[l] = __builtin_sqrtf(root[l]);
    V wp = 1.0f - 2.0f * k.plane * along / root;
    wp = wp > 0.0f ? wp : V{};
    return d2 >= k.planeNearSquared ? w * (wp * wp) : w;
}

} // namespace bmfr::cpu
