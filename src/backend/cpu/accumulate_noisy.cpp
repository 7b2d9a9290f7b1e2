#include "backend/cpu/fast_passes.h"
#include "core/reprojection.h"
#include "core/simd.h"
#include "filters/bmfr/temporal_blend.h"
#include <atomic>

namespace bmfr::cpu {

using namespace simd;

namespace {

struct Phase1 {
    const Settings& s;
    const FrameInput& in;
    const BmfrTimeline& t;
    Buffers& b;
};

// One pixel record per load: the previous surface (32 bytes) and colour + length (16 bytes).
BMFR_SIMD_CLONES void accumulateRows(const Phase1& a, long y0, long y1, int64_t& bad,
                                     int64_t& lost) {
    const Settings& s = a.s;
    const FrameInput& in = a.in;
    const BmfrTimeline& t = a.t;
    const int w = t.width, h = t.height, cur = t.cur, prev = 1 - t.cur;
    const long last = long(w) * h - 1;
    const bool history = t.hasHistory;
    const bool demodulate = s.stages.demodulate && !s.colorIsDemodulated;
    const float eps = s.albedoEpsilon, limP = s.positionLimitSquared, limN = s.normalLimitSquared;
    const float* prevSurface = a.b.surface[prev].data();
    const float* prevNoisy = a.b.noisy[prev].data();
    float* surface = a.b.surface[cur].data();
    float* noisy = a.b.noisy[cur].data();

    for (long i = y0 * w; i < y1 * w; ++i) {
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

        Vec2 pp{-1e6f, -1e6f}; // out of every image: TAA and phase III skip it
        uint8_t accept = 0;
        float samples = 0.0f, blend = 1.0f;
        if (history && projectToPixel(t.previousViewProjection, {p[0], p[1], p[2]},
                                      t.previousJitter, w, h, pp)) {
            const BilinearFootprint fp = bilinearFootprint(pp);
            f4 old{};
            float total = 0.0f;
            for (int k = 0; k < 4; ++k) {
                const int x = tapX(fp, k), y = tapY(fp, k);
                if (x < 0 || y < 0 || x >= w || y >= h) continue;
                const long j = long(y) * w + x;
                const f4 dp = load4(prevSurface + 8 * j) - p;
                if (!(dot3(dp, dp) < limP)) continue;
                const f4 dn = load4(prevSurface + 8 * j + 4) - n;
                if (!(dot3(dn, dn) < limN)) continue;
                accept |= uint8_t(1u << k);
                old += fp.weight[k] * load4(prevNoisy + 4 * j); // colour and length together
                total += fp.weight[k];
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
    }
}

} // namespace

InputCounters accumulateNoisy(const BmfrPassContext& ctx, Buffers& b) {
    const Phase1 a{ctx.settings, ctx.frame, ctx.timeline, b};
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
