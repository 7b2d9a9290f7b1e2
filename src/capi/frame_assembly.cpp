#include "capi/frame_assembly.h"
#include "temporal/frame_buffers.h"
#include <bmfr/error.h>

namespace bmfr::capi {

namespace {

constexpr int kMaxExtraImages = 16;

/// "extraK" as K, or -1.
int extraIndex(std::string_view name) {
    if (name.rfind("extra", 0) != 0 || name.size() < 6 || name.size() > 7) return -1;
    int k = 0;
    for (size_t i = 5; i < name.size(); ++i) {
        if (name[i] < '0' || name[i] > '9') return -1;
        k = 10 * k + (name[i] - '0');
    }
    if (name.size() == 7 && name[5] == '0') return -1; // "extra01"
    return k < kMaxExtraImages ? k : -1;
}

const FrameBuffer* frameBuffer(std::string_view name) {
    for (const FrameBuffer& b : kFrameBuffers)
        if (name == b.member) return &b;
    return nullptr;
}

std::string channelError(std::string_view name, const SharedImage& image,
                         const std::string& takes) {
    return "image '" + std::string(name) + "' is " + formatName(image.format) + " (" +
           std::to_string(image.channels()) + " channels); it takes " + takes;
}

std::string rangeText(ChannelRange r) {
    if (r.lo == r.hi) return std::to_string(r.lo);
    return std::to_string(r.lo) + " to " + std::to_string(r.hi);
}

/// True when the C++ API reads the image without a copy of its own: packed floats of exactly
/// the channels it stages (any other layout it would copy into a buffer made on first use).
bool packedAsStaged(const SharedImage& image, int staged) {
    return readsInPlace(image) && image.channels() == staged &&
           image.rowStride == size_t(image.width) * image.pixelStride;
}

ImageView convert(BMFRFilterImpl& f, const std::string& name, const SharedImage& image,
                  const ImagePlan& plan) {
    auto found = f.converted.find(name);
    if (found == f.converted.end()) found = f.converted.emplace(name, 0).first;
    std::vector<float>& buffer = found->second;
    switch (plan.kind) {
    case ImagePlan::Octahedral:
        return decodeOctahedralNormals(image, f.frame.normalOctUnorm, buffer);
    case ImagePlan::Depth:
        return positionsFromDepth(image, f.frame.viewProjection, f.frame.jitter, buffer);
    case ImagePlan::Motion:
        return convertMotion(image, f.frame.motion, f.frame.jitter, f.previousJitter, buffer);
    default:
        return copyToFloats(image, plan.channels, buffer);
    }
}

} // namespace

std::vector<std::string> imageNames() {
    std::vector<std::string> names;
    for (const FrameBuffer& b : kFrameBuffers) names.emplace_back(b.member);
    names.emplace_back("depth");
    for (int k = 0; k < kMaxExtraImages; ++k) names.push_back("extra" + std::to_string(k));
    names.emplace_back("output");
    return names;
}

bool isImageName(std::string_view name) {
    return frameBuffer(name) || extraIndex(name) >= 0 || name == "depth" || name == "output";
}

ImagePlan planImage(std::string_view name, const SharedImage& image,
                    const FrameConventions& frame) {
    const int c = image.channels();
    if (name == "output") {
        if (c != 3 && c != 4) throw Error(channelError(name, image, "3 or 4"));
        return {};
    }
    if (name == "depth") {
        if (c != 1) throw Error(channelError(name, image, "1 (view depth)"));
        return {ImagePlan::Depth, 3};
    }
    if (extraIndex(name) >= 0) {
        if (c != 1) throw Error(channelError(name, image, "1"));
        return packedAsStaged(image, 1) ? ImagePlan{} : ImagePlan{ImagePlan::Copy, 1};
    }
    const FrameBuffer& b = *frameBuffer(name);
    if (name == "normal" && c == 2) return {ImagePlan::Octahedral, 3};
    if (c < b.channels.lo || c > b.channels.hi) {
        const std::string takes =
            rangeText(b.channels) + (name == "normal" ? " (2: octahedral)" : "");
        throw Error(channelError(name, image, takes));
    }
    if (name == "motion") {
        // With a depth offset (3 channels) the C++ staging splits it in any case.
        if (frame.motion.isIdentity() && (packedAsStaged(image, 2) || packedAsStaged(image, 3)))
            return {};
        return {ImagePlan::Motion, c >= 3 ? 3 : 2};
    }
    return packedAsStaged(image, b.staged) ? ImagePlan{} : ImagePlan{ImagePlan::Copy, b.staged};
}

const FrameInput& assembleFrame(BMFRFilterImpl& f) {
    if (!f.frame.hasViewProjection)
        throw Error("matrix 'viewProjection' is not set (bmfrSetFilterMatrix)");
    if (f.images.count("position") && f.images.count("depth"))
        throw Error("images 'position' and 'depth' are both set: give one (unset the other)");
    FrameInput& in = f.frameInput;
    for (const FrameBuffer& b : kFrameBuffers) in.*(b.view) = ImageView{};
    in.extras.clear(); // keeps its capacity
    in.viewProjection = f.frame.viewProjection;
    in.jitter[0] = f.frame.jitter[0];
    in.jitter[1] = f.frame.jitter[1];
    int extras = 0;
    for (const auto& [name, image] : f.images) {
        if (name == "output") continue;
        const ImagePlan plan = planImage(name, image, f.frame);
        const ImageView view =
            plan.kind == ImagePlan::InPlace ? inPlaceView(image) : convert(f, name, image, plan);
        const int k = extraIndex(name);
        if (k >= 0) {
            if (int(in.extras.size()) <= k) in.extras.resize(size_t(k) + 1); // within capacity
            in.extras[size_t(k)] = view;
            ++extras;
        } else if (name == "depth") {
            in.position = view;
        } else {
            in.*(frameBuffer(name)->view) = view;
        }
    }
    if (extras != int(in.extras.size()))
        throw Error("image 'extra" + std::to_string(in.extras.size() - 1) + "' is set but not " +
                    "every extra before it: extras are numbered from extra0 up");
    const bool restart = f.frame.accumulationMode != BMFR_ACCUMULATION_MODE_CONTINUE;
    const bool skipped = f.frame.frameIndex >= 0 && f.previousFrameIndex >= 0 &&
                         f.frame.frameIndex != f.previousFrameIndex + 1;
    in.reset = restart || skipped;
    return in;
}

} // namespace bmfr::capi
