// Mara et al. 2017's stages over one frame's buffers, per pixel and BMFR_HD (stage numbers from
// their Fig. 2 and Table 1). Every backend runs these bodies; the reference backend as one loop
// per stage.
#pragma once
#include "filters/mara2017/mara_kernels.h"
#include "temporal/modulation.h"
#include "temporal/reprojection.h"

namespace bmfr {

/// One frame's buffers (packed; channels as noted) and the settings in the units the stages use
/// (pixels for radii). `prev*` are the previous history slot's.
struct MaraFrame {
    InputPlanes in;
    InputModes modes;
    PreviousFrame previous;
    Vec3 eye; ///< the camera centre
    int width = 0, height = 0;
    bool factored = false; ///< the frame has FrameInput::matteIndirect
    bool glossy = false;   ///< the frame has FrameInput::glossyIndirect
    float h = 0.98f, d0 = 0.05f, d1 = 0.07f;
    bool cumulativeStart = true, clampHistory = true, virtualReprojection = true;
    bool normaliseConfidence = false;
    int clampRadius = 1; ///< the clamp's box is (2 clampRadius + 1)^2
    MaraEdgeWeights edges;
    int preTaps = 50, finalTaps = 50;
    int rotationWidth = 16;               ///< pixels along a row that share a spiral rotation
    float preRadius = 1, preSigma = 0.5f; ///< pixels
    int maxRadius = 16;                   ///< R, pixels
    float lowConfidence = 0.5f, radiusBoost = 6, finalSigma = 0.5f;
    float glossyScale = 7, glossyExponent = 0.1f, glossyEpsilon = 1e-4f, glossyTapSigmas = 3;
    /// Unit spiral offsets, kMaraSpiralRotations x taps x 2, already turned by the frame's
    /// rotation; preOffsets holds stage 4's as whole pixels and preGauss their Gaussian weights.
    const float *preSpiral = nullptr, *finalSpiral = nullptr;
    const int* preOffsets = nullptr;
    const float* preGauss = nullptr;
    uint32_t frame = 0, seed = 0;
    // History.
    const float *prevMatte = nullptr, *prevGlossy = nullptr;
    const float *prevPosition = nullptr, *prevNormal = nullptr;
    const uint8_t* prevCount = nullptr;
    float *matteHistory = nullptr, *glossyHistory = nullptr;
    float *position = nullptr, *normal = nullptr;
    uint8_t* count = nullptr; ///< frames of history, 1..255 (a debug view)
    // This frame.
    float *matte = nullptr, *glossySignal = nullptr; ///< 3: M and G as filtered
    float* expected = nullptr;      ///< 3: where this surface point was a frame ago
    float* previousPixel = nullptr; ///< 2: its previous pixel; far outside = none
    float* temporal = nullptr;      ///< 3: stage 3's output T
    float* confidence = nullptr;    ///< 1: stage 3's c
    float* glossyTemporal = nullptr;
    float* rowMin = nullptr; ///< 1: stage 5's first (horizontal) min
    float* radius = nullptr; ///< 1: stage 5's r, pixels
    float* median = nullptr; ///< 3: stage 6
    float *matteOut = nullptr, *glossyRow = nullptr, *glossyOut = nullptr;
    float* composed = nullptr;
    uint8_t* accept = nullptr; ///< bilinear taps with confidence > 0 (bit i = tap i)
};

/// Input pass at pixel i: inputs read and sanitised, M and G chosen (the whole demodulated
/// colour as matte without the factorisation), the features stored, and where the point was.
BMFR_HD void maraInputPixel(const MaraFrame& f, long i, int64_t& bad) {
    const int x = int(i % f.width), y = int(i / f.width);
    const PixelInput px = readPixel(f.in, i, f.modes, bad);
    const Vec3 m = f.in.matteIndirect ? finiteOrZero(load3(f.in.matteIndirect, i), bad) : px.color;
    store3(f.matte, i, vmax(m, Vec3{}));
    if (f.glossy)
        store3(f.glossySignal, i, vmax(finiteOrZero(load3(f.in.glossyIndirect, i), bad), {}));
    store3(f.position, i, px.position);
    store3(f.normal, i, px.normal);
    // The buffers read later are counted here, once.
    if (f.in.directLight) finiteOrZero(load3(f.in.directLight, i), bad);
    if (f.in.specularF0) finiteOrZero(load3(f.in.specularF0, i), bad);
    if (f.in.roughness) finiteOrZero(f.in.roughness[i], bad);
    if (f.in.glossyHitDistance) finiteOrZero(f.in.glossyHitDistance[i], bad);
    PreviousSurface was;
    const bool found =
        findPreviousSurface(f.in, i, x, y, px.position, px.normal, f.previous, bad, was);
    store3(f.expected, i, was.position);
    f.previousPixel[2 * i] = found ? was.pixel.x : -1e6f;
    f.previousPixel[2 * i + 1] = found ? was.pixel.y : -1e6f;
}

/// Per-channel min and max of v's (2r + 1)^2 box around (x, y), inside the image.
BMFR_HD void maraBox(const float* v, int w, int h, int x, int y, int r, Vec3& lo, Vec3& hi) {
    lo = {INFINITY, INFINITY, INFINITY}, hi = {-INFINITY, -INFINITY, -INFINITY};
    for (int dy = -r; dy <= r; ++dy)
        for (int dx = -r; dx <= r; ++dx) {
            const int qx = x + dx, qy = y + dy;
            if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
            const Vec3 q = load3(v, long(qy) * w + qx);
            lo = vmin(lo, q), hi = vmax(hi, q);
        }
}

/// The history's blend weight for confidence c and n frames of history: c, or with the
/// cumulative start at most n / (n + 1), the running mean's.
BMFR_HD float maraHistoryWeight(const MaraFrame& f, float c, int n) {
    if (!f.cumulativeStart) return c;
    const float mean = float(n) / float(n + 1);
    return c < mean ? c : mean;
}

/// Stage 3 at (x, y): each bilinear tap of the previous frame weighted by its confidence (the
/// world distance between where the point was and what that pixel saw), the history clamped
/// to the new 3x3 and blended in with weight c, the bilinear sum of the taps' confidences.
BMFR_HD void maraMatteTemporalPixel(const MaraFrame& f, int x, int y) {
    const long i = long(y) * f.width + x;
    const Vec3 m = load3(f.matte, i);
    const Vec2 pp{f.previousPixel[2 * i], f.previousPixel[2 * i + 1]};
    Vec3 t = m;
    float c = 0;
    uint8_t accept = 0, samples = 1;
    if (pp.x > -1e5f) {
        const BilinearFootprint fp = bilinearFootprint(pp);
        const Vec3 expected = load3(f.expected, i);
        Vec3 sum{};
        float best = 0;
        long nearest = -1;
        for (int k = 0; k < 4; ++k) {
            const int qx = tapX(fp, k), qy = tapY(fp, k);
            if (qx < 0 || qy < 0 || qx >= f.width || qy >= f.height) continue;
            const long j = long(qy) * f.width + qx;
            if (f.prevCount[j] == 0) continue;
            const float ck =
                maraConfidence(length(load3(f.prevPosition, j) - expected), f.h, f.d0, f.d1);
            if (!(ck > 0)) continue;
            const float wk = fp.weight[k] * ck;
            accept |= uint8_t(1u << k);
            sum += wk * load3(f.prevMatte, j);
            c += wk;
            if (wk > best) best = wk, nearest = j;
        }
        if (c > 0) {
            Vec3 hist = sum / c;
            if (f.clampHistory) {
                Vec3 lo, hi;
                maraBox(f.matte, f.width, f.height, x, y, f.clampRadius, lo, hi);
                hist = clamp(hist, lo, hi);
            }
            const int n = int(f.prevCount[nearest]);
            t = lerp(m, hist, maraHistoryWeight(f, c, n));
            samples = uint8_t(n + 1 < 255 ? n + 1 : 255);
        }
    }
    store3(f.temporal, i, t);
    f.confidence[i] = c;
    f.accept[i] = accept;
    f.count[i] = samples;
}

/// A sparse cross-bilateral at (x, y) of `src` (3 floats per pixel): the centre and `taps`
/// spiral taps (unit offsets `spiral`, scaled by `radius` pixels), Gaussian weights of sigma
/// pixels times the edge weight. Taps outside the image are skipped. `offsets` and `gauss`,
/// when given, hold the taps' whole-pixel offsets and Gaussian weights already.
BMFR_HD Vec3 maraSparseBilateral(const MaraFrame& f, const float* src, int x, int y,
                                 const float* spiral, const int* offsets, const float* gauss,
                                 int taps, float radius, float sigma) {
    const long i = long(y) * f.width + x;
    const Vec3 centre = load3(src, i);
    if (!(radius >= 0.5f)) return centre;
    const Vec3 pc = load3(f.position, i), nc = load3(f.normal, i);
    Vec3 sum = centre;
    float total = 1.0f;
    for (int k = 0; k < taps; ++k) {
        const int dx = offsets ? offsets[2 * k] : maraTapOffset(spiral[2 * k], radius);
        const int dy = offsets ? offsets[2 * k + 1] : maraTapOffset(spiral[2 * k + 1], radius);
        const int qx = x + dx, qy = y + dy;
        if (qx < 0 || qy < 0 || qx >= f.width || qy >= f.height) continue;
        const long j = long(qy) * f.width + qx;
        const float g = gauss ? gauss[k] : maraGaussian(float(dx * dx + dy * dy), sigma);
        const float w =
            g * maraEdgeWeight(nc, pc, load3(f.normal, j), load3(f.position, j), f.edges);
        if (!(w > 0)) continue;
        sum += w * load3(src, j);
        total += w;
    }
    return sum / total;
}

/// Stage 4 at (x, y): the sparse pre-bilateral of T, stored as the matte history only (new
/// samples on screen are never blurred by it).
BMFR_HD void maraPreBilateralPixel(const MaraFrame& f, int x, int y) {
    const int r = maraPixelRotation(x, y, f.rotationWidth, f.frame, f.seed, 4);
    const long i = long(y) * f.width + x;
    store3(f.matteHistory, i,
           maraSparseBilateral(f, f.temporal, x, y, f.preSpiral + 2 * f.preTaps * r,
                               f.preOffsets + 2 * f.preTaps * r,
                               f.preGauss ? f.preGauss + f.preTaps * r : nullptr, f.preTaps,
                               f.preRadius, f.preSigma));
}

/// The confidence stage 5 reads at pixel i.
BMFR_HD float maraStage5Confidence(const MaraFrame& f, long i) {
    return f.normaliseConfidence && f.h > 0 ? f.confidence[i] / f.h : f.confidence[i];
}

/// Stage 5, first pass at (x, y): the min of c over x - R .. x + R (inside the image).
BMFR_HD void maraRowMinPixel(const MaraFrame& f, int x, int y) {
    const long row = long(y) * f.width;
    float m = INFINITY;
    const int x0 = x - f.maxRadius > 0 ? x - f.maxRadius : 0;
    const int x1 = x + f.maxRadius < f.width - 1 ? x + f.maxRadius : f.width - 1;
    for (int qx = x0; qx <= x1; ++qx) m = std::fmin(m, maraStage5Confidence(f, row + qx));
    f.rowMin[row + x] = m;
}

/// Stage 5's radius from the 2R x 2R min m at pixel i: (1 - m) R, boosted where c is low.
BMFR_HD float maraDisocclusionRadius(const MaraFrame& f, long i, float m) {
    float r = (1.0f - m) * float(f.maxRadius);
    if (maraStage5Confidence(f, i) < f.lowConfidence) r *= f.radiusBoost;
    return r;
}

/// Stage 5, second pass at (x, y): the min of the row mins over y - R .. y + R, then r.
BMFR_HD void maraColumnMinPixel(const MaraFrame& f, int x, int y) {
    float m = INFINITY;
    const int y0 = y - f.maxRadius > 0 ? y - f.maxRadius : 0;
    const int y1 = y + f.maxRadius < f.height - 1 ? y + f.maxRadius : f.height - 1;
    for (int qy = y0; qy <= y1; ++qy) m = std::fmin(m, f.rowMin[long(qy) * f.width + x]);
    const long i = long(y) * f.width + x;
    f.radius[i] = maraDisocclusionRadius(f, i, m);
}

/// Stage 6 at (x, y): the per-channel 3x3 median of T (edge pixels repeat), outside the
/// history loop: a firefly still enters the history but is not shown.
BMFR_HD void maraMedianPixel(const MaraFrame& f, int x, int y) {
    float v[3][9];
    int n = 0;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx, ++n) {
            int qx = x + dx, qy = y + dy;
            qx = qx < 0 ? 0 : qx >= f.width ? f.width - 1 : qx;
            qy = qy < 0 ? 0 : qy >= f.height ? f.height - 1 : qy;
            const long j = long(qy) * f.width + qx;
            for (int c = 0; c < 3; ++c) v[c][n] = f.temporal[3 * j + c];
        }
    const long i = long(y) * f.width + x;
    store3(f.median, i, {maraMedian9(v[0]), maraMedian9(v[1]), maraMedian9(v[2])});
}

