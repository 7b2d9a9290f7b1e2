// The bench's memory baselines: how long this machine takes to stream the bytes a BMFR frame
// moves, measured in the same run as the passes themselves.
#pragma once
#include <span>

namespace bmfr::app {

/// Planes (one float per pixel) a pass reads and writes per frame.
struct PassTraffic {
    int reads, writes;
};

/// What the fast passes stream, pass by pass (see stream_floor.cpp for the count), with float
/// or half history planes (BmfrSettings::halfHistory; two half planes count as one float plane,
/// rounded down, so the figure stays a floor).
std::span<const PassTraffic> fastPassTraffic(bool halfHistory = false);
/// The least any implementation must stream: one pass over the inputs and the history (float or
/// half as BmfrSettings::halfHistory stores it), everything else kept in cache.
std::span<const PassTraffic> singlePassTraffic(bool halfHistory = false);

/// Bytes the planes of `passes` come to for a width x height frame.
double trafficBytes(int width, int height, std::span<const PassTraffic> passes);

/// Median ms (over `repeats`) to stream, for a width x height frame, the planes of `passes` in
/// turn, with `threads` workers (0 = all cores). No arithmetic beyond one add per plane read;
/// ordinary stores, so each written line is also read first (write-allocate).
double streamFloorMs(int width, int height, int threads, int repeats,
                     std::span<const PassTraffic> passes);

} // namespace bmfr::app
