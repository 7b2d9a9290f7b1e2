#include "backend/cpu/fast_passes.h"
#include "core/simd.h"
#include "filters/bmfr/householder_fit.h"
#include <algorithm>
#include <cmath>

namespace bmfr::cpu {

using namespace simd;

namespace {

constexpr int kGroup = 4; // columns per sweep: four accumulators plus v stay in registers

/// d[g] = v . a_g over rows [begin, rows) for up to four columns a_g (stride `rows`).
BMFR_SIMD_INLINE void dotGroup(const float* v, const float* a, int count, int rows, int begin,
                               float* d) {
    const int body = std::min((begin + 7) & ~7, rows), tail = body + (rows - body) / 8 * 8;
    float head[kGroup] = {};
    for (int i = begin; i < body; ++i)
        for (int g = 0; g < count; ++g) head[g] += v[i] * a[long(g) * rows + i];
    for (int i = tail; i < rows; ++i)
        for (int g = 0; g < count; ++g) head[g] += v[i] * a[long(g) * rows + i];
    f8 acc[kGroup] = {};
    for (int i = body; i < tail; i += 8) {
        const f8 x = load8(v + i);
        for (int g = 0; g < kGroup; ++g)
            if (g < count) acc[g] += x * load8(a + long(g) * rows + i);
    }
    for (int g = 0; g < count; ++g) d[g] = head[g] + hsum8(acc[g]);
}

/// a_g -= f[g] v over rows [begin, rows) for up to four columns.
BMFR_SIMD_INLINE void axpyGroup(const float* v, float* a, int count, int rows, int begin,
                                const float* f) {
    const int body = std::min((begin + 7) & ~7, rows), tail = body + (rows - body) / 8 * 8;
    for (int i = begin; i < body; ++i)
        for (int g = 0; g < count; ++g) a[long(g) * rows + i] -= f[g] * v[i];
    for (int i = tail; i < rows; ++i)
        for (int g = 0; g < count; ++g) a[long(g) * rows + i] -= f[g] * v[i];
    f8 fs[kGroup];
    for (int g = 0; g < kGroup; ++g) fs[g] = splat8(g < count ? f[g] : 0.0f);
    for (int i = body; i < tail; i += 8) {
        const f8 x = load8(v + i);
        for (int g = 0; g < kGroup; ++g)
            if (g < count) {
                float* col = a + long(g) * rows + i;
                store8(col, load8(col) - fs[g] * x);
            }
    }
}

} // namespace

BMFR_SIMD_CLONES int solveHouseholderFast(float* columns, int featureCount, int rows,
                                          float* coeffs) {
    const int M = featureCount, total = featureCount + 3;
    HouseholderSteps q;
    for (int k = 0; k < M; ++k) {
        float* v = columns + long(k) * rows;
        float below = 0.0f;
        dotGroup(v, v, 1, rows, k + 1, &below);
        const float vtv = q.reflect(columns, k, total, rows, below);
        if (q.dead[k]) continue;
        for (int j = k + 1; j < total; j += kGroup) {
            const int count = total - j < kGroup ? total - j : kGroup;
            float* a = columns + long(j) * rows;
            float f[kGroup];
            dotGroup(v, a, count, rows, k, f);
            for (int g = 0; g < count; ++g) f[g] = 2.0f * f[g] / vtv;
            axpyGroup(v, a, count, rows, k, f);
            for (int g = 0; g < count; ++g) q.R[k][j + g] = a[long(g) * rows + k];
        }
    }

    return q.solve(M, coeffs);
}

} // namespace bmfr::cpu
