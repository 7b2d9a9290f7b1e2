// The BMFR fitting core: least squares by Householder QR of the augmented matrix [T+N, z_rgb]
// (paper section 4.2). The steps are BMFR_HD; solveHouseholder is the plain column-by-column
// solver the reference backend uses, the CPU backend's is backend/cpu/bmfr/cpu_householder.cpp.
#pragma once
#include "core/host_device.h"
#include <bmfr/features.h>
#include <cmath>

namespace bmfr {

/// Solves min ||A a_c - z_c|| for the three colour channels c at once.
/// `columns` holds M feature columns then 3 colour columns, each `rows` floats, column-major
/// with stride `rows`; it is overwritten (only R is formed, never Q; one R for three channels).
/// Writes M x 3 coefficients to `coeffs` (coeffs[m*3 + c]). A column whose remaining norm is
/// negligible (rank deficiency the regularisation did not cure) gets coefficient 0, so the
/// result is always finite for finite input. Returns the number of such columns.
int solveHouseholder(float* columns, int featureCount, int rows, float* coeffs);
/// The same compiled for AVX2 (eight-wide dot products: other roundings); the reference backend
/// takes it where the CPU path (BMFR_CPU_ISA) allows AVX2.
int solveHouseholderAvx2(float* columns, int featureCount, int rows, float* coeffs);

/// What the Householder solvers share: R of the augmented QR (M rows of M feature entries then
/// 3 colour entries), the dependent-column decisions, and back substitution. Each solver brings
/// its own dot products and updates; this part makes them agree on rank-deficient blocks.
struct HouseholderSteps {
    float R[kMaxFeatures][kMaxFeatures + 3];
    bool dead[kMaxFeatures] = {};
    float largestNorm = 0.0f;
    int deficient = 0;

    /// Turns column k (`columns`, `stride` floats apart) into step k's reflector v, given below =
    /// the sum of v[i]^2 for i > k, and records R[k][k]. Returns v.v; marks dead[k] instead when
    /// the column is dependent: its remaining norm is negligible next to the largest seen (without
    /// regularisation a dependent column leaves only rounding error), so it gets coefficient 0.
    BMFR_HD float reflect(float* columns, int k, int total, long stride, float below) {
        float* v = columns + long(k) * stride;
        const float norm = std::sqrt(v[k] * v[k] + below);
        largestNorm = std::fmax(largestNorm, norm);
        if (!(norm > 1e-5f * largestNorm) || !(norm > 1e-30f)) {
            dead[k] = true;
            ++deficient;
            for (int j = k; j < total; ++j) R[k][j] = j == k ? 0.0f : columns[long(j) * stride + k];
            return 0.0f;
        }
        // Sign choice avoids cancellation in v_k = x_k - alpha.
        const float alpha = v[k] > 0 ? -norm : norm;
        v[k] -= alpha;
        R[k][k] = alpha;
        return v[k] * v[k] + below;
    }

    /// Back substitution for the three channels into coeffs[m*3 + c]; returns the number of
    /// dependent columns. The channels advance together: three independent chains of
    /// multiply-adds and divisions instead of one three times as long (each channel's sums are
    /// formed in the same order either way).
    BMFR_HD int solve(int M, float* coeffs) const {
        for (int k = M - 1; k >= 0; --k) {
            if (dead[k]) {
                for (int c = 0; c < 3; ++c) coeffs[k * 3 + c] = 0.0f;
                continue;
            }
            float s[3] = {R[k][M], R[k][M + 1], R[k][M + 2]};
            for (int j = k + 1; j < M; ++j)
                for (int c = 0; c < 3; ++c) s[c] -= R[k][j] * coeffs[j * 3 + c];
            for (int c = 0; c < 3; ++c) coeffs[k * 3 + c] = s[c] / R[k][k];
        }
        return deficient;
    }
};

} // namespace bmfr
