// The BMFR fitting kernel (paper section 4.2), one block at a time: gather the block's features
// and phase I colour, scale each feature column to the block, add the regularisation noise,
// solve the least squares by Householder QR, and write the weighted sum of the noise-free
// features to the pixels the block owns. BMFR_HD over raw arrays; the CPU backend's fitter
// (backend/cpu/bmfr/cpu_fit_blocks.cpp) is the same maths streamed from planes. With
// BmfrSettings::excludeEmitters the block's emitter pixels (emitter_mask.h) sit the fit out.
#pragma once
#include "core/border.h"
#include "filters/bmfr/block_grid.h"
#include "filters/bmfr/emitter_exclusion.h"
#include "filters/bmfr/feature_columns.h"
#include "filters/bmfr/firefly_clamp.h"
#include "filters/bmfr/householder_qr.h"
#include "temporal/pixel_input.h"

namespace bmfr {

/// How BMFR reads its colour input.
inline InputModes inputModes(const BmfrSettings& s) {
    return {s.colorIsDemodulated, s.stages.demodulate, s.albedoEpsilon};
}

/// BmfrSettings::excludeEmitters for one frame's fit (emitter_exclusion.h).
struct EmitterExclusion {
    bool on = false;         ///< asked for, and no emission buffer to do it instead
    float ratio = 16.0f;     ///< BmfrSettings::emitterRatio
    InputModes modes;        ///< how phase I read the current samples
    uint8_t* bits = nullptr; ///< 1 where the output is an emitter's own sample; null: not kept
    /// The previous frame's emitters (maskSeed), null without history: a pixel was one when
    /// `previous` has `previousBit` at the nearest tap of its previous pixel, whose x and y are
    /// previousX[i * previousStep] and previousY[i * previousStep].
    const uint8_t* previous = nullptr;
    uint8_t previousBit = 1;
    const float *previousX = nullptr, *previousY = nullptr;
    int previousStep = 1;
    /// The current samples' luminances where a backend has them (SampleLuminance); none: read
    /// from the input.
    KnownSamples known = {};
};

/// The bilinear tap of image pixel i's previous pixel with the largest weight (the first of
/// equals) inside a w x h frame, as (tx, ty); false when none is, or without a previous frame.
BMFR_HD bool previousNearestTap(const EmitterExclusion& e, long i, int w, int h, int& tx, int& ty) {
    if (!e.previous) return false;
    const long j = i * e.previousStep;
    const BilinearFootprint fp = bilinearFootprint(Vec2{e.previousX[j], e.previousY[j]});
    int best = -1;
    float weight = -1.0f;
    for (int t = 0; t < 4; ++t) {
        const int x = tapX(fp, t), y = tapY(fp, t);
        if (x >= 0 && y >= 0 && x < w && y < h && fp.weight[t] > weight)
            best = t, weight = fp.weight[t];
    }
    if (best < 0) return false;
    tx = tapX(fp, best), ty = tapY(fp, best);
    return true;
}

/// Whether image pixel i of a w x h frame was an emitter in the previous frame: at
/// previousNearestTap.
BMFR_HD bool wasEmitter(const EmitterExclusion& e, long i, int w, int h) {
    int x, y;
    return previousNearestTap(e, i, w, h, x, y) && (e.previous[long(y) * w + x] & e.previousBit);
}

/// How far from a light of the previous frame (pixels, in the previous frame) its history
/// smears under motion: the emitter mask's two pixels of growth.
inline constexpr int kEmitterSmearReach = 2;

/// Whether a pixel within kEmitterSmearReach of image pixel i's previousNearestTap was an
/// emitter in the previous frame.
BMFR_HD bool besidePreviousEmitter(const EmitterExclusion& e, long i, int w, int h) {
    int x, y;
    if (!previousNearestTap(e, i, w, h, x, y)) return false;
    for (int v = y - kEmitterSmearReach; v <= y + kEmitterSmearReach; ++v)
        for (int u = x - kEmitterSmearReach; u <= x + kEmitterSmearReach; ++u)
            if (u >= 0 && v >= 0 && u < w && v < h && (e.previous[long(v) * w + u] & e.previousBit))
                return true;
    return false;
}

/// The history length by which the firefly clamp fades at image pixel i (fireflyFade):
/// `length`, phase I's, or 1 (the clamp in full) beside a light of the previous frame. There a
/// bright pixel with a long history is the light's history smeared past its edge, which the
/// clamp keeps out of the fit, not the estimator's tail.
BMFR_HD float fireflyFadeLength(const EmitterExclusion& e, long i, int w, int h, float length) {
    return besidePreviousEmitter(e, i, w, h) ? 1.0f : length;
}

/// This frame's emitter exclusion, writing its bits to `bits`.
inline EmitterExclusion emitterExclusion(const BmfrSettings& s, const InputPlanes& in,
                                         uint8_t* bits) {
    return {s.excludeEmitters && in.emission == nullptr, s.emitterRatio, inputModes(s), bits};
}

/// One frame's fit: its sources and output are packed images (3 values per pixel), the normals
/// and phase I's colour stored as H (NoisyAccumulationOf).
template <class H> struct BlockFitOf {
    BlockGrid grid;
    const Feature* features = nullptr;
    int featureCount = 0;
    const float* noise = nullptr; ///< featureCount x blockPixels regularisation noise
    const H* normal = nullptr;
    const float* position = nullptr;
    const H* color = nullptr; ///< phase I output
    InputPlanes in;           ///< for the extra feature buffers
    float* fitted = nullptr;  ///< the block writes the pixels it owns
    EmitterExclusion emitters;
    bool clampFireflies = false;     ///< BmfrSettings::clampFireflies
    const uint8_t* length = nullptr; ///< phase I's history lengths, which fade the clamp
};
using BlockFit = BlockFitOf<float>;

/// fireflyFadeLength of pixel k of block (bx, by) of `g` (mirrored in at the border), with
/// lengthAt(i) the history length of image pixel i in the backend's storage.
template <class LengthAt>
BMFR_HD float blockFadeLength(const BlockGrid& g, const EmitterExclusion& e, int bx, int by, int k,
                              LengthAt&& lengthAt) {
    bool owned;
    const long i = blockPixel(g, bx, by, k, owned);
    return fireflyFadeLength(e, i, g.width, g.height, float(lengthAt(i)));
}

/// blockFadeLength from the fit's own history lengths.
template <class H> BMFR_HD float blockFadeLength(const BlockFitOf<H>& a, int bx, int by, int k) {
    return blockFadeLength(a.grid, a.emitters, bx, by, k, [&](long i) { return a.length[i]; });
}

/// One worker's scratch for a block of W pixels and M features.
struct BlockFitScratch {
    float* clean;    ///< M x W scaled feature columns, noise-free (for the weighted sum)
    float* work;     ///< (M + 3) x W noised columns then colour, overwritten by the QR
    float* sum;      ///< 3 x W weighted sums
    float* sources;  ///< (6 + InputPlanes::kMaxExtras) x W gathered normal, position and extras
    int* imageIndex; ///< W: image pixel of each block pixel, -1 when not owned
    uint8_t* mask;   ///< W: the emitter mask (emitter_exclusion.h)
    int* histogram;  ///< kMaskBuckets
};

/// Leaves the emitter pixels of block (bx, by) out of the least squares: their rows of the
/// M + 3 columns (`stride` floats apart, the colour last) become zero. Returns how many there
/// are; `mask` says which, and which are the emitter this frame (maskEmitter). `quartile` as
/// emitterMask's; `lum`, when given, the colour columns' luminances as they are.
BMFR_HD int excludeEmitterRows(const BlockGrid& g, const InputPlanes& in, const EmitterExclusion& e,
                               int bx, int by, float* columns, int M, long stride, int* histogram,
                               uint8_t* mask, int quartile = -1, const float* lum = nullptr) {
    const int B = g.blockSize;
    const float* z[3] = {columns + M * stride, columns + (M + 1) * stride,
                         columns + (M + 2) * stride};
    const int ox = g.originX(bx), oy = g.originY(by);
    const bool inside = ox >= 0 && oy >= 0 && ox + B <= g.width && oy + B <= g.height;
    const int excluded = emitterMask(
        B, e.ratio, SampleLuminance{in, e.modes, e.known},
        [&](int k) {
            return lum ? lum[k] : luminance({z[0][k], z[1][k], z[2][k]});
        },
        [&](int k) {
            bool owned;
            return blockPixel(g, bx, by, k, owned);
        },
        [&](long i) { return wasEmitter(e, i, g.width, g.height); }, histogram, mask, quartile,
        inside ? long(oy) * g.width + ox : -1);
    if (excluded)
        for (int k = 0; k < B * B; ++k)
            if (mask[k] & kMaskExcluded)
                for (int f = 0; f < M + 3; ++f) columns[f * stride + k] = 0.0f;
    return excluded;
}

/// Gathers block (bx, by) as structure-of-arrays, mirroring the image in at the border, and
/// marks the pixels it owns.
template <class H>
BMFR_HD void gatherBlock(const BlockFitOf<H>& a, int bx, int by, const BlockFitScratch& sc) {
    const BlockGrid& g = a.grid;
    const int B = g.blockSize, W = B * B, M = a.featureCount;
    float* n[3] = {sc.sources, sc.sources + W, sc.sources + 2 * W};
    float* p[3] = {sc.sources + 3 * W, sc.sources + 4 * W, sc.sources + 5 * W};
    float* z[3] = {sc.work + long(M) * W, sc.work + long(M + 1) * W, sc.work + long(M + 2) * W};
    const int ox = g.originX(bx), oy = g.originY(by);
    const bool inside = ox >= 0 && oy >= 0 && ox + B <= g.width && oy + B <= g.height;
    for (int ly = 0; ly < B; ++ly) {
        const int uy = oy + ly, iy = inside ? uy : mirrorIndex(uy, g.height);
        const bool rowInside = uy >= 0 && uy < g.height;
        for (int lx = 0; lx < B; ++lx) {
            const int ux = ox + lx, ix = inside ? ux : mirrorIndex(ux, g.width);
            const int k = ly * B + lx;
            const long idx = long(iy) * g.width + ix;
            for (int c = 0; c < 3; ++c) {
                n[c][k] = a.normal[3 * idx + c];
                p[c][k] = a.position[3 * idx + c];
                z[c][k] = a.color[3 * idx + c];
            }
            for (int e = 0; e < a.in.extraCount; ++e) {
                const float v = a.in.extras[e][idx];
                sc.sources[(6 + e) * long(W) + k] = std::isfinite(v) ? v : 0.0f;
            }
            sc.imageIndex[k] = rowInside && ux >= 0 && ux < g.width ? int(idx) : -1;
        }
    }
    buildFeatureColumns(a.features, M, {{n[0], n[1], n[2]}, {p[0], p[1], p[2]}, sc.sources + 6 * W},
                        W, sc.clean);
}

/// Fits block (bx, by). `solve(columns, M, rows, coeffs)` is a Householder solver with
/// solveHouseholder's contract (the backend picks its build of it).
template <class H, typename Solve>
BMFR_HD void fitBlock(const BlockFitOf<H>& a, int bx, int by, const BlockFitScratch& sc,
                      Solve&& solve) {
    const int W = a.grid.blockSize * a.grid.blockSize, M = a.featureCount;
    gatherBlock(a, bx, by, sc);
    for (int f = 0; f < M; ++f) {
        float* col = sc.clean + long(f) * W;
        if (a.features[f].scaled) {
            float mn = col[0], mx = col[0];
            for (int k = 1; k < W; ++k) {
                mn = col[k] < mn ? col[k] : mn;
                mx = mx < col[k] ? col[k] : mx;
            }
            for (int k = 0; k < W; ++k) col[k] = scaleFeature(col[k], mn, mx);
        }
        float* dst = sc.work + long(f) * W;
        const float* nz = a.noise + long(f) * W;
        for (int k = 0; k < W; ++k) dst[k] = col[k] + nz[k];
    }

    if (a.clampFireflies) {
        float* const z[3] = {sc.work + long(M) * W, sc.work + long(M + 1) * W,
                             sc.work + long(M + 2) * W};
        clampFireflies(a.grid.blockSize, z, sc.histogram, sc.mask,
                       [&](int k) { return blockFadeLength(a, bx, by, k); });
    }
    const int excluded = a.emitters.on ? excludeEmitterRows(a.grid, a.in, a.emitters, bx, by,
                                                            sc.work, M, W, sc.histogram, sc.mask)
                                       : 0;
    float coeffs[kMaxFeatures * 3];
    solve(sc.work, M, W, coeffs);

    // Weighted sum with the noise-free features; only owned pixels are written.
    for (int k = 0; k < 3 * W; ++k) sc.sum[k] = 0.0f;
    for (int f = 0; f < M; ++f) {
        const float* col = sc.clean + long(f) * W;
        for (int c = 0; c < 3; ++c) {
            const float w = coeffs[f * 3 + c];
            float* out = sc.sum + long(c) * W;
            for (int k = 0; k < W; ++k) out[k] += w * col[k];
        }
    }
    for (int k = 0; k < W; ++k) {
        const int idx = sc.imageIndex[k];
        if (idx < 0) continue;
        for (int c = 0; c < 3; ++c) {
            const float v = sc.sum[long(c) * W + k];
            a.fitted[3L * idx + c] = v > 0.0f ? v : 0.0f;
        }
        if (!a.emitters.on) continue;
        const bool emitter = excluded && maskEmitter(sc.mask[k]);
        if (emitter) store3(a.fitted, idx, emitterSample(a.in, idx, a.emitters.modes));
        if (a.emitters.bits) a.emitters.bits[idx] = emitter;
    }
}

} // namespace bmfr
