// The row kernel of TAA, shared by BMFR's fused resolve pass and the standalone TAA pass.
#pragma once
#include "core/reprojection.h"
#include "core/simd.h"

namespace bmfr::cpu {

/// A resolved row: 8 floats per pixel, RGB + 0 then the same colour in YCoCg + 0.
BMFR_SIMD_INLINE void storeResolved(float* record, simd::f4 rgb) {
    simd::store4(record, rgb);
    simd::store4(record + 4, simd::rgbToYCoCg4(rgb));
}

/// TAA of image row y (Karis 2014, the authors' variant): clamp box = mean of the 3x3 box and
/// 5-tap cross bounds in YCoCg; bilinear history at previousPixel, renormalised at the border.
/// up/mid/down are resolved rows y-1, y, y+1; where a row or column lies outside the image the
/// nearest inside one stands in, which leaves every min and max unchanged. `history` is the
/// previous output (3 floats per pixel, readable 4 floats past its end); `out` gets 3 floats
/// per pixel. With enabled = false the row is copied.
BMFR_SIMD_INLINE void taaRow(const float* up, const float* mid, const float* down,
                             const float* history, const float* previousPixel, float* out, int w,
                             int h, float alpha, bool enabled) {
    using namespace simd;
    for (int x = 0; x < w; ++x) {
        const f4 c = load4(mid + 8 * x);
        float* o = out + 3 * x;
        BilinearFootprint fp;
        if (enabled) fp = bilinearFootprint({previousPixel[2 * x], previousPixel[2 * x + 1]});
        if (!enabled || fp.x0 < -1 || fp.y0 < -1 || fp.x0 >= w || fp.y0 >= h) {
            o[0] = c[0], o[1] = c[1], o[2] = c[2];
            continue;
        }
        const int xl = 8 * (x > 0 ? x - 1 : x) + 4, xc = 8 * x + 4,
                  xr = 8 * (x + 1 < w ? x + 1 : x) + 4;
        const f4 centre = load4(mid + xc), left = load4(mid + xl), right = load4(mid + xr);
        const f4 top = load4(up + xc), bottom = load4(down + xc);
        const f4 crossLo = min4(min4(min4(centre, left), min4(right, top)), bottom);
        const f4 crossHi = max4(max4(max4(centre, left), max4(right, top)), bottom);
        const f4 c0 = load4(up + xl), c1 = load4(up + xr), c2 = load4(down + xl),
                 c3 = load4(down + xr);
        const f4 boxLo = min4(crossLo, min4(min4(c0, c1), min4(c2, c3)));
        const f4 boxHi = max4(crossHi, max4(max4(c0, c1), max4(c2, c3)));

        const TapSet taps = tapSet(fp, w, h);
        f4 old{};
        float total = 0.0f;
        for (int t = 0; t < 4; ++t) {
            const float wt = taps.inside[t] ? fp.weight[t] : 0.0f; // zero adds exactly nothing
            old += wt * load4(history + 3 * taps.index[t]);
            total += wt;
        }
        if (total > 0.0f) old = old / total;
        const f4 lo = 0.5f * (boxLo + crossLo), hi = 0.5f * (boxHi + crossHi);
        const f4 clamped = yCoCgToRgb4(min4(max4(rgbToYCoCg4(old), lo), hi));
        const f4 r = lerp4(clamped, c, alpha);
        o[0] = r[0], o[1] = r[1], o[2] = r[2];
    }
}

} // namespace bmfr::cpu
