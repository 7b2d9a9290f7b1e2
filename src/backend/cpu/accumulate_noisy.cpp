#include "backend/cpu/fast_passes.h"
#include "backend/cpu/reproject8.h"
#include "core/simd.h"
#include "filters/bmfr/temporal_blend.h"
#include <atomic>

namespace bmfr::cpu {

using namespace simd;

namespace {

// One pixel record per load: the previous surface (32 bytes) and colour + length (16 bytes).
BMFR_SIMD_CLONES void accumulateRows(const FrameArgs& a, long y0, long y1, int64_t& bad,
                                     int64_t& lost) {
    const Settings& s = a.s;
    const FrameInput& in = a.in;
    const BmfrTimeline& t = a.t;
    const int w = t.width, h = t.height, cur = t.cur, prev = 1 - t.cur;
    const long last = long(w) * h - 1;
    const bool history = t.hasHistory;
    const bool demodulate = s.stages.demodulate && !s.colorIsDemodulated;
    const float eps = s.albedoEpsilon, limP = s.positionLimitSquared, limN = s.normalLimitSquared;
    const f8 limits = {limP, limP, limP, limP, limN, limN, limN, limN};
    const float* prevSurface = a.b.surface[prev].data();
    const float* prevNoisy = a.b.noisy[prev].data();
    float* surface = a.b.surface[cur].data();
    float* noisy = a.b.noisy[cur].data();

    auto pixel = [&](long i, const Reprojected& r) __attribute__((always_inline)) {
        const bool end = i == last;
        const f4 n = finiteOrZero4(loadXyz(in.normal.data + 3 * i, end), bad);
        const f4 p = finiteOrZero4(loadXyz(in.position.data + 3 * i, end), bad);
        const f4 alb = finiteOrZero4(loadXyz(in.albedo.data + 3 * i, end), bad);
        f4 c = finiteOrZero4(loadXyz(in.color.data + 3 * i, end), bad);
        const f4 g = alb > eps ? alb : splat4(eps);
        if (in.emission.data) {
            f4 e = finiteOrZero4(loadXyz(in.emission.data + 3 * i, end), bad);
            if (s.colorIsDemodulated) e = e / g;
            c = max4(c - e, f4{});
        }
        for (const ImageView& e : in.extras)
            if (!std::isfinite(e.data[i])) ++bad;
        if (demodulate) c = c / g;
        c[3] = 0.0f;
        store4(surface + 8 * i, p);
        store4(surface + 8 * i + 4, n);

        uint8_t accept = 0;
        float samples = 0.0f, blend = 1.0f;
        const Vec2 pp = history ? r.pixel : Vec2{-1e6f, -1e6f}; // far out: phase III skips it
        if (history && r.valid) {
            const BilinearFootprint& fp = r.footprint;
            const TapSet taps = tapSet(fp, w, h);
            const f8 pn = {p[0], p[1], p[2], 0.0f, n[0], n[1], n[2], 0.0f};
            f8 d[4];
            for (int k = 0; k < 4; ++k) {
                d[k] = load8(prevSurface + 8 * taps.index[k]) - pn;
                d[k] *= d[k];
            }
            // All four taps' squared distances at once: positions in lanes 0-3, normals 4-7.
            const f8 dist = sum3Of4(d[0], d[1], d[2], d[3]);
            const i8 pass = dist < limits;
            f4 old{};
            float total = 0.0f;
            for (int k = 0; k < 4; ++k) {
                const bool ok = taps.inside[k] && pass[k] && pass[k + 4];
                accept |= uint8_t(ok ? 1u << k : 0u);
                const float wt = ok ? fp.weight[k] : 0.0f; // a zero weight adds exactly nothing
                old += wt * load4(prevNoisy + 4 * taps.index[k]); // colour and length together
                total += wt;
            }
            if (total > 0.0f) {
                old = old / total;
                samples = old[3];
                blend = firstBlendWeight(samples, s.firstBlendAlpha);
                if (s.stages.firstAccumulation) c = lerp4(old, c, blend);
            }
        }
        if (history && accept == 0) ++lost;
        c[3] = blend < 1.0f ? float(nextHistoryLength(samples)) : 1.0f;
        store4(noisy + 4 * i, c);
        a.b.previousPixel[2 * i] = pp.x;
        a.b.previousPixel[2 * i + 1] = pp.y;
        a.b.acceptMask[i] = accept;
    };

    const Mat4& m = t.previousViewProjection;
    Reprojected lanes[8];
    for (long y = y0; y < y1; ++y) {
        int x = 0;
        if (history)
            for (; x + 8 <= w; x += 8) {
                const long i = y * w + x;
                reproject8(in.position.data + 3 * i, m, t.previousJitter, w, h, lanes);
                for (int l = 0; l < 8; ++l) pixel(i + l, lanes[l]);
            }
        for (; x < w; ++x) {
            const long i = y * w + x;
            int64_t counted = 0; // pixel() counts this pixel's bad values
            const f4 p = finiteOrZero4(loadXyz(in.position.data + 3 * i, i == last), counted);
            pixel(i, history ? reprojectOne({p[0], p[1], p[2]}, m, t.previousJitter, w, h)
                             : Reprojected{});
        }
    }
}

} // namespace

InputCounters accumulateNoisy(const BmfrPassContext& ctx, Buffers& b) {
    const FrameArgs a{ctx.settings, ctx.frame, ctx.timeline, b};
    std::atomic<int64_t> nonFinite{0}, discarded{0};
    ctx.pool.parallelFor(ctx.timeline.height, 8, [&](long y0, long y1) {
        int64_t bad = 0, lost = 0;
        accumulateRows(a, y0, y1, bad, lost);
        nonFinite += bad;
        discarded += lost;
    });
    return {nonFinite.load(), discarded.load()};
}

} // namespace bmfr::cpu
