// 16-bit float storage of history (the BMFR authors' USE_HALF_PRECISION_IN_TMP_DATA): the one
// rounding every backend applies where a history plane is stored as half.
#pragma once
#include "core/host_device.h"
#include "core/vec.h"
#if defined(__CUDACC__)
#include <cuda_fp16.h>
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
#else
    return float(_Float16(x));
#endif
}

/// roundToHalf of each component.
BMFR_HD Vec3 roundToHalf(Vec3 v) {
    return {roundToHalf(v.x), roundToHalf(v.y), roundToHalf(v.z)};
}

} // namespace bmfr
