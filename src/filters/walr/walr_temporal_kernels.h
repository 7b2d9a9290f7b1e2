// WALR's preprocess and postprocess (paper sections 4.2 and 4.4), per pixel and BMFR_HD:
// reprojection through the shared findPreviousSurface with motion dilation, Catmull-Rom history
// resampling, depth rejection with the motion's depth offset, the cumulative-then-exponential
// average, and the variance-clipped post blend that shares the preprocess's sample count.
#pragma once
#include "filters/walr/atrous_averages.h"
#include "filters/walr/normal_features.h"
#include "temporal/blend_weights.h"
#include "temporal/catmull_rom.h"
#include "temporal/modulation.h"
#include "temporal/reprojection.h"
#include "temporal/variance_clip.h"

namespace bmfr {

/// One frame's WALR buffers (packed; channels as noted); `prev*` are the previous slot's.
struct WalrFrame {
    InputPlanes in;
    InputModes modes;
    PreviousFrame previous;
    Mat4 viewProjection;
    ViewBasis view;
    DiscardLimits limits;
    float preAlpha = 0.2f, depthTolerance = 0.02f;
    bool depthTest = true; ///< else the shared world position and normal limits
    bool dilation = true;
    int width = 0, height = 0;
    // History.
    const float *prevPre = nullptr, *prevPost = nullptr, *prevDepth = nullptr;
    const float *prevPosition = nullptr, *prevNormal = nullptr;
    const uint8_t* prevCount = nullptr;
    float *pre = nullptr, *depth = nullptr, *position = nullptr, *normal = nullptr;
    uint8_t* count = nullptr; ///< samples in the preprocess average, 1..255
    // This frame.
    float* signal = nullptr;        ///< 3: what is filtered, before accumulation
    float* features = nullptr;      ///< 2: octahedral view-space normal in [0, 1]
    float* offset = nullptr;        ///< 2: previous pixel minus pixel; NaN = none
    float* expectedDepth = nullptr; ///< this surface's view depth in the previous frame
    float* previousPixel = nullptr; ///< 2: after dilation; far outside = none
    float* postHistory = nullptr;   ///< 3: the resampled post history
    uint8_t* accept = nullptr;      ///< 15 = history kept, 0 = rejected (debug view)
};

/// Pass 1a at pixel i: the inputs read and sanitised, the signal, the features, the depth, and
/// where the surface was.
BMFR_HD void walrInputPixel(const WalrFrame& f, long i, int64_t& bad) {
    const int x = int(i % f.width), y = int(i / f.width);
    const PixelInput px = readPixel(f.in, i, f.modes, bad);
    Vec3 y3 = px.color;
    if (f.in.diffuseIndirect) y3 = vmax(finiteOrZero(load3(f.in.diffuseIndirect, i), bad), {});
    store3(f.signal, i, y3);
    store3(f.position, i, px.position);
    store3(f.normal, i, px.normal);
    const float z = transformPoint(f.viewProjection, px.position).w;
    f.depth[i] = z;
    const Vec2 feat = walrNormalFeatures(px.normal, px.position, f.view);
    f.features[2 * i] = feat.x, f.features[2 * i + 1] = feat.y;
    PreviousSurface was;
    const bool found =
        findPreviousSurface(f.in, i, x, y, px.position, px.normal, f.previous, bad, was);
    f.offset[2 * i] = found ? was.pixel.x - float(x) : NAN;
    f.offset[2 * i + 1] = found ? was.pixel.y - float(y) : NAN;
    float expected = NAN;
    if (found) {
        if (f.in.motionDepth && std::isfinite(f.in.motionDepth[i]))
            expected = z + f.in.motionDepth[i];
        else if (!f.in.motionDepth)
            expected = transformPoint(f.previous.viewProjection, was.position).w;
    }
    if (f.in.motionDepth && !std::isfinite(f.in.motionDepth[i])) ++bad;
    f.expectedDepth[i] = expected;
}

/// The offset pixel (x, y) reprojects with: its own, or with dilation that of the nearest
/// surface (smallest positive depth) in its 3x3, so that edges move with the foreground.
BMFR_HD Vec2 walrDilatedOffset(const WalrFrame& f, int x, int y) {
    long best = long(y) * f.width + x;
    if (f.dilation) {
        float z = f.depth[best] > 0 ? f.depth[best] : INFINITY;
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const int qx = x + dx, qy = y + dy;
                if (qx < 0 || qy < 0 || qx >= f.width || qy >= f.height) continue;
                const long j = long(qy) * f.width + qx;
                if (f.depth[j] > 0 && f.depth[j] < z) z = f.depth[j], best = j;
            }
    }
    return {f.offset[2 * best], f.offset[2 * best + 1]};
}

