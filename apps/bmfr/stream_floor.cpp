#include "stream_floor.h"
#include "core/parallel.h"
#include "core/stopwatch.h"
#include <algorithm>
#include <vector>

namespace bmfr::app {

namespace {

// accumulate: 4 packed xyz inputs (12) + previous surface and colour history (10); writes
//             surface (6), colour and length (4), previous pixel (2), accept mask (1 byte,
//             counted as a plane).
// fit:        surface and colour (9); writes the fitted colour (3).
// resolve:    fitted (3), accept + length + previous pixel (4), previous phase III output (3),
//             albedo (3), previous output (3); writes phase III output (3) and output (3).
constexpr PassTraffic kFast[] = {{22, 13}, {9, 3}, {16, 6}};

// One pass that reads the four packed xyz inputs (12) and the float history (surface 6, colour
// and length 4, phase III output 3, output 3), and writes the new history and the output (16).
constexpr PassTraffic kSinglePass[] = {{28, 16}};

// The same with half normals, phase I colour and length, and phase III colour: accumulate
// reads 18.5 and writes 9.5, the fit reads 6, resolve reads 14 and writes 4.5 planes.
constexpr PassTraffic kFastHalf[] = {{18, 9}, {6, 3}, {14, 4}};
// Half normals (1.5), colour and length (2) and phase III colour (1.5), read and written.
constexpr PassTraffic kSinglePassHalf[] = {{23, 11}};

} // namespace

std::span<const PassTraffic> fastPassTraffic(bool halfHistory) {
    if (halfHistory) return kFastHalf;
    return kFast;
}
std::span<const PassTraffic> singlePassTraffic(bool halfHistory) {
    if (halfHistory) return kSinglePassHalf;
    return kSinglePass;
}

double trafficBytes(int width, int height, std::span<const PassTraffic> passes) {
    double planes = 0;
    for (const PassTraffic& pass : passes) planes += pass.reads + pass.writes;
    return planes * double(width) * double(height) * sizeof(float);
}

double streamFloorMs(int width, int height, int threads, int repeats,
                     std::span<const PassTraffic> passes) {
    const long n = long(width) * height;
    int reads = 0, writes = 0;
    for (const PassTraffic& pass : passes)
        reads = std::max(reads, pass.reads), writes = std::max(writes, pass.writes);
    ThreadPool pool(threads);
    std::vector<std::vector<float>> in(static_cast<size_t>(reads)),
        out(static_cast<size_t>(writes));
    // Filled in parallel so pages land where the workers run.
    for (auto& p : in) p.resize(size_t(n));
    for (auto& p : out) p.resize(size_t(n));
    pool.parallelFor(n, 1 << 16, [&](long i0, long i1) {
        for (auto& p : in) std::fill(p.begin() + i0, p.begin() + i1, 1.0f);
        for (auto& p : out) std::fill(p.begin() + i0, p.begin() + i1, 0.0f);
    });
    std::vector<double> times;
    for (int r = 0; r < repeats; ++r) {
        Stopwatch clock;
        for (const PassTraffic& pass : passes)
            pool.parallelFor(height, 8, [&](long y0, long y1) {
                const long end = y1 * width;
                long i = y0 * width;
                for (; i + 64 <= end; i += 64) { // fixed trip counts: the loops vectorise
                    float sum[64] = {};
                    for (int p = 0; p < pass.reads; ++p) {
                        const float* src = in[size_t(p)].data() + i;
                        for (int k = 0; k < 64; ++k) sum[k] += src[k];
                    }
                    for (int p = 0; p < pass.writes; ++p) {
                        float* dst = out[size_t(p)].data() + i;
                        for (int k = 0; k < 64; ++k) dst[k] = sum[k];
                    }
                }
                for (; i < end; ++i) {
                    float sum = 0.0f;
                    for (int p = 0; p < pass.reads; ++p) sum += in[size_t(p)][size_t(i)];
                    for (int p = 0; p < pass.writes; ++p) out[size_t(p)][size_t(i)] = sum;
                }
            });
        times.push_back(clock.elapsed());
    }
    std::nth_element(times.begin(), times.begin() + long(times.size()) / 2, times.end());
    return times[times.size() / 2];
}

} // namespace bmfr::app
