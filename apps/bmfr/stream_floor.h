// The bench's memory baseline: how long this machine takes to stream the bytes the fast BMFR
// passes move, measured in the same run as the passes themselves.
#pragma once

namespace bmfr::app {

/// Median ms (over `repeats`) to stream, for a width x height frame, the planes each fast pass
/// reads and writes (one float per pixel each; see stream_floor.cpp for the count), with
/// `threads` workers (0 = all cores). No arithmetic beyond one add per plane read.
double streamFloorMs(int width, int height, int threads, int repeats);

} // namespace bmfr::app
