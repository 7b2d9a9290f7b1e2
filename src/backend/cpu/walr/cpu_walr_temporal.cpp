#include "backend/cpu/walr/cpu_walr_temporal.h"
#include "backend/cpu/modulation8.h"
#include "backend/cpu/pixel_input8.h"
#include "backend/cpu/reproject8.h"
#include <algorithm>
#include <cmath>
#include <cstring>

namespace bmfr::cpu {

using namespace simd;

namespace {

/// transformPoint(m, p).w for eight points, in its order of operations.
BMFR_SIMD_INLINE f8 depth8(const Mat4& m, const f8 p[3]) {
    return ((m.m[3][0] * p[0] + m.m[3][1] * p[1]) + m.m[3][2] * p[2]) + m.m[3][3];
}

BMFR_SIMD_INLINE void inputGroup(const WalrFrame& f, int x, int y, int n, int64_t& bad) {
    const long i = long(y) * f.width + x;
    const Inputs8 px = readInputs8(f.in, f.modes, i, n, bad);
    f8 y3[3] = {px.color[0], px.color[1], px.color[2]};
    if (f.in.diffuseIndirect) {
        loadXyz8(f.in.diffuseIndirect + 3 * i, n, y3);
        finiteOrZero8(y3, bad);
        for (f8& v : y3) v = max8(v, f8{});
    }
    storeXyz8(f.signal + 3 * i, n, y3);
    storeXyz8(f.position + 3 * i, n, px.position);
    storeXyz8(f.normal + 3 * i, n, px.normal);
    const f8 z = depth8(f.viewProjection, px.position);
    storeFirst(f.depth + i, z, n);
    for (int l = 0; l < n; ++l) {
        const Vec3 nl{px.normal[0][l], px.normal[1][l], px.normal[2][l]};
        const Vec3 pl{px.position[0][l], px.position[1][l], px.position[2][l]};
        const Vec2 feat = walrNormalFeatures(nl, pl, f.view);
        f.features[2 * (i + l)] = feat.x, f.features[2 * (i + l) + 1] = feat.y;
    }
    Surface8 was;
    const i8 found =
        previousSurface8(f.in, f.previous, i, x, y, n, px.position, px.normal, bad, was);
    const f8 lane = {0, 1, 2, 3, 4, 5, 6, 7}, none = splat8(NAN);
    storeXy8(f.offset + 2 * i, n, found ? was.px - (float(x) + lane) : none,
             found ? was.py - float(y) : none);
    f8 expected;
    if (f.in.motionDepth) {
        const f8 md = loadFirst(f.in.motionDepth + i, n);
        const i8 finite = finite8(md);
        bad += countLanes(~finite);
        expected = found & finite ? z + md : none;
    } else {
        expected = found ? depth8(f.previous.viewProjection, was.position) : none;
    }
    storeFirst(f.expectedDepth + i, expected, n);
}

/// catmullRomWeights for eight fractions, in its order of operations.
BMFR_SIMD_INLINE void catmullRomWeights8(f8 t, f8 w[4]) {
    w[0] = t * (-0.5f + t * (1.0f - 0.5f * t));
    w[1] = 1.0f + t * t * (-2.5f + 1.5f * t);
    w[2] = t * (0.5f + t * (2.0f - 1.5f * t));
    w[3] = t * t * (-0.5f + 0.5f * t);
}

/// Lane l's three channels at column x0 + l (+ 1 in the `upper` lanes, with `split`) of row
/// `row` of a packed xyz image.
BMFR_SIMD_INLINE void runTap(const float* image, long at, bool split, i8 upper, f8 v[3]) {
    deinterleave3(image + 3 * at, v[0], v[1], v[2]);
    if (!split) return;
    f8 w[3];
    deinterleave3(image + 3 * (at + 1), w[0], w[1], w[2]);
    for (int c = 0; c < 3; ++c) v[c] = upper ? w[c] : v[c];
}

/// sampleCatmullRom2 of eight lanes whose 4x4 footprints lie side by side, lane l's starting at
/// column x0 + l (+ 1 in the `upper` lanes, with `split`) of row y0, all inside the image (so
/// no tap is clamped).
BMFR_SIMD_INLINE void catmullRomRun8(const WalrFrame& f, int x0, int y0, bool split, i8 upper,
                                     f8 fx, f8 fy, f8 a[3], f8 b[3]) {
    f8 wx[4], wy[4];
    catmullRomWeights8(fx, wx);
    catmullRomWeights8(fy, wy);
    f8 sumA[3] = {}, sumB[3] = {};
    for (int j = 0; j < 4; ++j) {
        const long row = long(y0 + j) * f.width + x0;
        f8 rowA[3] = {}, rowB[3] = {};
        for (int k = 0; k < 4; ++k) {
            f8 v[3];
            runTap(f.prevPre, row + k, split, upper, v);
            for (int c = 0; c < 3; ++c) rowA[c] += wx[k] * v[c];
            if (!f.prevPost) continue;
            runTap(f.prevPost, row + k, split, upper, v);
            for (int c = 0; c < 3; ++c) rowB[c] += wx[k] * v[c];
        }
        for (int c = 0; c < 3; ++c) sumA[c] += wy[j] * rowA[c], sumB[c] += wy[j] * rowB[c];
    }
    for (int c = 0; c < 3; ++c) a[c] = max8(sumA[c], f8{}), b[c] = max8(sumB[c], f8{});
}

/// The history lookup of walrAccumulatePixel for eight pixels of a row, away from the image's
/// sides, under the depth test: each lane's previous position (pp, walrDilatedOffset's), whether
/// its nearest previous pixel keeps the history, and that pixel's samples. The same operations
/// lane for lane, the 3x3 search in the same order.
BMFR_SIMD_INLINE void historyLookup8(const WalrFrame& f, int x, int y, f8& ppx, f8& ppy, i8& keep,
                                     f8& samples) {
    const int w = f.width;
    const long i = long(y) * w + x;
    const i8 lane = {0, 1, 2, 3, 4, 5, 6, 7};
    i8 best = lane + int(i);
    if (f.dilation) {
        const f8 centre = load8(f.depth + i);
        f8 z = centre > 0.0f ? centre : splat8(INFINITY);
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const long o = i + long(dy) * w + dx;
                const f8 d = load8(f.depth + o);
                const i8 closer = (d > 0.0f) & (d < z);
                z = closer ? d : z;
                best = closer ? lane + int(o) : best;
            }
    }
    f8 offX, offY;
    for (int l = 0; l < 8; ++l)
        offX[l] = f.offset[2 * best[l]], offY[l] = f.offset[2 * best[l] + 1];
    ppx = (float(x) + __builtin_convertvector(lane, f8)) + offX;
    ppy = float(y) + offY;
    const i8 near = (abs8(ppx) < 1e8f) & (abs8(ppy) < 1e8f); // finite, and ints below
    f8 rx = near ? ppx + 0.5f : f8{}, ry = near ? ppy + 0.5f : f8{};
    for (int l = 0; l < 8; ++l) rx[l] = std::floor(rx[l]), ry[l] = std::floor(ry[l]);
    const i8 nx = __builtin_convertvector(rx, i8), ny = __builtin_convertvector(ry, i8);
    const i8 inside = near & (nx >= 0) & (ny >= 0) & (nx < w) & (ny < f.height);
    const i8 j = inside ? ny * w + nx : lane + int(i);
    f8 count, previousDepth;
    for (int l = 0; l < 8; ++l) count[l] = f.prevCount[j[l]], previousDepth[l] = f.prevDepth[j[l]];
    samples = inside ? count : f8{};
    const f8 e = load8(f.expectedDepth + i);
    keep = inside & (count > 0.0f) & (e > 0.0f) & (abs8(e - previousDepth) <= f.depthTolerance * e);
}

BMFR_SIMD_INLINE void accumulateGroup(const WalrFrame& f, int x, int y, int n, float* averages) {
    const long i = long(y) * f.width + x;
    f8 ppx{}, ppy{}, samples{};
    i8 keep{};
    // The vector lookup reads the 3x3 around each lane, and indexes pixels as int.
    const bool vector = n == 8 && f.depthTest && x >= 1 && x + 9 <= f.width && y >= 1 &&
                        y + 1 < f.height && long(f.width) * f.height < (1L << 31);
    if (vector) historyLookup8(f, x, y, ppx, ppy, keep, samples);
    for (int l = 0; l < n && !vector; ++l) {
        const Vec2 off = walrDilatedOffset(f, x + l, y);
        const Vec2 pp{float(x + l) + off.x, float(y) + off.y};
        ppx[l] = pp.x, ppy[l] = pp.y;
        if (!(std::isfinite(pp.x) && std::isfinite(pp.y) && std::fabs(pp.x) < 1e8f &&
              std::fabs(pp.y) < 1e8f))
            continue;
        const int nx = int(std::floor(pp.x + 0.5f)), ny = int(std::floor(pp.y + 0.5f));
        if (nx < 0 || ny < 0 || nx >= f.width || ny >= f.height) continue;
        const long j = long(ny) * f.width + nx;
        keep[l] = f.prevCount[j] > 0 && walrSameSurface(f, i + l, j) ? -1 : 0;
        samples[l] = float(f.prevCount[j]);
    }
    f8 y3[3];
    loadXyz8(f.signal + 3 * i, n, y3);
    f8 acc[3] = {y3[0], y3[1], y3[2]}, post[3] = {y3[0], y3[1], y3[2]};
    if (anyLane(keep)) {
        f8 h[3], hp[3];
        // Side by side: each kept lane's footprint starts one column after the last lane's, or
        // (split) one further in some lanes, as a depth step or a small zoom spreads them.
        f8 bx = ppx, by = ppy;
        for (int l = 0; l < 8; ++l) bx[l] = std::floor(bx[l]), by[l] = std::floor(by[l]);
        int x0 = 1 << 30, x1 = -(1 << 30), y0 = 0;
        bool run = true;
        for (int l = 0; l < n; ++l) {
            if (!keep[l]) continue;
            const int start = int(bx[l]) - 1 - l;
            if (x0 > x1) y0 = int(by[l]) - 1;
            x0 = std::min(x0, start), x1 = std::max(x1, start);
            run = run && int(by[l]) - 1 == y0;
        }
        run = run && x1 - x0 <= 1 && x0 >= 0 && x1 + 10 < f.width && y0 >= 0 && y0 + 3 < f.height;
        if (run) {
            i8 upper{}; // lanes starting one further (only kept lanes have finite positions)
            for (int l = 0; l < n; ++l) upper[l] = keep[l] && int(bx[l]) - 1 - l == x1 ? -1 : 0;
            catmullRomRun8(f, x0, y0, x1 > x0, upper, ppx - bx, ppy - by, h, hp);
        } else {
            for (int l = 0; l < n; ++l) {
                if (!keep[l]) continue;
                Vec3 a, b;
                sampleCatmullRom2(f.prevPre, f.prevPost, f.width, f.height, {ppx[l], ppy[l]}, a, b);
                h[0][l] = a.x, h[1][l] = a.y, h[2][l] = a.z;
                hp[0][l] = b.x, hp[1][l] = b.y, hp[2][l] = b.z;
            }
        }
        const f8 w = firstBlendWeight8(samples, f.preAlpha);
        for (int c = 0; c < 3; ++c) {
            acc[c] = keep ? lerp8(h[c], y3[c], w) : y3[c];
            post[c] = keep ? hp[c] : y3[c];
        }
    }
    const f8 count = keep ? min8(samples + 1.0f, splat8(255.0f)) : splat8(1.0f);
    storeXyz8(f.pre + 3 * i, n, acc);
    storeXyz8(f.postHistory + 3 * i, n, post);
    storeBytes(f.count + i, __builtin_convertvector(count, i8), n);
    storeBytes(f.accept + i, keep & 15, n);
    const f8 far = splat8(-1e6f);
    storeXy8(f.previousPixel + 2 * i, n, keep ? ppx : far, keep ? ppy : far);
    f8 fx, fy;
    loadXy8(f.features + 2 * i, n, fx, fy);
    f8 a[kWalrAverages] = {fx, fy, fx * fx, fx * fy, fy * fy};
    for (int c = 0; c < 3; ++c)
        a[5 + 3 * c] = acc[c], a[6 + 3 * c] = acc[c] * fx, a[7 + 3 * c] = acc[c] * fy;
    if (n < 8) {
        for (int l = 0; l < n; ++l)
            for (int k = 0; k < kWalrAverages; ++k) averages[16 * (i + l) + k] = a[k][l];
        return;
    }
    // Each pixel's 16 floats (the last two unused, written 0) as two 8x8 transposes: 16 vector
    // stores, not 112 scalar ones.
    const f8 high[8] = {a[8], a[9], a[10], a[11], a[12], a[13], f8{}, f8{}};
    f8 rows[8];
    transpose8(a, rows);
    for (int l = 0; l < 8; ++l) store8(averages + 16 * (i + l), rows[l]);
    transpose8(high, rows);
    for (int l = 0; l < 8; ++l) store8(averages + 16 * (i + l) + 8, rows[l]);
}

/// walrPostPixel of the n <= 8 pixels from column x of row y.
BMFR_SIMD_INLINE void postGroup(const WalrPost& p, int x, int y, int n) {
    if (x < 1 || x + 9 > p.width) { // the 3x3 boxes reach past a side of the image
        for (int l = 0; l < n; ++l) walrPostPixel(p, x + l, y);
        return;
    }
    const long i = long(y) * p.width + x;
    f8 out[3];
    deinterleave3(p.spatial + 3 * i, out[0], out[1], out[2]);
    const f8 count = __builtin_convertvector(loadBytes(p.count + i, 8), f8);
    const i8 blend = count > 1.0f;
    if (p.enabled && anyLane(blend)) {
        // neighbourhoodMoments, in its order: rows, then columns, inside the image.
        f8 s1[3] = {}, s2[3] = {}, m = {};
        for (int qy = y - 1; qy <= y + 1; ++qy) {
            if (qy < 0 || qy >= p.height) continue;
            for (int dx = -1; dx <= 1; ++dx) {
                f8 v[3];
                deinterleave3(p.spatial + 3 * (long(qy) * p.width + x + dx), v[0], v[1], v[2]);
                for (int c = 0; c < 3; ++c) s1[c] += v[c], s2[c] += v[c] * v[c];
                m += 1.0f;
            }
        }
        f8 h[3], mean[3], d[3];
        deinterleave3(p.postHistory + 3 * i, h[0], h[1], h[2]);
        // varianceClip: towards the mean into mean +- gamma deviation.
        f8 t = splat8(1.0f);
        for (int c = 0; c < 3; ++c) {
            mean[c] = s1[c] / m;
            f8 var = s2[c] / m - mean[c] * mean[c];
            var = var > 0.0f ? var : f8{}; // std::fmax(var, 0): a NaN gives 0
            f8 deviation = var;
            for (int l = 0; l < 8; ++l) deviation[l] = __builtin_sqrtf(deviation[l]);
            const f8 extent = p.gamma * deviation;
            d[c] = h[c] - mean[c];
            const f8 a = abs8(d[c]);
            t = a > extent ? min8(t, extent / a) : t;
        }
        f8 w = 1.0f / count; // secondBlendWeight
        w = w > p.alpha ? w : splat8(p.alpha);
        for (int c = 0; c < 3; ++c) {
            const f8 clipped = mean[c] + t * d[c];
            out[c] = blend ? lerp8(clipped, out[c], w) : out[c];
        }
    }
    storeXyz8(p.post + 3 * i, n, out);
    if (!p.diffuseIndirect) {
        remodulate8(out, p.in, i, n, true, p.albedoEpsilon);
        storeXyz8(p.output + 3 * i, n, out);
        return;
    }
    int64_t unused = 0; // counted in the input pass
    f8 albedo[3], color[3], signal[3];
    loadXyz8(p.in.albedo + 3 * i, n, albedo);
    loadXyz8(p.in.color + 3 * i, n, color);
    loadXyz8(p.signal + 3 * i, n, signal);
    finiteOrZero8(albedo, unused);
    finiteOrZero8(color, unused);
    for (int c = 0; c < 3; ++c) {
        albedo[c] = max8(albedo[c], f8{});
        out[c] = (color[c] - albedo[c] * signal[c]) + albedo[c] * out[c];
    }
    storeXyz8(p.output + 3 * i, n, out);
}

BMFR_SIMD_DISPATCH(void, postRows, (const WalrPost& p, long y0, long y1), (p, y0, y1)) {
    for (long y = y0; y < y1; ++y)
        for (int x = 0; x < p.width; x += 8) postGroup(p, x, int(y), std::min(8, p.width - x));
}

BMFR_SIMD_DISPATCH(void, inputRows, (const WalrFrame& f, long y0, long y1, int64_t& bad),
                   (f, y0, y1, bad)) {
    for (long y = y0; y < y1; ++y)
        for (int x = 0; x < f.width; x += 8)
            inputGroup(f, x, int(y), std::min(8, f.width - x), bad);
}

BMFR_SIMD_DISPATCH(void, accumulateRows, (const WalrFrame& f, long y0, long y1, float* averages),
                   (f, y0, y1, averages)) {
    for (long y = y0; y < y1; ++y)
        for (int x = 0; x < f.width; x += 8)
            accumulateGroup(f, x, int(y), std::min(8, f.width - x), averages);
}

} // namespace

int64_t walrInputRows(const WalrFrame& f, long y0, long y1) {
    int64_t bad = 0;
    inputRows(f, y0, y1, bad);
    return bad;
}

void walrAccumulateRows(const WalrFrame& f, long y0, long y1, float* averages) {
    accumulateRows(f, y0, y1, averages);
}

void walrPostRows(const WalrPost& p, long y0, long y1) {
    postRows(p, y0, y1);
}

} // namespace bmfr::cpu
