#include "backend/cpu/svgf/cpu_svgf_atrous.h"
#include "backend/cpu/simd.h"
#include <algorithm>
#include <cmath>

namespace bmfr::cpu {

using namespace simd;

namespace {

/// One level's planes and constants. Plane pointers are at (0, 0) of their image; a row is
/// `pitch` floats apart, with `apron` readable floats before x = 0 and after x = width - 1.
struct LevelArgs {
    const float *nx, *ny, *nz, *depth, *gradX, *gradY, *mask;
    const float* in[5]; ///< R, G, B, variance, luminance
    float* out[5];
    long pitch;
    int width, height, radius, step, normalExponent;
    float phiDepth, phiLuminance;
};

BMFR_SIMD_INLINE f8 luminanceOf(f8 r, f8 g, f8 b) {
    const f8 c[3] = {r, g, b};
    return luminance8(c);
}

/// max(0, c)^e by repeated squaring, as the reference's normalWeight; kExponent > 0 fixes e at
/// compile time (the default 128 is seven squarings in a row), 0 reads it from `e`.
template <int kExponent> BMFR_SIMD_INLINE f8 normalPower(f8 c, int e) {
    f8 base = max8(f8{}, c), result = splat8(1.0f);
    if constexpr (kExponent > 0) e = kExponent;
    for (; e > 0; e >>= 1, base *= base)
        if (e & 1) result *= base;
    return result;
}

/// kExponent and kRadius > 0 fix the normal exponent and the kernel radius at compile time (the
/// defaults: the taps unrolled, their constants folded); 0 reads them from `a`. Two passes per
/// eight pixels, the taps' weights and then the colour sums, so that neither holds more vectors
/// than the sixteen AVX2 registers.
template <int kExponent, int kRadius>
BMFR_SIMD_INLINE void atrousRowsOf(const LevelArgs& a, long y0, long y1) {
    const int r = kRadius > 0 ? kRadius : a.radius, step = a.step;
    const float centre = atrousTap(r, 0) * atrousTap(r, 0);
    const f8 zero{};
    alignas(32) float weights[8 * 24]; // (2 r + 1)^2 - 1 taps, r <= 2
    long offsets[24];
    for (long y = y0; y < y1; ++y)
        for (int x = 0; x < a.width; x += 8) {
            const long c = y * a.pitch + x;
            // 3x3 Gaussian prefilter of the variance, over pixels with a sample.
            f8 gv{}, gw{};
            for (int dy = -1; dy <= 1; ++dy) {
                if (y + dy < 0 || y + dy >= a.height) continue;
                for (int dx = -1; dx <= 1; ++dx) {
                    const long q = c + dy * a.pitch + dx;
                    const float k = (dx == 0 ? 0.5f : 0.25f) * (dy == 0 ? 0.5f : 0.25f);
                    const f8 km = k * load8(a.mask + q); // k, or 0 without a sample
                    gv += km * load8(a.in[3] + q);
                    gw += km;
                }
            }
            const f8 variance = gw > zero ? gv / gw : zero;
            f8 sd = max8(variance, zero);
            for (int l = 0; l < 8; ++l) sd[l] = std::sqrt(sd[l]);
            const f8 inverseLum = 1.0f / (a.phiLuminance * sd + 1e-10f);
            const f8 nx0 = load8(a.nx + c), ny0 = load8(a.ny + c), nz0 = load8(a.nz + c);
            const f8 z0 = load8(a.depth + c), l0 = load8(a.in[4] + c);
            const f8 gx0 = a.phiDepth * load8(a.gradX + c), gy0 = a.phiDepth * load8(a.gradY + c);
            int taps = 0;
            for (int ky = -r; ky <= r; ++ky) {
                const long qy = y + long(ky) * step;
                if (qy < 0 || qy >= a.height) continue;
                for (int kx = -r; kx <= r; ++kx) {
                    if (kx == 0 && ky == 0) continue;
                    const long q = c + long(ky) * step * a.pitch + long(kx) * step;
                    const f8 dotN =
                        nx0 * load8(a.nx + q) + ny0 * load8(a.ny + q) + nz0 * load8(a.nz + q);
                    const f8 wn = normalPower<kExponent>(dotN, a.normalExponent);
                    const f8 slope = gx0 * float(kx * step) + gy0 * float(ky * step);
                    const f8 depthArg = abs8(z0 - load8(a.depth + q)) / (abs8(slope) + 1e-6f);
                    const f8 arg = depthArg + abs8(l0 - load8(a.in[4] + q)) * inverseLum;
                    const float tap = atrousTap(r, kx) * atrousTap(r, ky) / centre;
                    // Every factor is finite (the exponential of -arg <= 0 is at most 1), so a
                    // tap without a sample (mask 0), or with wn = 0, adds exactly nothing, as
                    // the reference's skip.
                    store8(weights + 8 * taps,
                           tap * load8(a.mask + q) * wn * expNonPositive8(-arg));
                    offsets[taps++] = q;
                }
            }
            const f8 r0 = load8(a.in[0] + c), g0 = load8(a.in[1] + c), b0 = load8(a.in[2] + c);
            const f8 v0 = load8(a.in[3] + c);
            f8 sumR = r0, sumG = g0, sumB = b0, sumV = v0, sumW = splat8(1.0f);
            for (int t = 0; t < taps; ++t) {
                const f8 wgt = load8(weights + 8 * t);
                const long q = offsets[t];
                sumR += wgt * load8(a.in[0] + q), sumG += wgt * load8(a.in[1] + q);
                sumB += wgt * load8(a.in[2] + q);
                sumV += wgt * wgt * load8(a.in[3] + q);
                sumW += wgt;
            }
            const i8 sampled = load8(a.mask + c) > zero;
            const f8 out[4] = {sampled ? sumR / sumW : r0, sampled ? sumG / sumW : g0,
                               sampled ? sumB / sumW : b0, sampled ? sumV / (sumW * sumW) : v0};
            const int n = std::min(8, a.width - x);
            for (int k = 0; k < 4; ++k) storeFirst(a.out[k] + c, out[k], n);
            storeFirst(a.out[4] + c, luminanceOf(out[0], out[1], out[2]), n);
        }
}

BMFR_SIMD_DISPATCH(void, atrousRows, (const LevelArgs& a, long y0, long y1), (a, y0, y1)) {
    if (a.normalExponent == 128 && a.radius == 2)
        atrousRowsOf<128, 2>(a, y0, y1);
    else
        atrousRowsOf<0, 0>(a, y0, y1);
}

} // namespace

bool cpuAtrousSupports(const SvgfSettings& s) {
    return float(int(s.phiNormal)) == s.phiNormal;
}

void CpuAtrous::reserve(int w, int h, const SvgfSettings& s) {
    // Taps reach radius x the largest step beyond the row; eight lanes read past its end.
    const int reach = s.kernelRadius * (1 << (s.iterations - 1));
    const int apron = (reach + 8 + 7) / 8 * 8;
    if (w == width_ && h == height_ && apron == apron_) return;
    width_ = w, height_ = h, apron_ = apron;
    pitch_ = (w + 7) / 8 * 8 + 2L * apron;
    planeFloats_ = pitch_ * h;
    // Zeros: the aprons' mask stays 0 (no sample) and their colour finite.
    planes_.assign(size_t(planeFloats_) * Count + 2 * size_t(apron), 0.0f);
}

int CpuAtrous::run(ThreadPool& pool, const SvgfSettings& s, const AtrousLevel& g,
                   float* const filtered[2], float* colorHistory) {
    const int w = g.width, h = g.height;
    reserve(w, h, s);
    const long pitch = pitch_;
    pool.parallelFor(h, 8, [&](long y0, long y1) {
        for (long y = y0; y < y1; ++y)
            for (int x = 0; x < w; ++x) {
                const long i = y * w + x, p = y * pitch + x;
                plane(Nx)[p] = g.normal[3 * i];
                plane(Ny)[p] = g.normal[3 * i + 1];
                plane(Nz)[p] = g.normal[3 * i + 2];
                plane(Depth)[p] = g.depth[i];
                plane(GradX)[p] = g.depthGradient[2 * i];
                plane(GradY)[p] = g.depthGradient[2 * i + 1];
                plane(Mask)[p] = g.length[i] > 0 ? 1.0f : 0.0f;
                for (int k = 0; k < 4; ++k) plane(Colour + k)[p] = filtered[0][4 * i + k];
                const float* rgb = filtered[0] + 4 * i;
                plane(Colour + 4)[p] = luminance({rgb[0], rgb[1], rgb[2]});
            }
    });
    LevelArgs a{plane(Nx),
                plane(Ny),
                plane(Nz),
                plane(Depth),
                plane(GradX),
                plane(GradY),
                plane(Mask),
                {},
                {},
                pitch,
                w,
                h,
                s.kernelRadius,
                1,
                int(s.phiNormal),
                s.phiDepth,
                s.phiLuminance};
    auto colour = [this](int set, int k) { return plane(Colour + 5 * set + k); };
    const int last = runAtrousLevels(
        s,
        [&](int from, int to, int step) {
            for (int k = 0; k < 5; ++k) a.in[k] = colour(from, k), a.out[k] = colour(to, k);
            a.step = step;
            pool.parallelFor(h, 2, [&](long y0, long y1) { atrousRows(a, y0, y1); });
        },
        [&](int k) {
            pool.parallelFor(h, 8, [&](long y0, long y1) {
                for (long y = y0; y < y1; ++y)
                    for (int x = 0; x < w; ++x)
                        for (int ch = 0; ch < 3; ++ch)
                            colorHistory[3 * (y * w + x) + ch] = colour(k, ch)[y * pitch + x];
            });
        });
    pool.parallelFor(h, 8, [&](long y0, long y1) {
        for (long y = y0; y < y1; ++y)
            for (int x = 0; x < w; ++x)
                for (int ch = 0; ch < 4; ++ch)
                    filtered[last][4 * (y * w + x) + ch] = colour(last, ch)[y * pitch + x];
    });
    return last;
}

} // namespace bmfr::cpu
