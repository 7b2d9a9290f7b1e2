#include "backend/cpu/walr/cpu_walr_spatial.h"
#include "backend/cpu/simd.h"
#include <cstring>
#include <type_traits>

namespace bmfr::cpu {

using namespace simd;

void EdgePlanes::allocate(int width, int height, bool stepped) {
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
    for (std::vector<uint16_t>& b : chordBound) b.resize(size_t(4 * planeSize * height));
    if (stepped)
        for (std::vector<uint8_t>* runs : {&flatRuns, &shortestRuns})
            if (runs->size() != size_t(8 * planeSize * height))
                runs->assign(size_t(8 * planeSize * height), 255);
}

namespace {

/// Rows y0 .. y1 - 1 of the planes from the guide, eight pixels at a time.
BMFR_SIMD_DISPATCH(void, fillRows, (const EdgeGuide& g, EdgePlanes& e, long y0, long y1),
                   (g, e, y0, y1)) {
    float* const planes = e.planes.data() + EdgePlanes::kPad;
    for (long y = y0; y < y1; ++y) {
        float* const row = planes + y * e.rowStride;
        const long i0 = y * g.width;
        // The last group's lanes past the row read as 0 and land in its padding, which holds 0.
        for (int x = 0; x < g.width; x += 8) {
            const int n = g.width - x < 8 ? g.width - x : 8;
            f8 p[3], q[3];
            loadXyz8(g.position + 3 * (i0 + x), n, p);
            loadXyz8(g.normal + 3 * (i0 + x), n, q);
            for (int c = 0; c < 3; ++c) {
                store8(row + c * e.planeSize + x, p[c]);
                store8(row + (3 + c) * e.planeSize + x, q[c]);
            }
            store8(row + 6 * e.planeSize + x, loadFirst(g.depth + i0 + x, n));
        }
    }
}

} // namespace

void EdgePlanes::fill(ThreadPool& pool, const EdgeGuide& g) {
    allocate(g.width, g.height, g.stepped());
    for (int run = 0; run < 256; ++run) skipOf[run] = skipOverRun(g.stepFraction, run);
    chordLength = 0;
    skippedTaps = 0;
    pool.parallelFor(g.height, 16, [&](long y0, long y1) { fillRows(g, *this, y0, y1); });
}

namespace {

constexpr int kMaxStep = 81; // 3^(T - 1) for the largest T

/// Relative slack for rounding in the chord bounds and the test on them: well above the few
/// float roundings (2^-24 each) of any one computation.
constexpr float kChordSlack = 0x1p-20f;

/// max(|v[0]|, |v[1]|, |v[2]|)
template <class V> BMFR_SIMD_INLINE V largest3(const V v[3]) {
    return maxOf(absOf(v[0]), maxOf(absOf(v[1]), absOf(v[2])));
}

/// Eight (or, on the AVX-512 path, sixteen) non-negative floats as halves no smaller (F16C's
/// rounding up; on the baseline path the nearest half, one step up where it fell below), and
/// back.
template <cpu::Isa kIsa, class V> BMFR_SIMD_INLINE void storeBounds(uint16_t* p, V v) {
    using H = HalfOf<kIsa>;
    if constexpr (std::is_same_v<H, F16cHalf>) {
        HalvesOf<V> h;
        asm("vcvtps2ph $2, %1, %0" : "=vm"(h) : "v"(v));
        std::memcpy(p, &h, sizeof h);
    } else {
        static_assert(std::is_same_v<V, f8>);
        v = v > 65504.0f ? splat8(__builtin_inff()) : v;
        _Float16 h[8];
        store8(h, v);
        const i8 below = load8(h) < v;
        u16x8 bits;
        std::memcpy(&bits, h, sizeof bits);
        bits -= __builtin_convertvector(below, u16x8); // a true lane is -1
        std::memcpy(p, &bits, sizeof bits);
    }
}
template <cpu::Isa kIsa, class V = f8> BMFR_SIMD_INLINE V loadBounds(const uint16_t* p) {
    using H = HalfOf<kIsa>;
    if constexpr (std::is_same_v<H, F16cHalf>)
        return loadHalves<V>(reinterpret_cast<const F16cHalf*>(p));
    else
        return load8(reinterpret_cast<const H*>(p));
}

/// Sixteen lanes on the AVX-512 path (at eight, a seventh of the spatial filter's time at
/// 720p): each lane's operations are the same at either width.
BMFR_SIMD_DISPATCH(void, chordBoundRows,
                   (const EdgeGuide& g, const EdgePlanes& e, int length, const uint16_t* below,
                    uint16_t* out, long y0, long y1),
                   (g, e, length, below, out, y0, y1)) {
    using V = std::conditional_t<kIsa == Isa::Avx512, f32x16, f8>;
    using I = IntOf<V>;
    constexpr int kLanes = kLanesOf<V>;
    const long chordRow = 4 * e.planeSize;
    const float* p[3] = {e.plane(0), e.plane(1), e.plane(2)};
    const float third = 1.0f / 3.0f, twoThirds = 2.0f / 3.0f;
    const V infinity = splat<V>(__builtin_inff());
    const I lane = laneIndices<I>();
    for (long y = y0; y < y1; ++y)
        for (int x = 0; x < g.width; x += kLanes) {
            for (int d = 0; d < 4; ++d) {
                const int ux = walrTapX(4 + d), uy = walrTapY(4 + d), span = 3 * length;
                uint16_t* dst = out + d * e.planeSize + EdgePlanes::kPad + y * chordRow + x;
                // The columns whose segment stays in the image: [lo, hi).
                const int lo = ux < 0 ? span : 0, hi = ux > 0 ? g.width - span : g.width;
                const int from = x > lo ? x : lo, to = x + kLanes < hi ? x + kLanes : hi;
                if (y + span * uy >= g.height || from >= to) {
                    storeBounds<kIsa>(dst, infinity);
                    continue;
                }
                // One comparison: GCC 12 builds a sixteen-lane mask of several lane by lane.
                typedef uint32_t U __attribute__((vector_size(sizeof(I))));
                const I valid = U(lane + (x - from)) < U(I{} + (to - from));
                // The positions at 0, L, 2 L and 3 L along the segment.
                V r[4][3];
                for (int j = 0; j < 4; ++j) {
                    const long q = y * e.rowStride + x + long(j * length) * (uy * e.rowStride + ux);
                    for (int c = 0; c < 3; ++c) r[j][c] = loadVector<V>(p[c] + q);
                }
                // How far the inner two stray from the whole chord, at their parameters.
                V d1[3], d2[3];
                for (int c = 0; c < 3; ++c) {
                    const V chord = r[3][c] - r[0][c];
                    d1[c] = r[1][c] - (r[0][c] + third * chord);
                    d2[c] = r[2][c] - (r[0][c] + twoThirds * chord);
                }
                const V a1 = largest3(d1), a2 = largest3(d2);
                V bound = maxOf(a1, a2);
                if (below) { // each third's own bound plus its chord's distance from the whole's
                    const long b = d * e.planeSize + EdgePlanes::kPad + y * chordRow + x;
                    const long along = long(length) * (uy * chordRow + ux);
                    bound = maxOf(loadBounds<kIsa, V>(below + b) + a1,
                                  maxOf(loadBounds<kIsa, V>(below + b + along) + bound,
                                        loadBounds<kIsa, V>(below + b + 2 * along) + a2));
                }
                const V magnitude =
                    largest3(r[0]) + largest3(r[1]) + largest3(r[2]) + largest3(r[3]) + bound;
                bound = bound + kChordSlack * magnitude;
                storeBounds<kIsa>(dst, valid ? bound : infinity);
            }
        }
}

/// shortestRuns from flatRuns for rows y0 .. y1 - 1: the smallest of each eight in a row, 32
/// at a time.
BMFR_SIMD_DISPATCH(void, shortestRunRows, (EdgePlanes & e, long y0, long y1), (e, y0, y1)) {
    typedef uint8_t u8x32 __attribute__((vector_size(32)));
    const long size = e.planeSize, runs = 8 * size * y0, end = 8 * size * y1;
    const uint8_t* in = e.flatRuns.data();
    uint8_t* out = e.shortestRuns.data();
    for (long row = runs; row < end; row += size) {
        // The last 7 columns keep their 255: no run starting there is read.
        long c = 0;
        for (; c + 32 + 7 <= size; c += 32) {
            u8x32 m, v;
            std::memcpy(&m, in + row + c, sizeof m);
            for (int j = 1; j < kTraceRun; ++j) {
                std::memcpy(&v, in + row + c + j, sizeof v);
                m = v < m ? v : m;
            }
            std::memcpy(out + row + c, &m, sizeof m);
        }
        for (; c + 7 < size; ++c) {
            uint8_t m = in[row + c];
            for (int j = 1; j < kTraceRun; ++j) m = in[row + c + j] < m ? in[row + c + j] : m;
            out[row + c] = m;
        }
    }
}

/// The traced taps of eight pixels (x .. x + 7, y): weight and steps per tap and lane, as
/// traceTap gives them (weight 0 = dropped).
struct BlockTaps {
    float weight[8][8];
    int steps[8][8];
};

/// kStepped: stepped tracing (its own instantiation, since its code in the exact trace's loop
/// measured 8% off the whole spatial filter).
template <cpu::Isa kIsa, bool kStepped>
BMFR_SIMD_INLINE void traceBlock(const EdgeGuide& g, EdgePlanes& e, const WalrLevel& l, bool last,
                                 int x, int y, BlockTaps& out, long& skipped) {
    // Read once: the stores below (memcpy and memset among them) might otherwise alias them.
    const long rowStride = e.rowStride, planeSize = e.planeSize;
    const int width = g.width, height = g.height, step = l.step;
    const int first = l.iteration > 0 ? step / 3 + 1 : 1; // traced by the last iteration
    const bool tracing = g.tracing, replacement = g.replacement;
    const bool chordReady = e.chordLength == step;
    // Stepped tracing: the lanes' runs, carried and written back; the last iteration's shortest.
    constexpr bool stepping = kStepped;
    const long runRow = 8 * planeSize;
    uint8_t* const runs = stepping ? e.flatRun(0) + y * runRow + x : nullptr;
    const uint8_t* const shortest = stepping && l.iteration > 0 ? e.shortestRun(0) : nullptr;
    const long blockState = (long(y) * e.blocksPerRow + x / 8) * 64;
    float* const blockMin = e.tracedMin.data() + blockState;
    int32_t* const blockEdge = e.tracedEdge.data() + blockState;
    const uint16_t* const chords = e.chordBounds(0); // direction d's at + d * planeSize
    const long o = long(y) * rowStride + x;
    const float *px = e.plane(0), *py = e.plane(1), *pz = e.plane(2);
    const f8 p[3] = {load8(px + o), load8(py + o), load8(pz + o)};
    const f8 n[3] = {load8(e.plane(3) + o), load8(e.plane(4) + o), load8(e.plane(5) + o)};
    const f8 z = load8(e.plane(6) + o);
    const f8 zc = z > 0.0f ? z : f8{};
    const f8 a = g.nearFraction * zc, b = g.farFraction * zc;
    const f8 slope = b > a ? 1.0f / (b - a) : f8{}; // rampSlope per lane
    const f8 normalSum = abs8(n[0]) + abs8(n[1]) + abs8(n[2]);
    const f8 flatBelow = a * (1.0f - kChordSlack);
    const i8 laneX = i8{0, 1, 2, 3, 4, 5, 6, 7} + x;
    const i8 exists = laneX < width;
    f8 running[kMaxStep + 1]; // the traced minimum after k steps, for replacements
    for (int tap = 0; tap < 8; ++tap) {
        const int ux = walrTapX(tap), uy = walrTapY(tap), ey = y + step * uy;
        const long along = uy * rowStride + ux; // plane floats from one step to the next
        const long along8 = uy * runRow + ux;   // the same in the run planes
        const i8 endX = laneX + step * ux;
        const i8 inside = (laneX < width) & (endX >= 0) & (endX < width);
        if (ey < 0 || ey >= height || !anyLane(inside)) {
            store8(out.weight[tap], f8{});
            std::memset(out.steps[tap], 0, sizeof out.steps[tap]);
            if constexpr (stepping)
                storeBytes(runs + tap * planeSize, exists ? i8{} : i8{} + 255, 8);
            continue;
        }
        // Each lane's plane distance at step k, as edgeWeight computes it (padding keeps the
        // loads in bounds), and the largest coordinate of its offset from the centre.
        auto distanceAt = [&](int k, f8* offset) __attribute__((always_inline)) {
            const long q = o + k * along;
            const f8 d0 = load8(px + q) - p[0], d1 = load8(py + q) - p[1],
                     d2 = load8(pz + q) - p[2];
            const f8 dd = n[0] * d0 + n[1] * d1 + n[2] * d2;
            if (offset) *offset = max8(abs8(d0), max8(abs8(d1), abs8(d2)));
            return abs8(dd);
        };
        // Each lane's edgeWeight at step k along the tap.
        auto weightAt = [&](int k) __attribute__((always_inline)) {
            const f8 dd = distanceAt(k, nullptr);
            return dd > a ? (dd < b ? (b - dd) * slope : f8{}) : splat8(1.0f);
        };
        // Lanes where every step of the tap provably weighs 1: the plane distance is linear
        // along the chord from the centre (distance 0) to the end, and the positions stray from
        // it by at most the segment's bound in each coordinate, so by normalSum times it.
        auto flatTap = [&]() __attribute__((always_inline)) {
            // Taps 0 to 3 run backwards along the segments of taps 7 to 4 from their ends.
            const int back = tap < 4 ? step : 0;
            const long at = long(y + back * uy) * 4 * planeSize + x + back * ux;
            const uint16_t* bounds = chords + (tap < 4 ? 3 - tap : tap - 4) * planeSize + at;
            __builtin_prefetch(bounds + 32); // four blocks on: measured 5% off the whole filter
            const f8 bound = loadBounds<kIsa>(bounds);
            f8 offset;
            const f8 reach = distanceAt(step, &offset) + normalSum * bound;
            const f8 slack = kChordSlack * normalSum * (offset + bound);
            return reach + slack < flatBelow;
        };
        f8 m = splat8(1.0f);
        i8 edge{};
        const long i = long(y) * width + x;
        float* const stateMin = blockMin + 8 * tap;
        int32_t* const stateEdge = blockEdge + 8 * tap;
        auto loadTrace = [&]() __attribute__((always_inline)) {
            if (first > 1) {
                m = load8(stateMin);
                std::memcpy(&edge, stateEdge, sizeof edge);
            }
        };
        auto storeTrace = [&]() __attribute__((always_inline)) {
            if (last) return;
            store8(stateMin, m);
            std::memcpy(stateEdge, &edge, sizeof edge);
        };
        // steppedTrace, eight lanes on one schedule: the skips are the run's.
        auto steppedSteps = [&](i8 & flat) __attribute__((always_inline)) {
            int evaluated = 0;
            auto stepOn = [&](int k) __attribute__((always_inline)) {
                const f8 w = weightAt(k);
                m = w < m ? w : m;
                const i8 at = i8{} + k;
                edge = (edge == 0) & (m <= 0.0f) ? at : edge;
                flat = m >= 1.0f ? at : flat;
                return (++evaluated & 3) != 0 || anyLane(inside & (m > 0.0f));
            };
            if (!shortest) {
                for (int k = 1; k <= step; ++k)
                    if (!stepOn(k)) return;
                return;
            }
            const int third = step / 3;
            const uint8_t* ahead = shortest + tap * planeSize + y * runRow + x;
            __builtin_prefetch(ahead + third * along8 + 64); // rows away: eight blocks on
            __builtin_prefetch(ahead + 2 * third * along8 + 64);
            const int skip[2] = {e.skipOf[ahead[third * along8]],
                                 e.skipOf[ahead[2 * third * along8]]};
            for (int j = 0; j < 2; ++j) {
                const int anchor = (j + 1) * third;
                const int from = anchor + 1 + skip[j];
                for (int k = from < step ? from : step; k <= anchor + third; ++k)
                    if (!stepOn(k)) return;
            }
        };
        if (!tracing) {
            m = weightAt(step);
        } else if constexpr (stepping) {
            loadTrace();
            i8 flat = first > 1 ? loadBytes(runs + tap * planeSize, 8) : i8{};
            if (anyLane(inside & (m > 0.0f))) steppedSteps(flat);
            storeTrace();
            storeBytes(runs + tap * planeSize, exists ? (inside ? flat : i8{}) : i8{} + 255, 8);
        } else {
            loadTrace();
            // Steps first .. step. Past a lane's first zero m stays 0, so the count of steps
            // with m > 0 finds that zero, and the test that every lane has met one can wait a
            // few steps.
            auto traceSteps = [&]() __attribute__((always_inline)) {
                i8 positive{}; // minus that count
                for (int k = first; k <= step; ++k) {
                    const f8 w = weightAt(k);
                    m = w < m ? w : m;
                    running[k] = m;
                    positive += m > 0.0f;
                    if (((k - first) & 3) == 3 && !anyLane(inside & (m > 0.0f))) break;
                }
                edge = (edge == 0) & (m <= 0.0f) ? first - positive : edge;
            };
            if (!chordReady || anyLane(inside & (m > 0.0f) & ~flatTap()))
                traceSteps();
            else
                ++skipped;
            storeTrace();
        }
        const i8 kept = inside & (m > 0.0f);
        f8 weight = kept ? m : f8{};
        i8 steps = kept ? i8{} + step : i8{};
        const i8 replaced = inside & ~kept & (edge > 1);
        if (tracing && replacement && anyLane(replaced)) {
            // replacementStep(replacementHash(...)) (edge_tracing.h) of the eight lanes at once,
            // in its operations: most lanes of a block cut by an edge are replaced.
            const u32x8 hash = replacementHashOf(u32x8(laneX - x) + uint32_t(i), l.frame,
                                                 l.iteration, tap, l.seed);
            const f8 unit = __builtin_convertvector(i8(hash >> 8), f8) * (1.0f / 16777216.0f);
            const i8 replacedStep =
                1 + __builtin_convertvector(unit * __builtin_convertvector(edge - 1, f8), i8);
            // The largest step that a replacement reads before `first` (stepped: any step).
            const i8 early = stepping ? replaced : replaced & (replacedStep < first);
            const int deepest = -hminLanes(early ? -replacedStep : i8{});
            // Steps traced by an earlier iteration, traced again for the lanes that read them
            // (their running minima go where this iteration's trace, which starts at `first`,
            // left none); with stepped tracing every step a replacement reads, since a stepped
            // trace skips some.
            f8 before = splat8(1.0f);
            for (int k = 1; k <= deepest; ++k) {
                const f8 w = weightAt(k);
                before = w < before ? w : before;
                running[k] = before;
            }
            // Each replaced lane's running minimum at its step; the others read one that a
            // replaced lane reads, and keep their own.
            const int any = hminLanes(replaced ? replacedStep : i8{} + kMaxStep);
            const i8 at = (replaced ? replacedStep : i8{} + any) * 8 + (laneX - x);
            weight = replaced ? gather8(reinterpret_cast<const float*>(running), at) : weight;
            steps = replaced ? replacedStep : steps;
        }
        store8(out.weight[tap], weight);
        std::memcpy(out.steps[tap], &steps, sizeof steps);
    }
}

/// The averages of one pixel from its traced taps, its 16 interleaved floats (14 averages and 2
/// unused) as one vector on the AVX-512 path and two elsewhere (GCC splits a 64-byte vector
/// through memory on AVX2: measured 1.9x the instructions). With halfIn or halfOut the input or
/// output holds 16 halves per pixel instead, converted sixteen at a time on the AVX-512 path and
/// eight elsewhere.
template <cpu::Isa kIsa>
BMFR_SIMD_INLINE void gatherPixel(const WalrLevel& l, const BlockTaps& t, const long (&along)[8],
                                  int lane, long i) {
    using V = std::conditional_t<kIsa == Isa::Avx512, f32x16, f8>;
    using H = HalfOf<kIsa>;
    constexpr int kParts = 16 / kLanesOf<V>, kLanes = kLanesOf<V>;
    constexpr bool kSixteenHalves = kParts == 1 && std::is_same_v<H, F16cHalf>;
    auto load = [&](long j, V* v) __attribute__((always_inline)) {
        if (l.halfIn) {
            const H* h = reinterpret_cast<const H*>(l.in) + 16 * j;
            if constexpr (kSixteenHalves) {
                v[0] = loadHalves<V>(h);
            } else if constexpr (kParts == 1) {
                v[0] = __builtin_shufflevector(load8(h), load8(h + 8), 0, 1, 2, 3, 4, 5, 6, 7, 8, 9,
                                               10, 11, 12, 13, 14, 15);
            } else {
                v[0] = load8(h), v[1] = load8(h + 8);
            }
        } else {
            for (int p = 0; p < kParts; ++p) v[p] = loadVector<V>(l.in + 16 * j + kLanes * p);
        }
    };
    float total = l.weightIn ? l.weightIn[i] : 1.0f;
    V sum[kParts], v[kParts];
    load(i, v);
    for (int p = 0; p < kParts; ++p) sum[p] = total * v[p];
    for (int tap = 0; tap < 8; ++tap) {
        const float wt = t.weight[tap][lane];
        if (!(wt > 0)) continue;
        const long j = i + t.steps[tap][lane] * along[tap];
        const float w = l.weightIn ? wt * l.weightIn[j] : wt;
        load(j, v);
        for (int p = 0; p < kParts; ++p) sum[p] += w * v[p];
        total += w;
    }
    for (int p = 0; p < kParts; ++p) sum[p] = sum[p] / total;
    if (l.halfOut) {
        H* h = reinterpret_cast<H*>(l.out) + 16 * i;
        if constexpr (kSixteenHalves) {
            storeHalves(h, sum[0]);
        } else if constexpr (kParts == 1) {
            store8(h, eightLanes(sum[0], 0));
            store8(h + 8, eightLanes(sum[0], 8));
        } else {
            store8(h, sum[0]), store8(h + 8, sum[1]);
        }
    } else {
        for (int p = 0; p < kParts; ++p) storeVector(l.out + 16 * i + kLanes * p, sum[p]);
    }
    if (l.weightOut) l.weightOut[i] = total;
}

/// Trace and gather rows y0 .. y1 - 1 of one iteration, eight pixels at a time.
BMFR_SIMD_DISPATCH(void, atrousRows,
                   (const EdgeGuide& g, EdgePlanes& e, const WalrLevel& l, bool last, int y0,
                    int y1, long& skipped),
                   (g, e, l, last, y0, y1, skipped)) {
    long along[8]; // pixels from one step along each tap direction to the next
    for (int tap = 0; tap < 8; ++tap) along[tap] = long(walrTapY(tap)) * g.width + walrTapX(tap);
    BlockTaps taps;
    auto rows = [&](auto stepped) __attribute__((always_inline)) {
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < g.width; x += 8) {
                traceBlock<kIsa, decltype(stepped)::value>(g, e, l, last, x, y, taps, skipped);
                const int count = g.width - x < 8 ? g.width - x : 8;
                for (int lane = 0; lane < count; ++lane)
                    gatherPixel<kIsa>(l, taps, along, lane, long(y) * g.width + x + lane);
            }
    };
    if (g.stepped())
        rows(std::true_type{});
    else
        rows(std::false_type{});
}

/// choleskyClamped, choleskySolve and the prediction of walrPredict<float>, eight pixels wide.
BMFR_SIMD_DISPATCH(void, solveBlock,
                   (const float* averages, const float* features, float eps, long i, int count,
                    float* out),
                   (averages, features, eps, i, count, out)) {
    f8 a[16], fx{}, fy{};
    if (count == 8) { // the eight pixels' 16 floats each, transposed
        for (int half = 0; half < 2; ++half) {
            f8 rows[8];
            for (int lane = 0; lane < 8; ++lane)
                rows[lane] = load8(averages + 16 * (i + lane) + 8 * half);
            transpose8(rows, a + 8 * half);
        }
        loadXy8(features + 2 * i, 8, fx, fy);
    } else {
        for (int lane = 0; lane < count; ++lane) {
            for (int k = 0; k < kWalrAverages; ++k) a[k][lane] = averages[16 * (i + lane) + k];
            fx[lane] = features[2 * (i + lane)], fy[lane] = features[2 * (i + lane) + 1];
        }
        for (int lane = count; lane < 8; ++lane)
            for (int k = 0; k < kWalrAverages; ++k) a[k][lane] = k == 2 || k == 4 ? 1.0f : 0.0f;
    }
    // A loop GCC makes one vsqrtps (the file is compiled without math-errno).
    auto root = [](f8 v) {
        for (int lane = 0; lane < 8; ++lane) v[lane] = __builtin_sqrtf(v[lane]);
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

void EdgePlanes::buildChordBounds(ThreadPool& pool, const EdgeGuide& g) {
    const int below = chordLength;
    const int level = below ? 1 - chordLevel : chordLevel;
    const uint16_t* from = below ? chordBound[chordLevel].data() : nullptr;
    uint16_t* to = chordBound[level].data();
    const int length = below ? below : 1;
    pool.parallelFor(g.height, 4,
                     [&](long y0, long y1) { chordBoundRows(g, *this, length, from, to, y0, y1); });
    chordLevel = level;
    chordLength = 3 * length;
}

void EdgePlanes::buildShortestRuns(ThreadPool& pool, int height) {
    pool.parallelFor(height, 8, [&](long y0, long y1) { shortestRunRows(*this, y0, y1); });
}

void walrAtrousIteration(ThreadPool& pool, const EdgeGuide& g, EdgePlanes& e, const WalrLevel& l,
                         bool last) {
    if (g.stepped() && l.iteration > 0) e.buildShortestRuns(pool, g.height);
    if (g.tracing && !g.stepped() && l.iteration >= 2)
        while (e.chordLength < l.step) e.buildChordBounds(pool, g);
    // Plain row order: columns of single blocks (so that vertical steps revisit cached rows)
    // measured 1.5x slower, and bands cut into strips no faster.
    pool.parallelFor(g.height, 2, [&](long y0, long y1) {
        long skipped = 0;
        atrousRows(g, e, l, last, int(y0), int(y1), skipped);
        e.skippedTaps += skipped;
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
