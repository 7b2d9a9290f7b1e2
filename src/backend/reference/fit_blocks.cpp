#include "backend/reference/reference_passes.h"
#include "filters/bmfr/block_grid.h"
#include "filters/bmfr/feature_columns.h"
#include "filters/bmfr/householder_fit.h"
#include <algorithm>
#include <cstring>

namespace bmfr::reference {

namespace {

/// Gathers the block's pixels as structure-of-arrays (normal, position, extras, colour) and
/// marks the pixels it owns. Interior blocks skip the mirroring arithmetic.
void gatherBlock(const BmfrPassContext& ctx, const Buffers& st, const BlockGrid& g, int bx, int by,
                 FitScratch& sc) {
    const BmfrTimeline& t = ctx.timeline;
    const int B = g.blockSize, W = B * B, M = int(ctx.settings.features.size());
    const float* normal = st.normal[t.cur].data();
    const float* position = st.position[t.cur].data();
    const float* color = st.accumulatedNoisy[t.cur].data();
    const auto& extras = ctx.frame.extras;
    float* n[3] = {sc.soa.data(), sc.soa.data() + W, sc.soa.data() + 2 * W};
    float* p[3] = {sc.soa.data() + 3 * W, sc.soa.data() + 4 * W, sc.soa.data() + 5 * W};
    float* z[3] = {sc.work.data() + long(M) * W, sc.work.data() + long(M + 1) * W,
                   sc.work.data() + long(M + 2) * W};
    const int ox = g.originX(bx), oy = g.originY(by);
    const bool inside = ox >= 0 && oy >= 0 && ox + B <= g.width && oy + B <= g.height;
    for (int ly = 0; ly < B; ++ly) {
        const int uy = oy + ly, iy = inside ? uy : mirrorIndex(uy, g.height);
        const bool rowInside = uy >= 0 && uy < g.height;
        for (int lx = 0; lx < B; ++lx) {
            const int ux = ox + lx, ix = inside ? ux : mirrorIndex(ux, g.width);
            const int k = ly * B + lx;
            const long idx = long(iy) * g.width + ix;
            for (int c = 0; c < 3; ++c) {
                n[c][k] = normal[3 * idx + c];
                p[c][k] = position[3 * idx + c];
                z[c][k] = color[3 * idx + c];
            }
            for (size_t e = 0; e < extras.size(); ++e) {
                const float v = extras[e].data[idx];
                sc.soa[(6 + e) * size_t(W) + size_t(k)] = std::isfinite(v) ? v : 0.0f;
            }
            sc.imageIndex[k] = rowInside && ux >= 0 && ux < g.width ? int(idx) : -1;
        }
    }
    buildFeatureColumns(ctx.settings.features,
                        {{n[0], n[1], n[2]}, {p[0], p[1], p[2]}, sc.soa.data() + 6 * W}, W,
                        sc.clean.data());
}

/// out[c][k] = sum_f coeffs[f][c] * clean[f][k]; compiled for AVX2 and baseline, chosen at run
/// time.
__attribute__((target_clones("avx2", "default"))) void
weightedSum(const float* clean, const float* coeffs, int M, int W, float* sum) {
    std::fill(sum, sum + 3 * W, 0.0f);
    for (int f = 0; f < M; ++f) {
        const float* col = clean + long(f) * W;
        for (int c = 0; c < 3; ++c) {
            const float a = coeffs[f * 3 + c];
            float* out = sum + long(c) * W;
            for (int k = 0; k < W; ++k) out[k] += a * col[k];
        }
    }
}

void fitBlock(const BmfrPassContext& ctx, Buffers& st, const BlockGrid& g, int bx, int by,
              FitScratch& sc) {
    const Settings& s = ctx.settings;
    const int W = g.blockSize * g.blockSize, M = int(s.features.size());
    gatherBlock(ctx, st, g, bx, by, sc);

    const float* noise = ctx.timeline.noise.data();
    for (int f = 0; f < M; ++f) {
        float* col = sc.clean.data() + long(f) * W;
        if (s.features[f].scaled) {
            auto [lo, hi] = std::minmax_element(col, col + W);
            const float mn = *lo, mx = *hi;
            for (int k = 0; k < W; ++k) col[k] = scaleFeature(col[k], mn, mx);
        }
        float* dst = sc.work.data() + long(f) * W;
        const float* nz = noise + long(f) * W;
        for (int k = 0; k < W; ++k) dst[k] = col[k] + nz[k];
    }

    float coeffs[kMaxFeatures * 3];
    solveHouseholder(sc.work.data(), M, W, coeffs);

    // Weighted sum with the noise-free features; only owned pixels are written.
    float* sum = sc.sum.data();
    weightedSum(sc.clean.data(), coeffs, M, W, sum);
    float* fitted = st.fitted.data();
    for (int k = 0; k < W; ++k) {
        const int idx = sc.imageIndex[k];
        if (idx < 0) continue;
        for (int c = 0; c < 3; ++c) fitted[3L * idx + c] = std::max(0.0f, sum[long(c) * W + k]);
    }
}

} // namespace

void fitBlocks(const BmfrPassContext& ctx, Buffers& st) {
    const BmfrTimeline& t = ctx.timeline;
    if (!ctx.settings.stages.fitting) {
        std::memcpy(st.fitted.data(), st.accumulatedNoisy[t.cur].data(),
                    st.fitted.pixels.size() * sizeof(float));
        return;
    }
    const BlockGrid g = makeBlockGrid(t.width, t.height, ctx.settings.blockSize, t.frameIndex);
    ctx.pool.parallelFor(g.blockCount(), 1, [&](long b0, long b1) {
        FitScratch& sc = st.scratch[ThreadPool::currentThreadIndex()];
        for (long b = b0; b < b1; ++b)
            fitBlock(ctx, st, g, int(b % g.blocksX), int(b / g.blocksX), sc);
    });
}

} // namespace bmfr::reference
