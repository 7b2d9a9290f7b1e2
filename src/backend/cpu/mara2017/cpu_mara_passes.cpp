// The CPU backend's Mara 2017: the reference stages, except the input pass, stages 3 and 8 and
// the composition, eight pixels at a time (cpu_mara_temporal.h), and stage 5, whose two 1D min
// passes over 2R + 1 pixels (129 at 1280 wide) become van Herk / Gil-Werman running minima: three
// comparisons per pixel whatever R, with the same minima bit for bit, the column pass eight
// columns at a time; and stages 4, 6 and 7
// (cpu_mara_rows.h) and 9 and 10 (cpu_mara_glossy.h), eight pixels at a time.
#include "backend/backend_registry.h"
#include "backend/cpu/mara2017/cpu_mara_glossy.h"
#include "backend/cpu/mara2017/cpu_mara_rows.h"
#include "backend/cpu/mara2017/cpu_mara_temporal.h"
#include "backend/cpu/mara2017/cpu_running_min.h"
#include "backend/reference/mara2017/reference_mara_stages.h"
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>

namespace bmfr::cpu {

namespace {

/// The running minimum's longest line with its padding, for radius r.
int longestRun(int w, int h, int r) {
    return std::max(w, h) + 4 * r + 2;
}

/// Stage 5's column minima for columns [x0, x1) of an image w x h, eight columns at a time
/// (their rows are eight consecutive floats), the rest one by one.
BMFR_SIMD_DISPATCH(void, columnMinima,
                   (const float* in, int w, int h, int r, float* out, long x0, long x1,
                    simd::f8* g8, float* g),
                   (in, w, h, r, out, x0, x1, g8, g)) {
    const int longest = longestRun(w, h, r);
    long x = x0;
    for (; x + 8 <= x1; x += 8) runningMin(in + x, w, h, r, out + x, w, g8, g8 + longest);
    for (; x < x1; ++x) runningMin(in + x, w, h, r, out + x, w, g, g + longest);
}

class CpuMaraPasses final : public reference::HostMaraPipeline {
  public:
    void allocate(int w, int h, const Mara2017Settings& s, int threads) override {
        HostMaraPipeline::allocate(w, h, s, threads);
        const size_t n = size_t(w) * size_t(h);
        stage5_.reserve(n);
        const size_t longest = size_t(longestRun(w, h, maraFrameSettings(s, w).maxRadius));
        scratch_.reserve(2 * longest * size_t(threads));
        scratch8_.reserve(2 * longest * size_t(threads) * 8 + 8);
        tables_.reserve(std::max(s.preTaps, s.finalTaps));
        glossy_.reserve(
            maraGlossyScratch(w, maraGlossyReachBound(s.glossySigmaScale, s.glossySigmaExponent,
                                                      s.glossySigmaEpsilon, s.glossyTapSigmas)) *
            size_t(threads));
    }

  protected:
    int64_t matteTemporal(const MaraPassContext& ctx, const MaraFrame& f) override {
        std::atomic<int64_t> nonFinite{0};
        ctx.pool.parallelFor(f.height, 4,
                             [&](long y0, long y1) { nonFinite += maraInputRows(f, y0, y1); });
        ctx.pool.parallelFor(f.height, 4,
                             [&](long y0, long y1) { maraMatteTemporalRows(f, y0, y1); });
        return nonFinite.load();
    }

    void compose(const MaraPassContext& ctx, const MaraFrame& f) override {
        ctx.pool.parallelFor(f.height, 8, [&](long y0, long y1) { maraComposeRows(f, y0, y1); });
    }

    void glossyTemporal(const MaraPassContext& ctx, const MaraFrame& f) override {
        ctx.pool.parallelFor(f.height, 4,
                             [&](long y0, long y1) { maraGlossyTemporalRows(f, y0, y1); });
    }

