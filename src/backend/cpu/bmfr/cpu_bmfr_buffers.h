// The CPU backend's BMFR: its buffers and passes. Per-pixel buffers are planes (eight pixels per
// load), phase I and the fit run one row of blocks at a time, and phase III runs fused with TAA
// row by row.
#pragma once
#include "backend/cpu/simd.h"
#include "core/image.h"
#include "filters/bmfr/block_grid.h"
#include "filters/bmfr/bmfr_passes.h"
#include "filters/bmfr/visibility_taps.h"
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstring>
#include <vector>

namespace bmfr::cpu {

/// Per-thread scratch of the fitter (one block) and of the fused resolve pass (three rows).
struct Scratch {
    std::vector<float> clean;    ///< M scaled feature columns, noise-free (used for the sum)
    std::vector<float> work;     ///< M noised columns + 3 colour columns, overwritten by QR
    std::vector<float> soa;      ///< (9 + InputPlanes::kMaxExtras) x W: a border block's normal,
                                 ///< position, colour; extras
    std::vector<int> imageIndex; ///< image pixel of each block pixel, -1 when not owned
    std::vector<float> ones;     ///< one block row of 1 (+8 of padding): the constant feature
    std::vector<float> rows;     ///< 3 resolved rows (see taa_rows.h)
    std::vector<uint8_t> mask;   ///< the emitter mask (emitter_exclusion.h)
    std::vector<int> histogram;  ///< and its luminance histogram
    std::vector<float> lum;      ///< the block's colour luminances (+32 of padding)
    std::vector<int> buckets;    ///< maskBucket of every kMaskStride-th of them (+8)
};

/// Planes of one value per pixel, stored as float or, with BmfrSettings::halfHistory, as half
/// (16-bit float). Planes are `stride` values apart.
struct PlaneSet {
    std::vector<std::byte> bytes;
    size_t stride = 0;
    bool half = false;

    void assign(int channels, size_t planeStride, bool asHalf) {
        stride = planeStride, half = asHalf;
        bytes.assign(size_t(channels) * stride * elementSize(), std::byte{0});
    }
    size_t elementSize() const { return half ? sizeof(_Float16) : sizeof(float); }
    template <class T> T* plane(int channel) {
        return reinterpret_cast<T*>(bytes.data()) + size_t(channel) * stride;
    }
    template <class T> const T* plane(int channel) const {
        return reinterpret_cast<const T*>(bytes.data()) + size_t(channel) * stride;
    }
    /// Where value i of a channel lies, whatever the storage.
    const void* address(int channel, size_t i = 0) const {
        return bytes.data() + (size_t(channel) * stride + i) * elementSize();
    }
    /// Values [from, from + n) of a channel as floats, eight at a time.
    void copyOut(int channel, size_t from, size_t n, float* dst) const {
        if (!half) return (void)std::copy_n(plane<float>(channel) + from, n, dst);
        const _Float16* src = plane<_Float16>(channel) + from;
        size_t k = 0;
        for (; k + 8 <= n; k += 8) simd::store8(dst + k, simd::load8(src + k));
        for (; k < n; ++k) dst[k] = float(src[k]);
    }
    /// Value i of a channel as float, whatever the storage.
    float at(int channel, size_t i) const {
        return half ? float(plane<_Float16>(channel)[i]) : plane<float>(channel)[i];
    }
};

/// Per-pixel buffers are planes, one value per pixel and channel (structure of arrays), so
/// eight neighbouring pixels are one load. Planes are `stride` values apart; the stride leaves
/// at least 8 values after the last pixel, so an 8-value load at any pixel stays inside.
/// Positions, the previous pixel and the fitted frame stay float; normals, the phase I colour
/// and history length, and the phase III colour are half under BmfrSettings::halfHistory.
struct Buffers {
    int width = 0, height = 0;
    size_t stride = 0;

    // History, [slot].
    PlaneSet position[2];          ///< 3 planes: position xyz (sanitised), always float
    PlaneSet normal[2];            ///< 3 planes: normal xyz (sanitised)
    PlaneSet noisy[2];             ///< 4 planes: phase I colour (demodulated), history length
    PlaneSet accumulatedFitted[2]; ///< 3 planes: phase III colour
    std::vector<float> output[2];  ///< 3 floats per pixel (the public image), +24 of padding
    /// BmfrSettings::excludeEmitters or visibilityTaps: each pixel's tap class (kTapLit,
    /// kTapEmitter), which the fit writes.
    std::vector<uint8_t> tapClass[2];
    std::atomic<long> emitterPixels[2] = {}; ///< how many kTapEmitter bits are set, [slot]

