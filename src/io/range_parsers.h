// The command line's frame ranges and crops, parsed with their bounds checked.
#pragma once
#include <array>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace bmfr {

/// Throws bmfr::Error when `spec` is not of the form "A:B", "A:", ":B" or "" (whatever the
/// sequence's length).
void checkFrameRangeSyntax(const std::string& spec);

/// "A:B" (frames A..B-1), "A:" or ":B" of a sequence of `count` frames; "" = all. Throws
/// bmfr::Error for anything else or a range outside [0, count).
std::pair<int, int> parseFrameRange(const std::string& spec, int count);

/// "x,y,w,h", each in [0, 65536]. Throws bmfr::Error otherwise.
std::array<int, 4> parseCrop(const std::string& text);

/// "BUFFER=LAYER" items (`--channel albedo=ViewLayer.DiffCol`) as a map; the buffer names are
/// checked where the map is used (SequenceReader::setLayerOverrides). Throws bmfr::Error.
std::map<std::string, std::string> parseLayerMap(const std::vector<std::string>& items);

} // namespace bmfr
