// Temporal anti-aliasing of a filter's output (Karis 2014, the BMFR authors' variant): the
// history sampled bilinearly where the surface was last frame, clamped to the current
// neighbourhood in YCoCg, blended with the current frame. Per pixel and BMFR_HD; the CPU
// backend's eight-wide version (backend/cpu/taa_rows.h) mirrors taaPixel.
#pragma once
#include "core/color.h"
#include "temporal/reprojection.h"
#include <bmfr/temporal_settings.h>

namespace bmfr {

/// How TAA weighs the current frame against the history.
struct TaaBlend {
    float alpha = 0.2f; ///< weight of the current frame (TemporalSettings::taaBlendAlpha)
    /// With a value above 0, the weight rises where resampling the history blurs it
    /// (TemporalSettings::taaMotionWeight, taaBlurLimit): px^2 of blur the history may gather.
    float blurLimit = 0.0f;
};

/// Fractions of a pixel within this of a whole pixel count as none in bilinearBlur: the
/// reprojection of a still camera lands that close to the pixel centres, not on them.
constexpr float kTaaStillFraction = 1.0f / 32.0f;

/// The blur one bilinear resampling adds to the history along one axis, px^2: the variance
/// a (1 - a) of its weights about the sampled point, for the fraction a; 0 within
/// kTaaStillFraction of a whole pixel.
BMFR_HD float axisBlur(float a) {
    const bool still = a < kTaaStillFraction || a > 1.0f - kTaaStillFraction;
    return still ? 0.0f : a * (1 - a);
}

/// The blur one bilinear resampling adds to the history, px^2: axisBlur of the fractions
/// ax = w1 + w3 and ay = w2 + w3 of the footprint's weights. 0 where the history moved by
/// whole pixels, 0.5 at half a pixel on both axes.
BMFR_HD float bilinearBlur(const float weight[4]) {
    return axisBlur(weight[1] + weight[3]) + axisBlur(weight[2] + weight[3]);
}

/// TAA's weight of the current frame where the history is resampled with blur `blur` (px^2).
/// An exponential history resampled with blur b at every frame, with weight (1 - a) for the
/// history, gathers (1 - a) b / a px^2 of blur; the weight keeps that at blurLimit, and never
/// falls below the blend's alpha.
BMFR_HD float taaCurrentWeight(const TaaBlend& blend, float blur) {
    if (!(blend.blurLimit > 0.0f)) return blend.alpha;
    const float a = blur / (blur + blend.blurLimit);
    return a > blend.alpha ? a : blend.alpha;
}

/// The values TAA blends: linear radiance, display values (TemporalSettings::taaToneMapped,
/// the authors') or range-compressed radiance (TemporalSettings::taaRangeCompressed).
enum class TaaSpace : uint8_t { Linear, Display, Compressed };

/// One frame's TAA inputs: packed images of 3 floats per pixel, and the previous pixel of each
/// pixel (2 floats) from the filter's reprojection.
struct TaaInputs {
    const float* current = nullptr; ///< this frame's colour before TAA
    const float* ycocg = nullptr;   ///< rgbToYCoCg of `current`, precomputed once per pixel
    const float* history = nullptr; ///< the previous frame's TAA output
    const float* previousPixel = nullptr;
    int width = 0, height = 0;
    TaaBlend blend;
    /// The filter's accept mask (bit t = bilinear tap t passed the history discard test), or
    /// null. With it the history is gathered from the accepted taps only, so it never mixes
    /// in the surface behind an edge, and a pixel with none keeps its current colour
    /// (TemporalSettings::taaSameSurface); without it from every tap (the authors').
    const uint8_t* accept = nullptr;
    /// Display: TAA on gammaEncode values (the authors' code runs it on its tone-mapped frame):
    /// the current frame, its clamp box and the history are encoded, the result decoded back to
    /// linear, so values above 1 come out as 1. Compressed: the same with compressRange and
    /// expandRange, which clip nothing.
    TaaSpace space = TaaSpace::Linear;
};

/// The space the settings ask for: the tone-mapped one over the compressed one.
inline TaaSpace taaSpaceOf(const TemporalSettings& s) {
    if (s.taaToneMapped) return TaaSpace::Display;
    return s.taaRangeCompressed ? TaaSpace::Compressed : TaaSpace::Linear;
}

/// The blend the settings ask for.
inline TaaBlend taaBlend(const TemporalSettings& s) {
    return {s.taaBlendAlpha, s.taaMotionWeight ? s.taaBlurLimit : 0.0f};
}

/// A filter's TAA inputs (ycocg is the pass's own): `accept` is used only when the settings
/// ask for the same-surface history.
inline TaaInputs taaInputs(const float* current, const float* history, const float* previousPixel,
                           int width, int height, const TemporalSettings& s,
                           const uint8_t* accept) {
    return {current,      nullptr, history,     previousPixel,
            width,        height,  taaBlend(s), s.taaSameSurface ? accept : nullptr,
            taaSpaceOf(s)};
}

/// Where TAA blends a colour (TaaInputs::space).
BMFR_HD Vec3 taaSpace(const TaaInputs& a, Vec3 c) {
    if (a.space == TaaSpace::Display) return gammaEncode(c);
    return a.space == TaaSpace::Compressed ? compressRange(c) : c;
}
/// What TAA outputs for a result in its space: linear again.
BMFR_HD Vec3 taaOutput(const TaaInputs& a, Vec3 v) {
    if (a.space == TaaSpace::Display) return gammaDecode(v);
    return a.space == TaaSpace::Compressed ? expandRange(v) : v;
}

/// Clamp box of pixel (x, y): the mean of the 3x3 box and the 5-tap cross bounds, in YCoCg.
BMFR_HD void taaClampBox(const TaaInputs& a, int x, int y, Vec3& lo, Vec3& hi) {
    const float inf = INFINITY;
    Vec3 boxLo{inf, inf, inf}, boxHi{-inf, -inf, -inf}, crossLo = boxLo, crossHi = boxHi;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            const int sx = x + dx, sy = y + dy;
            if (sx < 0 || sy < 0 || sx >= a.width || sy >= a.height) continue;
            const Vec3 v = load3(a.ycocg, long(sy) * a.width + sx);
            boxLo = vmin(boxLo, v);
            boxHi = vmax(boxHi, v);
            if (dx == 0 || dy == 0) {
                crossLo = vmin(crossLo, v);
                crossHi = vmax(crossHi, v);
            }
        }
    lo = 0.5f * (boxLo + crossLo);
    hi = 0.5f * (boxHi + crossHi);
}

