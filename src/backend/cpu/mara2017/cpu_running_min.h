// Van Herk / Gil-Werman running minimum: the min over a window of 2r + 1 in three comparisons
// per value, whatever r (the CPU backend's Mara stage 5).
#pragma once
#include "backend/cpu/simd.h"
#include <cmath>
#include <type_traits>

namespace bmfr::cpu {

/// std::fmin as x86-64's libm computes it (a NaN gives the other value; otherwise a < b ? a :
/// b, minss), inline: the library call was a third of stage 5. Of eight lanes too.
inline float fminInline(float a, float b) {
    return b != b ? a : (a < b ? a : b);
}
BMFR_SIMD_INLINE simd::f8 fminInline(simd::f8 a, simd::f8 b) {
    return (b != b) | (a < b) ? a : b;
}

/// out[k * outStride] = min of in over [k - r, k + r] inside [0, n), for k in [0, n); `g` and
/// `h` hold n + 2r + (2r + 1) values each. T = f8 takes eight neighbouring columns at once
/// (in and out are then eight consecutive floats per k), each lane as T = float would.
template <class T>
BMFR_SIMD_INLINE void runningMin(const float* in, long inStride, int n, int r, float* out,
                                 long outStride, T* g, T* h) {
    constexpr bool kEight = std::is_same_v<T, simd::f8>;
    const int window = 2 * r + 1;
    const int padded = n + 2 * r;
    const int blocks = (padded + window - 1) / window;
    const int total = blocks * window;
    auto value = [&] [[gnu::always_inline]] (int j) {
        const bool inside = j >= r && j < r + n;
        if constexpr (kEight)
            return inside ? simd::load8(in + long(j - r) * inStride) : simd::splat8(INFINITY);
        else
            return inside ? in[long(j - r) * inStride] : INFINITY;
    };
    for (int b = 0; b < total; b += window) {
        g[b] = value(b);
        for (int j = b + 1; j < b + window; ++j) g[j] = fminInline(g[j - 1], value(j));
        h[b + window - 1] = value(b + window - 1);
        for (int j = b + window - 2; j >= b; --j) h[j] = fminInline(h[j + 1], value(j));
    }
    // Window [k, k + 2r] in padded coordinates: the suffix min of its first block and the
    // prefix min of its last (the same block when k starts one).
    for (int k = 0; k < n; ++k) {
        const T m = fminInline(h[k], g[k + 2 * r]);
        if constexpr (kEight)
            simd::store8(out + long(k) * outStride, m);
        else
            out[long(k) * outStride] = m;
    }
}

} // namespace bmfr::cpu
