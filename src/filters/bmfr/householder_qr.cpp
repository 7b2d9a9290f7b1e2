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

// Compiled for AVX2 and baseline, chosen at run time: the dot and axpy loops double in width.
// Internal linkage: GCC would give an external clone's resolver default visibility.
__attribute__((target_clones("avx2", "default"))) int
solveHouseholderClones(float* columns, int featureCount, int rows, float* coeffs) {
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
    return solveHouseholderClones(columns, featureCount, rows, coeffs);
}

} // namespace bmfr
