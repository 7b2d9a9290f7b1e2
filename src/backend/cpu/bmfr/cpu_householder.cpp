#include "backend/cpu/bmfr/cpu_bmfr_buffers.h"
#include "backend/cpu/simd.h"
#include "filters/bmfr/householder_qr.h"
#include <algorithm>
#include <cmath>

namespace bmfr::cpu {

using namespace simd;

namespace {

constexpr int kGroup = 4; // columns per sweep: four accumulators plus v stay in registers

/// d[g] = v . a_g over rows [begin, rows) for `count` columns a_g, `stride` floats apart.
template <int count>
BMFR_SIMD_INLINE void dotGroupOf(const float* v, const float* a, int rows, long stride, int begin,
                                 float* d) {
    const int body = std::min((begin + 7) & ~7, rows), tail = body + (rows - body) / 8 * 8;
    float head[count] = {};
    for (int i = begin; i < body; ++i)
        for (int g = 0; g < count; ++g) head[g] += v[i] * a[long(g) * stride + i];
    for (int i = tail; i < rows; ++i)
        for (int g = 0; g < count; ++g) head[g] += v[i] * a[long(g) * stride + i];
    f8 acc[kGroup] = {};
    for (int i = body; i < tail; i += 8) {
        const f8 x = load8(v + i);
        for (int g = 0; g < count; ++g) acc[g] += x * load8(a + long(g) * stride + i);
    }
    for (int g = 0; g < count; ++g) d[g] = head[g] + hsum8(acc[g]);
}

BMFR_SIMD_INLINE void dotGroup(const float* v, const float* a, int count, int rows, long stride,
                               int begin, float* d) {
    switch (count) {
    case 1:
        return dotGroupOf<1>(v, a, rows, stride, begin, d);
    case 2:
        return dotGroupOf<2>(v, a, rows, stride, begin, d);
    case 3:
        return dotGroupOf<3>(v, a, rows, stride, begin, d);
    default:
        return dotGroupOf<kGroup>(v, a, rows, stride, begin, d);
    }
}

/// One sweep over `count` columns a_g (`stride` floats apart) from row k: a_g -= f[g] v. With
/// `next` (column k + 1, the next step's reflector) it also forms the next step's dot products
/// in the same sweep: d[g] = next . a_g over rows > k, after the update. When a_0 is `next`
/// itself, d[0] is instead the next step's sum of squares below its diagonal (rows > k + 1).
template <int count, bool look, bool self>
BMFR_SIMD_INLINE void updateGroupOf(const float* v, float* a, int rows, long stride, int k,
                                    const float* f, const float* next, float* d) {
    const int body = std::min((k + 2 + 7) & ~7, rows), tail = body + (rows - body) / 8 * 8;
    auto scalarRows = [&](int i0, int i1, float* sum) {
        for (int i = i0; i < i1; ++i)
            for (int g = 0; g < count; ++g) a[long(g) * stride + i] -= f[g] * v[i];
        if (!look) return;
        for (int i = std::max(i0, k + 1); i < i1; ++i)
            for (int g = 0; g < count; ++g)
                if (!(self && g == 0 && i == k + 1)) sum[g] += next[i] * a[long(g) * stride + i];
    };
    float head[count] = {}, rest[count] = {};
    scalarRows(k, body, head);
    scalarRows(tail, rows, rest);
    f8 fs[count], acc[count] = {};
    for (int g = 0; g < count; ++g) fs[g] = splat8(f[g]);
    for (int i = body; i < tail; i += 8) {
        const f8 x = load8(v + i);
        f8 col[count];
        for (int g = 0; g < count; ++g) {
            float* p = a + long(g) * stride + i;
            col[g] = load8(p) - fs[g] * x;
            store8(p, col[g]);
        }
        if (!look) continue;
        const f8 u = self ? col[0] : load8(next + i);
        for (int g = 0; g < count; ++g) acc[g] += u * col[g];
    }
    if (look)
        for (int g = 0; g < count; ++g) d[g] = head[g] + hsum8(acc[g]) + rest[g];
}

template <int count>
BMFR_SIMD_INLINE void updateGroupOf(const float* v, float* a, int rows, long stride, int k,
                                    const float* f, const float* next, float* d) {
    if (!next) return updateGroupOf<count, false, false>(v, a, rows, stride, k, f, next, d);
    if (next == a) return updateGroupOf<count, true, true>(v, a, rows, stride, k, f, next, d);
    updateGroupOf<count, true, false>(v, a, rows, stride, k, f, next, d);
}

BMFR_SIMD_INLINE void updateGroup(const float* v, float* a, int count, int rows, long stride, int k,
                                  const float* f, const float* next, float* d) {
    switch (count) {
    case 1:
        return updateGroupOf<1>(v, a, rows, stride, k, f, next, d);
    case 2:
        return updateGroupOf<2>(v, a, rows, stride, k, f, next, d);
    case 3:
        return updateGroupOf<3>(v, a, rows, stride, k, f, next, d);
    default:
        return updateGroupOf<kGroup>(v, a, rows, stride, k, f, next, d);
    }
}

BMFR_SIMD_DISPATCH(int, solveHouseholderPaths,
                   (float* columns, int featureCount, int rows, long stride, float* coeffs),
                   (columns, featureCount, rows, stride, coeffs)) {
    const int M = featureCount, total = featureCount + 3;
    auto column = [&](int j) { return columns + long(j) * stride; };
    HouseholderSteps q;
    // ahead[j]: column k . column j over rows >= k before step k's reflection, from the
    // previous step's sweep; ahead[k] is then the sum of squares below the diagonal.
    float ahead[kMaxFeatures + 3], dots[kMaxFeatures + 3], f[kMaxFeatures + 3];
    bool haveAhead = false;
    for (int k = 0; k < M; ++k) {
        float* v = column(k);
        const bool fromAhead = haveAhead;
        haveAhead = false;
        float below = fromAhead ? ahead[k] : 0.0f;
        if (!fromAhead) dotGroup(v, v, 1, rows, stride, k + 1, &below);
        const float vtv = q.reflect(columns, k, total, stride, below);
        if (q.dead[k]) continue;
        if (fromAhead) {
            // v differs from column k only in row k, by -R[k][k].
            for (int j = k + 1; j < total; ++j) dots[j] = ahead[j] - q.R[k][k] * column(j)[k];
        } else {
            for (int j = k + 1; j < total; j += kGroup)
                dotGroup(v, column(j), std::min(kGroup, total - j), rows, stride, k, dots + j);
        }
        for (int j = k + 1; j < total; ++j) f[j] = 2.0f * dots[j] / vtv;
        const float* next = k + 1 < M ? column(k + 1) : nullptr;
        for (int j = k + 1; j < total; j += kGroup)
            updateGroup(v, column(j), std::min(kGroup, total - j), rows, stride, k, f + j, next,
                        ahead + j);
        for (int j = k + 1; j < total; ++j) q.R[k][j] = column(j)[k];
        haveAhead = next != nullptr;
    }

    return q.solve(M, coeffs);
}

} // namespace

int solveHouseholderFast(float* columns, int featureCount, int rows, long stride, float* coeffs) {
    return solveHouseholderPaths(columns, featureCount, rows, stride, coeffs);
}

int solveHouseholderFast(float* columns, int featureCount, int rows, float* coeffs) {
    return solveHouseholderPaths(columns, featureCount, rows, rows, coeffs);
}

} // namespace bmfr::cpu
