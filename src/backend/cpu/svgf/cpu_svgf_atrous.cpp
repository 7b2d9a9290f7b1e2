#include "backend/cpu/svgf/cpu_svgf_atrous.h"
#include "backend/cpu/simd.h"
#include "backend/cpu/svgf/cpu_svgf_weights.h"
#include "core/staggered_allocator.h"
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
    float* history; ///< the RGB also packed (3 floats per pixel, rows `width` apart), or null
    bool last;      ///< the last level: its variance and luminance have no reader
    long pitch;
    int width, height, radius, step, normalExponent;
    float phiDepth, phiLuminance;
};

/// kExponent and kRadius > 0 fix the normal exponent and the kernel radius at compile time (the
/// defaults: the taps unrolled, their constants folded); 0 reads them from `a`. V is eight or
/// sixteen lanes. Each tap's weight is one power of two: the tap's, the edge terms' and (for
/// the default exponent) the normal's logarithms added. A row of taps is weighed together and
/// then added, tap by tap, so that their exponentials' chains interleave. kLast leaves out the
/// variance and luminance (LevelArgs::last).
template <class V, int kExponent, int kRadius, bool kLast>
BMFR_SIMD_INLINE void atrousRowsOf(const LevelArgs& a, long y0, long y1, long stride) {
    constexpr int kLanes = kLanesOf<V>;
    const auto load = loadVector<V>;
    const int r = kRadius > 0 ? kRadius : a.radius, step = a.step;
    const float centre = atrousTap(r, 0) * atrousTap(r, 0);
    const V zero{};
    // The logarithms of the taps' weights relative to the centre's, numbered row by row.
    const int side = 2 * r + 1, half = side * side / 2;
    float log2Tap[25];
    for (int d = 0; d < side * side; ++d)
        log2Tap[d] = std::log2(atrousTap(r, d % side - r) * atrousTap(r, d / side - r) / centre);
    for (long y = y0; y < y1; y += stride)
        for (int x = 0; x < a.width; x += kLanes) {
            const long c = y * a.pitch + x;
            // The planes a pixel reads first, 128 floats ahead: its gradient, the variance
            // prefilter's next row and the taps' leading row. Together with the taps' rows they
            // are more streams than the hardware prefetcher follows.
            const long ahead = c + 128, lead = ahead + long(r) * step * a.pitch;
            for (const float* p :
                 {a.gradX + ahead, a.gradY + ahead, a.mask + ahead + a.pitch,
                  a.in[3] + ahead + a.pitch, a.depth + lead, a.nx + lead, a.ny + lead, a.nz + lead})
                __builtin_prefetch(p);
            for (const float* p : a.in) __builtin_prefetch(p + lead);
            // 3x3 Gaussian prefilter of the variance, over pixels with a sample.
            V gv{}, gw{};
            for (int dy = -1; dy <= 1; ++dy) {
                if (y + dy < 0 || y + dy >= a.height) continue;
                for (int dx = -1; dx <= 1; ++dx) {
                    const long q = c + dy * a.pitch + dx;
                    const float k = (dx == 0 ? 0.5f : 0.25f) * (dy == 0 ? 0.5f : 0.25f);
                    const V km = k * load(a.mask + q); // k, or 0 without a sample
                    gv += km * load(a.in[3] + q);
                    gw += km;
                }
            }
            const V variance = gw > zero ? gv / gw : zero;
            V sd = maxOf(variance, zero);
            for (int l = 0; l < kLanes; ++l) sd[l] = std::sqrt(sd[l]);
            const V inverseLum = -kLog2E / (a.phiLuminance * sd + 1e-10f);
            const V nx0 = load(a.nx + c), ny0 = load(a.ny + c), nz0 = load(a.nz + c);
            const V z0 = load(a.depth + c), l0 = load(a.in[4] + c);
            const V gx0 = a.phiDepth * load(a.gradX + c), gy0 = a.phiDepth * load(a.gradY + c);
            const V r0 = load(a.in[0] + c), g0 = load(a.in[1] + c), b0 = load(a.in[2] + c);
            const V v0 = load(a.in[3] + c);
            V sumR = r0, sumG = g0, sumB = b0, sumV = v0, sumW = splat<V>(1.0f);
            // Inlined: an out-of-line copy would not share the caller's vector registers.
            auto add = [&] [[gnu::always_inline]] (V wgt, long q) {
                sumR += wgt * load(a.in[0] + q), sumG += wgt * load(a.in[1] + q);
                sumB += wgt * load(a.in[2] + q);
                if constexpr (!kLast) sumV += wgt * wgt * load(a.in[3] + q);
                sumW += wgt;
            };
            // The slope along a tap, (kx gx0 + ky gy0) step: step is a power of two and |kx|,
            // |ky| <= 2, so scaling the gradient by the step first rounds nothing, and the taps
            // unrolled take kx and ky as constants.
            const V gxs = gx0 * float(step), gys = gy0 * float(step);
            // -log2(e) / (|slope| + 1e-6) per direction (the luminance term's reciprocal also
            // carries -log2(e), so that a term is one multiply-add into the exponent), the taps
            // numbered row by row: tap d and its mirror (-kx, -ky), numbered 2 half - d, share it.
            V inverseSlope[12];
#pragma GCC unroll 12
            for (int d = 0; d < half; ++d) {
                const int kx = d % side - r, ky = d / side - r;
                const V slope = kx == 0   ? gys * float(ky)
                                : ky == 0 ? gxs * float(kx)
                                          : gxs * float(kx) + gys * float(ky);
                inverseSlope[d] = -kLog2E / (absOf(slope) + 1e-6f);
            }
#pragma GCC unroll 5
            for (int ky = -r; ky <= r; ++ky) {
                const long qy = y + long(ky) * step;
                if (qy < 0 || qy >= a.height) continue;
                V u[5], wn[5];
                long qs[5];
#pragma GCC unroll 5
                for (int kx = -r; kx <= r; ++kx) {
                    if (kx == 0 && ky == 0) continue;
                    const long q = c + long(ky) * step * a.pitch + long(kx) * step;
                    const int d = (ky + r) * side + kx + r, t = kx + r;
                    const V depthTerm =
                        absOf(z0 - load(a.depth + q)) * inverseSlope[d < half ? d : 2 * half - d] +
                        log2Tap[d];
                    qs[t] = q;
                    u[t] = absOf(l0 - load(a.in[4] + q)) * inverseLum + depthTerm;
                    if constexpr (kExponent == 128) {
                        const V away = 1.0f - nx0 * load(a.nx + q) - ny0 * load(a.ny + q) -
                                       nz0 * load(a.nz + q);
                        u[t] = normalLog2Power128(away) + u[t];
                    } else {
                        // A tap without a sample, whose normal planes hold 0, weighs 0, as the
                        // reference's skip.
                        wn[t] = normalPower<kExponent>(nx0 * load(a.nx + q) + ny0 * load(a.ny + q) +
                                                           nz0 * load(a.nz + q),
                                                       a.normalExponent);
                    }
                }
                const int skip = ky == 0 ? r : -1;
                exp2NonPositiveRows<3>(u, side, skip);
#pragma GCC unroll 5
                for (int t = 0; t < side; ++t) {
                    if (t == skip) continue;
                    add(kExponent == 128 ? u[t] : wn[t] * u[t], qs[t]);
                }
            }
            const IntOf<V> sampled = load(a.mask + c) > zero;
            // One division for the four normalisations.
            const V inverseW = 1.0f / sumW;
            const V out[4] = {sampled ? sumR * inverseW : r0, sampled ? sumG * inverseW : g0,
                              sampled ? sumB * inverseW : b0,
                              sampled ? sumV * (inverseW * inverseW) : v0};
            const int n = std::min(kLanes, a.width - x);
            for (int k = 0; k < (kLast ? 3 : 4); ++k) storeFirstLanes(a.out[k] + c, out[k], n);
            if constexpr (!kLast) storeFirstLanes(a.out[4] + c, luminanceOf(out), n);
            if (a.history) {
                float* packed = a.history + 3 * (y * a.width + x);
                for (int h = 0; h < kLanes; h += 8) { // eight lanes at a time
                    if (h >= n) break;
                    const f8 rgb[3] = {eightLanes(out[0], h), eightLanes(out[1], h),
                                       eightLanes(out[2], h)};
                    storeXyz8(packed + 3 * h, std::min(8, n - h), rgb);
                }
            }
        }
}

