// Van Herk / Gil-Werman running minimum: the min over a window of 2r + 1 in three comparisons
// per value, whatever r (the CPU backend's Mara stage 5).
#pragma once
#include <cmath>

namespace bmfr::cpu {

/// std::fmin as x86-64's libm computes it (a NaN gives the other value; otherwise a < b ? a :
/// b, minss), inline: the library call was a third of stage 5.
inline float fminInline(float a, float b) {
    return b != b ? a : (a < b ? a : b);
}

/// out[k * outStride] = min of in over [k - r, k + r] inside [0, n), for k in [0, n); `g` and
/// `h` hold n + 2r + (2r + 1) floats each.
inline void runningMin(const float* in, long inStride, int n, int r, float* out, long outStride,
                       float* g, float* h) {
    const int window = 2 * r + 1;
    const int padded = n + 2 * r;
    const int blocks = (padded + window - 1) / window;
    const int total = blocks * window;
    auto value = [&](int j) { return j >= r && j < r + n ? in[long(j - r) * inStride] : INFINITY; };
    for (int b = 0; b < total; b += window) {
        g[b] = value(b);
        for (int j = b + 1; j < b + window; ++j) g[j] = fminInline(g[j - 1], value(j));
        h[b + window - 1] = value(b + window - 1);
        for (int j = b + window - 2; j >= b; --j) h[j] = fminInline(h[j + 1], value(j));
    }
    // Window [k, k + 2r] in padded coordinates: the suffix min of its first block and the
    // prefix min of its last (the same block when k starts one).
    for (int k = 0; k < n; ++k) out[long(k) * outStride] = fminInline(h[k], g[k + 2 * r]);
}

} // namespace bmfr::cpu
