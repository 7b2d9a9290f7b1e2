// The row kernel of TAA, shared by BMFR's fused resolve pass and the standalone TAA pass.
#pragma once
#include "backend/cpu/reproject8.h"
#include "backend/cpu/simd.h"
#include "core/color.h"
#include "temporal/taa.h"
#include <cstddef>

namespace bmfr::cpu {

/// A resolved row: six planes (R, G, B, then Y, Co, Cg) of `pitch` floats each, pixel x of
/// plane c at row[c * pitch + kRowPad + x]. The pads hold the edge pixel's YCoCg at x = -1 and
/// x = width (so the 3x3 clamp box needs no border test) and room for whole 8-pixel groups.
struct ResolvedRows {
    static constexpr int kRowPad = 8;
    static constexpr int kPlanes = 6;
    /// Floats between planes for rows `width` pixels wide.
    static size_t pitch(int width) { return size_t((width + 7) / 8 * 8 + 2 * kRowPad); }
    /// Floats of one resolved row.
    static size_t rowFloats(int width) { return kPlanes * pitch(width); }
};

/// taaSpace (encode) or taaOutput (temporal/taa.h) of eight pixels in `space`: gammaEncode or
/// gammaDecode lane by lane, compressRange or expandRange eight wide.
BMFR_SIMD_INLINE void spaceLanes8(simd::f8 v[3], TaaSpace space, bool encode) {
    using namespace simd;
    if (space == TaaSpace::Compressed) {
        f8 m = v[0] > v[1] ? v[0] : v[1];
        m = m > v[2] ? m : v[2];
        m = m > 0.0f ? m : 0.0f;
        f8 d = encode ? 1.0f + m : 1.0f - m;
        if (!encode) d = d > 1.0f / 65536.0f ? d : 1.0f / 65536.0f;
        for (int c = 0; c < 3; ++c) v[c] = v[c] / d;
        return;
    }
    if (space != TaaSpace::Display) return;
    alignas(32) float t[8];
    for (int c = 0; c < 3; ++c) {
        store8(t, v[c]);
        for (float& x : t) x = encode ? gammaEncode(x) : gammaDecode(x);
        v[c] = load8(t);
    }
}

/// Writes eight pixels' RGB and YCoCg at x (all eight lanes; the row has room for them), in
/// TAA's space.
BMFR_SIMD_INLINE void storeResolved8(float* row, size_t pitch, int x, const simd::f8 linear[3],
                                     TaaSpace space) {
    using namespace simd;
    f8 rgb[3] = {linear[0], linear[1], linear[2]}, ycocg[3];
    spaceLanes8(rgb, space, true);
    rgbToYCoCg8(rgb, ycocg);
    float* p = row + ResolvedRows::kRowPad + x;
    for (int c = 0; c < 3; ++c)
        store8(p + c * pitch, rgb[c]), store8(p + (3 + c) * pitch, ycocg[c]);
}

/// Fills the pads at x = -1 and x = width once a row is complete.
BMFR_SIMD_INLINE void finishResolvedRow(float* row, size_t pitch, int width) {
    for (int c = 3; c < 6; ++c) {
        float* p = row + c * pitch + ResolvedRows::kRowPad;
        p[-1] = p[0], p[width] = p[width - 1];
    }
}

/// Rows per task of a banded TAA pass (ringRows): each band resolves its halo rows again.
inline constexpr long kRingRowsPerTask = 32;

/// Rows [y0, y1) of an image h rows high through a ring of three resolved rows (`ring` holds
/// 3 ResolvedRows::rowFloats(w) floats): resolve(y, row) fills image row y's resolved row a
/// row ahead of taa(y, up, mid, down), which gets rows y - 1, y and y + 1 (the nearest inside
/// one past the image's edge). With `halo` the rows either side of the band are resolved too
/// (a neighbouring band makes them again, not shared); without, only the band's own rows, and
/// `up` at the band's first row is stale (for a TAA that only copies). Callers inside a
/// BMFR_SIMD_DISPATCH body pass [[gnu::always_inline]] lambdas: a lambda does not inherit the
/// body's target, so one compiled out of line would run the baseline instructions.
template <class Resolve, class Taa>
BMFR_SIMD_INLINE void ringRows(float* ring, int w, long h, long y0, long y1, bool halo,
                               Resolve&& resolve, Taa&& taa) {
    auto row = [&] [[gnu::always_inline]] (long y) {
        return ring + size_t(y % 3) * ResolvedRows::rowFloats(w);
    };
    long next = halo && y0 > 0 ? y0 - 1 : y0;
    for (long y = y0; y < y1; ++y) {
        const long last = y + 1 < h && (halo || y + 1 < y1) ? y + 1 : y;
        for (; next <= last; ++next) resolve(next, row(next));
        const float* mid = row(y);
        taa(y, y > 0 ? row(y - 1) : mid, mid, y + 1 < h ? row(y + 1) : mid);
    }
}

/// taaCurrentWeight(blend, bilinearBlur(weight)) (temporal/taa.h) of eight pixels.
BMFR_SIMD_INLINE simd::f8 currentWeight8(TaaBlend blend, const simd::f8 weight[4]) {
    using namespace simd;
    if (!(blend.blurLimit > 0.0f)) return splat8(blend.alpha);
    const f8 ax = weight[1] + weight[3], ay = weight[2] + weight[3];
    const float lo = kTaaStillFraction, hi = 1.0f - kTaaStillFraction;
    const f8 bx = (ax < lo) | (ax > hi) ? 0.0f : ax * (1 - ax);
    const f8 by = (ay < lo) | (ay > hi) ? 0.0f : ay * (1 - ay);
    const f8 blur = bx + by;
    const f8 a = blur / (blur + blend.blurLimit);
    return a > blend.alpha ? a : splat8(blend.alpha);
}

/// TAA of image row y (Karis 2014, the authors' variant), eight pixels at a time: clamp box =
/// mean of the 3x3 box and 5-tap cross bounds in YCoCg; bilinear history at (previousX,
/// previousY), renormalised at the border. up/mid/down are resolved rows y-1, y, y+1; where a
/// row lies outside the image the nearest inside one stands in, which leaves every min and max
/// unchanged. `history` is the previous output (3 floats per pixel); `out` gets 3 floats per
/// pixel. With enabled = false the row is copied. `accept` (the row's accept masks, or null)
/// restricts the history to the accepted taps, as TaaInputs::accept. The rows hold values in
/// `space` (storeResolved8), the history is encoded into it and the output decoded. The
/// current frame's weight is taaCurrentWeight (temporal/taa.h) of `blend`.
BMFR_SIMD_INLINE void taaRow(const float* up, const float* mid, const float* down, size_t pitch,
                             const float* previousX, const float* previousY, const float* history,
                             float* out, int w, int h, TaaBlend blend, bool enabled,
                             const uint8_t* accept, TaaSpace space) {
    using namespace simd;
    const int pad = ResolvedRows::kRowPad;
    for (int x = 0; x < w; x += 8) {
        const int n = w - x < 8 ? w - x : 8;
        f8 c[3];
        for (int ch = 0; ch < 3; ++ch) c[ch] = load8(mid + ch * pitch + pad + x);
        if (!enabled) {
            storeXyz8(out + 3 * x, n, c);
            continue;
        }
        const Footprint8 fp = footprint8(load8(previousX + x), load8(previousY + x));
        const i8 mask = accept ? loadBytes(accept + x, n) : i8{} + 15;
        const i8 use = (fp.x0 >= -1) & (fp.y0 >= -1) & (fp.x0 < w) & (fp.y0 < h) & (mask != 0);
        if (!anyLane(use & firstLanes(n))) {
            f8 r[3] = {c[0], c[1], c[2]};
            spaceLanes8(r, space, false);
            storeXyz8(out + 3 * x, n, r);
            continue;
        }
        f8 lo[3], hi[3];
        for (int ch = 0; ch < 3; ++ch) {
            const size_t o = (3 + ch) * pitch + pad + x;
            const f8 centre = load8(mid + o), left = load8(mid + o - 1), right = load8(mid + o + 1);
            const f8 top = load8(up + o), bottom = load8(down + o);
            const f8 crossLo = min8(min8(min8(centre, left), min8(right, top)), bottom);
            const f8 crossHi = max8(max8(max8(centre, left), max8(right, top)), bottom);
            const f8 c0 = load8(up + o - 1), c1 = load8(up + o + 1), c2 = load8(down + o - 1),
                     c3 = load8(down + o + 1);
            const f8 boxLo = min8(crossLo, min8(min8(c0, c1), min8(c2, c3)));
            const f8 boxHi = max8(crossHi, max8(max8(c0, c1), max8(c2, c3)));
            lo[ch] = 0.5f * (boxLo + crossLo), hi[ch] = 0.5f * (boxHi + crossHi);
        }
        const Taps8 taps = taps8(fp, w, h, use & firstLanes(n));
        const i8 tapUse[4] = {
            taps.inside[0] & ((mask & 1) != 0), taps.inside[1] & ((mask & 2) != 0),
            taps.inside[2] & ((mask & 4) != 0), taps.inside[3] & ((mask & 8) != 0)};
        f8 old[3];
        const f8 total = weightedTaps<3>(
            taps, fp.weight, tapUse,
            [&](int k, f8* v) {
                tapXyz(taps, history, k, v);
                spaceLanes8(v, space, true);
            },
            old);
        const i8 some = total > 0.0f;
        for (int ch = 0; ch < 3; ++ch) old[ch] = some ? old[ch] / total : old[ch];
        f8 y[3], clamped[3], r[3];
        rgbToYCoCg8(old, y);
        for (int ch = 0; ch < 3; ++ch) y[ch] = min8(max8(y[ch], lo[ch]), hi[ch]);
        yCoCgToRgb8(y, clamped);
        const f8 weight = currentWeight8(blend, fp.weight);
        for (int ch = 0; ch < 3; ++ch)
            r[ch] = (accept ? use & some : use) ? lerp8(clamped[ch], c[ch], weight) : c[ch];
        spaceLanes8(r, space, false);
        storeXyz8(out + 3 * x, n, r);
    }
}

} // namespace bmfr::cpu
