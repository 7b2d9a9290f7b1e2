// Turns a FrameInput of any layout (RGB or RGBA, any row stride) into the packed planes the
// passes read. Packed RGB buffers, what renderers usually hand over, are used in place; any
// other is copied once per frame into buffers kept between frames.
#pragma once
#include "temporal/frame_buffers.h"
#include "temporal/pixel_input.h"
#include <bmfr/frame.h>
#include <vector>

namespace bmfr {

/// Planes a frame can have: one per buffer, the motion's depth offset and the extras.
inline constexpr int kStagedPlanes = kFrameBufferCount + InputPlanes::kMaxExtras;

/// The frame's planes, each from pack(view, channels, slot, first): channels [first, first +
/// channels) of a buffer the frame has, packed; slot (below kStagedPlanes) names the buffer.
/// One list of which buffer becomes which plane, for the host staging and the cuda backend's.
template <class Pack> InputPlanes stagePlanes(const FrameInput& f, Pack&& pack) {
    InputPlanes p;
    p.width = f.color.width, p.height = f.color.height;
    int slot = 0;
#define BMFR_STAGE_BUFFER(m, file, channels, staged, required, motion)                             \
    p.m = f.m.data ? pack(f.m, staged, slot, 0) : nullptr;                                         \
    ++slot;
    BMFR_FRAME_BUFFERS(BMFR_STAGE_BUFFER)
#undef BMFR_STAGE_BUFFER
    p.motionDepth = f.motion.data && f.motion.channels >= 3 ? pack(f.motion, 1, slot, 2) : nullptr;
    ++slot;
    p.extraCount = int(f.extras.size());
    for (int e = 0; e < p.extraCount; ++e)
        p.extras[e] =
            f.extras[size_t(e)].data ? pack(f.extras[size_t(e)], 1, slot + e, 0) : nullptr;
    // The visibility is fitted as the extra after the frame's own (BmfrSettings).
    if (p.visibility) p.extras[p.extraCount++] = p.visibility;
    return p;
}

/// True when channels [first, first + channels) of v are the whole of it, packed.
inline bool isPacked(const ImageView& v, int channels, int first) {
    return first == 0 && v.channels == channels && v.stride() == long(v.width) * channels;
}

class InputStaging {
  public:
    /// The frame's planes; valid until the next call. The frame must have passed
    /// checkFrameInput.
    const InputPlanes& stage(const FrameInput& frame);

  private:
    /// Channels [first, first + channels) of v, packed (v itself when it already is).
    const float* packed(const ImageView& v, int channels, std::vector<float>& copy, int first = 0);
    InputPlanes planes_;
    std::vector<float> copies_[kStagedPlanes]; ///< by stagePlanes slot
};

/// Throws bmfr::Error when the view is missing, of another size, or not 3 or 4 channels.
void checkOutput(const MutableImageView& out, int width, int height);
/// Writes a packed 3-channel host image into a caller's host view (3 or 4 channels, any row
/// stride). Throws bmfr::Error when the view is missing, its size differs, or it is in device
/// memory.
void writeOutput(const ImageView& packedRgb, const MutableImageView& out);

} // namespace bmfr
