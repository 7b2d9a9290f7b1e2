// SVGF's normal weight for a vector of pixels, shared by the CPU backend's a-trous levels and
// its variance estimate.
#pragma once
#include "backend/cpu/simd.h"
#include <bmfr/filters/svgf_filter.h>

namespace bmfr::cpu {

/// Whether the vector passes run these settings: an integer normal exponent (repeated squaring,
/// as the reference's normalWeight); others take the reference's stages.
inline bool cpuNormalPowerSupports(const SvgfSettings& s) {
    return float(int(s.phiNormal)) == s.phiNormal;
}

/// max(0, c)^e by repeated squaring, as the reference's normalWeight; kExponent > 0 fixes e at
/// compile time (the default 128 is seven squarings in a row), 0 reads it from `e`.
template <int kExponent, class V> BMFR_SIMD_INLINE V normalPower(V c, int e) {
    V base = simd::maxOf(V{}, c), result = simd::splat<V>(1.0f);
    if constexpr (kExponent > 0) e = kExponent;
    for (; e > 0; e >>= 1, base *= base)
        if (e & 1) result *= base;
    return result;
}

/// 128 log2(1 - x), with x = 1 - c, for the default normal exponent as an exponential's
/// argument: the series of ln(1 - x) to x^2. Where the weight matters (x < 0.06, c^128 above
/// 4e-4) its relative error is below 0.94%, and below 0.054% where c^128 exceeds 0.05; from
/// x = 1 on (c <= 0, no sample) the argument is below -277, a weight below 2^-126
/// (exp2NonPositiveRows' floor) where the reference's is 0.
template <class V> BMFR_SIMD_INLINE V normalLog2Power128(V x) {
    constexpr float k = -128.0f / 0.693147180559945f;
    return x * (k + x * (k / 2));
}

} // namespace bmfr::cpu
