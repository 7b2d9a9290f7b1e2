// BMFR's per-pixel images, written once for the backends that keep them as images of their own
// kind: Img<T> is Image<T> on the reference backend and DeviceImage<T> on CUDA, and H is how the
// planes halfHistory rounds are stored (float, or Half). Each backend adds its own scratch.
#pragma once
#include "filters/bmfr/bmfr_passes.h"
#include <cstdint>

namespace bmfr {

template <template <class> class Img, class H> struct BmfrImages {
    // History, [slot].
    Img<H> normal[2];              ///< sanitised features (discard tests)
    Img<float> position[2];        ///< sanitised features (discard tests)
    Img<H> accumulatedNoisy[2];    ///< phase I output, demodulated
    Img<uint8_t> historyLength[2]; ///< phase I sample count, 1..255
    Img<uint8_t> emitter[2];       ///< BmfrSettings::excludeEmitters: the fit's emitter bits
    Img<uint8_t> lit[2];           ///< BmfrSettings::visibilityTaps: litClass of each pixel
    Img<H> accumulatedFitted[2];   ///< phase III accumulation, demodulated
    Img<float> output[2];          ///< final (TAA) output, linear
    // This frame only.
    Img<float> previousPixel; ///< 2 channels: continuous pixel in the previous frame
    Img<uint8_t> acceptMask;  ///< accepted bilinear taps, bit i = tap i
    Img<float> fitted;        ///< phase II output, demodulated
    Img<float> fittedSecond;  ///< BmfrSettings::secondGrid: the shifted grid's fit
    Img<float> remodulated;   ///< phase III output before TAA
    Img<float> ycocg;         ///< TAA scratch
    Img<float> change;        ///< adaptiveHistory: recordHistoryChange's 2 channels

    /// Sizes every image for w x h with these settings (those a setting turns off: empty).
    void allocate(int w, int h, const BmfrSettings& s) {
        const auto on = [&](bool used, int n) { return used ? n : 0; };
        for (int k = 0; k < 2; ++k) {
            normal[k].resize(w, h, 3), position[k].resize(w, h, 3);
            accumulatedNoisy[k].resize(w, h, 3), historyLength[k].resize(w, h, 1);
            emitter[k].resize(on(s.excludeEmitters, w), on(s.excludeEmitters, h), 1);
            lit[k].resize(on(s.visibilityTaps, w), on(s.visibilityTaps, h), 1);
            accumulatedFitted[k].resize(w, h, 3), output[k].resize(w, h, 3);
        }
        previousPixel.resize(w, h, 2), acceptMask.resize(w, h, 1), fitted.resize(w, h, 3);
        fittedSecond.resize(on(s.secondGrid, w), on(s.secondGrid, h), 3);
        remodulated.resize(w, h, 3), ycocg.resize(w, h, 3);
        change.resize(on(s.adaptiveHistory, w), on(s.adaptiveHistory, h), 2);
    }
};

} // namespace bmfr
