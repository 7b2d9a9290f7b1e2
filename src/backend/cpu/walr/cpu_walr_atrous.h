// The CPU backend's WALR a-trous iteration: eight pixels of a row at once, positions and normals
// read as planes. Mirrors walrAtrousPixel (filters/walr/atrous_averages.h) bit for bit.
#pragma once
#include "core/parallel.h"
#include "filters/walr/atrous_averages.h"

namespace bmfr::cpu {

/// The guide's positions and normals as six planes (x, y, z of each), filled once per frame.
struct EdgePlanes {
    std::vector<float> planes;
    const float* position[3] = {};
    const float* normal[3] = {};
    void fill(ThreadPool& pool, const EdgeGuide& g);
};

/// One iteration of walrAtrousPixel over the whole image.
void walrAtrousIteration(ThreadPool& pool, const EdgeGuide& g, const EdgePlanes& planes,
                         const WalrLevel& level);

} // namespace bmfr::cpu