/// Stage 7 at (x, y): the final sparse bilateral of radius r (stage 5), sigma finalSigma r.
BMFR_HD void maraFinalBilateralPixel(const MaraFrame& f, const float* src, int x, int y) {
    const long i = long(y) * f.width + x;
    const float r = f.radius[i];
    const int rot = maraPixelRotation(x, y, f.rotationWidth, f.frame, f.seed, 7);
    store3(f.matteOut, i,
           maraSparseBilateral(f, src, x, y, f.finalSpiral + 2 * f.finalTaps * rot, nullptr,
                               nullptr, f.finalTaps, r, f.finalSigma * r));
}

/// Bilinear sample of `history` (3 floats per pixel) at a continuous pixel, over the taps
/// inside the image, renormalised; false when none is.
BMFR_HD bool maraBilinear(const float* history, int w, int h, Vec2 p, Vec3& out) {
    const BilinearFootprint fp = bilinearFootprint(p);
    Vec3 sum{};
    float total = 0;
    for (int k = 0; k < 4; ++k) {
        const int qx = tapX(fp, k), qy = tapY(fp, k);
        if (qx < 0 || qy < 0 || qx >= w || qy >= h || !(fp.weight[k] > 0)) continue;
        sum += fp.weight[k] * load3(history, long(qy) * w + qx);
        total += fp.weight[k];
    }
    if (!(total > 0)) return false;
    out = sum / total;
    return true;
}

