// Phase I, the fit's and phase III's parameters for one frame, from the settings and the history,
// over any backend's buffers kept as interleaved images with the reference backend's names (normal,
// position, accumulatedNoisy, historyLength, accumulatedFitted: [2] by slot; previousPixel,
// acceptMask, fitted; under adaptiveHistory change, 2 channels, and changeTiles). The reference
// and CUDA backends share it.
#pragma once
#include "filters/bmfr/accumulation_kernels.h"
#include "filters/bmfr/bmfr_passes.h"
#include "filters/bmfr/fitting_kernel.h"
#include <type_traits>
#include <utility>

namespace bmfr {

/// How Buffers stores the history planes that halfHistory rounds: float or Half.
template <class Buffers>
using HistoryStorage = std::remove_pointer_t<decltype(std::declval<Buffers&>().normal[0].data())>;

/// Phase I of this frame, reading the input from `in` (host or device planes).
template <class Buffers>
NoisyAccumulationOf<HistoryStorage<Buffers>> noisyAccumulation(const BmfrPassContext& ctx,
                                                               const InputPlanes& in, Buffers& b) {
    const BmfrSettings& s = ctx.settings;
    const TemporalHistory& t = ctx.history;
    const int cur = t.cur, prev = 1 - t.cur;
    NoisyAccumulationOf<HistoryStorage<Buffers>> a;
    a.in = in;
    a.modes = inputModes(s);
    a.previous = t.previous;
    a.limits = {s.positionLimitSquared, s.normalLimitSquared};
    a.minAlpha = s.firstBlendAlpha, a.accumulate = s.stages.firstAccumulation;
    a.halfHistory = s.halfHistory;
    a.width = t.width, a.height = t.height;
    a.normal = b.normal[cur].data(), a.position = b.position[cur].data();
    a.prevNormal = b.normal[prev].data(), a.prevPosition = b.position[prev].data();
    a.prevNoisy = b.accumulatedNoisy[prev].data(), a.prevLength = b.historyLength[prev].data();
    a.noisy = b.accumulatedNoisy[cur].data(), a.length = b.historyLength[cur].data();
    a.previousPixel = b.previousPixel.data(), a.accept = b.acceptMask.data();
    if (t.hasHistory() && emitterExclusion(s, in, nullptr).on)
        a.prevEmitter = b.emitter[prev].data();
    if (const float* visibility = in.visibility; t.hasHistory() && s.visibilityTaps && visibility)
        a.visibility = visibility, a.prevLit = b.lit[prev].data();
    if (s.adaptiveHistory) {
        a.change = b.change.data();
        a.prevChangeTiles = b.changeTiles.data(); // the previous frame's, measured after this
        a.secondMinAlpha = s.secondBlendAlpha;
    }
    return a;
}

/// The fit of this frame, given the backend's copies of the features and of the noise.
template <class Buffers>
BlockFitOf<HistoryStorage<Buffers>> blockFit(const BmfrPassContext& ctx, const InputPlanes& in,
                                             Buffers& b, const Feature* features,
                                             const float* noise) {
    const BmfrSettings& s = ctx.settings;
    const TemporalHistory& t = ctx.history;
    BlockFitOf<HistoryStorage<Buffers>> a;
    a.grid = makeBlockGrid(t.width, t.height, s.blockSize, t.frameIndex);
    a.features = features, a.featureCount = int(s.features.size());
    a.noise = noise;
    a.normal = b.normal[t.cur].data(), a.position = b.position[t.cur].data();
    a.color = b.accumulatedNoisy[t.cur].data();
    a.in = in;
    a.fitted = b.fitted.data();
    a.emitters = emitterExclusion(s, in, b.emitter[t.cur].data());
    if (a.emitters.on && t.hasHistory()) {
        a.emitters.previous = b.emitter[1 - t.cur].data();
        a.emitters.previousX = b.previousPixel.data(),
        a.emitters.previousY = a.emitters.previousX + 1;
        a.emitters.previousStep = 2;
    }
    a.clampFireflies = s.clampFireflies;
    a.length = b.historyLength[t.cur].data();
    return a;
}

/// Phase III of this frame, with phase I's decisions.
template <class Buffers>
FittedAccumulationOf<HistoryStorage<Buffers>>
fittedAccumulation(const BmfrPassContext& ctx, const InputPlanes& in, Buffers& b) {
    const BmfrSettings& s = ctx.settings;
    const TemporalHistory& t = ctx.history;
    FittedAccumulationOf<HistoryStorage<Buffers>> a;
    a.in = in;
    a.accumulate = t.hasHistory() && s.stages.secondAccumulation;
    a.remodulate = s.stages.demodulate || s.colorIsDemodulated;
    a.albedoEpsilon = s.albedoEpsilon, a.minAlpha = s.secondBlendAlpha, a.width = t.width;
    a.halfHistory = s.halfHistory;
    a.fitted = b.fitted.data(), a.prevAccumulated = b.accumulatedFitted[1 - t.cur].data();
    a.previousPixel = b.previousPixel.data(), a.accept = b.acceptMask.data();
    a.length = b.historyLength[t.cur].data(), a.accumulated = b.accumulatedFitted[t.cur].data();
    if (s.adaptiveHistory) a.changeTiles = b.changeTiles.data();
    return a;
}

} // namespace bmfr
