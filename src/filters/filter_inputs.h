// Which optional inputs each filter reads under its settings, and what it does without those
// it is designed around: one table for the CLI's and Python's warnings and bmfr::filterInputs.
#pragma once
#include <bmfr/filter.h>
#include <bmfr/filters/bmfr_filter.h>
#include <bmfr/filters/mara2017_filter.h>
#include <bmfr/filters/svgf_filter.h>
#include <bmfr/filters/walr_filter.h>
#include <string>
#include <vector>

namespace bmfr {

std::vector<InputUse> inputsRead(const BmfrSettings& s);
std::vector<InputUse> inputsRead(const SvgfSettings& s);
std::vector<InputUse> inputsRead(const WalrSettings& s);
std::vector<InputUse> inputsRead(const Mara2017Settings& s);

/// A warning for the first input in `uses` that the filter is designed around (a non-empty
/// InputUse::without) and `frame` lacks: "the frame has no matte_indirect: ..."; "" when none.
/// The first only: the rest of a missing factorisation follows from it.
std::string missingInputWarning(const std::vector<InputUse>& uses, const FrameInput& frame);

} // namespace bmfr
