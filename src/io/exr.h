// Reading and writing linear float images as OpenEXR.
#pragma once
#include "core/image.h"
#include <string>

namespace bmfr {

/// Reads an EXR as `channels` floats per pixel (3: R,G,B, or a single channel replicated;
/// 2: R,G; 1: Y, R or the only channel). Throws bmfr::Error naming the file when it is missing,
/// unreadable, empty or lacks the channels.
ImageF readExr(const std::string& path, int channels);

/// Writes 1, 2 or 3-channel float images (Y / R,G / R,G,B) atomically (temp file + rename).
void writeExr(const std::string& path, const ImageF& image);

} // namespace bmfr
