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
/// 32-byte surface and 16-byte colour records, and marks the pixels it owns.
BMFR_SIMD_INLINE void gatherBlock(const Phase2& a, int ox, int oy, Scratch& sc) {
    const BlockGrid& g = a.grid;
    const int B = g.blockSize, W = B * B, M = int(a.ctx.settings.features.size());
    const float* surface = a.b.surface[a.ctx.timeline.cur].data();
    const float* noisy = a.b.noisy[a.ctx.timeline.cur].data();
    float* soa = sc.soa.data();
    float* z = sc.work.data() + long(M) * W;
    const bool inside = ox >= 0 && oy >= 0 && ox + B <= g.width && oy + B <= g.height;
    gatherExtras(a, ox, oy, inside, sc);
    if (inside && B % 8 == 0) {
        // Interior block: eight pixels per step, records transposed into columns.
        for (int ly = 0; ly < B; ++ly) {
            const long row = long(oy + ly) * g.width + ox;
            for (int lx = 0; lx < B; lx += 8) {
                const int k = ly * B + lx;
                f8 r[8];
                for (int l = 0; l < 8; ++l) r[l] = load8(surface + 8 * (row + lx + l));
                transpose8x8(r);
                for (int ch = 0; ch < 3; ++ch) {
                    store8(soa + (3 + ch) * W + k, r[ch]);
                    store8(soa + ch * W + k, r[4 + ch]);
                }
                // Overlapping 8-float loads: pixel l's record then pixel l + 1's.
                for (int l = 0; l < 8; ++l) r[l] = load8(noisy + 4 * (row + lx + l));
                transpose8x8(r);
                for (int ch = 0; ch < 3; ++ch) store8(z + ch * W + k, r[ch]);
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
            const f4 p = load4(surface + 8 * idx), n = load4(surface + 8 * idx + 4);
            const f4 c = load4(noisy + 4 * idx);
            for (int ch = 0; ch < 3; ++ch) {
                soa[ch * W + k] = n[ch];
                soa[(3 + ch) * W + k] = p[ch];
                z[ch * W + k] = c[ch];
            }
            sc.imageIndex[k] = rowInside && ux >= 0 && ux < g.width ? int(idx) : -1;
        }
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
    const float* soa = sc.soa.data();
    const BlockSources src{
        {soa, soa + W, soa + 2 * W}, {soa + 3 * W, soa + 4 * W, soa + 5 * W}, soa + 6 * W};
    buildFeatureColumns(s.features, src, W, sc.clean.data());
    const float* noise = a.ctx.timeline.noise.data();
    for (int f = 0; f < M; ++f)
        scaleAndNoise(sc.clean.data() + long(f) * W, sc.work.data() + long(f) * W,
                      noise + long(f) * W, W, s.features[f].scaled);

    float coeffs[kMaxFeatures * 3];
    solveHouseholderFast(sc.work.data(), M, W, coeffs);

    // Weighted sum of the noise-free features, 8 pixels at a time, straight to owned pixels.
    float* fitted = a.b.fitted.data();
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
            // Eight owned neighbours in one image row: transpose back into 4-float records.
            f8 r[8] = {sum[0], sum[1], sum[2]};
            transpose8x8(r);
            for (int l = 0; l < 8; ++l) {
                f4 v = {r[l][0], r[l][1], r[l][2], 0.0f};
                store4(fitted + 4L * (first + l), v);
            }
            continue;
        }
        for (int l = 0; l < n; ++l) {
            const int idx = sc.imageIndex[k + l];
            if (idx < 0) continue;
            store4(fitted + 4L * idx, f4{sum[0][l], sum[1][l], sum[2][l], 0.0f});
        }
    }
}

} // namespace

void fitBlocks(const BmfrPassContext& ctx, Buffers& b) {
    const BmfrTimeline& t = ctx.timeline;
    if (!ctx.settings.stages.fitting) {
        const float* noisy = b.noisy[t.cur].data();
        ctx.pool.parallelFor(long(t.width) * t.height, 4096, [&](long i0, long i1) {
            for (long i = i0; i < i1; ++i) {
                f4 c = load4(noisy + 4 * i);
                c[3] = 0.0f;
                store4(b.fitted.data() + 4 * i, c);
            }
        });
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
