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

/// Records p .. p + L - 1 of a packed xyz buffer as x, y and z vectors of L lanes.
template <class V> BMFR_SIMD_INLINE void loadXyzRun(const float* p, V out[3]) {
    if constexpr (kLanesOf<V> == 8) {
        deinterleave3(p, out[0], out[1], out[2]);
    } else {
        f8 lo[3], hi[3];
        deinterleave3(p, lo[0], lo[1], lo[2]);
        deinterleave3(p + 24, hi[0], hi[1], hi[2]);
        for (int c = 0; c < 3; ++c)
            out[c] = __builtin_shufflevector(lo[c], hi[c], 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12,
                                             13, 14, 15);
    }
}

/// e[(k - 1) w + x] = maraEdgeWeight of pixel (x, y) against pixel (x, y) + k (dx, dy), for
/// k = 1 .. reach and the pairs inside the image. Sixteen pairs at a time on the AVX-512 path,
/// eight elsewhere.
BMFR_SIMD_DISPATCH(void, pairRow, (const MaraFrame& f, int y, int dx, int dy, int reach, float* e),
                   (f, y, dx, dy, reach, e)) {
    using V = std::conditional_t<kIsa == Isa::Avx512, f32x16, f8>;
    constexpr int L = kLanesOf<V>;
    const int w = f.width;
    const long row = long(y) * w;
    // Each run of pixels against all its partners, so that the run is read once.
    for (int x = 0; x < w; x += L) {
        const long i = row + x;
        V pc[3] = {}, nc[3] = {}; // a run past the row's end takes the pairs one by one
        if (x + L <= w) {
            loadXyzRun(f.position + 3 * i, pc);
            loadXyzRun(f.normal + 3 * i, nc);
        }
        for (int k = 1; k <= reach && y + k * dy < f.height; ++k) {
            float* ek = e + long(k - 1) * w;
            const long step = long(k) * (dx + long(dy) * w);
            const int end = w - k * dx; // pairs from x < end
            if (x + L <= end) {
                V pq[3], nq[3];
                loadXyzRun(f.position + 3 * (i + step), pq);
                loadXyzRun(f.normal + 3 * (i + step), nq);
                storeVector(ek + x, edgeWeightOf(nc, pc, nq, pq, f.edges));
                continue;
            }
            for (int l = 0; x + l < end; ++l) {
                const long c = i + l, q = c + step;
                ek[x + l] = maraEdgeWeight(load3(f.normal, c), load3(f.position, c),
                                           load3(f.normal, q), load3(f.position, q), f.edges);
            }
        }
    }
}

/// Row y of one pass from the pair weights: `below[k - 1]` points at the pairs that start at
/// this row's pixels (tap +k), `above[k - 1]` at those that end there (tap -k, the pair's start
/// k pixels back along the pass).
BMFR_SIMD_DISPATCH(void, passRow,
                   (const MaraFrame& f, const float* src, float* dst, int y, int dx, int dy,
                    const float* const* below, const float* const* above),
                   (f, src, dst, y, dx, dy, below, above)) {
    const int w = f.width;
    const long row = long(y) * w;
    // The last roughness's reach and Gaussian (a power and an exponential per tap): runs along
    // a row mostly share one roughness.
    float g[kMaraGlossyMaxReach + 1], lastRough = NAN;
    int lastReach = 0, taps = 0;
    int x = 0;
    while (x < w) {
        const long i = row + x;
        const float rough = f.in.roughness ? f.in.roughness[i] : 1.0f;
        bool shared = x + 8 <= w;
        for (int l = 1; shared && l < 8; ++l)
            shared = !f.in.roughness || std::memcmp(&f.in.roughness[i + l], &rough, 4) == 0;
        if (shared && std::memcmp(&rough, &lastRough, 4) != 0) {
            float sigma = 0;
            lastRough = rough, lastReach = reachOf(f, rough, sigma), taps = 0;
            for (int k = 1; k <= std::min(lastReach, kMaraGlossyMaxReach); ++k, ++taps) {
                g[k] = maraGaussian(float(k * k), sigma);
                if (!(g[k] > 0)) break;
            }
        }
        const int reach = shared ? lastReach : 0;
        // Eight at once when they share a sigma and, along a row, every tap is inside.
        if (!shared || reach > kMaraGlossyMaxReach ||
            (dx && (x - reach < 0 || x + 7 + reach >= w))) {
            const int end = shared ? x + 8 : x + 1;
            for (; x < end; ++x) maraGlossyPassPixel(f, src, dst, x, y, dx, dy);
            continue;
        }
        f8 sum[3];
        deinterleave3(src + 3 * i, sum[0], sum[1], sum[2]);
        f8 total = f8{} + 1.0f;
        for (int k = 1; k <= taps; ++k)
            for (int side = -1; side <= 1; side += 2) {
                const int qy = y + side * k * dy;
                if (qy < 0 || qy >= f.height) continue;
                const long j = i + long(side) * k * (dx + long(dy) * w);
                f8 s[3];
                deinterleave3(src + 3 * j, s[0], s[1], s[2]);
                const f8 e = side < 0 ? load8(above[k - 1] + x - k * dx) : load8(below[k - 1] + x);
                f8 wt = g[k] * e;
                wt = wt > 0.0f ? wt : 0.0f;
                for (int c = 0; c < 3; ++c) sum[c] = sum[c] + wt * s[c];
                total = total + wt;
            }
        interleave3(sum[0] / total, sum[1] / total, sum[2] / total, dst + 3 * i);
        x += 8;
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
    // The vertical pass keeps the pairs of the last reach + 1 rows.
    return size_t(reach + 1) * size_t(reach) * size_t(width);
}

void maraGlossyRows(const MaraFrame& f, const float* src, float* dst, long y0, long y1, bool down,
                    int reach, float* scratch) {
    const int w = f.width;
    const float* below[kMaraGlossyMaxReach];
    const float* above[kMaraGlossyMaxReach];
    if (!down) { // each row's pairs serve it alone
        for (long y = y0; y < y1; ++y) {
            pairRow(f, int(y), 1, 0, reach, scratch);
            for (int k = 1; k <= reach; ++k)
                below[k - 1] = above[k - 1] = scratch + long(k - 1) * w;
            passRow(f, src, dst, int(y), 1, 0, below, above);
        }
        return;
    }
    // Down the columns: the pairs that start at row r in slot r mod (reach + 1), made from
    // `reach` rows above the first (those the first rows' upward taps need) onwards.
    const long slot = long(reach) * w;
    auto rowPairs = [&](long r) { return scratch + (r % (reach + 1)) * slot; };
    for (long r = std::max(0L, y0 - reach); r < y1; ++r) {
        pairRow(f, int(r), 0, 1, reach, rowPairs(r));
        if (r < y0) continue;
        for (int k = 1; k <= reach; ++k) {
            below[k - 1] = rowPairs(r) + long(k - 1) * w;
            above[k - 1] = r - k >= 0 ? rowPairs(r - k) + long(k - 1) * w : nullptr;
        }
        passRow(f, src, dst, int(r), 0, 1, below, above);
    }
}

} // namespace bmfr::cpu
