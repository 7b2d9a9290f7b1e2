#include "backend/cpu/svgf_passes.h"
#include "core/color.h"
#include "core/reprojection.h"
#include "filters/bmfr/temporal_blend.h"
#include "filters/pixel_input.h"
#include "filters/svgf/edge_stopping.h"
#include <atomic>

namespace bmfr::cpu {

int64_t svgfAccumulate(const SvgfPassContext& ctx) {
    const SvgfSettings& s = ctx.settings;
    const FrameInput& in = ctx.frame;
    SvgfState& st = ctx.state;
    const int w = st.width, h = st.height, cur = st.cur, prev = 1 - st.cur;
    const DiscardLimits limits{s.positionLimitSquared, s.normalLimitSquared};
    std::atomic<int64_t> nonFinite{0};
    ctx.pool.parallelFor(h, 4, [&](long y0, long y1) {
        int64_t bad = 0;
        for (long i = y0 * w; i < y1 * w; ++i) {
            const PixelInput px =
                readPixel(in, i, s.colorIsDemodulated, true, s.albedoEpsilon, bad);
            const Vec3 n = px.normal, p = px.position, c = px.color;
            store3(st.normal[cur].data(), i, n);
            store3(st.position[cur].data(), i, p);
            st.depth.data()[i] = transformPoint(in.viewProjection, p).w;
            const bool present = !in.sampleMask.data || in.sampleMask.data[i] > 0.5f;

            Vec2 pp{-1e6f, -1e6f};
            uint8_t accept = 0;
            float samples = 0;
            Vec3 oldColor{};
            float oldM1 = 0, oldM2 = 0, total = 0;
            if (st.hasHistory &&
                projectToPixel(st.previousViewProjection, p, st.previousJitter, w, h, pp)) {
                BilinearFootprint fp = bilinearFootprint(pp);
                accept = acceptTaps(fp, p, n, st.position[prev].data(), st.normal[prev].data(), w,
                                    h, limits);
                // Taps that never had a sample carry no history.
                for (int t = 0; t < 4; ++t)
                    if ((accept >> t & 1) &&
                        st.historyLength[prev].data()[long(tapY(fp, t)) * w + tapX(fp, t)] == 0)
                        accept &= uint8_t(~(1u << t));
                total = gatherAccepted(fp, accept, w, [&](long j, float wt) {
                    oldColor += wt * load3(st.color[prev].data(), j);
                    oldM1 += wt * st.moments[prev].data()[2 * j];
                    oldM2 += wt * st.moments[prev].data()[2 * j + 1];
                    samples += wt * float(st.historyLength[prev].data()[j]);
                });
            }
            st.previousPixel.data()[2 * i] = pp.x, st.previousPixel.data()[2 * i + 1] = pp.y;
            st.accept.data()[i] = accept;
            Vec3 color{};
            float m1 = 0, m2 = 0;
            uint8_t length = 0;
            if (total > 0)
                oldColor = oldColor / total, oldM1 /= total, oldM2 /= total, samples /= total;
            if (!present) {
                // Fewer than 1 spp: keep the reprojected history unchanged.
                if (total > 0)
                    color = oldColor, m1 = oldM1, m2 = oldM2,
                    length = uint8_t(std::lrintf(samples));
            } else {
                const float l = luminance(c);
                const float wc = total > 0 ? firstBlendWeight(samples, s.colorAlpha) : 1.0f;
                const float wm = total > 0 ? firstBlendWeight(samples, s.momentsAlpha) : 1.0f;
                color = lerp(oldColor, c, wc);
                m1 = oldM1 + wm * (l - oldM1);
                m2 = oldM2 + wm * (l * l - oldM2);
                length = total > 0 ? nextHistoryLength(samples) : 1;
            }
            store3(st.integrated.data(), i, color);
            st.integratedMoments.data()[2 * i] = m1, st.integratedMoments.data()[2 * i + 1] = m2;
            st.historyLength[cur].data()[i] = length;
            store3(st.color[cur].data(), i, color); // replaced by the feedback level later
            st.moments[cur].data()[2 * i] = m1, st.moments[cur].data()[2 * i + 1] = m2;
        }
        nonFinite += bad;
    });
    // Screen-space depth gradient by central differences (one-sided at the border).
    ctx.pool.parallelFor(h, 4, [&](long y0, long y1) {
        for (long y = y0; y < y1; ++y)
            for (int x = 0; x < w; ++x) {
                auto z = [&](int xx, long yy) { return st.depth.data()[yy * w + xx]; };
                const int xl = x > 0 ? x - 1 : x, xr = x + 1 < w ? x + 1 : x;
                const long yu = y > 0 ? y - 1 : y, yd = y + 1 < h ? y + 1 : y;
                const long i = y * w + x;
                st.depthGradient.data()[2 * i] =
                    xr > xl ? (z(xr, y) - z(xl, y)) / float(xr - xl) : 0.0f;
                st.depthGradient.data()[2 * i + 1] =
                    yd > yu ? (z(x, yd) - z(x, yu)) / float(yd - yu) : 0.0f;
            }
    });
    return nonFinite.load();
}

void svgfEstimateVariance(const SvgfPassContext& ctx) {
    const SvgfSettings& s = ctx.settings;
    SvgfState& st = ctx.state;
    const int w = st.width, h = st.height;
    const uint8_t* len = st.historyLength[st.cur].data();
    const float* normal = st.normal[st.cur].data();
    ctx.pool.parallelFor(h, 4, [&](long y0, long y1) {
        for (long y = y0; y < y1; ++y)
            for (int x = 0; x < w; ++x) {
                const long i = y * w + x;
                float* out = st.filtered[0].data() + 4 * i;
                const Vec3 c = load3(st.integrated.data(), i);
                out[0] = c.x, out[1] = c.y, out[2] = c.z;
                float m1 = st.integratedMoments.data()[2 * i],
                      m2 = st.integratedMoments.data()[2 * i + 1];
                float variance = m2 - m1 * m1;
                if (len[i] > 0 && len[i] < s.spatialVarianceFrames) {
                    // Too little history: a 7x7 bilateral estimate of the moments instead.
                    const Vec3 n0 = load3(normal, i);
                    const float z0 = st.depth.data()[i], l0 = luminance(c);
                    const Vec2 grad{st.depthGradient.data()[2 * i],
                                    st.depthGradient.data()[2 * i + 1]};
                    float sw = 0, s1 = 0, s2 = 0;
                    for (int dy = -3; dy <= 3; ++dy)
                        for (int dx = -3; dx <= 3; ++dx) {
                            const int qx = x + dx;
                            const long qy = y + dy;
                            if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
                            const long j = qy * w + qx;
                            if (len[j] == 0) continue;
                            const float wq =
                                depthWeight(z0, st.depth.data()[j], grad, float(dx), float(dy),
                                            s.phiDepth) *
                                normalWeight(n0, load3(normal, j), s.phiNormal) *
                                std::exp(
                                    -std::fabs(l0 - luminance(load3(st.integrated.data(), j))) /
                                    10.0f);
                            sw += wq, s1 += wq * st.integratedMoments.data()[2 * j],
                                s2 += wq * st.integratedMoments.data()[2 * j + 1];
                        }
                    if (sw > 0) m1 = s1 / sw, m2 = s2 / sw;
                    // Boost the uncertain estimate of short histories (as the authors' code).
                    variance = (m2 - m1 * m1) * 4.0f / float(len[i]);
                }
                out[3] = std::fmax(variance, 0.0f);
                st.variance.data()[i] = out[3];
            }
    });
}

void svgfAtrous(ThreadPool& pool, const SvgfSettings& s, const ImageF& in, ImageF& out,
                const ImageF& normal, const ImageF& depth, const ImageF& depthGradient,
                const ImageU8& historyLength, int step) {
    const int w = in.width, h = in.height, r = s.kernelRadius;
    const uint8_t* len = historyLength.data();
    pool.parallelFor(h, 4, [&](long y0, long y1) {
        for (long y = y0; y < y1; ++y)
            for (int x = 0; x < w; ++x) {
                const long i = y * w + x;
                const float* c0 = in.data() + 4 * i;
                float* o = out.data() + 4 * i;
                if (len[i] == 0) {
                    for (int k = 0; k < 4; ++k) o[k] = c0[k];
                    continue;
                }
                // 3x3 Gaussian prefilter of the variance for the luminance weight.
                float gv = 0, gw = 0;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        const int qx = x + dx;
                        const long qy = y + dy;
                        if (qx < 0 || qy < 0 || qx >= w || qy >= h || len[qy * w + qx] == 0)
                            continue;
                        const float k = (dx == 0 ? 0.5f : 0.25f) * (dy == 0 ? 0.5f : 0.25f);
                        gv += k * in.data()[4 * (qy * w + qx) + 3], gw += k;
                    }
                const float variance = gw > 0 ? gv / gw : 0.0f;
                const float lumDenominator = luminanceDenominator(variance, s.phiLuminance);
                const Vec3 n0 = load3(normal.data(), i);
                const float z0 = depth.data()[i], l0 = luminance({c0[0], c0[1], c0[2]});
                const Vec2 grad{depthGradient.data()[2 * i], depthGradient.data()[2 * i + 1]};
                Vec3 sumC{c0[0], c0[1], c0[2]};
                float sumV = c0[3], sumW = 1.0f;
                const float centre = atrousTap(r, 0) * atrousTap(r, 0);
                for (int ky = -r; ky <= r; ++ky)
                    for (int kx = -r; kx <= r; ++kx) {
                        if (kx == 0 && ky == 0) continue;
                        const int qx = x + kx * step;
                        const long qy = y + ky * step;
                        if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
                        const long j = qy * w + qx;
                        if (len[j] == 0) continue;
                        const float* cq = in.data() + 4 * j;
                        const float wn = normalWeight(n0, load3(normal.data(), j), s.phiNormal);
                        if (wn <= 0.0f) continue;
                        const float arg =
                            depthArgument(z0, depth.data()[j], grad, float(kx * step),
                                          float(ky * step), s.phiDepth) +
                            std::fabs(l0 - luminance({cq[0], cq[1], cq[2]})) / lumDenominator;
                        const float wgt =
                            atrousTap(r, kx) * atrousTap(r, ky) / centre * wn * std::exp(-arg);
                        sumC += wgt * Vec3{cq[0], cq[1], cq[2]};
                        sumV += wgt * wgt * cq[3];
                        sumW += wgt;
                    }
                o[0] = sumC.x / sumW, o[1] = sumC.y / sumW, o[2] = sumC.z / sumW;
                o[3] = sumV / (sumW * sumW);
            }
    });
}

} // namespace bmfr::cpu
