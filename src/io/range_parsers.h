// The command line's frame ranges and crops, parsed with their bounds checked.
#pragma once
#include <array>
#include <string>
#include <utility>

namespace bmfr {

/// "A:B" (frames A..B-1), "A:" or ":B" of a sequence of `count` frames; "" = all. Throws
/// bmfr::Error for anything else or a range outside [0, count).
std::pair<int, int> parseFrameRange(const std::string& spec, int count);

/// "x,y,w,h", each in [0, 65536]. Throws bmfr::Error otherwise.
std::array<int, 4> parseCrop(const std::string& text);

} // namespace bmfr