/// TAA output of pixel (x, y). A pixel whose footprint lies wholly outside the image (no
/// history) keeps its current colour.
BMFR_HD Vec3 taaPixel(const TaaInputs& a, int x, int y) {
    const long i = long(y) * a.width + x;
    const Vec3 c = taaSpace(a, load3(a.current, i));
    const Vec2 pp{a.previousPixel[2 * i], a.previousPixel[2 * i + 1]};
    const BilinearFootprint fp = bilinearFootprint(pp);
    if (fp.x0 < -1 || fp.y0 < -1 || fp.x0 >= a.width || fp.y0 >= a.height) return taaOutput(a, c);
    const uint8_t taps = a.accept ? a.accept[i] : uint8_t(15);
    if (taps == 0) return taaOutput(a, c);
    Vec3 lo, hi;
    taaClampBox(a, x, y, lo, hi);
    // Bilinear history, renormalised at the image border (and over the accepted taps).
    Vec3 old{};
    float total = 0.0f;
    for (int t = 0; t < 4; ++t) {
        const int tx = tapX(fp, t), ty = tapY(fp, t);
        if (tx < 0 || ty < 0 || tx >= a.width || ty >= a.height || !(taps & (1 << t))) continue;
        old += fp.weight[t] * taaSpace(a, load3(a.history, long(ty) * a.width + tx));
        total += fp.weight[t];
    }
    if (total > 0.0f)
        old = old / total;
    else if (a.accept)
        return taaOutput(a, c);
    const Vec3 clamped = yCoCgToRgb(clamp(rgbToYCoCg(old), lo, hi));
    return taaOutput(a, lerp(clamped, c, taaCurrentWeight(a.blend, bilinearBlur(fp.weight))));
}

} // namespace bmfr
