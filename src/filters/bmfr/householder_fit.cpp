#include "filters/bmfr/householder_fit.h"
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

} // namespace

// Compiled for AVX2 and baseline, chosen at run time: the dot and axpy loops double in width.
__attribute__((target_clones("avx2", "default"))) int
solveHouseholder(float* columns, int featureCount, int rows, float* coeffs) {
    const int M = featureCount, total = featureCount + 3;
    TriangularR R;
    bool dead[kMaxFeatures] = {};
    float largestNorm = 0.0f;
    int deficient = 0;

    for (int k = 0; k < M; ++k) {
        float* v = columns + long(k) * rows;
        float below = dotFrom(v, v, k + 1, rows);
        float norm = std::sqrt(v[k] * v[k] + below);
        largestNorm = std::fmax(largestNorm, norm);
        // Without regularisation a dependent column leaves only rounding error behind.
        if (!(norm > 1e-5f * largestNorm) || !(norm > 1e-30f)) {
            dead[k] = true;
            ++deficient;
            dropColumn(R, columns, k, total, rows);
            continue;
        }
        // Sign choice avoids cancellation in v_k = x_k - alpha.
        float alpha = v[k] > 0 ? -norm : norm;
        v[k] -= alpha;
        float vtv = v[k] * v[k] + below;
        R[k][k] = alpha;
        for (int j = k + 1; j < total; ++j) {
            float* a = columns + long(j) * rows;
            float f = 2.0f * dotFrom(v, a, k, rows) / vtv;
            axpyFrom(f, v, a, k, rows);
            R[k][j] = a[k];
        }
    }

    backSubstitute(R, dead, M, coeffs);
    return deficient;
}

} // namespace bmfr
