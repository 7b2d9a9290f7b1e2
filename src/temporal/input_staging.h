// Turns a FrameInput of any layout (RGB or RGBA, any row stride) into the packed planes the
// passes read. Packed RGB buffers, what renderers usually hand over, are used in place; any
// other is copied once per frame into buffers kept between frames.
#pragma once
#include "temporal/pixel_input.h"
#include <bmfr/frame.h>
#include <vector>

namespace bmfr {

class InputStaging {
  public:
    /// The frame's planes; valid until the next call. The frame must have passed
    /// checkFrameInput.
    const InputPlanes& stage(const FrameInput& frame);

  private:
    /// Channels [first, first + channels) of v, packed (v itself when it already is).
    const float* packed(const ImageView& v, int channels, std::vector<float>& copy, int first = 0);
    InputPlanes planes_;
    std::vector<float> color_, albedo_, normal_, position_, emission_, sampleMask_, motion_;
    std::vector<float> motionDepth_, diffuseIndirect_;
    std::vector<float> previousPosition_, previousNormal_;
    std::vector<float> matte_, glossy_, direct_, f0_, roughness_, hitDistance_;
    std::vector<float> extras_[InputPlanes::kMaxExtras];
};

/// Throws bmfr::Error when the view is missing, of another size, or not 3 or 4 channels.
void checkOutput(const MutableImageView& out, int width, int height);
/// Writes a packed 3-channel image into a caller's view (3 or 4 channels, any row stride).
/// Throws bmfr::Error when the view is missing or its size differs.
void writeOutput(const ImageView& packedRgb, const MutableImageView& out);

} // namespace bmfr
