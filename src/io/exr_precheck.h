// A structural check of an EXR file's headers before OpenEXR opens it: OpenEXR sizes its own
// buffers from the header (attribute values, chunk offset tables) and would allocate what a
// corrupt or hostile file claims. Every size is checked here against caps and against the
// bytes the file actually has.
#pragma once
#include <cstdint>
#include <string>

namespace bmfr {

inline constexpr long kMaxExrSide = 65536;
inline constexpr long kMaxExrPixels = 1L << 28; ///< 16384 x 16384
/// No EXR compression packs pixel data more than this to one (deflate reaches about 1032:1).
inline constexpr long kMaxExrCompressionRatio = 4096;
/// The most one chunk (a block of scan lines or a tile) may hold uncompressed.
inline constexpr long kMaxExrChunkBytes = 256L << 20;

/// Throws bmfr::Error naming `path` when a header is malformed, an attribute claims more bytes
/// than the file has, the image is deep or over the caps, the chunk table (every level of a
/// tiled part) or the pixel data could not fit in `fileBytes`, or one chunk (a tile, a block of
/// lines over every channel) would be larger uncompressed than the file could hold or the cap.
void precheckExr(const std::string& path, uint64_t fileBytes);

} // namespace bmfr
