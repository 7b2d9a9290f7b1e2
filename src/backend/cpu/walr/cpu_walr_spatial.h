// The CPU backend's WALR spatial filter: edge tracing eight pixels at a time over padded planes
// of positions and normals, then each pixel's 14 averages gathered as one cache line per tap
// (half of one with half averages), and the per-pixel solve eight pixels at a time. Mirrors
// walrAtrousPixel and walrSolvePixel (filters/walr/atrous_averages.h) bit for bit, on averages
// interleaved 16 floats (or halves) per pixel.
//
// The trace skips taps whose steps provably all weigh 1: the segment from each pixel along each
// forward tap direction (4 to 7; taps 0 to 3 run along them backwards) has a bound on how far its
// positions stray from its chord (the straight line between its two end positions), built for the
// lengths 3, 9, 27 and 81, each from the one below (a one-step segment's bound is 0), and used
// from step 9 on. They are built sixteen lanes at a time on the AVX-512 path. Along the chord the
// plane distance is linear, so the end's distance plus the bound (with a margin for rounding) below
// the ramp's start mean no pixel of the segment can lower the traced minimum.
//
// The stepped trace (EdgeGuide::stepFraction) builds no chord bounds: each block's eight lanes
// skip what the shortest of their flat runs allows (steppedTrace), read from planes of runs
// that each iteration writes and the next reads as runs of eight (shortestRuns).
#pragma once
#include "core/parallel.h"
#include "filters/walr/atrous_averages.h"
#include <atomic>
#include <vector>

namespace bmfr::cpu {

/// The guide's positions, normals and depth as seven planes with rows padded on both sides, so
/// that every tap's trace loads eight lanes without bounds checks. Filled once per frame. Also
/// each pixel's trace along each of the 8 directions so far (smallest weight and first zero):
/// the segment of iteration t begins with that of iteration t - 1, so each iteration traces
/// only the steps beyond the last one's. And the chord bounds of the segments of length
/// `chordLength` that start at each pixel, along the four forward directions.
struct EdgePlanes {
    static constexpr int kPad = 96; ///< >= the largest step (81) + 16 lanes - 1
    std::vector<float> planes;
    std::vector<float> tracedMin; ///< [row][block of 8 pixels][direction][lane]
    std::vector<int32_t> tracedEdge;
    /// [level parity][row][forward direction][padded column]: the largest distance (in each
    /// coordinate) of a segment's positions from its chord; +inf where it leaves the image. As
    /// halves rounded up: a larger bound only skips less, and they are most of the bytes that
    /// building them moves.
    std::vector<uint16_t> chordBound[2];
    int chordLength = 0; ///< the segments' length in chordBound[chordLevel]; 0 = none yet
    int chordLevel = 0;
    /// Stepped tracing's flat runs (SteppedTrace::flat) and, from them, each run of eight
    /// pixels' shortest (traceSkip's), [row][direction][padded column], 255 in the padding;
    /// sized on first use. A block's trace reads its own runs before it writes them.
    std::vector<uint8_t> flatRuns, shortestRuns;
    int skipOf[256] = {}; ///< skipOverRun of each run, for this frame's fraction
    /// Taps of eight pixels whose steps the chord bounds let the trace skip, since fill.
    std::atomic<long> skippedTaps{0};
    long rowStride = 0; ///< floats from one row of a plane to the next
    long planeSize = 0; ///< floats from a row of one plane to the same row of the next
    long blocksPerRow = 0;
    const float* plane(int k) const { return planes.data() + k * planeSize + kPad; }
    /// The chord bounds along tap 4 + d's direction (walrTapX, walrTapY) at row 0, column 0.
    const uint16_t* chordBounds(int d) const {
        return chordBound[chordLevel].data() + d * planeSize + kPad;
    }
    /// The flat runs along tap direction d at row 0, column 0; the same of shortestRuns.
    uint8_t* flatRun(int d) { return flatRuns.data() + d * planeSize + kPad; }
    const uint8_t* shortestRun(int d) const { return shortestRuns.data() + d * planeSize + kPad; }
    /// Sizes the planes for a width x height guide, with the flat runs when `stepped` (fill
    /// does too, when they are not).
    void allocate(int width, int height, bool stepped);
    void fill(ThreadPool& pool, const EdgeGuide& g);
    /// Builds the chord bounds of length 3 L from those of length L (3 from none).
    void buildChordBounds(ThreadPool& pool, const EdgeGuide& g);
    /// Builds shortestRuns from flatRuns, after an iteration's trace.
    void buildShortestRuns(ThreadPool& pool, int height);
};

/// One a-trous iteration (walrAtrousPixel) over the whole image; level.layout must be
/// interleaved ({1, 16}). Iterations run in order from 0 after planes.fill; the `last` one
/// leaves no trace for a next (the next call must be iteration 0, after a fill).
void walrAtrousIteration(ThreadPool& pool, const EdgeGuide& g, EdgePlanes& planes,
                         const WalrLevel& level, bool last);

/// walrSolvePixel over the whole image from interleaved averages into `out` (3 floats per
/// pixel); features has 2 floats per pixel.
void walrSolveImage(ThreadPool& pool, int width, int height, const float* averages,
                    const float* features, float eps, float* out);

} // namespace bmfr::cpu
