#include "filters/frame_checks.h"
#include "core/mat4.h"
#include <bmfr/error.h>
#include <cmath>
#include <string>

namespace bmfr {

namespace {

void checkImage(const ImageView& v, const char* name, int channels, int w, int h) {
    if (!v.data) throw Error(std::string("input buffer '") + name + "' is missing");
    if (v.width <= 0 || v.height <= 0)
        throw Error(std::string("input buffer '") + name + "' has zero size (" +
                    std::to_string(v.width) + "x" + std::to_string(v.height) + ")");
    if (v.channels != channels)
        throw Error(std::string("input buffer '") + name + "' has " + std::to_string(v.channels) +
                    " channels, expected " + std::to_string(channels));
    if (v.width != w || v.height != h)
        throw Error(std::string("input buffer '") + name + "' is " + std::to_string(v.width) + "x" +
                    std::to_string(v.height) + ", colour is " + std::to_string(w) + "x" +
                    std::to_string(h));
}

} // namespace

void checkFrameInput(const FrameInput& f, const std::vector<Feature>& features) {
    const int w = f.color.width, h = f.color.height;
    checkImage(f.color, "color", 3, w, h);
    checkImage(f.albedo, "albedo", 3, w, h);
    checkImage(f.normal, "normal", 3, w, h);
    checkImage(f.position, "position", 3, w, h);
    if (f.emission.data) checkImage(f.emission, "emission", 3, w, h);
    for (size_t e = 0; e < f.extras.size(); ++e)
        checkImage(f.extras[e], ("extra" + std::to_string(e)).c_str(), 1, w, h);
    for (const Feature& feat : features)
        if (feat.source == FeatureSource::Extra && feat.extraIndex >= int(f.extras.size()))
            throw Error("feature extra" + std::to_string(feat.extraIndex) + " needs " +
                        std::to_string(feat.extraIndex + 1) + " extra buffers, the frame has " +
                        std::to_string(f.extras.size()));
    if (f.extras.size() > 16) throw Error("at most 16 extra buffers");
    if (f.sampleMask.data) checkImage(f.sampleMask, "sampleMask", 1, w, h);
    if (!isUsableCameraMatrix(f.viewProjection))
        throw Error("view-projection matrix is not finite or not invertible");
    for (float j : f.jitter)
        if (!std::isfinite(j) || std::fabs(j) > 1.0f)
            throw Error("sub-pixel jitter " + std::to_string(j) + " is outside [-1, 1] pixels");
}

} // namespace bmfr
