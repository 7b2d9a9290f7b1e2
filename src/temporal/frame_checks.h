// Input validation shared by every filter: the same inputs get the same errors.
#pragma once
#include <bmfr/frame.h>
#include <bmfr/temporal_settings.h>

namespace bmfr {

/// Throws bmfr::Error for missing, zero-size or mismatched buffers, wrong channel counts or row
/// strides, fewer than `extrasNeeded` extra buffers, non-finite or singular matrices, buffers
/// in more than one kind of memory, and device memory for a backend that cannot read it
/// (`backend`, by name, reads it when `readsDeviceMemory`).
void checkFrameInput(const FrameInput& frame, int extrasNeeded, const char* backend,
                     bool readsDeviceMemory);
/// True when the frame's buffers are in CUDA device memory (it passed checkFrameInput).
bool inDeviceMemory(const FrameInput& frame);

} // namespace bmfr
