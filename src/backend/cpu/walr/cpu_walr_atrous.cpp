#include "backend/cpu/walr/cpu_walr_atrous.h"
#include "backend/cpu/simd.h"

namespace bmfr::cpu {

using namespace simd;

void EdgePlanes::fill(ThreadPool& pool, const EdgeGuide& g) {
    const long n = long(g.width) * g.height;
    planes.resize(size_t(6 * n));
    for (int c = 0; c < 3; ++c) {
        position[c] = planes.data() + c * n;
        normal[c] = planes.data() + (3 + c) * n;
    }
    pool.parallelFor(g.height, 16, [&](long y0, long y1) {
        for (long i = y0 * g.width; i < y1 * g.width; ++i)
            for (int c = 0; c < 3; ++c) {
                planes[size_t(c * n + i)] = g.position[3 * i + c];
                planes[size_t((3 + c) * n + i)] = g.normal[3 * i + c];
            }
    });
}

namespace {

/// Eight pixels (x .. x + 7, y), all of whose taps in x lie inside the image.
BMFR_SIMD_CLONES void atrousBlock(const EdgeGuide& g, const EdgePlanes& e, const WalrLevel& l,
                                  int x, int y) {
    const long i = long(y) * g.width + x, stride = l.planeStride;
    f8 p[3], n[3];
    for (int c = 0; c < 3; ++c) p[c] = load8(e.position[c] + i), n[c] = load8(e.normal[c] + i);
    const f8 z = load8(g.depth + i);
    const f8 zc = z > 0.0f ? z : f8{};
    const f8 a = g.nearFraction * zc, b = g.farFraction * zc;
    f8 total = l.weightIn ? load8(l.weightIn + i) : splat8(1.0f);
    f8 sum[kWalrAverages];
    for (int k = 0; k < kWalrAverages; ++k) sum[k] = total * load8(l.in + k * stride + i);
    const int step = l.step;
    for (int tap = 0; tap < 8; ++tap) {
        const int ux = walrTapX(tap), uy = walrTapY(tap), ey = y + step * uy;
        if (ey < 0 || ey >= g.height) continue; // the whole row of taps is outside
        // Weight of each lane's tap, traced or at the end only, as traceTap.
        f8 m = splat8(1.0f);
        auto weightAt = [&](int k) {
            const long q = long(y + k * uy) * g.width + x + k * ux;
            const f8 d0 = load8(e.position[0] + q) - p[0], d1 = load8(e.position[1] + q) - p[1],
                     d2 = load8(e.position[2] + q) - p[2];
            f8 dd = n[0] * d0 + n[1] * d1 + n[2] * d2;
            dd = dd < 0.0f ? -dd : dd;
            const f8 ramp = (b - dd) / (b - a);
            return dd > a ? (dd < b ? ramp : f8{}) : splat8(1.0f);
        };
        if (!g.tracing) {
            m = weightAt(step);
        } else {
            for (int k = 1; k <= step; ++k) {
                const f8 w = weightAt(k);
                m = w < m ? w : m;
                if (!anyLane(m > 0.0f)) break;
            }
        }
        const i8 cut = m > 0.0f ? i8{} : ~i8{};
        const f8 wt = cut ? f8{} : m;
        const long j = long(ey) * g.width + x + step * ux;
        const f8 wj = l.weightIn ? wt * load8(l.weightIn + j) : wt;
        for (int k = 0; k < kWalrAverages; ++k) sum[k] += wj * load8(l.in + k * stride + j);
        total += wj;
        if (!g.tracing || !g.replacement || !anyLane(cut)) continue;
        // Lanes cut by an edge: the scalar replacement, in the same order of additions.
        for (int lane = 0; lane < 8; ++lane) {
            if (!cut[lane]) continue;
            const long pi = i + lane;
            const TracedTap t = traceTap(g, edgeCentre(g, pi), x + lane, y, ux, uy, step,
                                         replacementHash(pi, l.frame, l.iteration, tap, l.seed));
            if (!(t.weight > 0)) continue;
            const long r = long(y + t.steps * uy) * g.width + x + lane + t.steps * ux;
            const float w = l.weightIn ? t.weight * l.weightIn[r] : t.weight;
            for (int k = 0; k < kWalrAverages; ++k) sum[k][lane] += w * l.in[k * stride + r];
            total[lane] += w;
        }
    }
    for (int k = 0; k < kWalrAverages; ++k) store8(l.out + k * stride + i, sum[k] / total);
    if (l.weightOut) store8(l.weightOut + i, total);
}

} // namespace

void walrAtrousIteration(ThreadPool& pool, const EdgeGuide& g, const EdgePlanes& e,
                         const WalrLevel& l) {
    const int w = g.width, step = l.step;
    pool.parallelFor(g.height, 2, [&](long y0, long y1) {
        for (int y = int(y0); y < int(y1); ++y) {
            int x = 0;
            for (; x < w && x < step; ++x) walrAtrousPixel(g, l, x, y);
            for (; x + 8 + step <= w; x += 8) atrousBlock(g, e, l, x, y);
            for (; x < w; ++x) walrAtrousPixel(g, l, x, y);
        }
    });
}

} // namespace bmfr::cpu
