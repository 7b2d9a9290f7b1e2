#include "io/sequence.h"
#include <algorithm>
#include <bmfr/error.h>
#include <filesystem>

namespace bmfr {

namespace fs = std::filesystem;

FrameInput FrameData::input(bool motionInput) const {
    FrameInput in;
    in.color = view(color);
    in.albedo = view(albedo);
    in.normal = view(normal);
    in.position = view(position);
    if (emission.width) in.emission = view(emission);
    if (diffuseIndirect.width) in.diffuseIndirect = view(diffuseIndirect);
    if (visibility.width) in.visibility = view(visibility);
    if (matteIndirect.width) in.matteIndirect = view(matteIndirect);
    if (glossyIndirect.width) in.glossyIndirect = view(glossyIndirect);
    if (directLight.width) in.directLight = view(directLight);
    if (specularF0.width) in.specularF0 = view(specularF0);
    if (roughness.width) in.roughness = view(roughness);
    if (glossyHitDistance.width) in.glossyHitDistance = view(glossyHitDistance);
    for (const ImageF& e : extras) in.extras.push_back(view(e));
    if (motionInput) {
        if (motion.width) in.motion = view(motion);
        if (previousPosition.width) in.previousPosition = view(previousPosition);
        if (previousNormal.width) in.previousNormal = view(previousNormal);
    }
    in.reset = reset;
    in.viewProjection = viewProjection;
    in.jitter[0] = jitter[0];
    in.jitter[1] = jitter[1];
    return in;
}

const std::vector<DefaultPass> kDefaultPasses = {
    {"color", {"Combined"}},
    {"albedo", {"Denoising Albedo", "DiffCol"}},
    {"normal", {"Normal", "Denoising Normal"}},
    {"position", {"Position"}},
    {"emission", {"Emit"}},
    {"reference", {"Combined"}},
    // Cycles has no pass of these conventions (its Vector pass points the other way, y up).
    {"motion", {}},
    {"previous_position", {}},
    {"previous_normal", {}},
    {"diffuse_indirect", {}},
    {"matte_indirect", {}},
    {"glossy_indirect", {}},
    {"direct_light", {}},
    {"specular_f0", {}},
    {"roughness", {}},
    {"glossy_hit_distance", {}},
    {"visibility", {}},
};

std::vector<std::string> layeredBufferNames() {
    std::vector<std::string> names;
    for (const DefaultPass& d : kDefaultPasses) names.push_back(d.buffer);
    return names;
}

void SequenceReader::setLayerOverrides(const std::map<std::string, std::string>& layers) {
    const std::vector<std::string> names = layeredBufferNames();
    for (const auto& [buffer, layer] : layers)
        if (std::find(names.begin(), names.end(), buffer) == names.end()) {
            std::string list;
            for (size_t k = 0; k < names.size(); ++k)
                list += (k == 0 ? "" : k + 1 == names.size() ? " or " : ", ") + names[k];
            throw Error("--channel " + buffer + "=" + layer + ": unknown buffer (" + list + ")");
        }
    if (!layers.empty() && info_.layout != "manifest")
        throw Error("--channel: the " + info_.layout +
                    " layout has no multilayer files; layers apply to sequence.json folders");
    layerOverrides_ = layers;
}

void SequenceReader::checkFrame(int index, const FrameData& f) const {
    auto check = [&](const ImageF& img, const char* name) {
        if (img.width != info_.width || img.height != info_.height)
            throw Error(info_.directory + ": frame " + std::to_string(index) + " " + name + " is " +
                        std::to_string(img.width) + "x" + std::to_string(img.height) +
                        ", the sequence is " + std::to_string(info_.width) + "x" +
                        std::to_string(info_.height));
    };
    check(f.color, "color");
    check(f.albedo, "albedo");
    check(f.normal, "normal");
    check(f.position, "position");
    for (const ImageF& e : f.extras) check(e, "extra");
    if (f.reference.width) check(f.reference, "reference");
    if (f.emission.width) check(f.emission, "emission");
    if (f.motion.width) check(f.motion, "motion");
    if (f.previousPosition.width) check(f.previousPosition, "previous_position");
    if (f.previousNormal.width) check(f.previousNormal, "previous_normal");
    if (f.diffuseIndirect.width) check(f.diffuseIndirect, "diffuse_indirect");
    if (f.visibility.width) check(f.visibility, "visibility");
    for (const auto& [img, name] : f.maraBuffers())
        if (img->width) check(*img, name);
}

std::unique_ptr<SequenceReader> SequenceReader::open(const std::string& directory) {
    if (!fs::is_directory(directory)) throw Error("input directory not found: " + directory);
    if (fs::exists(fs::path(directory) / "sequence.json")) return openManifestLayout(directory);
    if (fs::exists(fs::path(directory) / "camera_matrices.h") ||
        fs::exists(fs::path(directory) / "color0.exr"))
        return openBmfrLayout(directory);
    throw Error(directory + ": neither sequence.json (bmfr layout) nor camera_matrices.h / "
                            "color0.exr (original BMFR dataset layout) found");
}

} // namespace bmfr