    // This frame only.
    std::vector<float> previousPixel; ///< 2 planes: continuous pixel in the previous frame
    std::vector<uint8_t> acceptMask;  ///< accepted bilinear taps, bit i = tap i (+8 padding)
    /// With a tap filter (resolve's TapFilter): the accept mask less the taps it drops, as TAA
    /// reads it. Phase III reads acceptMask and filters it again in registers.
    std::vector<uint8_t> resolvedAccept;
    bool acceptFiltered = false;     ///< this frame's resolve wrote resolvedAccept
    std::vector<float> fitted;       ///< 3 planes: phase II colour
    std::vector<float> fittedSecond; ///< BmfrSettings::secondGrid: 3 planes, the shifted fit
    std::vector<uint8_t>
        earlyRow; ///< rows phase I runs before the block rows (see accumulateAndFit)
    /// BmfrSettings::adaptiveHistory or excludeEmitters: 2 planes, recordHistoryChange's sample
    /// and history luminance (the emitter mask reads the first: SampleLuminance). Under
    /// adaptiveHistory, storeTileChange's record of each tile, from the last frame measured
    /// (phase I reads the previous frame's before measureHistoryChange overwrites them).
    std::vector<float> change, changeTiles;
    /// BmfrSettings::secondGrid: whether each block of the shifted grid owns a pixel without
    /// history, and the list of those that do (by * blocksX + bx).
    std::vector<uint8_t> secondPoor;
    std::vector<int> secondBlocks;

    std::vector<Scratch> scratch; ///< one per worker thread
    std::vector<float> noise;     ///< this frame's regularisation noise
    ImageF debugNoisy, debugFitted, debugLength, debugAccept;

