#include "backend/cpu/mara2017/cpu_mara_glossy.h"
#include "backend/cpu/mara2017/cpu_mara_edge_weight.h"
#include <algorithm>
#include <cmath>
#include <cstring>

namespace bmfr::cpu {

using namespace simd;

namespace {

/// The reach of pixels with this roughness, as maraGlossyPassPixel takes it.
int reachOf(const MaraFrame& f, float rough, float& sigma) {
    sigma = maraGlossySigma(std::isfinite(rough) ? rough : 1.0f, f.glossyScale, f.glossyExponent,
                            f.glossyEpsilon);
    return int(std::ceil(f.glossyTapSigmas * sigma));
}

/// Zeros either side of the passes' planar source rows and pair rows: the eight-wide taps of a
/// row's first and last pixels read them as taps outside the image, which weigh 0.
constexpr int kPad = kMaraGlossyMaxReach + 8;

/// A planar row: the `width` packed xyz records at `packed` as three planes `stride` floats
/// apart. The passes read their taps from planar copies of the packed rows, each row
/// deinterleaved once, so that a tap is one load per channel, not a deinterleave of its own (the
/// taps of one pixel overlap the next's).
BMFR_SIMD_DISPATCH(void, planarRow, (const float* packed, int width, long stride, float* planes),
                   (packed, width, stride, planes)) {
    int x = 0;
    for (; x + 8 <= width; x += 8) {
        f8 v[3];
        deinterleave3(packed + 3 * x, v[0], v[1], v[2]);
        for (int c = 0; c < 3; ++c) store8(planes + c * stride + x, v[c]);
    }
    for (; x < width; ++x)
        for (int c = 0; c < 3; ++c) planes[c * stride + x] = packed[3 * x + c];
}

/// Lanes x .. x + L - 1 of three planes `stride` floats apart.
template <class V> BMFR_SIMD_INLINE void loadPlanes(const float* p, long stride, int x, V out[3]) {
    for (int c = 0; c < 3; ++c) out[c] = loadVector<V>(p + c * stride + x);
}

/// e[(k - 1) stride + x] = maraEdgeWeight of pixel (x, y) against pixel (x, y) + k (dx, dy),
/// for k = 1 .. reach and the pairs inside the image; along a row, 0 for the pairs whose second
/// pixel lies past its end. guide[k] is the planar row (positions, then normals: six planes
/// `width` floats apart) of row y + k dy. Sixteen pairs at a time on the AVX-512 path, eight
/// elsewhere.
BMFR_SIMD_DISPATCH(void, pairRow,
                   (const MaraFrame& f, int y, int dx, int dy, int reach, const float* const* guide,
                    long stride, float* e),
                   (f, y, dx, dy, reach, guide, stride, e)) {
    using V = std::conditional_t<kIsa == Isa::Avx512, f32x16, f8>;
    constexpr int L = kLanesOf<V>;
    const int w = f.width;
    const long row = long(y) * w, normals = 3L * w;
    // Each run of pixels against all its partners, so that the run is read once.
    for (int x = 0; x < w; x += L) {
        const long i = row + x;
        V pc[3] = {}, nc[3] = {}; // a run past the row's end takes the pairs one by one
        if (x + L <= w) {
            loadPlanes(guide[0], w, x, pc);
            loadPlanes(guide[0] + normals, w, x, nc);
        }
        for (int k = 1; k <= reach && y + k * dy < f.height; ++k) {
            float* ek = e + long(k - 1) * stride;
            const long step = long(k) * (dx + long(dy) * w);
            const int end = w - k * dx; // pairs from x < end
            if (x + L <= end) {
                V pq[3], nq[3];
                loadPlanes(guide[k], w, x + k * dx, pq);
                loadPlanes(guide[k] + normals, w, x + k * dx, nq);
                storeVector(ek + x, edgeWeightOf<kIsa>(nc, pc, nq, pq, f.edges));
                continue;
            }
            for (int l = 0; x + l < end; ++l) {
                const long c = i + l, q = c + step;
                ek[x + l] = maraEdgeWeight(load3(f.normal, c), load3(f.position, c),
                                           load3(f.normal, q), load3(f.position, q), f.edges);
            }
            for (int l = std::max(0, end - x); dx && l < L && x + l < w; ++l) ek[x + l] = 0.0f;
        }
    }
}

/// The taps of G groups of eight pixels from column x of row y that share one roughness (its
/// `taps` Gaussian weights g[1 ..]): passRow's arguments. Each group's lanes add their taps in
/// the reference's order; a tap past either end of the row reads the pads, weight 0 and colour
/// 0, and adds nothing.
template <Isa kIsa, int G>
BMFR_SIMD_INLINE void passGroups(const MaraFrame& f, int x, int y, int dx, int dy, int taps,
                                 const float* g, const float* const* below,
                                 const float* const* above, const float* const* planar, long stride,
                                 float* out) {
    f8 sum[G][3], total[G];
    for (int q = 0; q < G; ++q) {
        loadPlanes(planar[0], stride, x + 8 * q, sum[q]);
        total[q] = splat8(1.0f);
    }
    for (int k = 1; k <= taps; ++k)
        for (int side = -1; side <= 1; side += 2) {
            const int qy = y + side * k * dy;
            if (qy < 0 || qy >= f.height) continue;
            const float* from = planar[side * k * dy];
            const float* e = side < 0 ? above[k - 1] - k * dx : below[k - 1];
            for (int q = 0; q < G; ++q) {
                const int at = x + 8 * q;
                f8 s[3];
                loadPlanes(from, stride, at + side * k * dx, s);
                const f8 wt = maxOn<kIsa>(f8{}, g[k] * load8(e + at));
                for (int c = 0; c < 3; ++c) sum[q][c] = sum[q][c] + wt * s[c];
                total[q] = total[q] + wt;
            }
        }
    for (int q = 0; q < G; ++q)
        interleave3(sum[q][0] / total[q], sum[q][1] / total[q], sum[q][2] / total[q], out + 24 * q);
}

/// Row y of one pass from the pair weights: `below[k - 1]` points at the pairs that start at
/// this row's pixels (tap +k), `above[k - 1]` at those that end there (tap -k, the pair's start
/// k pixels back along the pass). planar[d] is the planar row (planarRow, planes `stride` floats
/// apart, zeros for kPad floats either side) of src's row y + d dy, for the rows inside the
/// image; the pair rows have the same pads.
BMFR_SIMD_DISPATCH(void, passRow,
                   (const MaraFrame& f, const float* src, float* dst, int y, int dx, int dy,
                    const float* const* below, const float* const* above,
                    const float* const* planar, long stride),
                   (f, src, dst, y, dx, dy, below, above, planar, stride)) {
    const int w = f.width;
    const long row = long(y) * w;
    // The last roughness's reach and Gaussian (a power and an exponential per tap): runs along
    // a row mostly share one roughness.
    float g[kMaraGlossyMaxReach + 1], lastRough = NAN;
    int lastReach = 0, taps = 0;
    int x = 0;
    // Whether pixels x + from .. x + to - 1 lie in the row and have x's roughness, bit for bit.
    auto sameRoughness = [&](int from, int to) {
        if (x + to > w) return false;
        for (int l = from; f.in.roughness && l < to; ++l)
            if (std::memcmp(&f.in.roughness[row + x + l], &f.in.roughness[row + x], 4) != 0)
                return false;
        return true;
    };
    while (x < w) {
        const long i = row + x;
        const float rough = f.in.roughness ? f.in.roughness[i] : 1.0f;
        const bool shared = sameRoughness(1, 8);
        if (shared && std::memcmp(&rough, &lastRough, 4) != 0) {
            float sigma = 0;
            lastRough = rough, lastReach = reachOf(f, rough, sigma), taps = 0;
            for (int k = 1; k <= std::min(lastReach, kMaraGlossyMaxReach); ++k, ++taps) {
                g[k] = maraGaussian(float(k * k), sigma);
                if (!(g[k] > 0)) break;
            }
        }
        const int reach = shared ? lastReach : 0;
        // Eight at once when they share a sigma.
        if (!shared || reach > kMaraGlossyMaxReach) {
            const int end = shared ? x + 8 : x + 1;
            for (; x < end; ++x) maraGlossyPassPixel(f, src, dst, x, y, dx, dy);
            continue;
        }
        // Sixteen when the next eight share the roughness too: two groups' sums are independent
        // chains, and one group's (an add per tap) is what bounds the loop.
        const bool two = sameRoughness(8, 16);
        if (two)
            passGroups<kIsa, 2>(f, x, y, dx, dy, taps, g, below, above, planar, stride,
                                dst + 3 * i);
        else
            passGroups<kIsa, 1>(f, x, y, dx, dy, taps, g, below, above, planar, stride,
                                dst + 3 * i);
        x += 8 * (two ? 2 : 1);
    }
}

} // namespace

int maraGlossyReachBound(float scale, float exponent, float epsilon, float tapSigmas) {
    const float sigma = maraGlossySigma(1.0f, scale, exponent, epsilon);
    return std::min(kMaraGlossyMaxReach, int(std::ceil(tapSigmas * sigma)));
}

int maraGlossyReach(const MaraFrame& f) {
    float largest = f.in.roughness ? 0.0f : 1.0f;
    for (long i = 0, n = long(f.width) * f.height; f.in.roughness && i < n; ++i) {
        const float r = f.in.roughness[i];
        largest = std::isfinite(r) ? std::max(largest, r) : 1.0f;
        if (largest >= 1.0f) break;
    }
    float sigma = 0;
    return std::min(kMaraGlossyMaxReach, reachOf(f, largest, sigma));
}

size_t maraGlossyScratch(int width, int reach) {
    // The vertical pass keeps the pairs of the last reach + 1 rows, the planar guide rows
    // (six planes) of the reach + 1 rows its pairs span, and the planar source rows (three
    // planes) of the 2 reach + 1 rows its taps span; pair and source rows padded.
    const size_t padded = size_t(width) + 2 * kPad;
    return size_t(reach + 1) * size_t(reach) * padded + size_t(reach + 1) * 6 * size_t(width) +
           size_t(2 * reach + 1) * 3 * padded;
}

void maraGlossyRows(const MaraFrame& f, const float* src, float* dst, long y0, long y1, bool down,
                    int reach, float* scratch) {
    const int w = f.width;
    const long h = f.height, stride = w + 2L * kPad;
    const float* below[kMaraGlossyMaxReach];
    const float* above[kMaraGlossyMaxReach];
    // Planar rows in rings, each row made once: guide rows (positions, normals) in slot
    // r mod (reach + 1), source rows in slot r mod (2 reach + 1).
    const long pairRows = long(reach + 1) * reach, srcRows = 2L * reach + 1;
    float* guideRing = scratch + pairRows * stride;
    float* srcRing = guideRing + long(reach + 1) * 6 * w;
    // The pads, which only taps along a row read, of the rows that pass uses (slot 0):
    // pairRow and planarRow write only the rows' insides.
    auto zeroPads = [&](float* first, long rows) {
        for (float* r = first; r < first + rows * stride; r += stride) {
            std::fill(r, r + kPad, 0.0f);
            std::fill(r + kPad + w, r + stride, 0.0f);
        }
    };
    if (!down) {
        zeroPads(scratch, reach);
        zeroPads(srcRing, 3);
    }
    auto guideRow = [&](long r) { return guideRing + (r % (reach + 1)) * 6 * w; };
    // Along the rows every row goes through slot 0 (whose pads are zeroed).
    auto srcRow = [&](long r) { return srcRing + (down ? r % srcRows : 0) * 3 * stride + kPad; };
    auto makeGuide = [&](long r) {
        planarRow(f.position + 3 * r * w, w, w, guideRow(r));
        planarRow(f.normal + 3 * r * w, w, w, guideRow(r) + 3L * w);
    };
    auto makeSrc = [&](long r) { planarRow(src + 3 * r * w, w, stride, srcRow(r)); };
    const float* guide[kMaraGlossyMaxReach + 1];
    const float* planar[2 * kMaraGlossyMaxReach + 1];
    const float** planarAt = planar + kMaraGlossyMaxReach; // planarAt[d]: row y + d
    // Row r's pairs at tap k (1 .. reach) start at pairs(slot)[(k - 1) stride].
    auto pairs = [&](long slot) { return scratch + slot * reach * stride + kPad; };
    if (!down) { // each row's pairs serve it alone
        for (long y = y0; y < y1; ++y) {
            makeGuide(y);
            makeSrc(y);
            for (int k = 0; k <= reach; ++k) guide[k] = guideRow(y);
            planarAt[0] = srcRow(y);
            pairRow(f, int(y), 1, 0, reach, guide, stride, pairs(0));
            for (int k = 1; k <= reach; ++k)
                below[k - 1] = above[k - 1] = pairs(0) + long(k - 1) * stride;
            passRow(f, src, dst, int(y), 1, 0, below, above, planarAt, stride);
        }
        return;
    }
    // Down the columns: the pairs that start at row r in slot r mod (reach + 1), made from
    // `reach` rows above the first (those the first rows' upward taps need) onwards.
    auto rowPairs = [&](long r) { return pairs(r % (reach + 1)); };
    const long first = std::max(0L, y0 - reach);
    long guideMade = first, srcMade = first; // the next rows to make
    for (long r = first; r < y1; ++r) {
        const long last = std::min(r + reach, h - 1);
        for (; guideMade <= last; ++guideMade) makeGuide(guideMade);
        for (int k = 0; k <= last - r; ++k) guide[k] = guideRow(r + k);
        pairRow(f, int(r), 0, 1, reach, guide, stride, rowPairs(r));
        if (r < y0) continue;
        for (; srcMade <= last; ++srcMade) makeSrc(srcMade);
        for (long d = std::max(-long(reach), -r); d <= last - r; ++d) planarAt[d] = srcRow(r + d);
        for (int k = 1; k <= reach; ++k) {
            below[k - 1] = rowPairs(r) + long(k - 1) * stride;
            above[k - 1] = r - k >= 0 ? rowPairs(r - k) + long(k - 1) * stride : nullptr;
        }
        passRow(f, src, dst, int(r), 0, 1, below, above, planarAt, stride);
    }
}

} // namespace bmfr::cpu
