#include "backend/cpu/bmfr/cpu_bmfr_buffers.h"
#include "core/stopwatch.h"
#include "filters/bmfr/fitting_kernel.h"
#include <algorithm>
#include <atomic>

namespace bmfr::cpu {

namespace {

using Clock = Stopwatch::Clock;

/// Image rows [first, last) that block row `by` owns.
struct RowSpan {
    int first, last;
    bool empty() const { return first >= last; }
};
RowSpan ownedRows(const BlockGrid& g, int by) {
    const OwnedRect r = ownedRect(g, 0, by);
    return {r.y0, r.y1};
}

/// Marks the rows some block row reads through mirroring but does not own. Only the first and
/// the last rows of blocks mirror, and only images shorter than a block mirror more than
/// once; either way the marked rows are at most a block's height at each edge.
void markEarlyRows(const BlockGrid& g, std::vector<uint8_t>& early) {
    std::fill(early.begin(), early.end(), uint8_t{0});
    for (int by = 0; by < g.blocksY; ++by) {
        const RowSpan own = ownedRows(g, by);
        if (own.empty()) continue;
        const int oy = g.originY(by);
        for (int uy = oy; uy < oy + g.blockSize; ++uy) {
            const int y = mirrorIndex(uy, g.height);
            if (y < own.first || y >= own.last) early[size_t(y)] = 1;
        }
    }
}

/// Runs phase I over the rows of [first, last) whose early flag equals `early`.
void accumulateRuns(const FrameArgs& a, const std::vector<uint8_t>& flags, bool early, int first,
                    int last, PassCounters& c) {
    int y = first;
    while (y < last) {
        if (bool(flags[size_t(y)]) != early) {
            ++y;
            continue;
        }
        int end = y + 1;
        while (end < last && bool(flags[size_t(end)]) == early) ++end;
        accumulateNoisyRows(a, y, end, c);
        y = end;
    }
}

} // namespace

PassCounters accumulateAndFit(const BmfrPassContext& ctx, Buffers& b, StageSplit& split) {
    const TemporalHistory& t = ctx.history;
    FrameArgs a{ctx.settings, ctx.input, t, b};
    a.phaseOneEmitterTaps = t.hasHistory() &&
                            emitterExclusion(ctx.settings, ctx.input, nullptr).on &&
                            b.emitterPixels[1 - t.cur] > 0;
    if (t.hasHistory()) a.phaseOneVisibility = tapVisibility(ctx);
    const BlockGrid g = makeBlockGrid(t.width, t.height, ctx.settings.blockSize, t.frameIndex);
    const bool fitting = ctx.settings.stages.fitting;
    Stopwatch wallClock;
    std::atomic<int64_t> nonFinite{0}, discarded{0}, accumulateNs{0}, fitNs{0};
    auto ns = Stopwatch::nanoseconds;
    auto count = [&](const PassCounters& c) {
        nonFinite += c.nonFinite;
        discarded += c.discarded;
    };

    if (fitting) {
        markEarlyRows(g, b.earlyRow);
        ctx.pool.parallelFor(t.height, 8, [&](long y0, long y1) {
            PassCounters c;
            const auto t0 = Clock::now();
            accumulateRuns(a, b.earlyRow, true, int(y0), int(y1), c);
            accumulateNs += ns(t0, Clock::now());
            count(c);
        });
    } else {
        std::fill(b.earlyRow.begin(), b.earlyRow.end(), uint8_t{0});
    }
    ctx.pool.parallelFor(g.blocksY, 1, [&](long by0, long by1) {
        Scratch& sc = b.scratch[size_t(ThreadPool::currentThreadIndex())];
        for (long by = by0; by < by1; ++by) {
            const RowSpan own = ownedRows(g, int(by));
            if (own.empty()) continue;
            PassCounters c;
            const auto t0 = Clock::now();
            accumulateRuns(a, b.earlyRow, false, own.first, own.last, c);
            const auto t1 = Clock::now();
            if (fitting) {
                fitBlockRow(ctx, b, g, int(by), sc);
            } else {
                const size_t from = size_t(own.first) * size_t(t.width);
                const size_t pixels = size_t(own.last - own.first) * size_t(t.width);
                for (int ch = 0; ch < 3; ++ch)
                    b.noisy[t.cur].copyOut(ch, from, pixels, b.plane(b.fitted, ch) + from);
                // The fit writes the tap classes; without it they are the lit classes alone.
                if (!b.tapClass[t.cur].empty())
                    litClasses(tapVisibility(ctx), long(from), long(pixels),
                               b.tapClass[t.cur].data());
            }
            accumulateNs += ns(t0, t1);
            fitNs += ns(t1, Clock::now());
            count(c);
        }
    });

    const double wall = wallClock.elapsed();
    const double acc = double(accumulateNs.load()), fit = double(fitNs.load());
    split.accumulateMs = acc + fit > 0.0 ? wall * acc / (acc + fit) : wall;
    split.fitMs = wall - split.accumulateMs;
    return {nonFinite.load(), discarded.load()};
}

} // namespace bmfr::cpu
