// 16-bit float storage of history (the BMFR authors' USE_HALF_PRECISION_IN_TMP_DATA): the one
// rounding every backend applies where a history plane is stored as half.
#pragma once
#include "core/host_device.h"
#include "core/vec.h"
#include <cstdint>
#if defined(__CUDACC__)
#include <cuda_fp16.h>
#else
#include <bit>
#endif

namespace bmfr {

/// The largest finite half. Larger values are stored as this, not as infinity: a demodulated
/// emitter (radiance over a tiny albedo) can exceed it, and an infinite history never recovers.
inline constexpr float kHalfMax = 65504.0f;

/// x saturated to [-kHalfMax, kHalfMax] and rounded to the nearest half (ties to even), as a
/// float: what a half plane gives back for x.
BMFR_HD float roundToHalf(float x) {
    x = x < -kHalfMax ? -kHalfMax : (x > kHalfMax ? kHalfMax : x);
#if defined(__CUDACC__)
    return __half2float(__float2half_rn(x));
#elif defined(__FLT16_MAX__)
    return float(_Float16(x));
#else
    // Compilers without _Float16: the half's bits by integer arithmetic (as the CPU backend's
    // store8), then back. x is finite and at most kHalfMax here.
    uint32_t u = std::bit_cast<uint32_t>(x);
    const uint32_t sign = u & 0x80000000u;
    u ^= sign;
    uint32_t h;
    if (u < (113u << 23)) {
        h = std::bit_cast<uint32_t>(std::bit_cast<float>(u) + 0.5f) - 0x3f000000u;
    } else {
        h = (u + 0xC8000FFFu + ((u >> 13) & 1u)) >> 13;
    }
    const uint32_t magnitude =
        std::bit_cast<uint32_t>(std::bit_cast<float>((h & 0x7fffu) << 13) * 0x1p112f);
    return std::bit_cast<float>(magnitude | sign);
#endif
}

/// roundToHalf of each component.
BMFR_HD Vec3 roundToHalf(Vec3 v) {
    return {roundToHalf(v.x), roundToHalf(v.y), roundToHalf(v.z)};
}

#if !defined(__CUDACC__)
/// The value of an IEEE half given by its bits (host code: images handed over as half).
inline float halfBitsToFloat(uint16_t bits) {
    const uint32_t sign = uint32_t(bits & 0x8000u) << 16;
    const uint32_t exponent = (bits >> 10) & 0x1fu;
    const uint32_t mantissa = bits & 0x3ffu;
    if (exponent == 0) { // zero or subnormal: mantissa * 2^-24, exact in float
        const float v = float(mantissa) * 0x1p-24f;
        return sign ? -v : v;
    }
    if (exponent == 31) return std::bit_cast<float>(sign | 0x7f800000u | (mantissa << 13));
    return std::bit_cast<float>(sign | ((exponent + 112u) << 23) | (mantissa << 13));
}

/// The bits of roundToHalf(x) (saturated, ties to even): what a half image written with x holds.
inline uint16_t floatToHalfBits(float x) {
    const uint32_t u = std::bit_cast<uint32_t>(roundToHalf(x));
    const uint16_t sign = uint16_t((u >> 16) & 0x8000u);
    if (((u >> 23) & 0xffu) == 0xffu) return uint16_t(sign | 0x7e00u); // NaN stays NaN
    const float magnitude = std::bit_cast<float>(u & 0x7fffffffu);
    if (magnitude < 0x1p-14f) return uint16_t(sign | uint16_t(magnitude * 0x1p24f)); // subnormal
    const uint32_t exponent = ((u >> 23) & 0xffu) - 112u;
    return uint16_t(sign | (exponent << 10) | ((u >> 13) & 0x3ffu));
}
#endif

/// A history value stored in 16 bits (IEEE half): what a plane of Half holds under
/// BmfrSettings::halfHistory on a backend that keeps the bytes it moves (CUDA). Stored from x it
/// holds roundToHalf(x), so a kernel reads back the float that a float plane holding
/// roundToHalf(x) gives: one kernel, either storage, the same bits.
struct Half {
    uint16_t bits;
    BMFR_HD explicit Half(float x) {
        x = x < -kHalfMax ? -kHalfMax : (x > kHalfMax ? kHalfMax : x);
#if defined(__CUDACC__)
        bits = __half_as_ushort(__float2half_rn(x));
#else
        bits = floatToHalfBits(x);
#endif
    }
    Half() = default;
    BMFR_HD operator float() const {
#if defined(__CUDACC__)
        return __half2float(__ushort_as_half(bits));
#else
        return halfBitsToFloat(bits);
#endif
    }
};

BMFR_HD Vec3 load3(const Half* p, long i) {
    return {float(p[3 * i]), float(p[3 * i + 1]), float(p[3 * i + 2])};
}
BMFR_HD void store3(Half* p, long i, Vec3 v) {
    p[3 * i] = Half(v.x);
    p[3 * i + 1] = Half(v.y);
    p[3 * i + 2] = Half(v.z);
}

} // namespace bmfr
