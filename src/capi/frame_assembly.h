// The C API's images and per-frame conventions as one bmfr::FrameInput: which images are read in
// place, which are converted (half, octahedral normals, depth, motion in an engine's units), and
// the checks that name the image at fault.
#pragma once
#include "capi/api_objects.h"

namespace bmfr::capi {

/// The names bmfrSetFilterImage takes: every FrameInput buffer, "depth", "extra0" to "extra15"
/// and "output".
bool isImageName(std::string_view name);
std::vector<std::string> imageNames();

/// How an input image reaches the filter.
struct ImagePlan {
    enum Kind { InPlace, Copy, Octahedral, Depth, Motion } kind = InPlace;
    int channels = 0; ///< channels of the converted buffer (0 when read in place)
};

/// Throws bmfr::Error when image `name` has a channel count the filter does not take.
ImagePlan planImage(std::string_view name, const SharedImage& image, const FrameConventions& frame);

/// The frame to denoise (f.frameInput), its buffers in `f.converted` where converted. Throws
/// bmfr::Error naming the image or matrix at fault.
const FrameInput& assembleFrame(BMFRFilterImpl& f);

} // namespace bmfr::capi
