#include "backend/cpu/bmfr/cpu_bmfr_buffers.h"
#include "backend/cpu/modulation8.h"
#include "backend/cpu/reproject8.h"
#include "backend/cpu/taa_rows.h"
#include "filters/bmfr/history_change.h"

namespace bmfr::cpu {

using namespace simd;

namespace {

/// secondBlendWeight (temporal/blend_weights.h) for eight history lengths.
BMFR_SIMD_INLINE f8 secondBlendWeight8(f8 length, float minAlpha) {
    const f8 w = 1.0f / (length > 0.0f ? length : splat8(1.0f));
    return w > minAlpha ? w : splat8(minAlpha);
}

/// The accepted taps of pixels [i, i + n) less those across an emitter's edge: sameEmitterTaps
/// (filters/bmfr/) eight pixels at a time, from the tap classes the fit wrote.
template <class T>
BMFR_SIMD_INLINE i8 filterTaps(const FramePlanes<T>& pl, long i, int n, i8 accept,
                               const Taps8& taps) {
    const i8 own = loadBytes(pl.tapClass + i, n), bits = i8{} + int(kTapEmitter);
    for (int k = 0; k < 4; ++k) {
        const i8 has = (accept & (1 << k)) != 0;
        const i8 drop = ((tapBytes(taps, pl.prevTapClass, k) ^ own) & bits) != 0;
        accept = (has & drop) ? accept & ~(1 << k) : accept;
    }
    return accept;
}

/// Phase III of pixels [i, i + n) into the resolved row at x: accumulateFittedPixel
/// (filters/bmfr/accumulation_kernels.h) eight pixels at a time, after filterTaps. The history,
/// and the filtered accept masks, are stored only when `owned`.
template <class T>
BMFR_SIMD_INLINE void phase3Group(const FrameArgs& a, const FramePlanes<T>& pl, long i, int x,
                                  int n, bool owned, float* row, size_t pitch) {
    const BmfrSettings& s = a.s;
    const TemporalHistory& t = a.t;
    f8 c[3];
    for (int ch = 0; ch < 3; ++ch) c[ch] = load8(pl.fitted[ch] + i);
    i8 accept = loadBytes(pl.accept + i, n);
    const bool filter = a.filter.on();
    Footprint8 fp;
    Taps8 taps;
    const bool reads =
        t.hasHistory() && (filter || s.stages.secondAccumulation) && anyLane(accept != 0);
    if (reads) {
        fp = footprint8(load8(pl.previousPixel[0] + i), load8(pl.previousPixel[1] + i));
        taps = taps8(fp, t.width, t.height, accept != 0); // accepted taps are inside the image
    }
    if (filter) {
        if (reads) accept = filterTaps(pl, i, n, accept, taps);
        if (owned) storeBytes(pl.resolvedAccept + i, accept, n);
    }
    if (reads && s.stages.secondAccumulation && anyLane(accept != 0)) {
        const i8 use[4] = {(accept & 1) != 0, (accept & 2) != 0, (accept & 4) != 0,
                           (accept & 8) != 0};
        f8 old[3];
        const f8 total = weightedTaps<3>(
            taps, fp.weight, use,
            [&](int k, f8* v) {
                for (int ch = 0; ch < 3; ++ch) v[ch] = tapPlane(taps, pl.prevAccumulated[ch], k);
            },
            old);
        const i8 some = total > 0.0f;
        const f8 safe = some ? total : splat8(1.0f);
        f8 blend = secondBlendWeight8(load8(pl.noisy[3] + i), s.secondBlendAlpha);
        if (pl.changeTiles) {
            // adaptedBlendWeight; the eight pixels share a tile.
            const float lambda = pixelHistoryChange(pl.changeTiles, t.width, x, int(i / t.width));
            if (lambda > 0.0f) blend = blend + lambda * (1.0f - blend);
        }
        for (int ch = 0; ch < 3; ++ch) c[ch] = some ? lerp8(old[ch] / safe, c[ch], blend) : c[ch];
    }
    if (owned)
        for (int ch = 0; ch < 3; ++ch) storeFirst(pl.accumulated[ch] + i, c[ch], n);
    remodulate8(c, a.in, i, n, s.stages.demodulate || s.colorIsDemodulated, s.albedoEpsilon);
    storeResolved8(row, pitch, x, c, s.taa && t.hasHistory() ? taaSpaceOf(s) : TaaSpace::Linear);
}

/// Phase III of image row y into a resolved row. The halo rows a neighbouring task owns are
/// recomputed, not shared (owned = false).
template <class T>
BMFR_SIMD_INLINE void phase3Row(const FrameArgs& a, const FramePlanes<T>& pl, long y, bool owned,
                                float* row) {
    const int w = a.t.width;
    const size_t pitch = ResolvedRows::pitch(w);
    for (int x = 0; x < w; x += 8)
        phase3Group(a, pl, y * w + x, x, std::min(8, w - x), owned, row, pitch);
    finishResolvedRow(row, pitch, w);
}

BMFR_SIMD_DISPATCH(void, resolveRows, (const FrameArgs& a, long y0, long y1, float* ring),
                   (a, y0, y1, ring)) {
    const int w = a.t.width, h = a.t.height;
    const size_t pitch = ResolvedRows::pitch(w);
    const bool taa = a.s.taa && a.t.hasHistory();
    const float* history = a.b.output[1 - a.t.cur].data();
    float* out = a.b.output[a.t.cur].data();
    auto rows = [&] [[gnu::always_inline]] (const auto& pl) {
        const uint8_t* accept = a.filter.on() ? pl.resolvedAccept : pl.accept;
        // Phase III runs a row ahead of the TAA (and a halo row each side of [y0, y1) under
        // TAA), from one call site: each inlined copy of it is a large share of this file's
        // compile.
        ringRows(
            ring, w, h, y0, y1, taa,
            [&] [[gnu::always_inline]] (long y, float* row) {
                phase3Row(a, pl, y, y >= y0 && y < y1, row);
            },
            [&] [[gnu::always_inline]] (long y, const float* up, const float* mid,
                                        const float* down) {
                taaRow(up, mid, down, pitch, pl.previousPixel[0] + y * w,
                       pl.previousPixel[1] + y * w, history, out + 3 * y * w, w, h, taaBlend(a.s),
                       taa, a.s.taaSameSurface ? accept + y * w : nullptr,
                       taa ? taaSpaceOf(a.s) : TaaSpace::Linear);
            });
    };
    withFramePlanes<kIsa>(a.b, a.t.cur, a.s.halfHistory, rows);
}

/// tileHistoryChange (filters/bmfr/history_change.h) of tiles [k0, k1), a row of a tile eight
/// pixels at a time: the lanes are the spec's partial sums, added in its order. A lane without
/// history adds 0, which leaves a sum of non-negative values as it was.
BMFR_SIMD_DISPATCH(void, measureTiles,
                   (const float* sample, const float* history, int width, int height,
                    float threshold, float gain, long k0, long k1, float* tiles),
                   (sample, history, width, height, threshold, gain, k0, k1, tiles)) {
    static_assert(kChangeLanes == 8 && kChangeTile % 8 == 0);
    const int tilesX = changeTilesX(width);
    for (long k = k0; k < k1; ++k) {
        const int x0 = int(k % tilesX) * kChangeTile, y0 = int(k / tilesX) * kChangeTile;
        const int x1 = std::min(x0 + kChangeTile, width), y1 = std::min(y0 + kChangeTile, height);
        f8 sum{}, squares{}, past{};
        int n = 0;
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; x += 8) {
                const long i = long(y) * width + x;
                const f8 s = load8(sample + i), h = load8(history + i);
                const i8 with = (h >= 0.0f) & firstLanes(std::min(8, x1 - x));
                n += countLanes(with);
                sum += with ? s : f8{};
                squares += with ? s * s : f8{};
                past += with ? h : f8{};
            }
        float v[3][8];
        store8(v[0], sum), store8(v[1], squares), store8(v[2], past);
        storeTileChange(
            tiles, k,
            changeFromSums(n, laneTotal(v[0]), laneTotal(v[1]), laneTotal(v[2]), threshold, gain));
    }
}

} // namespace

void measureHistoryChange(const BmfrPassContext& ctx, Buffers& b) {
    const TemporalHistory& t = ctx.history;
    const float *sample = b.plane(b.change, 0), *history = b.plane(b.change, 1);
    const long tiles = long(b.changeTiles.size()) / kChangeTileValues;
    ctx.pool.parallelFor(tiles, 4, [&](long k0, long k1) {
        measureTiles(sample, history, t.width, t.height, ctx.settings.historyChangeThreshold,
                     ctx.settings.historyChangeGain, k0, k1, b.changeTiles.data());
    });
}

void resolve(const BmfrPassContext& ctx, Buffers& b, const TapFilter& filter) {
    const FrameArgs a{ctx.settings, ctx.input, ctx.history, b, filter};
    const long h = ctx.history.height, tasks = (h + kRingRowsPerTask - 1) / kRingRowsPerTask;
    ctx.pool.parallelFor(tasks, 1, [&](long k0, long k1) {
        float* ring = b.scratch[size_t(ThreadPool::currentThreadIndex())].rows.data();
        for (long k = k0; k < k1; ++k)
            resolveRows(a, k * kRingRowsPerTask, std::min(h, (k + 1) * kRingRowsPerTask), ring);
    });
}

} // namespace bmfr::cpu
