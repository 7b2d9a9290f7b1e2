#include "backend/cpu/svgf/cpu_svgf_accumulate.h"
#include "backend/cpu/pixel_input8.h"
#include "backend/cpu/reproject8.h"
#include <algorithm>
#include <cstring>

namespace bmfr::cpu {

using namespace simd;

namespace {

/// The n <= 8 pixels from column x of row y.
BMFR_SIMD_INLINE void accumulateGroup(const SvgfFrame& f, int x, int y, int n, int64_t& bad) {
    const long i = long(y) * f.width + x;
    const Inputs8 px = readInputs8(f.in, f.modes, i, n, bad);
    storeXyz8(f.normal + 3 * i, n, px.normal);
    storeXyz8(f.position + 3 * i, n, px.position);
    const Mat4& m = f.viewProjection;
    const f8* p = px.position;
    storeFirst(f.depth + i, ((m.m[3][0] * p[0] + m.m[3][1] * p[1]) + m.m[3][2] * p[2]) + m.m[3][3],
               n);
    const i8 present = f.in.sampleMask ? loadFirst(f.in.sampleMask + i, n) > 0.5f : ~i8{};
    Surface8 was;
    const i8 valid =
        previousSurface8(f.in, f.previous, i, x, y, n, px.position, px.normal, bad, was);
    i8 accept{};
    f8 old[6] = {}; // colour, moments, length
    f8 total{};
    if (anyLane(valid)) {
        const Footprint8 fp = footprint8(was.px, was.py);
        const Taps8 taps = taps8(fp, f.width, f.height, valid & firstLanes(n));
        const f8 limP = splat8(f.limits.positionSquared), limN = splat8(f.limits.normalSquared);
        i8 ok[4];
        forTaps(taps, [&] [[gnu::always_inline]] () {
            for (int k = 0; k < 4; ++k) {
                f8 q[3], qn[3];
                tapXyz(taps, f.prevPosition, k, q);
                tapXyz(taps, f.prevNormal, k, qn);
                f8 d[6];
                for (int c = 0; c < 3; ++c) d[c] = q[c] - was.position[c];
                for (int c = 0; c < 3; ++c) d[3 + c] = qn[c] - was.normal[c];
                // dot(d, d) in Vec3's order, so the decisions match the reference bit for bit.
                const f8 dp = (d[0] * d[0] + d[1] * d[1]) + d[2] * d[2];
                const f8 dn = (d[3] * d[3] + d[4] * d[4]) + d[5] * d[5];
                // Taps that never had a sample carry no history.
                ok[k] = valid & taps.inside[k] & (dp < limP) & (dn < limN) &
                        (tapBytes(taps, f.prevLength, k) != 0);
                accept |= ok[k] & (1 << k);
            }
        });
        total = weightedTaps<6>(
            taps, fp.weight, ok,
            [&](int k, f8* v) {
                tapXyz(taps, f.prevColor, k, v);
                tapXy(taps, f.prevMoments, k, v[3], v[4]);
                v[5] = __builtin_convertvector(tapBytes(taps, f.prevLength, k), f8);
            },
            old);
    }
    storeXy8(f.previousPixel + 2 * i, n, was.px, was.py);
    storeBytes(f.accept + i, accept, n);
    const i8 history = total > 0.0f;
    const f8 safe = history ? total : splat8(1.0f);
    for (f8& v : old) v = history ? v / safe : v;
    const f8 samples = old[5];
    // The new sample, blended into the history where there is one.
    const f8 l = luminance8(px.color);
    const f8 wc = history ? firstBlendWeight8(samples, f.colorAlpha) : splat8(1.0f);
    const f8 wm = history ? firstBlendWeight8(samples, f.momentsAlpha) : splat8(1.0f);
    f8 color[3], m1, m2, length;
    for (int c = 0; c < 3; ++c) color[c] = present ? lerp8(old[c], px.color[c], wc) : old[c];
    m1 = present ? old[3] + wm * (l - old[3]) : old[3];
    m2 = present ? old[4] + wm * (l * l - old[4]) : old[4];
    length = present ? (history ? nextHistoryLength8(samples) : splat8(1.0f))
                     : (history ? roundHalfEven8(samples) : f8{});
    storeXyz8(f.integrated + 3 * i, n, color);
    // f.color, which the reference also fills here, is left to the step-1 level's feedback:
    // every run of levels has one (runAtrousLevels), so the store would always be overwritten.
    storeXy8(f.moments + 2 * i, n, m1, m2);
    storeBytes(f.length + i, __builtin_convertvector(length, i8), n);
}

BMFR_SIMD_DISPATCH(void, accumulateRows, (const SvgfFrame& f, long y0, long y1, int64_t& bad),
                   (f, y0, y1, bad)) {
    for (long y = y0; y < y1; ++y)
        for (int x = 0; x < f.width; x += 8)
            accumulateGroup(f, x, int(y), std::min(8, f.width - x), bad);
}

} // namespace

int64_t svgfAccumulateRows(const SvgfFrame& f, long y0, long y1) {
    int64_t bad = 0;
    accumulateRows(f, y0, y1, bad);
    return bad;
}

} // namespace bmfr::cpu
