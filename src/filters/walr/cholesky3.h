// WALR's solve (paper Algorithms 1 and 2): the 3x3 normal equations of features (1, u, v) as a
// Cholesky factorisation whose pivots are floored at epsilon, then forward and back substitution
// for three right-hand sides (RGB) at once. The floor makes the solve exact for
// XX + diag(delta), delta_i = max(0, eps_i - pivot_i): a ridge on flat directions only.
#pragma once
#include "core/host_device.h"
#include <cmath>

namespace bmfr {

/// Lower-triangular C with C C^T = XX (+ the floors), XX_00 = 1.
template <class T> struct Cholesky3 { T c00 = 1, c10 = 0, c20 = 0, c11 = 1, c21 = 0, c22 = 1; };

/// Factorises [[1, m01, m02], [m01, m11, m12], [m02, m12, m22]] with the pivots of the two
/// normal features floored at eps (the constant feature's pivot is 1).
template <class T> BMFR_HD Cholesky3<T> choleskyClamped(T m01, T m02, T m11, T m12, T m22, T eps) {
    Cholesky3<T> c;
    c.c00 = 1;
    c.c10 = m01;
    c.c20 = m02;
    T p1 = m11 - c.c10 * c.c10;
    c.c11 = std::sqrt(p1 > eps ? p1 : eps);
    c.c21 = (m12 - c.c20 * c.c10) / c.c11;
    T p2 = m22 - c.c20 * c.c20 - c.c21 * c.c21;
    c.c22 = std::sqrt(p2 > eps ? p2 : eps);
    return c;
}

/// beta = (C C^T)^-1 rhs for one right-hand side (forward then back substitution).
template <class T> BMFR_HD void choleskySolve(const Cholesky3<T>& c, const T rhs[3], T beta[3]) {
    const T f0 = rhs[0] / c.c00;
    const T f1 = (rhs[1] - c.c10 * f0) / c.c11;
    const T f2 = (rhs[2] - c.c20 * f0 - c.c21 * f1) / c.c22;
    beta[2] = f2 / c.c22;
    beta[1] = (f1 - c.c21 * beta[2]) / c.c11;
    beta[0] = (f0 - c.c10 * beta[1] - c.c20 * beta[2]) / c.c00;
}

} // namespace bmfr