/// Where the reflection at pixel i was a frame ago: the virtual position X + d (X - eye) / |X -
/// eye| (Zimmer et al. 2015; exact for planar mirrors) projected by the previous camera.
BMFR_HD bool maraVirtualPreviousPixel(const MaraFrame& f, long i, Vec2& pixel) {
    const float d = f.in.glossyHitDistance[i];
    if (!std::isfinite(d) || d < 0) return false;
    const Vec3 x = load3(f.position, i), v = x - f.eye;
    const float len = length(v);
    if (!(len > 0)) return false;
    return projectToPixel(f.previous.viewProjection, x + (d / len) * v, f.previous.jitter, f.width,
                          f.height, pixel);
}

/// Stage 8 at (x, y): the glossy history at the virtual position's previous pixel, clamped to
/// the new 3x3 and blended with the primary surface's confidence c (and stage 3's count).
BMFR_HD void maraGlossyTemporalPixel(const MaraFrame& f, int x, int y) {
    const long i = long(y) * f.width + x;
    const Vec3 g = load3(f.glossySignal, i);
    Vec3 t = g;
    const float c = f.confidence[i];
    if (c > 0) {
        Vec2 pp{f.previousPixel[2 * i], f.previousPixel[2 * i + 1]};
        if (f.virtualReprojection && f.in.glossyHitDistance) {
            Vec2 v;
            if (maraVirtualPreviousPixel(f, i, v)) pp = v;
        }
        Vec3 hist;
        if (maraBilinear(f.prevGlossy, f.width, f.height, pp, hist)) {
            if (f.clampHistory) {
                Vec3 lo, hi;
                maraBox(f.glossySignal, f.width, f.height, x, y, f.clampRadius, lo, hi);
                hist = clamp(hist, lo, hi);
            }
            t = lerp(g, hist, maraHistoryWeight(f, c, int(f.count[i]) - 1));
        }
    }
    store3(f.glossyTemporal, i, t);
    store3(f.glossyHistory, i, t);
}

