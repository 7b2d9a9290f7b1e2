// The BMFR fitting core: least squares by Householder QR of the augmented matrix [T+N, z_rgb].
#pragma once
#include <bmfr/features.h>

namespace bmfr {

/// Solves min ||A a_c - z_c|| for the three colour channels c at once.
/// `columns` holds M feature columns then 3 colour columns, each `rows` floats, column-major
/// with stride `rows`; it is overwritten (only R is formed, never Q; one R for three channels).
/// Writes M x 3 coefficients to `coeffs` (coeffs[m*3 + c]). A column whose remaining norm is
/// negligible (rank deficiency the regularisation did not cure) gets coefficient 0, so the
/// result is always finite for finite input. Returns the number of such columns.
int solveHouseholder(float* columns, int featureCount, int rows, float* coeffs);

/// R of the augmented QR: M rows of M feature entries then 3 colour entries.
using TriangularR = float[kMaxFeatures][kMaxFeatures + 3];

/// Row k of R for a column judged dependent: its entries are kept as they stand, its pivot is 0.
inline void dropColumn(TriangularR& R, const float* columns, int k, int total, int rows) {
    for (int j = k; j < total; ++j) R[k][j] = j == k ? 0.0f : columns[long(j) * rows + k];
}

/// Back substitution of R a_c = (colour part of R) for the three channels; dependent columns
/// get coefficient 0. Shared by every solver so they agree on rank-deficient blocks.
inline void backSubstitute(const TriangularR& R, const bool* dead, int M, float* coeffs) {
    for (int c = 0; c < 3; ++c) {
        for (int k = M - 1; k >= 0; --k) {
            if (dead[k]) {
                coeffs[k * 3 + c] = 0.0f;
                continue;
            }
            float s = R[k][M + c];
            for (int j = k + 1; j < M; ++j) s -= R[k][j] * coeffs[j * 3 + c];
            coeffs[k * 3 + c] = s / R[k][k];
        }
    }
}

} // namespace bmfr
