#include "filters/filter_inputs.h"
#include "temporal/frame_buffers.h"
#include <algorithm>

namespace bmfr {

namespace {

/// Every filter reprojects through the motion vectors and the previous surface when given
/// (src/temporal/reprojection.h); without them, the cameras alone.
void addReprojection(std::vector<InputUse>& uses, bool previousNormal) {
    uses.push_back({"motion", ""});
    uses.push_back({"previous_position", ""});
    if (previousNormal) uses.push_back({"previous_normal", ""});
}

} // namespace

std::vector<InputUse> inputsRead(const BmfrSettings& s) {
    std::vector<InputUse> uses = {{"emission", ""}};
    addReprojection(uses, true);
    // On by default, and most engines have no such buffer: without it BMFR fits hard shadows
    // as the paper does, which is no reason to warn.
    if (s.visibilityFeature || s.visibilityTaps) uses.push_back({"visibility", ""});
    const bool extras = std::any_of(s.features.begin(), s.features.end(), [](const Feature& f) {
        return f.source == FeatureSource::Extra;
    });
    if (extras) uses.push_back({"extras", ""});
    return uses;
}

std::vector<InputUse> inputsRead(const SvgfSettings&) {
    std::vector<InputUse> uses = {{"emission", ""}, {"sample_mask", ""}};
    addReprojection(uses, true);
    return uses;
}

std::vector<InputUse> inputsRead(const WalrSettings& s) {
    std::vector<InputUse> uses;
    if (s.signal == WalrSignal::Color) uses.push_back({"emission", ""});
    addReprojection(uses, s.historyTest == WalrHistoryTest::World);
    if (s.signal == WalrSignal::DiffuseIndirect)
        uses.push_back({"diffuse_indirect", ""}); // its absence is an error (walr_hooks.h)
    return uses;
}

std::vector<InputUse> inputsRead(const Mara2017Settings& s) {
    std::vector<InputUse> uses = {{"emission", ""}};
    addReprojection(uses, false);
    const char* factored = " (bmfr render --paths mara writes it)";
    uses.push_back({"matte_indirect",
                    std::string("the whole demodulated colour is filtered as matte light, with no "
                                "glossy term and no separate direct light, a deviation from the "
                                "paper") +
                        factored});
    uses.push_back({"glossy_indirect", std::string("no glossy term") + factored});
    uses.push_back({"direct_light", std::string("direct light counts as 0") + factored});
    uses.push_back(
        {"specular_f0", std::string("Fresnel is 0, which drops the glossy term") + factored});
    uses.push_back({"roughness", std::string("roughness 1, the widest glossy filter") + factored});
    if (s.virtualReprojection)
        uses.push_back({"glossy_hit_distance",
                        std::string("reflections are reprojected with their surface, not their "
                                    "virtual position") +
                            factored});
    return uses;
}

std::string missingInputWarning(const std::vector<InputUse>& uses, const FrameInput& frame) {
    for (const InputUse& use : uses) {
        if (use.without.empty()) continue;
        for (const FrameBuffer& b : kFrameBuffers)
            if (use.buffer == b.file && !(frame.*b.view).data)
                return "the frame has no " + use.buffer + ": " + use.without;
    }
    return {};
}

} // namespace bmfr
