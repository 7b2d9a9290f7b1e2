#include "backend/cpu/bmfr/cpu_bmfr_buffers.h"
#include "backend/cpu/simd.h"
#include "filters/bmfr/householder_qr.h"
#include <algorithm>
#include <cmath>
#include <cstring>
#include <type_traits>

namespace bmfr::cpu {

using namespace simd;

namespace {

constexpr int kGroup = 4; // columns per sweep: four accumulators plus v stay in registers

/// The sweeps work on V, eight floats (f8) or, on the AVX-512 path, sixteen (f32x16).
/// Sum of the lanes as a fixed tree (repeatable): halves added until eight remain, then hsum8.
template <class V> BMFR_SIMD_INLINE float hsumV(V v) {
    if constexpr (kLanesOf<V> == 8) {
        return hsum8(v);
    } else {
        f8 lo, hi;
        std::memcpy(&lo, &v, sizeof lo);
        std::memcpy(&hi, reinterpret_cast<const char*>(&v) + sizeof lo, sizeof hi);
        return hsum8(lo + hi);
    }
}

/// The first row at or after `row` where whole vectors start.
template <class V> BMFR_SIMD_INLINE int alignedRow(int row, int rows) {
    return std::min((row + kLanesOf<V> - 1) & ~(kLanesOf<V> - 1), rows);
}

/// The row index of each lane of the vector that starts at row i.
template <class V> BMFR_SIMD_INLINE V rowsFrom(int i) {
    V v;
    for (int l = 0; l < kLanesOf<V>; ++l) v[l] = float(i + l);
    return v;
}

/// Whether the sweeps run their head rows as masked vectors: rows is a whole number of vectors
/// (every block, whose W is a multiple of 64). Else the rows before the first whole vector, up
/// to fifteen per column on the AVX-512 path and a large share of a small block's, go one by one.
template <class V> BMFR_SIMD_INLINE bool vectorHead(int rows) {
    return rows % kLanesOf<V> == 0;
}

/// d[g] = v . a_g over rows [begin, rows) for `count` columns a_g, `stride` floats apart.
template <class V, int count>
BMFR_SIMD_INLINE void dotGroupOf(const float* v, const float* a, int rows, long stride, int begin,
                                 float* d) {
    constexpr int L = kLanesOf<V>;
    V acc[kGroup] = {};
    if (vectorHead<V>(rows)) {
        // The vector holding row `begin` with the rows before it masked out, then whole ones.
        const int first = begin & ~(L - 1);
        for (int i = first; i < rows; i += L) {
            V x = loadVector<V>(v + i);
            if (i == first) x = rowsFrom<V>(i) >= float(begin) ? x : V{};
            for (int g = 0; g < count; ++g) acc[g] += x * loadVector<V>(a + long(g) * stride + i);
        }
        for (int g = 0; g < count; ++g) d[g] = hsumV(acc[g]);
        return;
    }
    const int body = alignedRow<V>(begin, rows), tail = body + (rows - body) / L * L;
    float head[count] = {};
    for (int i = begin; i < body; ++i)
        for (int g = 0; g < count; ++g) head[g] += v[i] * a[long(g) * stride + i];
    for (int i = tail; i < rows; ++i)
        for (int g = 0; g < count; ++g) head[g] += v[i] * a[long(g) * stride + i];
    for (int i = body; i < tail; i += L) {
        const V x = loadVector<V>(v + i);
        for (int g = 0; g < count; ++g) acc[g] += x * loadVector<V>(a + long(g) * stride + i);
    }
    for (int g = 0; g < count; ++g) d[g] = head[g] + hsumV(acc[g]);
}

template <class V>
BMFR_SIMD_INLINE void dotGroup(const float* v, const float* a, int count, int rows, long stride,
                               int begin, float* d) {
    switch (count) {
    case 1:
        return dotGroupOf<V, 1>(v, a, rows, stride, begin, d);
    case 2:
        return dotGroupOf<V, 2>(v, a, rows, stride, begin, d);
    case 3:
        return dotGroupOf<V, 3>(v, a, rows, stride, begin, d);
    default:
        return dotGroupOf<V, kGroup>(v, a, rows, stride, begin, d);
    }
}

/// One sweep over `count` columns a_g (`stride` floats apart) from row k: a_g -= f[g] v. With
/// `next` (column k + 1, the next step's reflector) it also forms the next step's dot products
/// in the same sweep: d[g] = next . a_g over rows > k, after the update. When a_0 is `next`
/// itself, d[0] is instead the next step's sum of squares below its diagonal (rows > k + 1).
template <class V, int count, bool look, bool self>
BMFR_SIMD_INLINE void updateGroupOf(const float* v, float* a, int rows, long stride, int k,
                                    const float* f, const float* next, float* d) {
    constexpr int L = kLanesOf<V>;
    V fs[count], acc[count] = {};
    for (int g = 0; g < count; ++g) fs[g] = splat<V>(f[g]);
    // Rows [i, i + L): update from row k, dot products from row k + 1 (k + 2 for the next
    // reflector's own sum of squares), the rows before them masked out in the vectors holding
    // them.
    auto sweep = [&](int i, auto masked) {
        const V x = loadVector<V>(v + i);
        V col[count];
        for (int g = 0; g < count; ++g) {
            float* p = a + long(g) * stride + i;
            const V old = loadVector<V>(p);
            col[g] = old - fs[g] * x;
            if constexpr (masked) col[g] = rowsFrom<V>(i) >= float(k) ? col[g] : old;
            storeVector(p, col[g]);
        }
        if constexpr (!look) return;
        const V u = self ? col[0] : loadVector<V>(next + i);
        for (int g = 0; g < count; ++g) {
            V term = u * col[g];
            if constexpr (masked) {
                const int from = self && g == 0 ? k + 2 : k + 1;
                term = rowsFrom<V>(i) >= float(from) ? term : V{};
            }
            acc[g] += term;
        }
    };
    if (vectorHead<V>(rows)) {
        const int first = k & ~(L - 1), body = std::min((k + 2 + L - 1) & ~(L - 1), rows);
        for (int i = first; i < body; i += L) sweep(i, std::true_type{});
        for (int i = body; i < rows; i += L) sweep(i, std::false_type{});
        if (look)
            for (int g = 0; g < count; ++g) d[g] = hsumV(acc[g]);
        return;
    }
    const int body = alignedRow<V>(k + 2, rows), tail = body + (rows - body) / L * L;
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
    for (int i = body; i < tail; i += L) sweep(i, std::false_type{});
    if (look)
        for (int g = 0; g < count; ++g) d[g] = head[g] + hsumV(acc[g]) + rest[g];
}

template <class V, int count>
BMFR_SIMD_INLINE void updateGroupOf(const float* v, float* a, int rows, long stride, int k,
                                    const float* f, const float* next, float* d) {
    if (!next) return updateGroupOf<V, count, false, false>(v, a, rows, stride, k, f, next, d);
    if (next == a) return updateGroupOf<V, count, true, true>(v, a, rows, stride, k, f, next, d);
    updateGroupOf<V, count, true, false>(v, a, rows, stride, k, f, next, d);
}

template <class V>
BMFR_SIMD_INLINE void updateGroup(const float* v, float* a, int count, int rows, long stride, int k,
                                  const float* f, const float* next, float* d) {
    switch (count) {
    case 1:
        return updateGroupOf<V, 1>(v, a, rows, stride, k, f, next, d);
    case 2:
        return updateGroupOf<V, 2>(v, a, rows, stride, k, f, next, d);
    case 3:
        return updateGroupOf<V, 3>(v, a, rows, stride, k, f, next, d);
    default:
        return updateGroupOf<V, kGroup>(v, a, rows, stride, k, f, next, d);
    }
}

// The AVX-512 path sweeps sixteen rows at a time, the others eight.
BMFR_SIMD_DISPATCH(int, solveHouseholderPaths,
                   (float* columns, int featureCount, int rows, long stride, float* coeffs),
                   (columns, featureCount, rows, stride, coeffs)) {
    using V = std::conditional_t<kIsa == Isa::Avx512, f32x16, f8>;
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
        if (!fromAhead) dotGroup<V>(v, v, 1, rows, stride, k + 1, &below);
        const float vtv = q.reflect(columns, k, total, stride, below);
        if (q.dead[k]) continue;
        if (fromAhead) {
            // v differs from column k only in row k, by -R[k][k].
            for (int j = k + 1; j < total; ++j) dots[j] = ahead[j] - q.R[k][k] * column(j)[k];
        } else {
            for (int j = k + 1; j < total; j += kGroup)
                dotGroup<V>(v, column(j), std::min(kGroup, total - j), rows, stride, k, dots + j);
        }
        for (int j = k + 1; j < total; ++j) f[j] = 2.0f * dots[j] / vtv;
        const float* next = k + 1 < M ? column(k + 1) : nullptr;
        for (int j = k + 1; j < total; j += kGroup)
            updateGroup<V>(v, column(j), std::min(kGroup, total - j), rows, stride, k, f + j, next,
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