/// Whether pixel i's history at previous pixel j is the same surface.
BMFR_HD bool walrSameSurface(const WalrFrame& f, long i, long j) {
    if (f.depthTest) {
        const float e = f.expectedDepth[i];
        return e > 0 && std::fabs(e - f.prevDepth[j]) <= f.depthTolerance * e;
    }
    int64_t unused = 0; // counted in walrInputPixel
    const Vec3 p = f.in.previousPosition ? finiteOrZero(load3(f.in.previousPosition, i), unused)
                                         : load3(f.position, i);
    const Vec3 n = f.in.previousNormal ? finiteOrZero(load3(f.in.previousNormal, i), unused)
                                       : load3(f.normal, i);
    const Vec3 dp = load3(f.prevPosition, j) - p, dn = load3(f.prevNormal, j) - n;
    return dot(dp, dp) < f.limits.positionSquared && dot(dn, dn) < f.limits.normalSquared;
}

/// Pass 1b at pixel (x, y): history test at the nearest previous pixel, Catmull-Rom resampling
/// of both histories, the moving average, and the averages of iteration 0.
BMFR_HD void walrAccumulatePixel(const WalrFrame& f, int x, int y, float* averages,
                                 const AverageLayout& layout) {
    const long i = long(y) * f.width + x;
    const Vec2 off = walrDilatedOffset(f, x, y);
    const Vec2 pp{float(x) + off.x, float(y) + off.y}; // NaN when there is none
    bool keep = false;
    long j = 0;
    if (std::isfinite(pp.x) && std::isfinite(pp.y) && std::fabs(pp.x) < 1e8f &&
        std::fabs(pp.y) < 1e8f) {
        const int nx = int(std::floor(pp.x + 0.5f)), ny = int(std::floor(pp.y + 0.5f));
        if (nx >= 0 && ny >= 0 && nx < f.width && ny < f.height) {
            j = long(ny) * f.width + nx;
            keep = f.prevCount[j] > 0 && walrSameSurface(f, i, j);
        }
    }
    const Vec3 y3 = load3(f.signal, i);
    Vec3 acc = y3, post = y3;
    uint8_t n = 1;
    if (keep) {
        const float samples = float(f.prevCount[j]);
        Vec3 h;
        sampleCatmullRom2(f.prevPre, f.prevPost, f.width, f.height, pp, h, post);
        acc = lerp(h, y3, firstBlendWeight(samples, f.preAlpha));
        n = uint8_t(samples < 255.0f ? samples + 1.0f : 255.0f);
    }
    store3(f.pre, i, acc);
    store3(f.postHistory, i, post);
    f.count[i] = n;
    f.accept[i] = keep ? 15 : 0;
    f.previousPixel[2 * i] = keep ? pp.x : -1e6f;
    f.previousPixel[2 * i + 1] = keep ? pp.y : -1e6f;
    float a[kWalrAverages];
    walrSampleProducts(acc, {f.features[2 * i], f.features[2 * i + 1]}, a);
    for (int k = 0; k < kWalrAverages; ++k) averages[layout.at(k, i)] = a[k];
}

/// What the postprocess reads and writes.
struct WalrPost {
    InputPlanes in;
    const float* spatial = nullptr;     ///< 3: the spatial filter's output
    const float* postHistory = nullptr; ///< 3: resampled in pass 1b
    const float* signal = nullptr;      ///< 3: the noisy signal (diffuse-indirect composition)
    const uint8_t* count = nullptr;
    float* post = nullptr;   ///< 3: this frame's post history
    float* output = nullptr; ///< 3: the final radiance
    int width = 0, height = 0;
    float alpha = 0.1f, gamma = 1.0f, albedoEpsilon = 0.001f;
    bool enabled = true, diffuseIndirect = false;
};

/// Pass 3 at pixel (x, y): the post history clipped to the spatial output's 3x3 variance box
/// and blended by the shared sample count, then composed into radiance: remodulated (colour
/// signal), or added to the unfiltered rest of the colour (diffuse-indirect signal).
BMFR_HD void walrPostPixel(const WalrPost& p, int x, int y) {
    const long i = long(y) * p.width + x;
    Vec3 out = load3(p.spatial, i);
    if (p.enabled && p.count[i] > 1) {
        const NeighbourhoodMoments m = neighbourhoodMoments(p.spatial, p.width, p.height, x, y);
        const Vec3 h = varianceClip(load3(p.postHistory, i), m, p.gamma);
        out = lerp(h, out, secondBlendWeight(p.count[i], p.alpha));
    }
    store3(p.post, i, out);
    if (!p.diffuseIndirect) {
        store3(p.output, i, remodulatePixel(out, p.in, i, true, p.albedoEpsilon));
        return;
    }
    int64_t unused = 0; // counted in walrInputPixel
    const Vec3 albedo = vmax(finiteOrZero(load3(p.in.albedo, i), unused), {});
    const Vec3 rest = finiteOrZero(load3(p.in.color, i), unused) - albedo * load3(p.signal, i);
    store3(p.output, i, rest + albedo * out);
}

} // namespace bmfr
