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

} // namespace bmfr