/// Stages 9 and 10 at (x, y): one 1D pass of the separable glossy cross-bilateral along
/// (dx, dy) = (1, 0) or (0, 1), sigma from this pixel's roughness, taps to glossyTapSigmas sigma.
BMFR_HD void maraGlossyPassPixel(const MaraFrame& f, const float* src, float* dst, int x, int y,
                                 int dx, int dy) {
    const long i = long(y) * f.width + x;
    const float rough = f.in.roughness ? f.in.roughness[i] : 1.0f;
    const float sigma = maraGlossySigma(std::isfinite(rough) ? rough : 1.0f, f.glossyScale,
                                        f.glossyExponent, f.glossyEpsilon);
    const int reach = int(std::ceil(f.glossyTapSigmas * sigma));
    const Vec3 pc = load3(f.position, i), nc = load3(f.normal, i);
    Vec3 sum = load3(src, i);
    float total = 1.0f;
    for (int k = 1; k <= reach; ++k) {
        const float g = maraGaussian(float(k * k), sigma); // once for both sides
        if (!(g > 0)) break;
        for (int side = -1; side <= 1; side += 2) {
            const int qx = x + side * k * dx, qy = y + side * k * dy;
            if (qx < 0 || qy < 0 || qx >= f.width || qy >= f.height) continue;
            const long j = long(qy) * f.width + qx;
            const float w =
                g * maraEdgeWeight(nc, pc, load3(f.normal, j), load3(f.position, j), f.edges);
            if (!(w > 0)) continue;
            sum += w * load3(src, j);
            total += w;
        }
    }
    store3(dst, i, sum / total);
}

