#include "backend/cpu/fast_passes.h"
#include "core/simd.h"
#include "filters/bmfr/block_grid.h"
#include "filters/bmfr/feature_columns.h"
#include <algorithm>

namespace bmfr::cpu {

using namespace simd;

namespace {

struct Phase2 {
    const BmfrPassContext& ctx;
    Buffers& b;
    BlockGrid grid;
};

/// Gathers the extra buffers some feature uses (non-finite values read as 0).
BMFR_SIMD_INLINE void gatherExtras(const Phase2& a, int ox, int oy, bool inside, Scratch& sc) {
    const BlockGrid& g = a.grid;
    const int B = g.blockSize, W = B * B;
    for (const Feature& f : a.ctx.settings.features) {
        if (f.source != FeatureSource::Extra) continue;
        const float* src = a.ctx.frame.extras[size_t(f.extraIndex)].data;
        float* dst = sc.soa.data() + (6 + size_t(f.extraIndex)) * size_t(W);
        for (int ly = 0; ly < B; ++ly) {
            const int iy = inside ? oy + ly : mirrorIndex(oy + ly, g.height);
            for (int lx = 0; lx < B; ++lx) {
                const int ix = inside ? ox + lx : mirrorIndex(ox + lx, g.width);
                const float v = src[long(iy) * g.width + ix];
                dst[ly * B + lx] = std::isfinite(v) ? v : 0.0f;
            }
        }
    }
}

/// Gathers the block's pixels (mirrored at the image border) as structure-of-arrays from the
/// surface and colour planes, and marks the pixels it owns.
BMFR_SIMD_INLINE void gatherBlock(const Phase2& a, int ox, int oy, Scratch& sc) {
    const BlockGrid& g = a.grid;
    const int B = g.blockSize, W = B * B, M = int(a.ctx.settings.features.size());
    const Buffers& b = a.b;
    const int cur = a.ctx.timeline.cur;
    // soa holds normal xyz then position xyz; the surface planes are position then normal.
    const float* from[6] = {b.plane(b.surface[cur], 3), b.plane(b.surface[cur], 4),
                            b.plane(b.surface[cur], 5), b.plane(b.surface[cur], 0),
                            b.plane(b.surface[cur], 1), b.plane(b.surface[cur], 2)};
    const float* colour[3] = {b.plane(b.noisy[cur], 0), b.plane(b.noisy[cur], 1),
                              b.plane(b.noisy[cur], 2)};
    float* soa = sc.soa.data();
    float* z = sc.work.data() + long(M) * qrColumnStride(W);
    const long zs = qrColumnStride(W);
    const bool inside = ox >= 0 && oy >= 0 && ox + B <= g.width && oy + B <= g.height;
    gatherExtras(a, ox, oy, inside, sc);
    if (inside && B % 8 == 0) {
        // Interior block: block rows are runs of image rows, eight pixels per load.
        for (int ly = 0; ly < B; ++ly) {
            const long row = long(oy + ly) * g.width + ox;
            for (int lx = 0; lx < B; lx += 8) {
                const int k = ly * B + lx;
                for (int ch = 0; ch < 6; ++ch) store8(soa + ch * W + k, load8(from[ch] + row + lx));
                for (int ch = 0; ch < 3; ++ch)
                    store8(z + ch * zs + k, load8(colour[ch] + row + lx));
                for (int l = 0; l < 8; ++l) sc.imageIndex[size_t(k + l)] = int(row + lx + l);
            }
        }
        return;
    }
    for (int ly = 0; ly < B; ++ly) {
        const int uy = oy + ly, iy = inside ? uy : mirrorIndex(uy, g.height);
        const bool rowInside = uy >= 0 && uy < g.height;
        for (int lx = 0; lx < B; ++lx) {
            const int ux = ox + lx, ix = inside ? ux : mirrorIndex(ux, g.width);
            const int k = ly * B + lx;
            const long idx = long(iy) * g.width + ix;
            for (int ch = 0; ch < 6; ++ch) soa[ch * W + k] = from[ch][idx];
            for (int ch = 0; ch < 3; ++ch) z[ch * zs + k] = colour[ch][idx];
            sc.imageIndex[k] = rowInside && ux >= 0 && ux < g.width ? int(idx) : -1;
        }
    }
}

/// Asks for a block's rows of the surface and colour planes ahead of its gather. They are short
/// runs (one block row each) in nine planes, which the hardware prefetchers do not follow; the
/// fit of the block before hides the wait.
BMFR_SIMD_INLINE void prefetchBlock(const Phase2& a, int bx, int by) {
    const BlockGrid& g = a.grid;
    if (bx >= g.blocksX || by >= g.blocksY) return;
    const int B = g.blockSize, ox = std::max(0, g.originX(bx)), oy = std::max(0, g.originY(by));
    const int x1 = std::min(g.width, g.originX(bx) + B), y1 = std::min(g.height, g.originY(by) + B);
    if (ox >= x1 || oy >= y1) return;
    const Buffers& b = a.b;
    const int cur = a.ctx.timeline.cur;
    const float* planes[9];
    for (int c = 0; c < 6; ++c) planes[c] = b.plane(b.surface[cur], c);
    for (int c = 0; c < 3; ++c) planes[6 + c] = b.plane(b.noisy[cur], c);
    for (int y = oy; y < y1; ++y)
        for (const float* p : planes) {
            const float* row = p + long(y) * g.width;
            for (int x = ox; x < x1; x += 16) __builtin_prefetch(row + x);
            __builtin_prefetch(row + x1 - 1);
        }
}

/// Block scaling and regularisation of one column: clean = scaled, noised = scaled + noise.
BMFR_SIMD_INLINE void scaleAndNoise(float* clean, float* noised, const float* noise, int W,
                                    bool scaled) {
    if (scaled) {
        f8 lo = splat8(clean[0]), hi = lo;
        int k = 0;
        for (; k + 8 <= W; k += 8) {
            const f8 v = load8(clean + k);
            lo = min8(lo, v), hi = max8(hi, v);
        }
        float mn = hmin8(lo), mx = hmax8(hi);
        for (; k < W; ++k) mn = std::min(mn, clean[k]), mx = std::max(mx, clean[k]);
        // scaleFeature's rule, with one reciprocal per column instead of a division per pixel.
        const float range = mx - mn, inv = range > 1.0f ? 1.0f / range : 1.0f;
        for (k = 0; k < W; ++k) clean[k] = (clean[k] - mn) * inv;
    }
    for (int k = 0; k < W; ++k) noised[k] = clean[k] + noise[k];
}

BMFR_SIMD_CLONES void fitBlock(const Phase2& a, int bx, int by, Scratch& sc) {
    const Settings& s = a.ctx.settings;
    const BlockGrid& g = a.grid;
    const int B = g.blockSize, W = B * B, M = int(s.features.size());
    const int ox = g.originX(bx), oy = g.originY(by);
    // Blocks that own no pixel (entirely outside the image after the offset) are skipped.
    if (ox + B <= 0 || oy + B <= 0 || ox >= g.width || oy >= g.height) return;
    gatherBlock(a, ox, oy, sc);
    prefetchBlock(a, bx + 1 < g.blocksX ? bx + 1 : 0, bx + 1 < g.blocksX ? by : by + 1);
    const float* soa = sc.soa.data();
    const BlockSources src{
        {soa, soa + W, soa + 2 * W}, {soa + 3 * W, soa + 4 * W, soa + 5 * W}, soa + 6 * W};
    buildFeatureColumns(s.features, src, W, sc.clean.data());
    const float* noise = a.ctx.timeline.noise.data();
    for (int f = 0; f < M; ++f)
        scaleAndNoise(sc.clean.data() + long(f) * W, sc.work.data() + long(f) * qrColumnStride(W),
                      noise + long(f) * W, W, s.features[f].scaled);

    float coeffs[kMaxFeatures * 3];
    solveHouseholderFast(sc.work.data(), M, W, qrColumnStride(W), coeffs);

    // Weighted sum of the noise-free features, 8 pixels at a time, straight to owned pixels.
    float* fitted[3] = {a.b.plane(a.b.fitted, 0), a.b.plane(a.b.fitted, 1),
                        a.b.plane(a.b.fitted, 2)};
    const float* clean = sc.clean.data();
    for (int k = 0; k < W; k += 8) {
        f8 sum[3] = {};
        const int n = std::min(8, W - k);
        if (n == 8) {
            for (int f = 0; f < M; ++f) {
                const f8 col = load8(clean + long(f) * W + k);
                for (int c = 0; c < 3; ++c) sum[c] += coeffs[f * 3 + c] * col;
            }
        } else {
            for (int f = 0; f < M; ++f)
                for (int l = 0; l < n; ++l)
                    for (int c = 0; c < 3; ++c)
                        sum[c][l] += coeffs[f * 3 + c] * clean[long(f) * W + k + l];
        }
        for (int c = 0; c < 3; ++c) sum[c] = max8(f8{}, sum[c]);
        const int first = sc.imageIndex[k];
        if (n == 8 && first >= 0 && sc.imageIndex[k + 7] == first + 7) {
            // Eight owned neighbours in one image row.
            for (int c = 0; c < 3; ++c) store8(fitted[c] + first, sum[c]);
            continue;
        }
        for (int l = 0; l < n; ++l) {
            const int idx = sc.imageIndex[k + l];
            if (idx < 0) continue;
            for (int c = 0; c < 3; ++c) fitted[c][idx] = sum[c][l];
        }
    }
}

} // namespace

void fitBlocks(const BmfrPassContext& ctx, Buffers& b) {
    const BmfrTimeline& t = ctx.timeline;
    if (!ctx.settings.stages.fitting) {
        for (int c = 0; c < 3; ++c)
            std::copy_n(b.plane(b.noisy[t.cur], c), size_t(t.width) * size_t(t.height),
                        b.plane(b.fitted, c));
        return;
    }
    const Phase2 a{ctx, b, makeBlockGrid(t.width, t.height, ctx.settings.blockSize, t.frameIndex)};
    ctx.pool.parallelFor(a.grid.blockCount(), 1, [&](long b0, long b1) {
        Scratch& sc = b.scratch[size_t(ThreadPool::currentThreadIndex())];
        for (long k = b0; k < b1; ++k)
            fitBlock(a, int(k % a.grid.blocksX), int(k / a.grid.blocksX), sc);
    });
}

} // namespace bmfr::cpu
