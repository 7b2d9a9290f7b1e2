// SVGF's per-pixel kernels (Schied et al. 2017, section 4): temporal accumulation of colour and
// luminance moments, depth and its gradient, the variance estimate, and one a-trous level.
// BMFR_HD over packed arrays; every backend loops over these.
#pragma once
#include "core/color.h"
#include "filters/svgf/edge_stopping.h"
#include "temporal/blend_weights.h"
#include "temporal/history.h"
#include "temporal/pixel_input.h"
#include "temporal/reprojection.h"
#include <bmfr/filters/svgf_filter.h>

namespace bmfr {

/// One frame's SVGF buffers (packed; channels as noted), `prev*` from the previous slot.
struct SvgfFrame {
    InputPlanes in;
    InputModes modes;
    PreviousFrame previous;
    Mat4 viewProjection; ///< this frame's, for the depth
    DiscardLimits limits;
    float colorAlpha = 0.2f, momentsAlpha = 0.2f;
    int width = 0, height = 0;
    // History.
    const float *prevNormal = nullptr, *prevPosition = nullptr, *prevColor = nullptr;
    const float* prevMoments = nullptr; ///< 2: luminance, luminance squared
    const uint8_t* prevLength = nullptr;
    float *normal = nullptr, *position = nullptr, *color = nullptr;
    float* moments = nullptr;  ///< 2: this frame's accumulated moments (the variance reads them)
    uint8_t* length = nullptr; ///< 0 = no sample yet (fewer than 1 spp)
    // This frame.
    float* integrated = nullptr;    ///< accumulated colour before filtering
    float* depth = nullptr;         ///< clip-space w of the first hit
    float* depthGradient = nullptr; ///< 2: screen-space dz/dx, dz/dy
    float* previousPixel = nullptr; ///< 2
    uint8_t* accept = nullptr;
};

/// Reprojection (the shared discard test), colour and moments accumulation and depth of pixel i.
BMFR_HD void svgfAccumulatePixel(const SvgfFrame& f, long i, int64_t& bad) {
    const PixelInput px = readPixel(f.in, i, f.modes, bad);
    const Vec3 n = px.normal, p = px.position, c = px.color;
    const int w = f.width, h = f.height;
    store3(f.normal, i, n);
    store3(f.position, i, p);
    f.depth[i] = transformPoint(f.viewProjection, p).w;
    const bool present = !f.in.sampleMask || f.in.sampleMask[i] > 0.5f;

    uint8_t accept = 0;
    float samples = 0, oldM1 = 0, oldM2 = 0, total = 0;
    Vec3 oldColor{};
    PreviousSurface was;
    if (findPreviousSurface(f.in, i, int(i % w), int(i / w), p, n, f.previous, bad, was)) {
        const BilinearFootprint fp = bilinearFootprint(was.pixel);
        accept =
            acceptTaps(fp, was.position, was.normal, f.prevPosition, f.prevNormal, w, h, f.limits);
        // Taps that never had a sample carry no history.
        for (int t = 0; t < 4; ++t)
            if ((accept >> t & 1) && f.prevLength[long(tapY(fp, t)) * w + tapX(fp, t)] == 0)
                accept &= uint8_t(~(1u << t));
        total = gatherAccepted(fp, accept, w, [&](long j, float wt) {
            oldColor += wt * load3(f.prevColor, j);
            oldM1 += wt * f.prevMoments[2 * j];
            oldM2 += wt * f.prevMoments[2 * j + 1];
            samples += wt * float(f.prevLength[j]);
        });
    }
    f.previousPixel[2 * i] = was.pixel.x;
    f.previousPixel[2 * i + 1] = was.pixel.y;
    f.accept[i] = accept;
    Vec3 color{};
    float m1 = 0, m2 = 0;
    uint8_t length = 0;
    if (total > 0) {
        oldColor = oldColor / total;
        oldM1 /= total;
        oldM2 /= total;
        samples /= total;
    }
    if (!present) {
        // Fewer than 1 spp: keep the reprojected history unchanged.
        if (total > 0) {
            color = oldColor;
            m1 = oldM1;
            m2 = oldM2;
            length = uint8_t(std::lrintf(samples));
        }
    } else {
        const float l = luminance(c);
        const float wc = total > 0 ? firstBlendWeight(samples, f.colorAlpha) : 1.0f;
        const float wm = total > 0 ? firstBlendWeight(samples, f.momentsAlpha) : 1.0f;
        color = lerp(oldColor, c, wc);
        m1 = oldM1 + wm * (l - oldM1);
        m2 = oldM2 + wm * (l * l - oldM2);
        length = total > 0 ? nextHistoryLength(samples) : 1;
    }
    store3(f.integrated, i, color);
    f.length[i] = length;
    store3(f.color, i, color); // replaced by the feedback level later
    f.moments[2 * i] = m1;
    f.moments[2 * i + 1] = m2;
}

/// Screen-space depth gradient of pixel (x, y) by central differences (one-sided at the border).
BMFR_HD Vec2 svgfDepthGradient(const SvgfFrame& f, int x, int y) {
    const int w = f.width, h = f.height;
    const int xl = x > 0 ? x - 1 : x, xr = x + 1 < w ? x + 1 : x;
    const int yu = y > 0 ? y - 1 : y, yd = y + 1 < h ? y + 1 : y;
    const float* z = f.depth;
    return {xr > xl ? (z[long(y) * w + xr] - z[long(y) * w + xl]) / float(xr - xl) : 0.0f,
            yd > yu ? (z[long(yd) * w + x] - z[long(yu) * w + x]) / float(yd - yu) : 0.0f};
}

/// svgfDepthGradient of pixel (x, y) into f.depthGradient.
BMFR_HD void svgfDepthGradientPixel(const SvgfFrame& f, int x, int y) {
    const long i = long(y) * f.width + x;
    const Vec2 g = svgfDepthGradient(f, x, y);
    f.depthGradient[2 * i] = g.x;
    f.depthGradient[2 * i + 1] = g.y;
}

/// Variance of pixel (x, y) from its moments, or a 7x7 bilateral estimate while its history is
/// short. Writes colour + variance (4 floats) to filtered and the variance to `variance`.
BMFR_HD void svgfVariancePixel(const SvgfFrame& f, const SvgfSettings& s, int x, int y,
                               float* filtered, float* varianceOut) {
    const int w = f.width, h = f.height;
    const long i = long(y) * w + x;
    const uint8_t* len = f.length;
    float* out = filtered + 4 * i;
    const Vec3 c = load3(f.integrated, i);
    out[0] = c.x, out[1] = c.y, out[2] = c.z;
    float m1 = f.moments[2 * i], m2 = f.moments[2 * i + 1];
    float variance = m2 - m1 * m1;
    if (len[i] > 0 && len[i] < s.spatialVarianceFrames) {
        // Too little history: a 7x7 bilateral estimate of the moments instead.
        const Vec3 n0 = load3(f.normal, i);
        const float z0 = f.depth[i], l0 = luminance(c);
        const Vec2 grad{f.depthGradient[2 * i], f.depthGradient[2 * i + 1]};
        float sw = 0, s1 = 0, s2 = 0;
        for (int dy = -3; dy <= 3; ++dy)
            for (int dx = -3; dx <= 3; ++dx) {
                const int qx = x + dx, qy = y + dy;
                if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
                const long j = long(qy) * w + qx;
                if (len[j] == 0) continue;
                const float wq =
                    depthWeight(z0, f.depth[j], grad, float(dx), float(dy), s.phiDepth) *
                    normalWeight(n0, load3(f.normal, j), s.phiNormal) *
                    std::exp(-std::fabs(l0 - luminance(load3(f.integrated, j))) / 10.0f);
                sw += wq;
                s1 += wq * f.moments[2 * j];
                s2 += wq * f.moments[2 * j + 1];
            }
        if (sw > 0) {
            m1 = s1 / sw;
            m2 = s2 / sw;
        }
        // Boost the uncertain estimate of short histories (as the authors' code).
        variance = (m2 - m1 * m1) * 4.0f / float(len[i]);
    }
    out[3] = std::fmax(variance, 0.0f);
    varianceOut[i] = out[3];
}

/// One a-trous level's inputs: colour + variance (4 floats per pixel) in, the guides.
struct AtrousLevel {
    const float* in = nullptr;
    float* out = nullptr;
    const float* normal = nullptr;
    const float* depth = nullptr;
    const float* depthGradient = nullptr;
    const uint8_t* length = nullptr;
    int width = 0, height = 0;
    int step = 1; ///< tap spacing, pixels
};

/// One a-trous level at pixel (x, y). Pixels without a sample (history length 0) are neither
/// written from nor read into.
BMFR_HD void svgfAtrousPixel(const AtrousLevel& a, const SvgfSettings& s, int x, int y) {
    const int w = a.width, h = a.height, r = s.kernelRadius, step = a.step;
    const long i = long(y) * w + x;
    const float* c0 = a.in + 4 * i;
    float* o = a.out + 4 * i;
    if (a.length[i] == 0) {
        for (int k = 0; k < 4; ++k) o[k] = c0[k];
        return;
    }
    // 3x3 Gaussian prefilter of the variance for the luminance weight.
    float gv = 0, gw = 0;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            const int qx = x + dx, qy = y + dy;
            if (qx < 0 || qy < 0 || qx >= w || qy >= h || a.length[long(qy) * w + qx] == 0)
                continue;
            const float k = (dx == 0 ? 0.5f : 0.25f) * (dy == 0 ? 0.5f : 0.25f);
            gv += k * a.in[4 * (long(qy) * w + qx) + 3];
            gw += k;
        }
    const float variance = gw > 0 ? gv / gw : 0.0f;
    const float lumDenominator = luminanceDenominator(variance, s.phiLuminance);
    const Vec3 n0 = load3(a.normal, i);
    const float z0 = a.depth[i], l0 = luminance({c0[0], c0[1], c0[2]});
    const Vec2 grad{a.depthGradient[2 * i], a.depthGradient[2 * i + 1]};
    Vec3 sumC{c0[0], c0[1], c0[2]};
    float sumV = c0[3], sumW = 1.0f;
    const float centre = atrousTap(r, 0) * atrousTap(r, 0);
    for (int ky = -r; ky <= r; ++ky)
        for (int kx = -r; kx <= r; ++kx) {
            if (kx == 0 && ky == 0) continue;
            const int qx = x + kx * step, qy = y + ky * step;
            if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
            const long j = long(qy) * w + qx;
            if (a.length[j] == 0) continue;
            const float* cq = a.in + 4 * j;
            const float wn = normalWeight(n0, load3(a.normal, j), s.phiNormal);
            if (wn <= 0.0f) continue;
            const float arg = depthArgument(z0, a.depth[j], grad, float(kx * step),
                                            float(ky * step), s.phiDepth) +
                              std::fabs(l0 - luminance({cq[0], cq[1], cq[2]})) / lumDenominator;
            const float wgt = atrousTap(r, kx) * atrousTap(r, ky) / centre * wn * std::exp(-arg);
            sumC += wgt * Vec3{cq[0], cq[1], cq[2]};
            sumV += wgt * wgt * cq[3];
            sumW += wgt;
        }
    o[0] = sumC.x / sumW, o[1] = sumC.y / sumW, o[2] = sumC.z / sumW;
    o[3] = sumV / (sumW * sumW);
}

} // namespace bmfr