    float* plane(std::vector<float>& v, int channel) { return v.data() + size_t(channel) * stride; }
    const float* plane(const std::vector<float>& v, int channel) const {
        return v.data() + size_t(channel) * stride;
    }
};

/// One frame's planes as raw pointers, taken once per task, with T (float or _Float16) the
/// storage of the history planes. Row kernels read them from this local copy: a pointer inside
/// a std::vector would be reloaded after every byte store (the accept mask), since a byte store
/// may alias anything.
template <class T> struct FramePlanes {
    const float* prevPosition[3];
    float* position[3];
    const T* prevNormal[3];
    T* normal[3];
    const T* prevNoisy[4];
    T* noisy[4];
    const T* prevAccumulated[3];
    T* accumulated[3];
    float* previousPixel[2];
    float* fitted[3];
    uint8_t* accept;
    uint8_t* resolvedAccept;
    const uint8_t* tapClass;     ///< this frame's tap classes
    const uint8_t* prevTapClass; ///< and the previous frame's
    float* change[2];            ///< null without BmfrSettings::adaptiveHistory and excludeEmitters
    const float* changeTiles;    ///< null without BmfrSettings::adaptiveHistory

    FramePlanes(Buffers& b, int cur) {
        for (int c = 0; c < 3; ++c) {
            prevPosition[c] = b.position[1 - cur].plane<float>(c);
            position[c] = b.position[cur].plane<float>(c);
            prevNormal[c] = b.normal[1 - cur].plane<T>(c);
            normal[c] = b.normal[cur].plane<T>(c);
        }
        for (int c = 0; c < 4; ++c) {
            prevNoisy[c] = b.noisy[1 - cur].plane<T>(c);
            noisy[c] = b.noisy[cur].plane<T>(c);
        }
        for (int c = 0; c < 3; ++c) {
            prevAccumulated[c] = b.accumulatedFitted[1 - cur].plane<T>(c);
            accumulated[c] = b.accumulatedFitted[cur].plane<T>(c);
            fitted[c] = b.plane(b.fitted, c);
        }
        for (int c = 0; c < 2; ++c) previousPixel[c] = b.plane(b.previousPixel, c);
        accept = b.acceptMask.data();
        resolvedAccept = b.resolvedAccept.data();
        tapClass = b.tapClass[cur].data(), prevTapClass = b.tapClass[1 - cur].data();
        const bool recorded = !b.change.empty();
        for (int c = 0; c < 2; ++c) change[c] = recorded ? b.plane(b.change, c) : nullptr;
        changeTiles = b.changeTiles.empty() ? nullptr : b.changeTiles.data();
    }
};

/// Calls body(FramePlanes<T>) with T the history storage a body compiled for `kIsa` uses:
/// float, or with `half` the path's half type (simd::HalfOf).
template <Isa kIsa, class Body>
BMFR_SIMD_INLINE void withFramePlanes(Buffers& b, int cur, bool half, Body&& body) {
    if (half)
        body(FramePlanes<simd::HalfOf<kIsa>>(b, cur));
    else
        body(FramePlanes<float>(b, cur));
}

/// The bits of a pixel's tap class: whether the key light reaches it (litClass, under
/// BmfrSettings::visibilityTaps) and whether it is an emitter's own sample (maskEmitter).
inline constexpr uint8_t kTapLit = 1, kTapEmitter = 2;

/// The taps the resolve pass drops before phase III and TAA read the accept mask: those across
/// an emitter's edge (sameEmitterTaps), as the taps whose emitter bit differs from their
/// pixel's. The fit writes the classes, so that the resolve pass reads one byte plane instead
/// of two bit planes. The reference's sameLitTaps needs no counterpart here: phase I already
/// dropped every tap across a shadow edge with the same test on the same classes
/// (accumulateNoisyPixel), so it would drop nothing more.
struct TapFilter {
    bool emitters = false; ///< emitter bits are set in this frame or the previous
    bool on() const { return emitters; }
};

/// What the row kernels of phase I and the resolve pass read.
struct FrameArgs {
    const BmfrSettings& s;
    const InputPlanes& in;
    const TemporalHistory& t;
    Buffers& b;
    TapFilter filter = {}; ///< the resolve pass's
    /// Phase I drops emitter taps (phaseOneEmitterTaps): the emitter exclusion is on and the
    /// previous frame has emitter pixels.
    bool phaseOneEmitterTaps = false;
    /// Phase I drops taps across a shadow edge (accumulateNoisyPixel): this frame's staged
    /// visibility under visibilityTaps, with a history; else null.
    const float* phaseOneVisibility = nullptr;
};

/// Wall time of the pass that interleaves phase I and the fit, split between them in
/// proportion to the time the workers spent in each.
struct StageSplit {
    double accumulateMs = 0.0, fitMs = 0.0;
};

/// Phase I and phase II, block row by block row: each task runs phase I over the image rows a
/// row of blocks owns, then fits those blocks while the rows are still in cache. Tasks on
/// different cores drift apart, so one core's memory-bound phase I overlaps the other's
/// arithmetic-bound fit. Rows that a block reads through mirroring at the top and bottom edges
/// but does not own are done first.
PassCounters accumulateAndFit(const BmfrPassContext& ctx, Buffers& b, StageSplit& split);

/// Phase I of image rows [y0, y1): sanitise and store features, demodulate, reproject, test
/// taps, accumulate colour. Counts are added to `counters`.
void accumulateNoisyRows(const FrameArgs& a, long y0, long y1, PassCounters& counters);
/// Phase II of block row `by`: per block gather, scale, regularise, Householder QR, back
/// substitution, weighted sum. Reads only the rows the blocks cover, mirrored at the edges.
void fitBlockRow(const BmfrPassContext& ctx, Buffers& b, const BlockGrid& grid, int by,
                 Scratch& sc);
/// The visibility the tap classes read: the frame's staged one under
/// BmfrSettings::visibilityTaps, else null.
inline const float* tapVisibility(const BmfrPassContext& ctx) {
    return ctx.settings.visibilityTaps ? ctx.input.visibility : nullptr;
}
/// The tap classes of pixels [from, from + n) without an emitter: kTapLit where `visibility`
/// (null: none) is above 0. Inlined, as the fitter calls it for each row of a block.
BMFR_SIMD_INLINE void litClasses(const float* visibility, long from, long n, uint8_t* classes) {
    uint8_t* out = classes + from;
    if (!visibility) return (void)std::memset(out, 0, size_t(n));
    const float* v = visibility + from;
    for (long x = 0; x < n; ++x) out[x] = litClass(v, x) ? kTapLit : 0; // vectorises
}
/// BmfrSettings::secondGrid: fits the blocks of the shifted grid that own a pixel without
/// history, and gives those pixels the mean of both fits.
void fitSecondGrid(const BmfrPassContext& ctx, Buffers& b);
/// BmfrSettings::adaptiveHistory: tileHistoryChange of every tile, from what phase I recorded.
void measureHistoryChange(const BmfrPassContext& ctx, Buffers& b);

/// Phase III and TAA in one pass over rows: the taps `filter` drops, second accumulation,
/// re-modulation, emission, TAA.
void resolve(const BmfrPassContext& ctx, Buffers& b, const TapFilter& filter);

/// Householder QR of the M + 3 columns (each `rows` long, `stride` floats apart) and back
/// substitution, as bmfr::solveHouseholder (filters/bmfr/householder_qr.h). Each step's column
/// updates and the next step's dot products share one sweep over four columns at a time. Returns
/// the number of dependent columns (coefficient 0). A stride that is not a multiple of 1024 floats
/// avoids 4K aliasing between a column's stores and the next column's loads.
int solveHouseholderFast(float* columns, int featureCount, int rows, long stride, float* coeffs);
/// The same with contiguous columns (stride = rows).
int solveHouseholderFast(float* columns, int featureCount, int rows, float* coeffs);

/// Floats between the fitter's QR columns for blocks of `rows` pixels: one cache line more than
/// the column, so columns do not alias in 4 KiB pages.
inline long qrColumnStride(int rows) {
    return (long(rows) + 7) / 8 * 8 + 16;
}

} // namespace bmfr::cpu
