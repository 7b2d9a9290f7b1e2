#include "backend/cpu/bmfr_passes.h"
#include "filters/bmfr/block_grid.h"
#include "filters/bmfr/feature_columns.h"
#include "filters/bmfr/householder_fit.h"
#include <algorithm>
#include <cstring>

namespace bmfr::cpu {

namespace {

/// Fills the block's noise-free feature columns and colour columns; marks owned pixels.
void gatherBlock(const BmfrPassContext& ctx, const BlockGrid& g, int bx, int by, FitScratch& sc) {
    const Settings& s = ctx.settings;
    const BmfrState& st = ctx.state;
    const int B = g.blockSize, W = B * B, M = int(s.features.size());
    const float* normal = st.normal[st.cur].data();
    const float* position = st.position[st.cur].data();
    const float* color = st.accumulatedNoisy[st.cur].data();
    const auto& extras = ctx.frame.extras;
    float extra[16] = {};
    const int ox = g.originX(bx), oy = g.originY(by);
    for (int ly = 0; ly < B; ++ly) {
        const int uy = oy + ly, iy = mirrorIndex(uy, g.height);
        const bool rowInside = uy >= 0 && uy < g.height;
        for (int lx = 0; lx < B; ++lx) {
            const int ux = ox + lx, ix = mirrorIndex(ux, g.width);
            const int k = ly * B + lx;
            const long idx = long(iy) * g.width + ix;
            Vec3 n = load3(normal, idx), p = load3(position, idx);
            for (size_t e = 0; e < extras.size(); ++e) {
                float v = extras[e].data[idx];
                extra[e] = std::isfinite(v) ? v : 0.0f;
            }
            for (int f = 0; f < M; ++f)
                sc.clean[long(f) * W + k] = featureValue(s.features[f], n, p, extra);
            Vec3 c = load3(color, idx);
            sc.work[long(M) * W + k] = c.x;
            sc.work[long(M + 1) * W + k] = c.y;
            sc.work[long(M + 2) * W + k] = c.z;
            sc.imageIndex[k] = rowInside && ux >= 0 && ux < g.width ? int(idx) : -1;
        }
    }
}

void fitBlock(const BmfrPassContext& ctx, const BlockGrid& g, int bx, int by, FitScratch& sc) {
    const Settings& s = ctx.settings;
    const int W = g.blockSize * g.blockSize, M = int(s.features.size());
    gatherBlock(ctx, g, bx, by, sc);

    const float* noise = ctx.state.noise.data();
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
    std::fill(sum, sum + 3 * W, 0.0f);
    for (int f = 0; f < M; ++f) {
        const float* col = sc.clean.data() + long(f) * W;
        for (int c = 0; c < 3; ++c) {
            const float a = coeffs[f * 3 + c];
            float* out = sum + long(c) * W;
            for (int k = 0; k < W; ++k) out[k] += a * col[k];
        }
    }
    float* fitted = ctx.state.fitted.data();
    for (int k = 0; k < W; ++k) {
        const int idx = sc.imageIndex[k];
        if (idx < 0) continue;
        for (int c = 0; c < 3; ++c) fitted[3L * idx + c] = std::max(0.0f, sum[long(c) * W + k]);
    }
}

} // namespace

void fitBlocks(const BmfrPassContext& ctx) {
    BmfrState& st = ctx.state;
    if (!ctx.settings.stages.fitting) {
        std::memcpy(st.fitted.data(), st.accumulatedNoisy[st.cur].data(),
                    st.fitted.pixels.size() * sizeof(float));
        return;
    }
    const BlockGrid g = makeBlockGrid(st.width, st.height, ctx.settings.blockSize, st.frameIndex);
    ctx.pool.parallelFor(g.blockCount(), 1, [&](long b0, long b1) {
        FitScratch& sc = st.scratch[ThreadPool::currentThreadIndex()];
        for (long b = b0; b < b1; ++b) fitBlock(ctx, g, int(b % g.blocksX), int(b / g.blocksX), sc);
    });
}

} // namespace bmfr::cpu
