// "Did you mean": the known name nearest to a mistyped one, for every place that takes a name
// (commands, flags, setting keys, filter names, JSON keys).
#pragma once
#include <string>
#include <vector>

namespace bmfr {

/// The name in `known` nearest to `given`, or "" when none is a near miss. Case, '-' and '_'
/// are ignored (so `blocksize` finds `blockSize` and `block_size` finds `block-size`).
std::string closestName(const std::string& given, const std::vector<std::string>& known);

/// " (did you mean 'NAME'?)" with closestName's answer, or "" when there is none.
std::string didYouMean(const std::string& given, const std::vector<std::string>& known,
                       const std::string& prefix = "");

} // namespace bmfr
