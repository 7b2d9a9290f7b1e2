// The backends' passes by filter: the one place that maps a Backend to its implementation.
#pragma once
#include "filters/bmfr/bmfr_passes.h"
#include "filters/mara2017/mara_passes.h"
#include "filters/svgf/svgf_passes.h"
#include "filters/walr/walr_passes.h"
#include <memory>

namespace bmfr {

/// Throws bmfr::Error when `backend` is not built into this library.
std::unique_ptr<BmfrPasses> makeBmfrPasses(Backend backend);
std::unique_ptr<SvgfPasses> makeSvgfPasses(Backend backend);
std::unique_ptr<WalrPasses> makeWalrPasses(Backend backend);
std::unique_ptr<MaraPasses> makeMaraPasses(Backend backend);

} // namespace bmfr