    void disocclusion(const MaraPassContext& ctx, const MaraFrame& f) override {
        const int r = f.maxRadius, w = f.width, hgt = f.height;
        const long n = long(w) * hgt;
        stage5_.resize(size_t(n));
        ctx.pool.parallelFor(hgt, 8, [&](long y0, long y1) {
            for (long i = y0 * w; i < y1 * w; ++i) stage5_[size_t(i)] = maraStage5Confidence(f, i);
        });
        const int longest = longestRun(w, hgt, r);
        const size_t perThread = 2 * size_t(longest);
        scratch_.resize(perThread * size_t(ctx.pool.threadCount()));
        scratch8_.resize(perThread * size_t(ctx.pool.threadCount()) * 8 + 8);
        // Eight-float vectors on 32 bytes: the vector's own allocation aligns floats only.
        simd::f8* const lines = reinterpret_cast<simd::f8*>(
            (reinterpret_cast<uintptr_t>(scratch8_.data()) + 31) & ~uintptr_t(31));
        ctx.pool.parallelFor(hgt, 8, [&](long y0, long y1) {
            float* g = scratch_.data() + perThread * size_t(ThreadPool::currentThreadIndex());
            for (long y = y0; y < y1; ++y)
                runningMin(stage5_.data() + y * w, 1, w, r, f.rowMin + y * w, 1, g, g + longest);
        });
        // Over groups of eight columns, so that a task's columns split into whole groups.
        ctx.pool.parallelFor((w + 7) / 8, 2, [&](long g0, long g1) {
            const long x0 = 8 * g0, x1 = std::min<long>(w, 8 * g1);
            const size_t at = perThread * size_t(ThreadPool::currentThreadIndex());
            columnMinima(f.rowMin, w, hgt, r, f.radius, x0, x1, lines + at, scratch_.data() + at);
        });
        ctx.pool.parallelFor(hgt, 8, [&](long y0, long y1) {
            for (long i = y0 * w; i < y1 * w; ++i)
                f.radius[i] = maraDisocclusionRadius(f, i, f.radius[i]);
        });
    }

    void preBilateral(const MaraPassContext& ctx, const MaraFrame& f) override {
        sparse(ctx, f, f.temporal, false);
    }

    void matteBilateral(const MaraPassContext& ctx, const MaraFrame& f, const float* src) override {
        sparse(ctx, f, src, true);
    }

    void median(const MaraPassContext& ctx, const MaraFrame& f) override {
        ctx.pool.parallelFor(f.height, 4, [&](long y0, long y1) { maraMedianRows(f, y0, y1); });
    }

    void glossyBilateral(const MaraPassContext& ctx, const MaraFrame& f) override {
        const int reach = maraGlossyReach(f);
        const size_t perThread = maraGlossyScratch(f.width, reach);
        glossy_.resize(perThread * size_t(ctx.pool.threadCount()));
        auto scratch = [&] {
            return glossy_.data() + perThread * size_t(ThreadPool::currentThreadIndex());
        };
        ctx.pool.parallelFor(f.height, 4, [&](long y0, long y1) {
            maraGlossyRows(f, f.glossyTemporal, f.glossyRow, y0, y1, false, reach, scratch());
        });
        // Down the columns each band first weighs the pairs of the `reach` rows above it: a
        // few bands per worker, not small chunks.
        const long bands = std::min<long>(4L * ctx.pool.threadCount(), (f.height + 31) / 32);
        ctx.pool.parallelFor(bands, 1, [&](long b0, long b1) {
            for (long b = b0; b < b1; ++b)
                maraGlossyRows(f, f.glossyRow, f.glossyOut, b * f.height / bands,
                               (b + 1) * f.height / bands, true, reach, scratch());
        });
    }

  private:
    /// Stage 4 or 7 in tiles, not rows: a 64-pixel radius reaches 129 rows, and a tile's taps
    /// stay in cache.
    void sparse(const MaraPassContext& ctx, const MaraFrame& f, const float* src, bool final) {
        if (final)
            tables_.buildFinal(f);
        else
            tables_.buildPre(f);
        const int tile = 64, across = (f.width + tile - 1) / tile;
        const long tiles = long(across) * ((f.height + tile - 1) / tile);
        ctx.pool.parallelFor(tiles, 1, [&](long t0, long t1) {
            for (long t = t0; t < t1; ++t) {
                const int x0 = int(t % across) * tile, y0 = int(t / across) * tile;
                maraSparseTile(f, src, final, x0, std::min(f.width, x0 + tile), y0,
                               std::min(f.height, y0 + tile), tables_);
            }
        });
    }

    std::vector<float> stage5_, scratch_;
    std::vector<float> scratch8_; ///< columnMinima's eight-column lines, per worker
    std::vector<float> glossy_;   ///< the glossy passes' pair weights, per worker
    MaraTapTables tables_;
};

} // namespace

template <> std::unique_ptr<MaraPasses> makePasses<Mara2017Settings>() {
    return std::make_unique<CpuMaraPasses>();
}

} // namespace bmfr::cpu
