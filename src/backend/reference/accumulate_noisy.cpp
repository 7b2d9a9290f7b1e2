#include "backend/reference/reference_passes.h"
#include "core/reprojection.h"
#include "filters/bmfr/temporal_blend.h"
#include "filters/pixel_input.h"
#include <atomic>

namespace bmfr::reference {

InputCounters accumulateNoisy(const BmfrPassContext& ctx, Buffers& st) {
    const Settings& s = ctx.settings;
    const FrameInput& in = ctx.frame;
    const BmfrTimeline& t = ctx.timeline;
    const int w = t.width, h = t.height, cur = t.cur, prev = 1 - t.cur;
    const bool history = t.hasHistory;
    const DiscardLimits limits{s.positionLimitSquared, s.normalLimitSquared};
    std::atomic<int64_t> nonFinite{0}, discarded{0};

    ctx.pool.parallelFor(h, 4, [&](long y0, long y1) {
        int64_t bad = 0, lost = 0;
        for (long y = y0; y < y1; ++y) {
            for (int x = 0; x < w; ++x) {
                const long i = y * w + x;
                const PixelInput px = readPixel(in, i, s.colorIsDemodulated, s.stages.demodulate,
                                                s.albedoEpsilon, bad);
                const Vec3 n = px.normal, p = px.position;
                Vec3 c = px.color;
                store3(st.normal[cur].data(), i, n);
                store3(st.position[cur].data(), i, p);

                Vec2 pp{-1e6f, -1e6f}; // out of every image: TAA and phase III skip it
                uint8_t accept = 0;
                float samples = 0.0f, blend = 1.0f;
                Vec3 old{};
                if (history &&
                    projectToPixel(t.previousViewProjection, p, t.previousJitter, w, h, pp)) {
                    BilinearFootprint fp = bilinearFootprint(pp);
                    accept = acceptTaps(fp, p, n, st.position[prev].data(), st.normal[prev].data(),
                                        w, h, limits);
                    const float* prevColor = st.accumulatedNoisy[prev].data();
                    const uint8_t* prevLength = st.historyLength[prev].data();
                    float total = gatherAccepted(fp, accept, w, [&](long j, float wt) {
                        old += wt * load3(prevColor, j);
                        samples += wt * float(prevLength[j]);
                    });
                    if (total > 0.0f) {
                        old = old / total;
                        samples /= total;
                        blend = firstBlendWeight(samples, s.firstBlendAlpha);
                    }
                }
                if (history && accept == 0) ++lost;
                st.historyLength[cur].data()[i] = blend < 1.0f ? nextHistoryLength(samples) : 1;
                if (s.stages.firstAccumulation && blend < 1.0f) c = lerp(old, c, blend);
                store3(st.accumulatedNoisy[cur].data(), i, c);
                st.previousPixel.data()[2 * i] = pp.x;
                st.previousPixel.data()[2 * i + 1] = pp.y;
                st.acceptMask.data()[i] = accept;
            }
        }
        nonFinite += bad;
        discarded += lost;
    });
    return {nonFinite.load(), discarded.load()};
}

} // namespace bmfr::reference
