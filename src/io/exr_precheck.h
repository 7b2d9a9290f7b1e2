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

/// Throws bmfr::Error naming `path` when a header is malformed, an attribute claims more bytes
/// than the file has, the image is deep or over the caps, or the chunk table or the pixel data
/// could not fit in `fileBytes`.
void precheckExr(const std::string& path, uint64_t fileBytes);

} // namespace bmfr