/// Rows y0, y0 + stride, ... below y1.
BMFR_SIMD_DISPATCH(void, atrousRows, (const LevelArgs& a, long y0, long y1, long stride),
                   (a, y0, y1, stride)) {
    using V = std::conditional_t<kIsa == Isa::Avx512, f32x16, f8>;
    if (a.normalExponent == 128 && a.radius == 2 && a.last)
        atrousRowsOf<V, 128, 2, true>(a, y0, y1, stride);
    else if (a.normalExponent == 128 && a.radius == 2)
        atrousRowsOf<V, 128, 2, false>(a, y0, y1, stride);
    else
        atrousRowsOf<V, 0, 0, false>(a, y0, y1, stride);
}

/// Rows of one residue modulo `step`, taken in order, share all but one of their taps' rows;
/// a task takes kPhaseRows of them.
constexpr long kPhaseRows = 16;

} // namespace

void CpuAtrous::reserve(int w, int h, const SvgfSettings& s) {
    // Taps reach radius x the largest step beyond the row; sixteen lanes read past its end.
    const int reach = s.kernelRadius * (1 << (s.iterations - 1));
    const int apron = (reach + 16 + 15) / 16 * 16;
    if (w == width_ && h == height_ && apron == apron_) return;
    width_ = w, height_ = h, apron_ = apron;
    pitch_ = (w + 15) / 16 * 16 + 2L * apron;
    planeFloats_ = long(staggeredPlaneFloats(size_t(pitch_ * h)));
    // Zeros: the aprons' mask stays 0 (no sample) and their colour finite.
    planes_.assign(size_t(planeFloats_) * Count + 2 * size_t(apron), 0.0f);
}

