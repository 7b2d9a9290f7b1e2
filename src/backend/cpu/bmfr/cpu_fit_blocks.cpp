#include "backend/cpu/bmfr/cpu_block_masks.h"
#include "backend/cpu/bmfr/cpu_bmfr_buffers.h"
#include "backend/cpu/simd.h"
#include "filters/bmfr/block_grid.h"
#include "filters/bmfr/feature_columns.h"
#include "filters/bmfr/fitting_kernel.h"
#include "filters/bmfr/second_grid.h"
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace bmfr::cpu {

using namespace simd;

namespace {

struct Phase2 {
    const BmfrPassContext& ctx;
    Buffers& b;
    BlockGrid grid;
    /// The fitter's sources: normal xyz, position xyz, phase I colour, each a channel of a
    /// plane set (float, or half under BmfrSettings::halfHistory).
    const PlaneSet* set[9];
    int channel[9];
    EmitterExclusion emitters; ///< its bits unused: the tap classes hold them
    float* out[3];             ///< the fitted planes, or with `second` the second grid's
    /// The tap classes the fit writes (TapFilter); null for the second grid and without
    /// excludeEmitters or visibilityTaps. `visibility` sets kTapLit where it is above 0.
    uint8_t* classes = nullptr;
    const float* visibility = nullptr;
    /// Phase I's luminances of the current samples (SampleLuminance), null without them; the
    /// second grid runs after phase I, and reads all, the main grid a block row's own rows.
    const float* knownSamples = nullptr;
    bool second = false;

    Phase2(const BmfrPassContext& c, Buffers& buffers, const BlockGrid& g, bool shifted = false)
        : ctx(c), b(buffers), grid(g), emitters(emitterExclusion(c.settings, c.input, nullptr)),
          second(shifted) {
        if (!b.change.empty()) knownSamples = b.plane(b.change, 0);
        for (int ch = 0; ch < 3; ++ch) out[ch] = b.plane(shifted ? b.fittedSecond : b.fitted, ch);
        std::vector<uint8_t>& tapClass = buffers.tapClass[c.history.cur];
        if (!shifted && !tapClass.empty()) classes = tapClass.data(), visibility = tapVisibility(c);
        // The previous frame's emitters are its tap classes' emitter bits. Without any, no
        // pixel was one (wasEmitter), and nothing need look.
        const int prev = 1 - c.history.cur;
        const std::vector<uint8_t>& previous = buffers.tapClass[size_t(prev)];
        if (emitters.on && c.history.hasHistory() && !previous.empty() &&
            b.emitterPixels[prev] > 0) {
            emitters.previous = previous.data(), emitters.previousBit = kTapEmitter;
            emitters.previousX = b.plane(b.previousPixel, 0);
            emitters.previousY = b.plane(b.previousPixel, 1);
        }
        const int cur = c.history.cur;
        for (int ch = 0; ch < 3; ++ch) {
            set[ch] = &b.normal[cur], set[3 + ch] = &b.position[cur], set[6 + ch] = &b.noisy[cur];
            channel[ch] = channel[3 + ch] = channel[6 + ch] = ch;
        }
    }
    bool half(int ch) const { return set[ch]->half; }
    template <class T> const T* plane(int ch) const { return set[ch]->plane<T>(channel[ch]); }
    const void* address(int ch, long i) const { return set[ch]->address(channel[ch], size_t(i)); }
    float value(int ch, long i) const { return set[ch]->at(channel[ch], size_t(i)); }
};

/// Where each source's block rows start and how far apart they are (floats). Inside the image
/// they are the planes themselves; at the border, the mirrored copy in scratch.
struct BlockRows {
    const float* source[6]; ///< normal xyz, position xyz
    const float* colour[3];
    long pitch[9] = {};  ///< floats between block rows: sources, then colour channels
    bool inside = false; ///< the block lies in the image; imageIndex is not filled
};

/// Gathers the extra buffers some feature uses (non-finite values read as 0).
BMFR_SIMD_INLINE void gatherExtras(const Phase2& a, int ox, int oy, bool inside, Scratch& sc) {
    const BlockGrid& g = a.grid;
    const int B = g.blockSize, W = B * B;
    for (const Feature& f : a.ctx.settings.features) {
        if (f.source != FeatureSource::Extra) continue;
        const float* src = a.ctx.input.extras[f.extraIndex];
        float* dst = sc.soa.data() + (9 + size_t(f.extraIndex)) * size_t(W);
        if (inside) { // rows of the image, eight values at a time
            for (int ly = 0; ly < B; ++ly) {
                const float* row = src + long(oy + ly) * g.width + ox;
                for (int lx = 0; lx < B; lx += 8) {
                    const int n = std::min(8, B - lx);
                    const f8 v = loadFirst(row + lx, n);
                    storeFirst(dst + ly * B + lx, finite8(v) ? v : f8{}, n);
                }
            }
            continue;
        }
        for (int ly = 0; ly < B; ++ly) {
            const int iy = inside ? oy + ly : mirrorIndex(oy + ly, g.height);
            for (int lx = 0; lx < B; ++lx) {
                const int ix = inside ? ox + lx : mirrorIndex(ox + lx, g.width);
                const float v = src[long(iy) * g.width + ix];
                dst[ly * B + lx] = std::isfinite(v) ? v : 0.0f;
            }
        }
    }
}

/// Copies n values of a float or half plane as floats, eight at a time while they last.
template <class T> BMFR_SIMD_INLINE void copyRun(float* dst, const T* src, int n) {
    int k = 0;
    for (; k + 8 <= n; k += 8) store8(dst + k, load8(src + k));
    if (k < n) storeFirst(dst + k, loadFirst(src + k, n - k), n - k);
}
template <Isa kIsa>
BMFR_SIMD_INLINE void copySourceRun(const Phase2& a, int ch, float* dst, long from, int n) {
    if (a.half(ch)) return copyRun(dst, a.plane<HalfOf<kIsa>>(ch) + from, n);
    copyRun(dst, a.plane<float>(ch) + from, n);
}

/// The rows of block (ox, oy). A block inside the image reads float planes in place and
/// converts half planes into scratch; a border block is copied into scratch as floats with the
/// image mirrored in, and marks the pixels it owns.
template <Isa kIsa>
BMFR_SIMD_INLINE BlockRows blockRows(const Phase2& a, int ox, int oy, Scratch& sc) {
    const BlockGrid& g = a.grid;
    const int B = g.blockSize, W = B * B;
    BlockRows r;
    r.inside = ox >= 0 && oy >= 0 && ox + B <= g.width && oy + B <= g.height;
    gatherExtras(a, ox, oy, r.inside, sc);
    if (r.inside) {
        // Float planes are read in place; half planes are converted into scratch.
        const long first = long(oy) * g.width + ox;
        for (int ch = 0; ch < 9; ++ch) {
            const float* rows = sc.soa.data() + long(ch) * W;
            long pitch = B;
            if (!a.half(ch)) {
                rows = a.plane<float>(ch) + first, pitch = g.width;
            } else {
                for (int ly = 0; ly < B; ++ly)
                    copySourceRun<kIsa>(a, ch, sc.soa.data() + long(ch) * W + ly * B,
                                        first + long(ly) * g.width, B);
            }
            (ch < 6 ? r.source[ch] : r.colour[ch - 6]) = rows;
            r.pitch[ch] = pitch;
        }
        return r;
    }
    float* copy[9];
    for (int ch = 0; ch < 9; ++ch) copy[ch] = sc.soa.data() + long(ch) * W;
    // Columns [xa, xb) of the block are in the image; the rest mirror in.
    const int xa = std::clamp(-ox, 0, B), xb = std::clamp(g.width - ox, xa, B);
    for (int ly = 0; ly < B; ++ly) {
        const int uy = oy + ly, iy = mirrorIndex(uy, g.height);
        const bool rowInside = uy >= 0 && uy < g.height;
        const long row = long(iy) * g.width;
        const int k = ly * B;
        for (int ch = 0; ch < 9; ++ch)
            copySourceRun<kIsa>(a, ch, copy[ch] + k + xa, row + ox + xa, xb - xa);
        for (int lx = 0; lx < B; ++lx) {
            const bool in = lx >= xa && lx < xb;
            if (!in) {
                const long idx = row + mirrorIndex(ox + lx, g.width);
                for (int ch = 0; ch < 9; ++ch) copy[ch][k + lx] = a.value(ch, idx);
            }
            sc.imageIndex[size_t(k + lx)] = rowInside && in ? int(row + ox + lx) : -1;
        }
    }
    for (int ch = 0; ch < 6; ++ch) r.source[ch] = copy[ch];
    for (int ch = 0; ch < 3; ++ch) r.colour[ch] = copy[6 + ch];
    for (long& pitch : r.pitch) pitch = B;
    return r;
}

/// Asks for a block's rows of the surface and colour planes ahead of its gather. They are short
/// runs (one block row each) in nine planes, which the hardware prefetchers do not follow; the
/// fit of the block before hides the wait.
BMFR_SIMD_INLINE void prefetchBlock(const Phase2& a, int bx, int by) {
    const BlockGrid& g = a.grid;
    if (bx >= g.blocksX || by >= g.blocksY) return;
    const int B = g.blockSize, ox = std::max(0, g.originX(bx)), oy = std::max(0, g.originY(by));
    const int x1 = std::min(g.width, g.originX(bx) + B), y1 = std::min(g.height, g.originY(by) + B);
    if (ox >= x1 || oy >= y1) return;
    const bool narrow = x1 - ox <= 32; // three lines cover a run of up to 32 floats
    for (int y = oy; y < y1; ++y)
        for (int ch = 0; ch < 9; ++ch) {
            const long row = long(y) * g.width;
            if (narrow) {
                __builtin_prefetch(a.address(ch, row + ox));
                __builtin_prefetch(a.address(ch, row + ox + 16));
            } else {
                for (int x = ox; x < x1; x += 16) __builtin_prefetch(a.address(ch, row + x));
            }
            __builtin_prefetch(a.address(ch, row + x1 - 1));
        }
}

/// Calls fn(offset in the source, offset in the block, lanes) for each run of up to eight pixels
/// of each block row. The presets' 32- and 16-pixel rows unroll, whole runs only.
template <class Fn> BMFR_SIMD_INLINE void forRowRuns(int B, long pitch, Fn&& fn) {
    auto fixed = [&](auto width) {
        constexpr int C = decltype(width)::value;
        for (int ly = 0; ly < C; ++ly)
            for (int lx = 0; lx < C; lx += 8) fn(ly * pitch + lx, ly * C + lx, 8);
    };
    if (B == 32) return fixed(std::integral_constant<int, 32>{});
    if (B == 16) return fixed(std::integral_constant<int, 16>{});
    for (int ly = 0; ly < B; ++ly)
        for (int lx = 0; lx < B; lx += 8) fn(ly * pitch + lx, ly * B + lx, std::min(8, B - lx));
}

/// One source's smallest and largest value and smallest magnitude over the block.
struct SourceRange {
    float lo, hi, minAbs;
};

BMFR_SIMD_INLINE SourceRange sourceRange(const float* from, long pitch, int B) {
    const f8 inf = splat8(HUGE_VALF);
    f8 lo = inf, hi = -inf, mag = inf;
    forRowRuns(B, pitch, [&](long s, int, int n) {
        const f8 v = loadFirst(from + s, n);
        const i8 in = firstLanes(n);
        lo = min8(lo, in ? v : inf), hi = max8(hi, in ? v : -inf);
        mag = min8(mag, in ? (v < 0.0f ? -v : v) : inf);
    });
    return {hmin8(lo), hmax8(hi), hmin8(mag)};
}

/// The block scaling of a column, as scaleFeature: v -> (v - lo) * scale, with lo = 0 and
/// scale = 1 when unscaled, and one reciprocal per column instead of a division per pixel.
struct ColumnScale {
    float lo = 0.0f, scale = 1.0f;
    ColumnScale(bool scaled, float mn, float mx) {
        if (!scaled) return;
        const float range = mx - mn;
        lo = mn, scale = range > 1.0f ? 1.0f / range : 1.0f;
    }
};

/// A column that is a source or its square, in one pass: read, square, scale, store the clean
/// value and the regularised one. The range comes from the source's, since v * v rounds
/// monotonically in |v|: the same min and max as squaring first.
BMFR_SIMD_INLINE void sourceColumn(const float* from, long pitch, int B, bool square, bool scaled,
                                   const SourceRange& r, const float* noise, float* clean,
                                   float* noised) {
    const float big = std::max(-r.lo, r.hi);
    const ColumnScale cs = square ? ColumnScale(scaled, r.minAbs * r.minAbs, big * big)
                                  : ColumnScale(scaled, r.lo, r.hi);
    const f8 lo = splat8(cs.lo), scale = splat8(cs.scale);
    auto emit = [&](auto squared) {
        forRowRuns(B, pitch, [&](long s, int k, int n) {
            f8 v = loadFirst(from + s, n);
            if constexpr (squared) v = v * v;
            v = (v - lo) * scale;
            storeFirst(clean + k, v, n);
            storeFirst(noised + k, v + loadFirst(noise + k, n), n);
        });
    };
    square ? emit(std::true_type{}) : emit(std::false_type{});
}

/// Any other column, a power other than 1 and 2, pixel by pixel.
BMFR_SIMD_INLINE void otherColumn(const Feature& f, const float* from, long pitch, int B,
                                  const float* noise, float* clean, float* noised) {
    float mn = HUGE_VALF, mx = -HUGE_VALF;
    for (int ly = 0; ly < B; ++ly)
        for (int lx = 0; lx < B; ++lx) {
            const float v = applyExponent(from[ly * pitch + lx], f.exponent);
            clean[ly * B + lx] = v, mn = std::min(mn, v), mx = std::max(mx, v);
        }
    const ColumnScale cs(f.scaled, mn, mx);
    for (int k = 0; k < B * B; ++k) {
        clean[k] = (clean[k] - cs.lo) * cs.scale;
        noised[k] = clean[k] + noise[k];
    }
}

/// The M feature columns, scaled (clean) and regularised (the QR's copy), and the colour
/// columns after them in the QR's copy.
BMFR_SIMD_INLINE void buildColumns(const Phase2& a, const BlockRows& r, Scratch& sc) {
    const std::vector<Feature>& features = a.ctx.settings.features;
    const int B = a.grid.blockSize, W = B * B, M = int(features.size());
    const long zs = qrColumnStride(W);
    const float* noise = a.b.noise.data();
    // Ranges of the six surface sources, computed when a column first needs them.
    SourceRange ranges[6];
    bool known[6] = {};
    for (int f = 0; f < M; ++f) {
        const Feature& feat = features[size_t(f)];
        float* clean = sc.clean.data() + long(f) * W;
        float* noised = sc.work.data() + long(f) * zs;
        const float* nz = noise + long(f) * W;
        if (feat.source == FeatureSource::One) {
            // A row of ones read for every block row (pitch 0).
            sourceColumn(sc.ones.data(), 0, B, false, feat.scaled, {1.0f, 1.0f, 1.0f}, nz, clean,
                         noised);
            continue;
        }
        const bool extra = feat.source == FeatureSource::Extra;
        const float* from = extra ? sc.soa.data() + (9 + long(feat.extraIndex)) * W
                                  : r.source[int(feat.source) - int(FeatureSource::NormalX)];
        const long pitch = extra ? B : r.pitch[int(feat.source) - int(FeatureSource::NormalX)];
        if (feat.exponent != 1.0f && feat.exponent != 2.0f) {
            otherColumn(feat, from, pitch, B, nz, clean, noised);
            continue;
        }
        SourceRange range;
        if (extra) {
            range = sourceRange(from, pitch, B);
        } else {
            const int src = int(feat.source) - int(FeatureSource::NormalX);
            if (!known[src]) ranges[src] = sourceRange(from, pitch, B), known[src] = true;
            range = ranges[src];
        }
        sourceColumn(from, pitch, B, feat.exponent == 2.0f, feat.scaled, range, nz, clean, noised);
    }
    for (int ch = 0; ch < 3; ++ch) {
        float* z = sc.work.data() + long(M + ch) * zs;
        for (int ly = 0; ly < B; ++ly) copyRun(z + ly * B, r.colour[ch] + ly * r.pitch[6 + ch], B);
    }
}

/// After the weighted sum: the excluded pixels that are the emitter this frame take their own
/// sample (emitter_exclusion.h), and every owned pixel gets its tap class.
void finishBlock(const Phase2& a, const BlockRows& rows, long first, int excluded,
                 const Scratch& sc) {
    const BlockGrid& g = a.grid;
    const int B = g.blockSize;
    if (!excluded && rows.inside) { // most blocks: no emitter, and every pixel owned
        if (!a.classes) return;
        for (int ly = 0; ly < B; ++ly)
            litClasses(a.visibility, first + long(ly) * g.width, B, a.classes);
        return;
    }
    long emitters = 0;
    for (int k = 0; k < B * B; ++k) {
        const long idx =
            rows.inside ? first + long(k / B) * g.width + k % B : long(sc.imageIndex[size_t(k)]);
        if (idx < 0) continue;
        const bool emitter = excluded && maskEmitter(sc.mask[size_t(k)]);
        if (emitter) {
            const Vec3 c = emitterSample(a.ctx.input, idx, a.emitters.modes);
            for (int ch = 0; ch < 3; ++ch) a.out[ch][idx] = c[ch];
        }
        if (!a.classes) continue;
        litClasses(a.visibility, idx, 1, a.classes);
        if (emitter) a.classes[idx] |= kTapEmitter;
        emitters += emitter;
    }
    if (emitters) a.b.emitterPixels[a.ctx.history.cur] += emitters;
}

/// Fits block (bx, by), and asks for block (nextX, nextY)'s rows while it does.
BMFR_SIMD_DISPATCH(void, fitBlock,
                   (const Phase2& a, int bx, int by, Scratch& sc, int nextX, int nextY),
                   (a, bx, by, sc, nextX, nextY)) {
    const BmfrSettings& s = a.ctx.settings;
    const BlockGrid& g = a.grid;
    const int B = g.blockSize, W = B * B, M = int(s.features.size());
    const int ox = g.originX(bx), oy = g.originY(by);
    // Blocks that own no pixel (entirely outside the image after the offset) are skipped.
    if (ox + B <= 0 || oy + B <= 0 || ox >= g.width || oy >= g.height) return;
    const BlockRows rows = blockRows<kIsa>(a, ox, oy, sc);
    buildColumns(a, rows, sc);
    prefetchBlock(a, nextX, nextY);
    EmitterExclusion emitters = a.emitters;
    if (emitters.on && a.knownSamples) {
        const OwnedRect own = ownedRect(g, bx, by);
        emitters.known = {a.knownSamples, a.second ? 0 : long(own.y0) * g.width,
                          long(a.second ? g.height : own.y1) * g.width};
    }
    const int excluded =
        s.clampFireflies || emitters.on
            ? clampAndMaskBlock({g, a.ctx.input, emitters, s.clampFireflies,
                                 a.b.noisy[a.ctx.history.cur], M, qrColumnStride(W)},
                                bx, by, sc.work.data(), sc)
            : 0;

    float coeffs[kMaxFeatures * 3];
    solveHouseholderFast(sc.work.data(), M, W, qrColumnStride(W), coeffs);

    // Weighted sum of the noise-free features, 8 pixels at a time, straight to owned pixels.
    float* const* fitted = a.out;
    const float* clean = sc.clean.data();
    const long first = long(oy) * g.width + ox;
    auto scatter = [&](int k, int n, f8 sum[3]) {
        for (int c = 0; c < 3; ++c) sum[c] = max8(f8{}, sum[c]);
        if (rows.inside && n == 8 && k % B + 8 <= B) {
            // Eight pixels of one block row, which is a run of an image row.
            const long idx = first + long(k / B) * g.width + k % B;
            for (int c = 0; c < 3; ++c) store8(fitted[c] + idx, sum[c]);
            return;
        }
        for (int l = 0; l < n; ++l) {
            const long idx = rows.inside ? first + long((k + l) / B) * g.width + (k + l) % B
                                         : long(sc.imageIndex[size_t(k + l)]);
            if (idx < 0) continue;
            for (int c = 0; c < 3; ++c) fitted[c][idx] = sum[c][l];
        }
    };
    int k = 0;
    for (; k + 16 <= W; k += 16) {
        // Two groups at a time, so each coefficient is broadcast once for sixteen pixels.
        f8 sum0[3] = {}, sum1[3] = {};
        for (int f = 0; f < M; ++f) {
            const f8 col0 = load8(clean + long(f) * W + k),
                     col1 = load8(clean + long(f) * W + k + 8);
            for (int c = 0; c < 3; ++c) {
                // Scalar times vector: one broadcast (see splat8).
                const float w = coeffs[f * 3 + c];
                sum0[c] += w * col0, sum1[c] += w * col1;
            }
        }
        scatter(k, 8, sum0), scatter(k + 8, 8, sum1);
    }
    for (; k < W; k += 8) {
        f8 sum[3] = {};
        const int n = std::min(8, W - k);
        for (int f = 0; f < M; ++f)
            for (int l = 0; l < n; ++l)
                for (int c = 0; c < 3; ++c)
                    sum[c][l] += coeffs[f * 3 + c] * clean[long(f) * W + k + l];
        scatter(k, n, sum);
    }
    if (a.emitters.on || a.classes) finishBlock(a, rows, first, excluded, sc);
}

} // namespace

namespace {

/// historyPoor over the history-length plane, float or half. Half lengths are compared as their
/// bits, without a conversion per pixel (a library call on the baseline path): lengths are never
/// negative, so their bit patterns order as their values, signed 16-bit integers included.
struct PoorLengths {
    typedef int16_t __attribute__((may_alias)) HalfBits;
    const float* length = nullptr;
    const HalfBits* bits = nullptr;
    int16_t limit = 0; ///< the bits of half 1, historyPoor's limit

    explicit PoorLengths(const PlaneSet& noisy) { // channel 3: the history length
        if (!noisy.half) {
            length = noisy.plane<float>(3);
            return;
        }
        static_assert(sizeof(_Float16) == sizeof(int16_t));
        bits = reinterpret_cast<const HalfBits*>(noisy.plane<_Float16>(3));
        const _Float16 one = 1.0f;
        std::memcpy(&limit, &one, sizeof limit);
    }
    /// Calls fn(poor) with poor(i) the test of pixel i, in the plane's own type.
    template <class Fn> void with(Fn&& fn) const {
        if (bits) return fn([b = bits, l = limit](size_t i) { return b[i] <= l; });
        fn([f = length](size_t i) { return historyPoor(f[i]); });
    }
    /// Whether a pixel of `r` has no history.
    bool any(const OwnedRect& r, int width) const {
        bool poor = false;
        with([&](auto test) {
            for (int y = r.y0; y < r.y1 && !poor; ++y) {
                const size_t row = size_t(y) * size_t(width);
                int any = 0; // a local or-reduction, so that the loop vectorises
                for (int x = r.x0; x < r.x1; ++x) any |= test(row + size_t(x));
                poor = any != 0;
            }
        });
        return poor;
    }
    /// The history-poor pixels of `r` take the mean of both grids' fits.
    void blend(const OwnedRect& r, int width, float* const fitted[3],
               const float* const second[3]) const {
        with([&](auto test) {
            for (int y = r.y0; y < r.y1; ++y) {
                const size_t row = size_t(y) * size_t(width) + size_t(r.x0);
                const int n = r.x1 - r.x0;
                // The row's tests first, then each channel's blend in a loop of its own: measured
                // faster (about 4% of the quality preset at 720p) than testing and blending pixel
                // by pixel.
                bool take[kMaxBlockSize];
                for (int x = 0; x < n; ++x) take[x] = test(row + size_t(x));
                for (int ch = 0; ch < 3; ++ch) {
                    float* __restrict f = fitted[ch] + row;
                    const float* __restrict o = second[ch] + row;
                    for (int x = 0; x < n; ++x) f[x] = take[x] ? blendSecondFit(f[x], o[x]) : f[x];
                }
            }
        });
    }
};

} // namespace

void fitSecondGrid(const BmfrPassContext& ctx, Buffers& b) {
    const TemporalHistory& t = ctx.history;
    const BlockGrid g =
        secondGrid(makeBlockGrid(t.width, t.height, ctx.settings.blockSize, t.frameIndex));
    const Phase2 a{ctx, b, g, true};
    const PoorLengths poor(b.noisy[t.cur]);
    float* const fitted[3] = {b.plane(b.fitted, 0), b.plane(b.fitted, 1), b.plane(b.fitted, 2)};
    // The blocks with a pixel without history, a tenth of them under a moving camera, found
    // row by row, then fitted as one list: they gather where the view uncovers something,
    // and rows of them left one worker with most of the work.
    ctx.pool.parallelFor(g.blocksY, 4, [&](long by0, long by1) {
        for (long by = by0; by < by1; ++by)
            for (int bx = 0; bx < g.blocksX; ++bx)
                b.secondPoor[size_t(by * g.blocksX + bx)] =
                    poor.any(ownedRect(g, bx, int(by)), g.width);
    });
    b.secondBlocks.clear();
    for (int k = 0; k < g.blockCount(); ++k)
        if (b.secondPoor[size_t(k)]) b.secondBlocks.push_back(k);
    const long n = long(b.secondBlocks.size());
    ctx.pool.parallelFor(n, 1, [&](long k0, long k1) {
        Scratch& sc = b.scratch[size_t(ThreadPool::currentThreadIndex())];
        for (long k = k0; k < k1; ++k) {
            const int block = b.secondBlocks[size_t(k)];
            const int bx = block % g.blocksX, by = block / g.blocksX;
            // Each fit asks for the next one's rows: they are rarely still in cache.
            const int next = k + 1 < k1 ? b.secondBlocks[size_t(k + 1)] : g.blockCount();
            fitBlock(a, bx, by, sc, next % g.blocksX, next / g.blocksX);
            // The blocks of a grid own disjoint pixels: each blends its own.
            poor.blend(ownedRect(g, bx, by), g.width, fitted, a.out);
        }
    });
}

void fitBlockRow(const BmfrPassContext& ctx, Buffers& b, const BlockGrid& grid, int by,
                 Scratch& sc) {
    const Phase2 a{ctx, b, grid};
    for (int bx = 0; bx < grid.blocksX; ++bx) fitBlock(a, bx, by, sc, bx + 1, by);
}

} // namespace bmfr::cpu
