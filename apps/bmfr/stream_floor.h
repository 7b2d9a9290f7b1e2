// The bench's memory baselines: how long this machine takes to stream the bytes a BMFR frame
// moves, measured in the same run as the passes themselves.
#pragma once
#include <span>

namespace bmfr::app {

/// Planes (one float per pixel) a pass reads and writes per frame.
struct PassTraffic {
    int reads, writes;
};

/// What the fast passes stream, pass by pass (see stream_floor.cpp for the count).
std::span<const PassTraffic> fastPassTraffic();
/// The least any implementation with float history must stream: one pass over the inputs and
/// the history, everything else kept in cache.
std::span<const PassTraffic> singlePassTraffic();

/// Median ms (over `repeats`) to stream, for a width x height frame, the planes of `passes` in
/// turn, with `threads` workers (0 = all cores). No arithmetic beyond one add per plane read;
/// ordinary stores, so each written line is also read first (write-allocate).
double streamFloorMs(int width, int height, int threads, int repeats,
                     std::span<const PassTraffic> passes);

} // namespace bmfr::app
