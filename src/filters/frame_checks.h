// Input validation shared by every filter: the same inputs get the same errors.
#pragma once
#include <bmfr/features.h>
#include <bmfr/frame.h>
#include <vector>

namespace bmfr {

/// Throws bmfr::Error for missing, zero-size or mismatched buffers, wrong channel counts,
/// missing extra buffers that `features` needs, and non-finite or singular matrices.
void checkFrameInput(const FrameInput& frame, const std::vector<Feature>& features);

} // namespace bmfr
