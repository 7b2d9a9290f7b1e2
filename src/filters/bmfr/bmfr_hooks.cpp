#include "filters/bmfr/bmfr_hooks.h"
#include <bmfr/error.h>
#include <string>

namespace bmfr {

int BmfrHooks::extrasNeeded(const BmfrSettings& settings) const {
    int n = 0;
    for (const Feature& f : settings.features)
        if (f.source == FeatureSource::Extra && f.extraIndex + 1 > n) n = f.extraIndex + 1;
    return n;
}

BmfrSettings BmfrHooks::widest(const BmfrSettings& settings) const {
    BmfrSettings s = settings;
    if (s.visibilityFeature) {
        Feature v;
        v.source = FeatureSource::Extra;
        s.features.push_back(v);
    }
    return s;
}

const BmfrSettings& BmfrHooks::select(const BmfrSettings& settings, const FrameInput& frame,
                                      const TemporalHistory& history, bool& changed) {
    const bool reads = settings.visibilityFeature || settings.visibilityTaps;
    const int extra = reads && frame.visibility.data ? int(frame.extras.size()) : -1;
    changed = extra != visibilityExtra;
    if (!changed) return active;
    if (visibilityExtra != -2 && history.hasHistory() && !frame.reset)
        throw Error(visibilityExtra < 0 || extra < 0
                        ? std::string("this frame ") + (extra < 0 ? "lacks" : "brings") +
                              " a visibility buffer and the earlier frames " +
                              (extra < 0 ? "had one" : "did not") +
                              " (visibilityFeature and visibilityTaps read it): give it on every "
                              "frame or none, or reset between"
                        : "this frame has " + std::to_string(frame.extras.size()) +
                              " extra buffers and a visibility buffer, the earlier frames " +
                              std::to_string(visibilityExtra) +
                              " (the visibility is fitted after the extras)");
    visibilityExtra = extra;
    active = settings;
    if (extra >= 0 && settings.visibilityFeature) {
        Feature v;
        v.source = FeatureSource::Extra;
        v.extraIndex = extra;
        active.features.push_back(v);
    }
    return active;
}

} // namespace bmfr