/// The composition at pixel i: with the factorisation, direct + (1 - F_s)^2 albedo M~ + F_s G~
/// + emission, F_s = Schlick(F0, n . view); without it, M~ re-modulated plus the emission.
BMFR_HD void maraComposePixel(const MaraFrame& f, long i) {
    const Vec3 m = load3(f.matteOut, i);
    if (!f.factored) {
        store3(f.composed, i, remodulatePixel(m, f.in, i, true, f.modes.albedoEpsilon));
        return;
    }
    int64_t unused = 0; // counted in maraInputPixel
    const Vec3 albedo = vmax(finiteOrZero(load3(f.in.albedo, i), unused), {});
    Vec3 fresnel{};
    if (f.in.specularF0) {
        const Vec3 p = load3(f.position, i), n = load3(f.normal, i), v = f.eye - p;
        const float len = length(v);
        const float cosine = len > 0 ? std::fabs(dot(n, v)) / len : 1.0f;
        fresnel = maraFresnel(vmax(finiteOrZero(load3(f.in.specularF0, i), unused), {}), cosine);
    }
    const Vec3 g = f.glossy ? load3(f.glossyOut, i) : Vec3{};
    const Vec3 direct =
        f.in.directLight ? finiteOrZero(load3(f.in.directLight, i), unused) : Vec3{};
    const Vec3 emission = f.in.emission ? finiteOrZero(load3(f.in.emission, i), unused) : Vec3{};
    store3(f.composed, i, maraCompose(direct, albedo, fresnel, m, g, emission));
}

} // namespace bmfr
