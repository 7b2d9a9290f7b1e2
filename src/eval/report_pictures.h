// The still pictures of a comparison: labelled rows of frames and insets, and error heat maps
// with their colour bars.
#pragma once
#include "eval/raster.h"
#include <array>
#include <string>
#include <vector>

namespace bmfr {

/// Images side by side, each with its label above; `crop` (x, y, w, h; w = 0 for the whole
/// frame) enlarged `zoom` times.
Raster labelledRow(const std::vector<const ImageF*>& images, const std::vector<std::string>& labels,
                   std::array<int, 4> crop = {0, 0, 0, 0}, int zoom = 1);

/// A 1-channel map through the heat colour map over [0, vmax], with a colour bar and its
/// labels ("0", vmax / 2, vmax) and `caption` underneath.
Raster heatMapWithBar(const ImageF& map, float vmax, const std::string& caption);

/// A common upper end for heat maps: the `percentile` of all their values, rounded up to 1, 2 or
/// 5 times a power of ten, within [0.01, 1].
float heatScale(const std::vector<const ImageF*>& maps, double percentile = 0.99);

/// Box-filtered reduction by an integer factor (1 = a copy).
Raster downscale(const Raster& r, int factor);
/// A 1-channel map in [0, 1] as grey levels.
Raster greyRaster(const ImageF& map);

} // namespace bmfr
