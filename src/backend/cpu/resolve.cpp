#include "backend/cpu/fast_passes.h"
#include "backend/cpu/taa_rows.h"
#include "filters/bmfr/temporal_blend.h"

namespace bmfr::cpu {

using namespace simd;

namespace {

/// Phase III of row y into a resolved row: second accumulation with phase I's taps,
/// re-modulation, emission. The history is written only for rows this task owns (`owned`);
/// the halo rows a neighbouring task owns are recomputed, not shared.
BMFR_SIMD_INLINE void phase3Row(const FrameArgs& a, long y, bool owned, float* row) {
    const Settings& s = a.s;
    const BmfrTimeline& t = a.t;
    const int w = t.width, cur = t.cur, prev = 1 - t.cur;
    const long last = long(w) * t.height - 1;
    const bool accumulate = t.hasHistory && s.stages.secondAccumulation;
    const bool remodulate = s.stages.demodulate || s.colorIsDemodulated;
    const float eps = s.albedoEpsilon;
    const float* hist = a.b.accumulatedFitted[prev].data();
    const float* noisy = a.b.noisy[cur].data();
    float* accumulated = a.b.accumulatedFitted[cur].data();
    for (int x = 0; x < w; ++x) {
        const long i = y * w + x;
        f4 c = load4(a.b.fitted.data() + 4 * i);
        const uint8_t accept = a.b.acceptMask[i];
        if (accumulate && accept) {
            const BilinearFootprint fp =
                bilinearFootprint({a.b.previousPixel[2 * i], a.b.previousPixel[2 * i + 1]});
            const long j = long(fp.y0) * w + fp.x0; // accepted taps are in the image
            const long offset[4] = {0, 1, w, long(w) + 1};
            f4 old{};
            float total = 0.0f;
            for (int k = 0; k < 4; ++k) {
                const float wt = accept & (1u << k) ? fp.weight[k] : 0.0f;
                const long tap = accept & (1u << k) ? j + offset[k] : 0;
                old += wt * load4(hist + 4 * tap);
                total += wt;
            }
            if (total > 0.0f) {
                const uint8_t length = uint8_t(noisy[4 * i + 3]);
                c = lerp4(old / total, c, secondBlendWeight(length, s.secondBlendAlpha));
            }
        }
        if (owned) store4(accumulated + 4 * i, c);
        const bool end = i == last;
        if (remodulate) {
            const f4 alb = loadXyz(a.in.albedo.data + 3 * i, end);
            c = c * ((alb - alb) == 0.0f && alb > eps ? alb : splat4(eps));
        }
        if (a.in.emission.data) {
            const f4 e = loadXyz(a.in.emission.data + 3 * i, end);
            if (finiteXyz(e)) c = c + e;
        }
        c[3] = 0.0f;
        storeResolved(row + 8 * x, c);
    }
}

constexpr int kRowsPerTask = 32;

BMFR_SIMD_CLONES void resolveRows(const FrameArgs& a, long y0, long y1, float* ring) {
    const int w = a.t.width, h = a.t.height;
    const bool taa = a.s.stages.taa && a.t.hasHistory;
    const float* history = a.b.output[1 - a.t.cur].data();
    float* out = a.b.output[a.t.cur].data();
    auto row = [&](long y) { return ring + size_t(y % 3) * size_t(w) * 8; };
    if (taa && y0 > 0) phase3Row(a, y0 - 1, false, row(y0 - 1));
    phase3Row(a, y0, true, row(y0));
    for (long y = y0; y < y1; ++y) {
        if (y + 1 < h && (taa || y + 1 < y1)) phase3Row(a, y + 1, y + 1 < y1, row(y + 1));
        const float* mid = row(y);
        const float* up = y > 0 ? row(y - 1) : mid;
        const float* down = y + 1 < h ? row(y + 1) : mid;
        taaRow(up, mid, down, history, a.b.previousPixel.data() + 2 * y * w, out + 3 * y * w, w, h,
               a.s.taaBlendAlpha, taa);
    }
}

} // namespace

void resolve(const BmfrPassContext& ctx, Buffers& b) {
    const FrameArgs a{ctx.settings, ctx.frame, ctx.timeline, b};
    const long h = ctx.timeline.height, tasks = (h + kRowsPerTask - 1) / kRowsPerTask;
    ctx.pool.parallelFor(tasks, 1, [&](long k0, long k1) {
        float* ring = b.scratch[size_t(ThreadPool::currentThreadIndex())].rows.data();
        for (long k = k0; k < k1; ++k)
            resolveRows(a, k * kRowsPerTask, std::min(h, (k + 1) * kRowsPerTask), ring);
    });
}

} // namespace bmfr::cpu
