#include "backend/cpu/bmfr/cpu_bmfr_buffers.h"
#include "backend/cpu/pixel_input8.h"
#include "backend/cpu/reproject8.h"
#include "backend/cpu/simd.h"
#include "filters/bmfr/emitter_exclusion.h"
#include "filters/bmfr/history_change.h"
#include <cmath>

namespace bmfr::cpu {

using namespace simd;

namespace {

/// recordHistoryChange (filters/bmfr/history_change.h) for eight pixels.
template <class T>
BMFR_SIMD_INLINE void recordHistoryChange8(const FramePlanes<T>& pl, long i, int n,
                                           const f8* sample, const f8* history, i8 reprojected) {
    const f8 s = luminance8(sample), h = luminance8(history);
    storeFirst(pl.change[0] + i, s > 0.0f ? s : f8{}, n);
    storeFirst(pl.change[1] + i, reprojected ? (h > 0.0f ? h : f8{}) : splat8(-1.0f), n);
}

/// phaseOneEmitterTaps (filters/bmfr/emitter_exclusion.h) for tap k of eight pixels whose
/// samples have luminance `sample`: the lanes of `ok` whose tap was an emitter pixel and is more
/// than 1 / kEmitterTapShare times as bright.
template <class T>
BMFR_SIMD_INLINE i8 droppedEmitterTap(const FramePlanes<T>& pl, const Taps8& taps, int k, i8 ok,
                                      f8 sample) {
    const i8 emitter = ok & ((tapBytes(taps, pl.prevTapClass, k) & int(kTapEmitter)) != 0);
    if (!anyLane(emitter)) return i8{};
    f8 tap[3];
    for (int c = 0; c < 3; ++c) tap[c] = tapPlane(taps, pl.prevNoisy[c], k);
    return emitter & (sample < kEmitterTapShare * luminance8(tap));
}

/// Phase I of the n <= 8 pixels from column x of row y: accumulateNoisyPixel
/// (filters/bmfr/accumulation_kernels.h) eight pixels at a time.
template <class T>
BMFR_SIMD_INLINE void accumulateGroup(const FrameArgs& a, const FramePlanes<T>& pl, int x, int y,
                                      int n, int64_t& bad, int64_t& lost) {
    const long i = long(y) * a.t.width + x;
    const BmfrSettings& s = a.s;
    const TemporalHistory& t = a.t;
    const InputModes modes{s.colorIsDemodulated, s.stages.demodulate, s.albedoEpsilon};
    const Inputs8 px = readInputs8(a.in, modes, i, n, bad);
    for (int c = 0; c < 3; ++c) {
        storeFirst(pl.position[c] + i, px.position[c], n);
        storeFirst(pl.normal[c] + i, px.normal[c], n);
    }
    f8 color[3] = {px.color[0], px.color[1], px.color[2]};
    f8 length = splat8(1.0f), history[3] = {};
    i8 reprojected{};
    i8 accept{};
    Surface8 was;
    const i8 valid =
        previousSurface8(a.in, t.previous, i, x, y, n, px.position, px.normal, bad, was);
    if (t.hasHistory()) {
        const Footprint8 fp = footprint8(was.px, was.py);
        const Taps8 taps = taps8(fp, t.width, t.height, valid & firstLanes(n));
        const f8 limP = splat8(s.positionLimitSquared), limN = splat8(s.normalLimitSquared);
        const f8 lum = a.phaseOneEmitterTaps ? luminance8(px.color) : f8{};
        // Phase I's shadow-edge taps (accumulateNoisyPixel): the pixels' lit classes.
        const i8 lit = a.phaseOneVisibility ? loadFirst(a.phaseOneVisibility + i, n) > 0.0f : i8{};
        i8 ok[4];
        forTaps(taps, [&] [[gnu::always_inline]] () {
            for (int k = 0; k < 4; ++k) {
                f8 d[6];
                for (int c = 0; c < 3; ++c) {
                    d[c] = tapPlane(taps, pl.prevPosition[c], k) - was.position[c];
                    d[3 + c] = tapPlane(taps, pl.prevNormal[c], k) - was.normal[c];
                }
                // dot(d, d) in Vec3's order, so the decisions match the reference bit for bit.
                const f8 dp = (d[0] * d[0] + d[1] * d[1]) + d[2] * d[2];
                const f8 dn = (d[3] * d[3] + d[4] * d[4]) + d[5] * d[5];
                ok[k] = taps.inside[k] & (dp < limP) & (dn < limN);
                if (a.phaseOneEmitterTaps) ok[k] &= ~droppedEmitterTap(pl, taps, k, ok[k], lum);
                if (a.phaseOneVisibility)
                    ok[k] &= ~(((tapBytes(taps, pl.prevTapClass, k) & int(kTapLit)) != 0) ^ lit);
                accept |= ok[k] & (1 << k);
            }
        });
        f8 old[4]; // colour and history length
        const f8 total = weightedTaps<4>(
            taps, fp.weight, ok,
            [&](int k, f8* v) {
                for (int c = 0; c < 4; ++c) v[c] = tapPlane(taps, pl.prevNoisy[c], k);
            },
            old);
        const f8 safe = total > 0.0f ? total : splat8(1.0f);
        f8 samples = old[3] / safe;
        if (pl.changeTiles) {
            // The eight pixels share a tile (kChangeTile is a multiple of 8).
            const float lambda = pixelHistoryChange(pl.changeTiles, t.width, x, y);
            if (lambda > 0.0f) {
                const f8 cap = splat8(shortenedHistory(255.0f, lambda, s.secondBlendAlpha));
                samples = samples < cap ? samples : cap;
            }
        }
        const f8 blend = firstBlendWeight8(samples, s.firstBlendAlpha);
        const i8 blended = (total > 0.0f) & (blend < 1.0f);
        if (s.stages.firstAccumulation)
            for (int c = 0; c < 3; ++c)
                color[c] = blended ? lerp8(old[c] / safe, color[c], blend) : color[c];
        length = blended ? nextHistoryLength8(samples) : length;
        reprojected = total > 0.0f;
        for (int c = 0; c < 3; ++c) history[c] = old[c] / safe;
        lost += countLanes((accept == 0) & firstLanes(n));
    }
    if (pl.change[0]) recordHistoryChange8(pl, i, n, px.color, history, reprojected);
    for (int c = 0; c < 3; ++c) storeFirst(pl.noisy[c] + i, color[c], n);
    storeFirst(pl.noisy[3] + i, length, n);
    storeFirst(pl.previousPixel[0] + i, was.px, n);
    storeFirst(pl.previousPixel[1] + i, was.py, n);
    storeBytes(pl.accept + i, accept, n);
}

BMFR_SIMD_DISPATCH(void, accumulateRows,
                   (const FrameArgs& a, long y0, long y1, int64_t& bad, int64_t& lost),
                   (a, y0, y1, bad, lost)) {
    const int w = a.t.width;
    auto rows = [&] [[gnu::always_inline]] (const auto& pl) {
        for (long y = y0; y < y1; ++y)
            for (int x = 0; x < w; x += 8)
                accumulateGroup(a, pl, x, int(y), std::min(8, w - x), bad, lost);
    };
    withFramePlanes<kIsa>(a.b, a.t.cur, a.s.halfHistory, rows);
}

} // namespace

void accumulateNoisyRows(const FrameArgs& a, long y0, long y1, PassCounters& counters) {
    accumulateRows(a, y0, y1, counters.nonFinite, counters.discarded);
}

} // namespace bmfr::cpu
