#include "filters/bmfr/householder_qr.h"
#include <cmath>

namespace bmfr {

namespace {

inline float dotFrom(const float* a, const float* b, int begin, int end) {
    float s = 0.0f;
#pragma omp simd reduction(+ : s)
    for (int i = begin; i < end; ++i) s += a[i] * b[i];
    return s;
}

inline void axpyFrom(float f, const float* v, float* a, int begin, int end) {
#pragma omp simd
    for (int i = begin; i < end; ++i) a[i] -= f * v[i];
}

// Compiled for AVX2 and baseline (solveHouseholder, solveHouseholderAvx2): the dot and axpy loops
// double in width.
template <int kWide>
[[gnu::always_inline]] inline int solveWith(float* columns, int featureCount, int rows,
                                            float* coeffs) {
    const int M = featureCount, total = featureCount + 3;
    HouseholderSteps q;
    for (int k = 0; k < M; ++k) {
        float* v = columns + long(k) * rows;
        const float vtv = q.reflect(columns, k, total, rows, dotFrom(v, v, k + 1, rows));
        if (q.dead[k]) continue;
        for (int j = k + 1; j < total; ++j) {
            float* a = columns + long(j) * rows;
            float f = 2.0f * dotFrom(v, a, k, rows) / vtv;
            axpyFrom(f, v, a, k, rows);
            q.R[k][j] = a[k];
        }
    }

    return q.solve(M, coeffs);
}

} // namespace

int solveHouseholder(float* columns, int featureCount, int rows, float* coeffs) {
    return solveWith<0>(columns, featureCount, rows, coeffs);
}

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
[[gnu::target("avx2")]] int solveHouseholderAvx2(float* columns, int featureCount, int rows,
                                                 float* coeffs) {
    return solveWith<1>(columns, featureCount, rows, coeffs);
}
#else
int solveHouseholderAvx2(float* columns, int featureCount, int rows, float* coeffs) {
    return solveHouseholder(columns, featureCount, rows, coeffs);
}
#endif

} // namespace bmfr
