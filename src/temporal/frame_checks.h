// Input validation shared by every filter: the same inputs get the same errors.
#pragma once
#include <bmfr/frame.h>

namespace bmfr {

/// Throws bmfr::Error for missing, zero-size or mismatched buffers, wrong channel counts or row
/// strides, fewer than `extrasNeeded` extra buffers, and non-finite or singular matrices.
void checkFrameInput(const FrameInput& frame, int extrasNeeded);

} // namespace bmfr
