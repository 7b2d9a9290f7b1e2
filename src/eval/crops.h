// Where `bmfr eval` puts its zoomed insets: windows where the methods disagree most, from
// distinct parts of the frame.
#pragma once
#include "core/image.h"
#include <array>
#include <vector>

namespace bmfr {

/// Up to `count` windows of `size` pixels (x, y, w, h). `errors` holds one per-pixel error map
/// (1 channel) per compared method. A window scores the spread of the methods' mean errors in it
/// (max - min), so that it shows where they differ; with one method, its error. Windows are
/// taken best first, at most one per cell of a grid over the frame, none overlapping and each
/// at least 1.5 sizes from the others.
std::vector<std::array<int, 4>> chooseCrops(const std::vector<ImageF>& errors, int count, int size);

} // namespace bmfr
