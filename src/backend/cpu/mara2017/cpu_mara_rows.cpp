#include "backend/cpu/mara2017/cpu_mara_rows.h"
#include "backend/cpu/libm_expf.h"
#include "backend/cpu/mara2017/cpu_mara_edge_weight.h"
#include "backend/cpu/simd.h"
#include "filters/mara2017/mara_passes.h"
#include <algorithm>
#include <cstring>

namespace bmfr::cpu {

using namespace simd;

namespace {

BMFR_SIMD_INLINE void sort2(f8& a, f8& b) {
    const f8 lo = a < b ? a : b, hi = a < b ? b : a;
    a = lo, b = hi;
}

/// Devillard's 19-exchange median of nine, per lane (exact: the same value as any median).
BMFR_SIMD_INLINE f8 median9(f8 p[9]) {
    sort2(p[1], p[2]), sort2(p[4], p[5]), sort2(p[7], p[8]);
    sort2(p[0], p[1]), sort2(p[3], p[4]), sort2(p[6], p[7]);
    sort2(p[1], p[2]), sort2(p[4], p[5]), sort2(p[7], p[8]);
    sort2(p[0], p[3]), sort2(p[5], p[8]), sort2(p[4], p[7]);
    sort2(p[3], p[6]), sort2(p[1], p[4]), sort2(p[2], p[5]);
    sort2(p[4], p[7]), sort2(p[4], p[2]), sort2(p[6], p[4]);
    sort2(p[4], p[2]);
    return p[4];
}

/// Lane l's record index[l] of a packed xyz buffer, as x, y and z lanes: eight 12-byte loads
/// and a transpose.
BMFR_SIMD_INLINE void gatherXyz8(const float* p, i8 index, f8 out[3]) {
    f4 r[8];
    for (int l = 0; l < 8; ++l) {
        const float* q = p + 3 * long(index[l]);
        r[l] = f4{q[0], q[1], q[2], 0.0f};
    }
    const f8 a0 = __builtin_shufflevector(r[0], r[4], 0, 1, 2, 3, 4, 5, 6, 7),
             a1 = __builtin_shufflevector(r[1], r[5], 0, 1, 2, 3, 4, 5, 6, 7),
             a2 = __builtin_shufflevector(r[2], r[6], 0, 1, 2, 3, 4, 5, 6, 7),
             a3 = __builtin_shufflevector(r[3], r[7], 0, 1, 2, 3, 4, 5, 6, 7);
    const f8 t0 = __builtin_shuffle(a0, a1, i8{0, 8, 1, 9, 4, 12, 5, 13}), // x0 x1 y0 y1
        t1 = __builtin_shuffle(a2, a3, i8{0, 8, 1, 9, 4, 12, 5, 13}),      // x2 x3 y2 y3
        t2 = __builtin_shuffle(a0, a1, i8{2, 10, 3, 11, 6, 14, 7, 15}),    // z0 z1 . .
        t3 = __builtin_shuffle(a2, a3, i8{2, 10, 3, 11, 6, 14, 7, 15});    // z2 z3 . .
    out[0] = __builtin_shuffle(t0, t1, i8{0, 1, 8, 9, 4, 5, 12, 13});
    out[1] = __builtin_shuffle(t0, t1, i8{2, 3, 10, 11, 6, 7, 14, 15});
    out[2] = __builtin_shuffle(t2, t3, i8{0, 1, 8, 9, 4, 5, 12, 13});
}

/// Lane l's record index[l] of a packed xyz buffer, eight or sixteen lanes.
template <class V> BMFR_SIMD_INLINE void gatherXyz(const float* p, IntOf<V> index, V out[3]) {
    if constexpr (kLanesOf<V> == 8) {
        gatherXyz8(p, index, out);
    } else {
        f8 lo[3], hi[3];
        gatherXyz8(p, eightLanes(index, 0), lo);
        gatherXyz8(p, eightLanes(index, 8), hi);
        for (int c = 0; c < 3; ++c) out[c] = joinLanes(lo[c], hi[c]);
    }
}

/// A run of eight or sixteen packed xyz records (a tap's neighbours) as x, y and z lanes.
template <Isa kIsa, class V> BMFR_SIMD_INLINE void runXyz(const float* p, V out[3]) {
    if constexpr (kLanesOf<V> == 8)
        deinterleave3<kIsa>(p, out[0], out[1], out[2]);
    else
        deinterleave3x16(p, out[0], out[1], out[2]);
}

/// One sparse tap for eight or sixteen centres (V): position, normal and colour weighted by g
/// and the edges. A lane whose g is 0 adds nothing (its weight is 0 even where its edge weight
/// is not finite), so g is how a caller leaves lanes out: a select by a mask in every tap ran lane
/// by lane at sixteen lanes (GCC 12).
template <Isa kIsa, class V> struct SparseSum {
    V pc[3], nc[3], sum[3];
    V total = V{} + 1.0f;

    /// The tap at the neighbours from pixel j, one run of the packed buffers.
    BMFR_SIMD_INLINE void addRun(const MaraFrame& f, const float* src, long j, V g) {
        V pq[3], nq[3], s[3];
        runXyz<kIsa>(f.position + 3 * j, pq);
        runXyz<kIsa>(f.normal + 3 * j, nq);
        runXyz<kIsa>(src + 3 * j, s);
        weigh(f, pq, nq, s, g);
    }

    /// The tap at each lane's own pixel index[l].
    BMFR_SIMD_INLINE void addGathered(const MaraFrame& f, const float* src, IntOf<V> index, V g) {
        V pq[3], nq[3], s[3];
        gatherXyz(f.position, index, pq);
        gatherXyz(f.normal, index, nq);
        gatherXyz(src, index, s);
        weigh(f, pq, nq, s, g);
    }

  private:
    BMFR_SIMD_INLINE void weigh(const MaraFrame& f, const V pq[3], const V nq[3], const V s[3],
                                V g) {
        const V wt = g * edgeWeightOf<kIsa>(nc, pc, nq, pq, f.edges);
        // Only where the weight is above 0 (not NaN, 0 times a non-finite edge weight): a lane
        // left out then keeps its sums whatever the tap's colour, so a run of sixteen gives each
        // lane the bits of a run of eight, which takes other lanes' taps.
        for (int c = 0; c < 3; ++c) sum[c] = wt > 0.0f ? sum[c] + wt * s[c] : sum[c];
        total = wt > 0.0f ? total + wt : total;
    }
};

/// The most taps of a sparse stage (the settings' range).
constexpr int kMaxTaps = 256;

/// The `taps` unit offsets of `spiral` scaled by `radius`, and their Gaussian weights of `sigma`,
/// as maraSparseBilateral computes them, the exponentials eight at a time (expfRun: a scalar
/// expf per tap was a seventh of stage 7).
template <Isa kIsa>
BMFR_SIMD_INLINE void scaledTaps(const float* spiral, int taps, float radius, float sigma, int* dx,
                                 int* dy, float* g) {
    alignas(32) float exponent[kMaxTaps];
    for (int k = 0; k < taps; ++k) {
        dx[k] = maraTapOffset(spiral[2 * k], radius);
        dy[k] = maraTapOffset(spiral[2 * k + 1], radius);
        exponent[k] = maraGaussianExponent(float(dx[k] * dx[k] + dy[k] * dy[k]), sigma);
    }
    std::fill(exponent + taps, exponent + (taps + 7) / 8 * 8, 0.0f);
    expfRun<kIsa>(exponent, taps, g);
}

/// Stage 7's taps at a radius outside the tables (MaraTapTables), per rotation as the runs need
/// them, kept while the radius stays: stage 5's box minimum holds one radius over long stretches
/// of a row, and building a radius's taps takes an exponential each.
struct RadiusTaps {
    float radius = -1.0f;
    int count[kMaraSpiralRotations];
    int dx[kMaraSpiralRotations][kMaxTaps], dy[kMaraSpiralRotations][kMaxTaps];
    float g[kMaraSpiralRotations][kMaxTaps];

