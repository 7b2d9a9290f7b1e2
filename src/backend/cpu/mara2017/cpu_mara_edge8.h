// maraEdgeWeight (filters/mara2017/mara_kernels.h) for eight taps, shared by the CPU backend's
// sparse and glossy bilaterals.
#pragma once
#include "backend/cpu/simd.h"
#include "filters/mara2017/mara_kernels.h"

namespace bmfr::cpu {

/// maraEdgeWeight for eight taps, operation for operation.
BMFR_SIMD_INLINE simd::f8 edgeWeight8(const simd::f8 nc[3], const simd::f8 pc[3],
                                      const simd::f8 nq[3], const simd::f8 pq[3],
                                      const MaraEdgeWeights& k) {
    using namespace simd;
    f8 cn = nc[0] * nq[0] + nc[1] * nq[1] + nc[2] * nq[2];
    cn = cn > 0.0f ? cn : 0.0f;
    const f8 c2 = cn * cn;
    f8 w = 1.0f - k.normal * (1.0f - c2 * c2);
    w = w > 0.0f ? w : 0.0f;
    const f8 dp[3] = {pq[0] - pc[0], pq[1] - pc[1], pq[2] - pc[2]};
    const f8 d2 = dp[0] * dp[0] + dp[1] * dp[1] + dp[2] * dp[2];
    f8 a = dp[0] * nq[0] + dp[1] * nq[1] + dp[2] * nq[2];
    f8 b = dp[0] * nc[0] + dp[1] * nc[1] + dp[2] * nc[2];
    a = a < 0.0f ? -a : a, b = b < 0.0f ? -b : b;
    const f8 along = a < b ? b : a;
    f8 root = d2;
    for (int l = 0; l < 8; ++l) root[l] = __builtin_sqrtf(root[l]);
    f8 wp = 1.0f - 2.0f * k.plane * along / root;
    wp = wp > 0.0f ? wp : 0.0f;
    return d2 >= k.planeNearSquared ? w * (wp * wp) : w;
}

} // namespace bmfr::cpu
