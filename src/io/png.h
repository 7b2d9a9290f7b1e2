// Tone-mapped 8-bit PNG output for viewing results.
#pragma once
#include "core/image.h"
#include <string>

namespace bmfr {

/// Writes linear radiance through the paper's display transform clamp(x^(1/2.2), 0, 1).
/// 1-channel images are written as grey, scaled by `scale` first.
void writePngToneMapped(const std::string& path, const ImageF& image, float scale = 1.0f);

} // namespace bmfr