    /// Rotation r's taps at radius `at`: the `taps` unit offsets of `spiral` scaled, with Gaussian
    /// weights of `sigma`.
    template <Isa kIsa>
    BMFR_SIMD_INLINE int build(int r, const float* spiral, int taps, float at, float sigma) {
        if (!(at == radius)) {
            radius = at;
            std::fill(count, count + kMaraSpiralRotations, -1);
        }
        if (count[r] >= 0) return count[r];
        // Below 4 pixels the taps land on at most 81 pixels: merged as MaraTapRuns merges them
        // (confident pixels whose history is not perfect sit just above (1 - h) R).
        int slot[81];
        const bool merge = at < 4.0f;
        if (merge) std::fill(slot, slot + 81, -1);
        int ox[kMaxTaps], oy[kMaxTaps];
        alignas(32) float gk[kMaxTaps];
        scaledTaps<kIsa>(spiral, taps, at, sigma, ox, oy, gk);
        int n = 0;
        for (int k = 0; k < taps; ++k) {
            int* t = merge ? &slot[9 * (oy[k] + 4) + ox[k] + 4] : nullptr;
            if (t && *t >= 0) {
                g[r][*t] += gk[k];
                continue;
            }
            if (t) *t = n;
            dx[r][n] = ox[k], dy[r][n] = oy[k], g[r][n] = gk[k];
            ++n;
        }
        return count[r] = n;
    }
};

/// RadiusTaps for the last few radii: a run whose lanes have two radii takes each in turn, and a
/// single radius would build each one's taps again, run after run.
struct RadiusCache {
    static constexpr int kSlots = 4;
    RadiusTaps slot[kSlots];
    int next = 0;
    /// The slot that holds, or will build, the taps of `radius`.
    RadiusTaps& of(float radius) {
        for (RadiusTaps& t : slot)
            if (t.radius == radius) return t;
        RadiusTaps& t = slot[next];
        next = (next + 1) % kSlots;
        return t;
    }
    void clear() {
        for (RadiusTaps& t : slot) t.radius = -1.0f;
    }
};

/// How many taps ahead sharedTaps prefetches a tap's three runs for stage 7, whose taps reach
/// hundreds of rows away (stage 4's disk stays in cache, and ran slower with it).
constexpr int kPrefetchTaps = 4;

/// Eight or sixteen centres (V) sharing one rotation and one radius: tap by tap, the
/// neighbours at one offset are one run of the packed buffers. `runs` holds the merged taps, or,
/// where null, the `taps` unit offsets of `spiral` are scaled by `radius` in `built`.
template <Isa kIsa, class V>
BMFR_SIMD_INLINE void sharedTaps(const MaraFrame& f, const float* src, int x, int y, IntOf<V> live,
                                 const MaraTapRuns* runs, int rotation, const float* spiral,
                                 int taps, float radius, float sigma, RadiusTaps& built,
                                 bool prefetch, SparseSum<kIsa, V>& acc) {
    using M = IntOf<V>;
    constexpr int kLanes = kLanesOf<V>;
    const int *dx, *dy;
    const float* g;
    int count;
    if (runs) {
        const int b = runs->begin[size_t(rotation)];
        dx = runs->dx.data() + b, dy = runs->dy.data() + b, g = runs->g.data() + b;
        count = runs->begin[size_t(rotation) + 1] - b;
    } else {
        count = built.build<kIsa>(rotation, spiral, taps, radius, sigma);
        dx = built.dx[rotation], dy = built.dy[rotation], g = built.g[rotation];
    }
    const M lane = laneIndices<M>();
    const V on = live ? V{} + 1.0f : V{}; // g times 1 is g, exactly
    const int w = f.width;
    for (int t = 0; t < count; ++t) {
        if (prefetch && t + kPrefetchTaps < count) {
            const int py = std::clamp(y + dy[t + kPrefetchTaps], 0, f.height - 1);
            const long pj = long(py) * w + x + dx[t + kPrefetchTaps];
            const float* buffers[3] = {f.position, f.normal, src};
            for (const float* b : buffers) {
                // The run's first and last floats, and every cache line between for sixteen.
                __builtin_prefetch(b + 3 * pj);
                if constexpr (kLanes == 16) {
                    __builtin_prefetch(b + 3 * pj + 16);
                    __builtin_prefetch(b + 3 * pj + 32);
                }
                __builtin_prefetch(b + 3 * pj + 3 * kLanes - 1);
            }
        }
        const int qy = y + dy[t], qx = x + dx[t];
        if (qy < 0 || qy >= f.height) continue;
        const long j = long(qy) * w + qx;
        if (qx >= 0 && qx + kLanes <= w) {
            acc.addRun(f, src, j, on * g[t]);
            continue;
        }
        const M lx = qx + lane, inside = live & (lx >= 0) & (lx < w);
        if (!anyLaneOf(inside)) continue;
        acc.addGathered(f, src, inside ? int(j) + lane : M{} + int(long(y) * w + x),
                        inside ? V{} + g[t] : V{});
    }
}

/// Eight centres with their own rotations or radii: each lane's taps, gathered.
template <Isa kIsa>
BMFR_SIMD_INLINE void laneTaps(const MaraFrame& f, const float* src, bool final, int x, int y,
                               int n, i8 live, f8 radius, const MaraTapTables& tables,
                               SparseSum<kIsa, f8>& acc) {
    const int w = f.width, taps = final ? f.finalTaps : f.preTaps;
    const i8 lane = laneIndices<i8>();
    // Every lane's taps, tap-major, so that the tap loop reads them as vectors.
    alignas(32) int ox[kMaxTaps * 8], oy[kMaxTaps * 8];
    alignas(32) float og[kMaxTaps * 8];
    int rotations[8] = {}; // each lane's, where it computed its taps
    for (int l = 0; l < 8; ++l) {
        const int r = maraPixelRotation(x + (l < n ? l : 0), y, f.rotationWidth, f.frame, f.seed,
                                        final ? 7 : 4);
        int t = -1;
        for (int k = 0; final && k < MaraTapTables::kRadii; ++k)
            if (radius[l] == tables.radius[k]) t = k;
        if (final && t < 0) { // as maraSparseBilateral computes them
            int same = 0;     // an earlier lane with this radius and rotation, whose taps it shares
            while (same < l && !(radius[same] == radius[l] && rotations[same] == r)) ++same;
            rotations[l] = r;
            if (same < l) {
                for (int k = 0; k < taps; ++k)
                    ox[8 * k + l] = ox[8 * k + same], oy[8 * k + l] = oy[8 * k + same],
                               og[8 * k + l] = og[8 * k + same];
                continue;
            }
            int dx[kMaxTaps], dy[kMaxTaps];
            alignas(32) float g[kMaxTaps];
            scaledTaps<kIsa>(f.finalSpiral + 2 * taps * r, taps, radius[l],
                             f.finalSigma * radius[l], dx, dy, g);
            for (int k = 0; k < taps; ++k)
                ox[8 * k + l] = dx[k], oy[8 * k + l] = dy[k], og[8 * k + l] = g[k];
            continue;
        }
        const int* offsets = final ? tables.offsets[t].data() : f.preOffsets;
        const float* gauss = final ? tables.gauss[t].data() : f.preGauss;
        for (int k = 0; k < taps; ++k)
            ox[8 * k + l] = offsets[2 * (taps * r + k)],
                       oy[8 * k + l] = offsets[2 * (taps * r + k) + 1],
                       og[8 * k + l] = gauss[taps * r + k];
    }
    const long i = long(y) * w + x;
    for (int k = 0; k < taps; ++k) {
        i8 dx, dy;
        std::memcpy(&dx, ox + 8 * k, sizeof dx), std::memcpy(&dy, oy + 8 * k, sizeof dy);
        const i8 qx = x + lane + dx, qy = y + dy;
        const i8 inside = live & (qx >= 0) & (qy >= 0) & (qx < w) & (qy < f.height);
        if (!anyLane(inside)) continue;
        acc.addGathered(f, src, inside ? qy * w + qx : i8{} + int(i),
                        inside ? load8(og + 8 * k) : f8{});
    }
}

/// Stage 4 or 7 of the n centres from x in row y, eight lanes (n below 8 only at a tile's end) or
/// sixteen (V; n is 16, within one run of rotationWidth). Sixteen with more than two radii take
/// two groups of eight.
template <Isa kIsa, class V>
BMFR_SIMD_INLINE void sparseGroup(const MaraFrame& f, const float* src, bool final, int y, int x,
                                  int n, const MaraTapTables& tables, RadiusCache& built) {
    using M = IntOf<V>;
    constexpr int kLanes = kLanesOf<V>;
    const long i = long(y) * f.width + x;
    float* dst = final ? f.matteOut : f.matteHistory;
    V radius = V{} + f.preRadius;
    if (final)
        for (int l = 0; l < kLanes; ++l) radius[l] = l < n ? f.radius[i + l] : 0.0f;
    const M live = (radius >= 0.5f) & (laneIndices<M>() < n);
    // One rotation for the lanes when runs of rotationWidth cover them: the lanes that share a
    // radius take its taps as runs together, when there are at most two radii (the other lanes
    // adding 0 meanwhile). More radii: sixteen lanes go as two groups of eight (decided before
    // the centres are read, which those read again), eight gather each lane's own taps.
    float radii[2] = {-1.0f, -1.0f}; // the first two radii of the live lanes
    int distinct = 0;                // how many there are, counted up to 3
    for (int l = 0; l < kLanes && distinct <= 2; ++l) {
        if (!live[l] || radius[l] == radii[0] || radius[l] == radii[1]) continue;
        if (distinct < 2) radii[distinct] = radius[l];
        ++distinct;
    }
    const bool ownTaps = f.rotationWidth % kLanes != 0 || distinct > 2;
    if constexpr (kLanes == 16) {
        if (ownTaps) {
            sparseGroup<kIsa, f8>(f, src, final, y, x, 8, tables, built);
            sparseGroup<kIsa, f8>(f, src, final, y, x + 8, n - 8, tables, built);
            return;
        }
    }
    SparseSum<kIsa, V> acc;
    if constexpr (kLanes == 8) {
        loadXyz8(f.position + 3 * i, n, acc.pc);
        loadXyz8(f.normal + 3 * i, n, acc.nc);
        loadXyz8(src + 3 * i, n, acc.sum);
    } else {
        runXyz<kIsa>(f.position + 3 * i, acc.pc);
        runXyz<kIsa>(f.normal + 3 * i, acc.nc);
        runXyz<kIsa>(src + 3 * i, acc.sum);
    }
    auto store = [&] [[gnu::always_inline]] (const V v[3]) {
        for (int h = 0; h < kLanes; h += 8) {
            const f8 half[3] = {eightLanes(v[0], h), eightLanes(v[1], h), eightLanes(v[2], h)};
            storeXyz8(dst + 3 * (i + h), std::min(8, n - h), half);
        }
    };
    if (!anyLaneOf(live)) return store(acc.sum);
    if (ownTaps) {
        if constexpr (kLanes == 8)
            laneTaps<kIsa>(f, src, final, x, y, n, live, radius, tables, acc);
    } else {
        const int rotation =
            maraPixelRotation(x, y, f.rotationWidth, f.frame, f.seed, final ? 7 : 4);
        auto taps = [&] [[gnu::always_inline]] (float shared, M lanes) {
            const MaraTapRuns* runs = final ? nullptr : &tables.pre;
            for (int t = 0; final && t < MaraTapTables::kRadii; ++t)
                if (shared == tables.radius[t]) runs = &tables.runs[t];
            sharedTaps<kIsa>(f, src, x, y, lanes, runs, rotation,
                             f.finalSpiral + 2 * f.finalTaps * rotation, f.finalTaps, shared,
                             f.finalSigma * shared, built.of(shared), final, acc);
        };
        if (distinct == 1) {
            taps(radii[0], live);
        } else {
            taps(radii[0], live & (radius == radii[0]));
            taps(radii[1], live & (radius == radii[1]));
        }
    }
    const V out[3] = {acc.sum[0] / acc.total, acc.sum[1] / acc.total, acc.sum[2] / acc.total};
    store(out);
}

BMFR_SIMD_DISPATCH(void, sparseRow,
                   (const MaraFrame& f, const float* src, bool final, int y, int x0, int x1,
                    const MaraTapTables& tables, RadiusCache& built),
                   (f, src, final, y, x0, x1, tables, built)) {
    for (int x = x0; x < x1;) {
        // Sixteen lanes on AVX-512 where a rotation's run covers them, as one register each.
        if constexpr (kIsa == Isa::Avx512) {
            if (f.rotationWidth % 16 == 0 && x % 16 == 0 && x + 16 <= x1) {
                sparseGroup<kIsa, f32x16>(f, src, final, y, x, 16, tables, built);
                x += 16;
                continue;
            }
        }
        sparseGroup<kIsa, f8>(f, src, final, y, x, std::min(8, x1 - x), tables, built);
        x += 8;
    }
}

BMFR_SIMD_DISPATCH(void, medianRow, (const MaraFrame& f, int y), (f, y)) {
    const int w = f.width;
    int rows[3];
    for (int d = -1; d <= 1; ++d)
        rows[d + 1] = y + d < 0 ? 0 : y + d >= f.height ? f.height - 1 : y + d;
    int x = 0;
    if (w >= 10) {
        maraMedianPixel(f, 0, y);
        for (x = 1; x + 8 < w; x += 8) {
            f8 v[3][9];
            for (int r = 0; r < 3; ++r)
                for (int dx = -1; dx <= 1; ++dx) {
                    f8 c[3];
                    deinterleave3<kIsa>(f.temporal + 3 * (long(rows[r]) * w + x + dx), c[0], c[1],
                                        c[2]);
                    for (int ch = 0; ch < 3; ++ch) v[ch][3 * r + dx + 1] = c[ch];
                }
            const f8 m[3] = {median9(v[0]), median9(v[1]), median9(v[2])};
            interleave3(m[0], m[1], m[2], f.median + 3 * (long(y) * w + x));
        }
    }
    for (; x < w; ++x) maraMedianPixel(f, x, y);
}

} // namespace

void maraSparseTile(const MaraFrame& f, const float* src, bool final, int x0, int x1, long y0,
                    long y1, const MaraTapTables& tables) {
    static thread_local RadiusCache built;
    built.clear(); // the spiral turns every frame
    for (long y = y0; y < y1; ++y) sparseRow(f, src, final, int(y), x0, x1, tables, built);
}

void MaraTapRuns::build(const int* offsets, const float* gauss, int taps) {
    begin.assign(1, 0);
    dx.clear(), dy.clear(), g.clear();
    for (int r = 0; r < kMaraSpiralRotations; ++r) {
        const size_t first = dx.size();
        for (int k = r * taps; k < (r + 1) * taps; ++k) {
            const int ox = offsets[2 * k], oy = offsets[2 * k + 1];
            size_t t = first;
            while (t < dx.size() && (dx[t] != ox || dy[t] != oy)) ++t;
            if (t == dx.size()) dx.push_back(ox), dy.push_back(oy), g.push_back(0.0f);
            g[t] += gauss[k];
        }
        begin.push_back(int(dx.size()));
    }
}

void MaraTapTables::reserve(int taps) {
    for (MaraTapRuns* t : {&pre, &runs[0], &runs[1], &runs[2], &runs[3]}) {
        t->begin.reserve(kMaraSpiralRotations + 1);
        t->dx.reserve(size_t(taps * kMaraSpiralRotations));
        t->dy.reserve(size_t(taps * kMaraSpiralRotations));
        t->g.reserve(size_t(taps * kMaraSpiralRotations));
    }
    for (int t = 0; t < kRadii; ++t) {
        offsets[t].reserve(size_t(2 * taps * kMaraSpiralRotations));
        gauss[t].reserve(size_t(taps * kMaraSpiralRotations));
    }
}

void MaraTapTables::buildPre(const MaraFrame& f) {
    pre.build(f.preOffsets, f.preGauss, f.preTaps);
}

void MaraTapTables::buildFinal(const MaraFrame& f) {
    // As maraDisocclusionRadius gives them for a box min of h (or 1, normalised) and of 0.
    const float confident = f.normaliseConfidence ? 0.0f : (1.0f - f.h) * float(f.maxRadius);
    const float candidates[kRadii] = {confident, float(f.maxRadius), confident * f.radiusBoost,
                                      float(f.maxRadius) * f.radiusBoost};
    for (int t = 0; t < kRadii; ++t) {
        radius[t] = candidates[t];
        maraTapTable(f.finalSpiral, f.finalTaps * kMaraSpiralRotations, radius[t],
                     f.finalSigma * radius[t], offsets[t], gauss[t]);
        runs[t].build(offsets[t].data(), gauss[t].data(), f.finalTaps);
    }
}

void maraMedianRows(const MaraFrame& f, long y0, long y1) {
    for (long y = y0; y < y1; ++y) medianRow(f, int(y));
}

} // namespace bmfr::cpu
