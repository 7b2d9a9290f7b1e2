#include "backend/cpu/walr/cpu_walr_spatial.h"
#include "backend/cpu/simd.h"
#include <cmath>
#include <cstring>

namespace bmfr::cpu {

using namespace simd;

void EdgePlanes::allocate(int width, int height) {
    // The seven planes' rows interleaved (row y of plane k at (7 y + k) * planeSize): a trace
    // step's three position loads then fall within one small stretch of memory.
    planeSize = width + 2 * kPad;
    rowStride = 7 * planeSize;
    // Zeroed once per size: every frame writes the whole interior, and the padding is only
    // ever read by lanes whose result is masked.
    if (planes.size() != size_t(rowStride * height))
        planes.assign(size_t(rowStride * height), 0.0f);
    blocksPerRow = (width + 7) / 8;
    tracedMin.resize(size_t(64 * blocksPerRow * height));
    tracedEdge.resize(tracedMin.size());
}

void EdgePlanes::fill(ThreadPool& pool, const EdgeGuide& g) {
    allocate(g.width, g.height);
    pool.parallelFor(g.height, 16, [&](long y0, long y1) {
        for (long y = y0; y < y1; ++y)
            for (long x = 0; x < g.width; ++x) {
                const long i = y * g.width + x, o = y * rowStride + kPad + x;
                for (int c = 0; c < 3; ++c) {
                    planes[size_t(c * planeSize + o)] = g.position[3 * i + c];
                    planes[size_t((3 + c) * planeSize + o)] = g.normal[3 * i + c];
                }
                planes[size_t(6 * planeSize + o)] = g.depth[i];
            }
    });
}

namespace {

constexpr int kMaxStep = 81; // 3^(T - 1) for the largest T

/// The traced taps of eight pixels (x .. x + 7, y): weight and steps per tap and lane, as
/// traceTap gives them (weight 0 = dropped).
struct BlockTaps {
    float weight[8][8];
    int steps[8][8];
};

BMFR_SIMD_DISPATCH(void, traceBlock,
                   (const EdgeGuide& g, EdgePlanes& e, const WalrLevel& l, int x, int y,
                    BlockTaps& out),
                   (g, e, l, x, y, out)) {
    const long o = long(y) * e.rowStride + x;
    const float *px = e.plane(0), *py = e.plane(1), *pz = e.plane(2);
    const f8 p[3] = {load8(px + o), load8(py + o), load8(pz + o)};
    const f8 n[3] = {load8(e.plane(3) + o), load8(e.plane(4) + o), load8(e.plane(5) + o)};
    const f8 z = load8(e.plane(6) + o);
    const f8 zc = z > 0.0f ? z : f8{};
    const f8 a = g.nearFraction * zc, b = g.farFraction * zc;
    const f8 slope = b > a ? 1.0f / (b - a) : f8{}; // rampSlope per lane
    const i8 laneX = i8{0, 1, 2, 3, 4, 5, 6, 7} + x;
    const int step = l.step;
    f8 running[kMaxStep + 1]; // the traced minimum after k steps, for replacements
    for (int tap = 0; tap < 8; ++tap) {
        const int ux = walrTapX(tap), uy = walrTapY(tap), ey = y + step * uy;
        const i8 endX = laneX + step * ux;
        const i8 inside = (laneX < g.width) & (endX >= 0) & (endX < g.width);
        for (int lane = 0; lane < 8; ++lane) out.weight[tap][lane] = 0, out.steps[tap][lane] = 0;
        if (ey < 0 || ey >= g.height || !anyLane(inside)) continue;
        // Each lane's edgeWeight at step k along the tap (padding keeps the loads in bounds).
        auto weightAt = [&](int k) __attribute__((always_inline)) {
            const long q = o + long(k * uy) * e.rowStride + k * ux;
            const f8 d0 = load8(px + q) - p[0], d1 = load8(py + q) - p[1],
                     d2 = load8(pz + q) - p[2];
            f8 dd = n[0] * d0 + n[1] * d1 + n[2] * d2;
            dd = dd < 0.0f ? -dd : dd;
            return dd > a ? (dd < b ? (b - dd) * slope : f8{}) : splat8(1.0f);
        };
        f8 m = splat8(1.0f);
        i8 edge{};
        const long i = long(y) * g.width + x;
        const long state = ((long(y) * e.blocksPerRow + x / 8) * 8 + tap) * 8;
        float* stateMin = e.tracedMin.data() + state;
        int32_t* stateEdge = e.tracedEdge.data() + state;
        const int first = l.iteration > 0 ? step / 3 + 1 : 1; // traced by the last iteration
        if (!g.tracing) {
            m = weightAt(step);
        } else {
            if (first > 1) {
                m = load8(stateMin);
                std::memcpy(&edge, stateEdge, sizeof edge);
            }
            // Past the first zero m stays 0, so the test for stopping can wait a few steps.
            for (int k = first; k <= step; ++k) {
                const f8 w = weightAt(k);
                m = w < m ? w : m;
                running[k] = m;
                edge = (edge == 0) & (m <= 0.0f) ? i8{} + k : edge;
                if (((k - first) & 3) == 3 && !anyLane(inside & (m > 0.0f))) break;
            }
            store8(stateMin, m);
            std::memcpy(stateEdge, &edge, sizeof edge);
        }
        for (int lane = 0; lane < 8; ++lane) {
            if (!inside[lane]) continue;
            if (m[lane] > 0) {
                out.weight[tap][lane] = m[lane], out.steps[tap][lane] = step;
            } else if (g.tracing && g.replacement && edge[lane] > 1) {
                const int kr = replacementStep(
                    replacementHash(i + lane, l.frame, l.iteration, tap, l.seed), edge[lane]);
                int unused = 0;
                // Steps traced by an earlier iteration are traced again for this one lane.
                out.weight[tap][lane] = kr >= first ? running[kr][lane]
                                                    : tracedWeight(g, edgeCentre(g, i + lane),
                                                                   x + lane, y, ux, uy, kr, unused);
                out.steps[tap][lane] = kr;
            }
        }
    }
}

/// The averages of one pixel from its traced taps, 14 channels as two eight-wide halves.
BMFR_SIMD_DISPATCH(void, gatherPixel,
                   (const EdgeGuide& g, const WalrLevel& l, const BlockTaps& t, int lane, long i),
                   (g, l, t, lane, i)) {
    float total = l.weightIn ? l.weightIn[i] : 1.0f;
    f8 lo = total * load8(l.in + 16 * i), hi = total * load8(l.in + 16 * i + 8);
    for (int tap = 0; tap < 8; ++tap) {
        const float wt = t.weight[tap][lane];
        if (!(wt > 0)) continue;
        const int k = t.steps[tap][lane];
        const long j = i + long(k * walrTapY(tap)) * g.width + k * walrTapX(tap);
        const float w = l.weightIn ? wt * l.weightIn[j] : wt;
        lo += w * load8(l.in + 16 * j);
        hi += w * load8(l.in + 16 * j + 8);
        total += w;
    }
    store8(l.out + 16 * i, lo / total);
    store8(l.out + 16 * i + 8, hi / total);
    if (l.weightOut) l.weightOut[i] = total;
}

/// choleskyClamped, choleskySolve and the prediction of walrPredict<float>, eight pixels wide.
BMFR_SIMD_DISPATCH(void, solveBlock,
                   (const float* averages, const float* features, float eps, long i, int count,
                    float* out),
                   (averages, features, eps, i, count, out)) {
    f8 a[kWalrAverages], fx{}, fy{};
    for (int lane = 0; lane < count; ++lane) {
        for (int k = 0; k < kWalrAverages; ++k) a[k][lane] = averages[16 * (i + lane) + k];
        fx[lane] = features[2 * (i + lane)], fy[lane] = features[2 * (i + lane) + 1];
    }
    for (int lane = count; lane < 8; ++lane)
        for (int k = 0; k < kWalrAverages; ++k) a[k][lane] = k == 2 || k == 4 ? 1.0f : 0.0f;
    auto root = [](f8 v) {
        for (int lane = 0; lane < 8; ++lane) v[lane] = std::sqrt(v[lane]);
        return v;
    };
    const f8 c00 = splat8(1.0f), c10 = a[0], c20 = a[1];
    const f8 p1 = a[2] - c10 * c10;
    const f8 c11 = root(p1 > eps ? p1 : splat8(eps));
    const f8 c21 = (a[3] - c20 * c10) / c11;
    const f8 p2 = a[4] - c20 * c20 - c21 * c21;
    const f8 c22 = root(p2 > eps ? p2 : splat8(eps));
    f8 rgb[3];
    for (int ch = 0; ch < 3; ++ch) {
        const f8 r0 = a[5 + 3 * ch], r1 = a[6 + 3 * ch], r2 = a[7 + 3 * ch];
        const f8 f0 = r0 / c00;
        const f8 f1 = (r1 - c10 * f0) / c11;
        const f8 f2 = (r2 - c20 * f0 - c21 * f1) / c22;
        const f8 b2 = f2 / c22;
        const f8 b1 = (f1 - c21 * b2) / c11;
        const f8 b0 = (f0 - c10 * b1 - c20 * b2) / c00;
        const f8 v = b0 + b1 * fx + b2 * fy;
        rgb[ch] = v > 0.0f ? v : f8{};
    }
    storeXyz8(out + 3 * i, count, rgb);
}

} // namespace

void walrAtrousIteration(ThreadPool& pool, const EdgeGuide& g, EdgePlanes& e, const WalrLevel& l) {
    // Plain row order: columns of single blocks (so that vertical steps revisit cached rows)
    // measured 1.5x slower, and bands cut into strips no faster; the trace is bound by its
    // arithmetic, not by memory.
    pool.parallelFor(g.height, 2, [&](long y0, long y1) {
        BlockTaps taps;
        for (int y = int(y0); y < int(y1); ++y)
            for (int x = 0; x < g.width; x += 8) {
                traceBlock(g, e, l, x, y, taps);
                const int count = g.width - x < 8 ? g.width - x : 8;
                for (int lane = 0; lane < count; ++lane)
                    gatherPixel(g, l, taps, lane, long(y) * g.width + x + lane);
            }
    });
}

void walrSolveImage(ThreadPool& pool, int width, int height, const float* averages,
                    const float* features, float eps, float* out) {
    pool.parallelFor(height, 8, [&](long y0, long y1) {
        for (long y = y0; y < y1; ++y)
            for (int x = 0; x < width; x += 8)
                solveBlock(averages, features, eps, y * width + x, width - x < 8 ? width - x : 8,
                           out);
    });
}

} // namespace bmfr::cpu
