// Per-frame line plots (one series per method) rendered to a raster.
#pragma once
#include "eval/raster.h"
#include <string>
#include <vector>

namespace bmfr {

struct Series {
    std::string name;
    std::vector<double> values; ///< one per frame; NaN values are skipped
};

/// x = firstFrame + index. Axes, grid, tick labels and a legend included.
Raster linePlot(const std::string& title, const std::vector<Series>& series, int firstFrame,
                int width = 720, int height = 360);

} // namespace bmfr
