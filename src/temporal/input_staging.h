// Turns a FrameInput of any layout (RGB or RGBA, any row stride) into the packed planes the
// passes read. Packed RGB buffers, what renderers usually hand over, are used in place; any
// other is copied once per frame into buffers kept between frames.
#pragma once
#include "temporal/pixel_input.h"
#include <bmfr/frame.h>
#include <vector>

namespace bmfr {

/// Planes a frame can have: 17 buffers and the extras.
inline constexpr int kStagedPlanes = 17 + InputPlanes::kMaxExtras;

/// The frame's planes, each from pack(view, channels, slot, first): channels [first, first +
/// channels) of a buffer the frame has, packed; slot (below kStagedPlanes) names the buffer.
/// One list of which buffer becomes which plane, for the host staging and the cuda backend's.
template <class Pack> InputPlanes stagePlanes(const FrameInput& f, Pack&& pack) {
    const auto put = [&pack](const ImageView& v, int channels, int slot,
                             int first = 0) -> const float* {
        return v.data ? pack(v, channels, slot, first) : nullptr;
    };
    InputPlanes p;
    p.width = f.color.width, p.height = f.color.height;
    p.color = put(f.color, 3, 0);
    p.albedo = put(f.albedo, 3, 1);
    p.normal = put(f.normal, 3, 2);
    p.position = put(f.position, 3, 3);
    p.emission = put(f.emission, 3, 4);
    p.sampleMask = put(f.sampleMask, 1, 5);
    p.motion = put(f.motion, 2, 6);
    p.motionDepth = f.motion.channels >= 3 ? put(f.motion, 1, 7, 2) : nullptr;
    p.diffuseIndirect = put(f.diffuseIndirect, 3, 8);
    p.previousPosition = put(f.previousPosition, 3, 9);
    p.previousNormal = put(f.previousNormal, 3, 10);
    p.matteIndirect = put(f.matteIndirect, 3, 11);
    p.glossyIndirect = put(f.glossyIndirect, 3, 12);
    p.directLight = put(f.directLight, 3, 13);
    p.specularF0 = put(f.specularF0, 3, 14);
    p.roughness = put(f.roughness, 1, 15);
    p.glossyHitDistance = put(f.glossyHitDistance, 1, 16);
    p.extraCount = int(f.extras.size());
    for (int e = 0; e < p.extraCount; ++e) p.extras[e] = put(f.extras[size_t(e)], 1, 17 + e);
    if (f.visibility.data)
        p.extras[p.extraCount++] = put(f.visibility, 1, 16 + InputPlanes::kMaxExtras);
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