SvgfFirstLevel CpuAtrous::firstLevel(int w, int h, const SvgfSettings& s) {
    reserve(w, h, s);
    return firstPlanes();
}

SvgfFirstLevel CpuAtrous::firstPlanes() {
    return {
        plane(Nx),
        plane(Ny),
        plane(Nz),
        plane(Depth),
        plane(GradX),
        plane(GradY),
        plane(Mask),
        {levelPlane(0, 0), levelPlane(0, 1), levelPlane(0, 2), levelPlane(0, 3), levelPlane(0, 4)},
        pitch_};
}

int CpuAtrous::run(ThreadPool& pool, const SvgfSettings& s, float* colorHistory) {
    const int w = width_, h = height_;
    const long pitch = pitch_;
    const SvgfFirstLevel g = firstPlanes(); // the guides
    LevelArgs a{g.nx,
                g.ny,
                g.nz,
                g.depth,
                g.gradX,
                g.gradY,
                g.mask,
                {},
                {},
                nullptr,
                false,
                pitch,
                w,
                h,
                s.kernelRadius,
                1,
                int(s.phiNormal),
                s.phiDepth,
                s.phiLuminance};
    // The step-1 level also writes the colour history (runAtrousLevels' keep then has nothing
    // left to copy).
    int levels = 0;
    return runAtrousLevels(
        s,
        [&](int from, int to, int step) {
            for (int k = 0; k < 5; ++k) a.in[k] = level(from, k), a.out[k] = levelPlane(to, k);
            a.step = step;
            a.history = step == 1 ? colorHistory : nullptr;
            a.last = ++levels == s.iterations;
            // Each task is a run of rows step apart, so that the taps' rows stay in cache from
            // one row to the next whatever the step.
            const long span = kPhaseRows * step, runs = (h + span - 1) / span;
            pool.parallelFor(runs * step, 1, [&](long k0, long k1) {
                for (long k = k0; k < k1; ++k) {
                    const long y0 = k / step * span + k % step;
                    atrousRows(a, y0, std::min<long>(h, y0 + span), step);
                }
            });
        },
        [](int) {});
}

void CpuAtrous::copyLevel(int set, float* rgbv) const {
    for (long y = 0; y < height_; ++y)
        for (int x = 0; x < width_; ++x)
            for (int k = 0; k < 4; ++k)
                rgbv[4 * (y * width_ + x) + k] = level(set, k)[y * pitch_ + x];
}

} // namespace bmfr::cpu
