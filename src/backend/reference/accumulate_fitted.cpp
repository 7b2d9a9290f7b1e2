#include "backend/reference/reference_passes.h"
#include "core/reprojection.h"
#include "filters/bmfr/temporal_blend.h"
#include "filters/pixel_input.h"

namespace bmfr::reference {

void accumulateFitted(const BmfrPassContext& ctx, Buffers& st) {
    const Settings& s = ctx.settings;
    const BmfrTimeline& t = ctx.timeline;
    const int w = t.width, cur = t.cur, prev = 1 - t.cur;
    const bool accumulate = t.hasHistory && s.stages.secondAccumulation;
    const bool remodulate = s.stages.demodulate || s.colorIsDemodulated;
    const float* albedo = ctx.frame.albedo.data;
    const float* emission = ctx.frame.emission.data;

    ctx.pool.parallelFor(t.height, 4, [&](long y0, long y1) {
        for (long i = y0 * w; i < y1 * w; ++i) {
            Vec3 c = load3(st.fitted.data(), i);
            const uint8_t accept = st.acceptMask.data()[i];
            if (accumulate && accept) {
                // Reuses phase I's reprojection and discard decisions (no second test).
                Vec2 pp{st.previousPixel.data()[2 * i], st.previousPixel.data()[2 * i + 1]};
                const float* hist = st.accumulatedFitted[prev].data();
                Vec3 old{};
                float total = gatherAccepted(bilinearFootprint(pp), accept, w,
                                             [&](long j, float wt) { old += wt * load3(hist, j); });
                if (total > 0.0f) {
                    float blend =
                        secondBlendWeight(st.historyLength[cur].data()[i], s.secondBlendAlpha);
                    c = lerp(old / total, c, blend);
                }
            }
            store3(st.accumulatedFitted[cur].data(), i, c);
            if (remodulate) c = c * guardAlbedo(load3(albedo, i), s.albedoEpsilon);
            if (emission) {
                Vec3 e = load3(emission, i);
                if (std::isfinite(e.x) && std::isfinite(e.y) && std::isfinite(e.z)) c = c + e;
            }
            store3(st.remodulated.data(), i, c);
        }
    });
}

} // namespace bmfr::reference
