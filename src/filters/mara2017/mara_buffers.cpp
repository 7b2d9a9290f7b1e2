#include "core/view_basis.h"
#include "filters/mara2017/mara_passes.h"
#include <cmath>

namespace bmfr {

void MaraBuffers::allocate(int w, int h) {
    for (int k = 0; k < 2; ++k) {
        matteHistory[k].resize(w, h, 3), glossyHistory[k].resize(w, h, 3);
        position[k].resize(w, h, 3), normal[k].resize(w, h, 3), count[k].resize(w, h, 1);
        output[k].resize(w, h, 3);
    }
    for (ImageF* img : {&matte, &glossy, &expected, &temporal, &glossyTemporal, &median, &matteOut,
                        &glossyRow, &glossyOut, &composed, &ycocg})
        img->resize(w, h, 3);
    previousPixel.resize(w, h, 2);
    confidence.resize(w, h, 1), rowMin.resize(w, h, 1), radius.resize(w, h, 1);
    accept.resize(w, h, 1);
}

void MaraBuffers::reserveTables(const Mara2017Settings& s) {
    preSpiral.reserve(size_t(2 * s.preTaps * kMaraSpiralRotations));
    finalSpiral.reserve(size_t(2 * s.finalTaps * kMaraSpiralRotations));
    preOffsets.reserve(size_t(2 * s.preTaps * kMaraSpiralRotations));
    preGauss.reserve(size_t(s.preTaps * kMaraSpiralRotations));
}

void maraSpiralTable(int taps, float frameRotation, std::vector<float>& out) {
    out.resize(size_t(2 * taps * kMaraSpiralRotations));
    for (int r = 0; r < kMaraSpiralRotations; ++r)
        for (int k = 0; k < taps; ++k) {
            const float turn = frameRotation + 6.28318531f * float(r) / kMaraSpiralRotations;
            const Vec2 o = maraSpiralTap(k, taps, turn);
            out[size_t(2 * (r * taps + k))] = o.x, out[size_t(2 * (r * taps + k) + 1)] = o.y;
        }
}

void maraTapTable(const float* spiral, int count, float radius, float sigma,
                  std::vector<int>& offsets, std::vector<float>& gauss) {
    offsets.resize(2 * size_t(count)), gauss.resize(size_t(count));
    for (size_t k = 0; k < size_t(count); ++k) {
        const int dx = maraTapOffset(spiral[2 * k], radius),
                  dy = maraTapOffset(spiral[2 * k + 1], radius);
        offsets[2 * k] = dx, offsets[2 * k + 1] = dy;
        gauss[k] = maraGaussian(float(dx * dx + dy * dy), sigma);
    }
}

MaraFrame maraFrameSettings(const Mara2017Settings& s, int width) {
    MaraFrame f;
    f.h = s.hysteresis, f.d0 = s.confidenceNear, f.d1 = s.confidenceFar;
    f.cumulativeStart = s.cumulativeStart, f.clampRadius = s.clampRadius;
    f.clampHistory = s.clampHistory, f.virtualReprojection = s.virtualReprojection;
    f.normaliseConfidence = s.normaliseConfidence;
    f.edges = {s.normalWeight, s.planeWeight, s.planeNear * s.planeNear};
    f.preTaps = s.preTaps, f.finalTaps = s.finalTaps, f.rotationWidth = s.rotationWidth;
    f.preRadius = 0.5f * s.preDiameter * float(width);
    f.preSigma = s.preSigma * f.preRadius;
    f.maxRadius = int(std::lround(s.maxRadius * float(width)));
    f.lowConfidence = s.lowConfidence, f.radiusBoost = s.radiusBoost, f.finalSigma = s.finalSigma;
    f.glossyScale = s.glossySigmaScale, f.glossyExponent = s.glossySigmaExponent;
    f.glossyEpsilon = s.glossySigmaEpsilon, f.glossyTapSigmas = s.glossyTapSigmas;
    f.seed = s.seed;
    return f;
}

MaraFrame MaraBuffers::frame(const MaraPassContext& ctx) {
    const Mara2017Settings& s = ctx.settings;
    const TemporalHistory& hist = ctx.history;
    const int cur = hist.cur, prev = 1 - cur, w = hist.width;
    MaraFrame f = maraFrameSettings(s, w);
    f.in = ctx.input;
    f.modes = {s.colorIsDemodulated, true, s.albedoEpsilon};
    f.previous = hist.previous;
    f.eye = viewBasisOf(ctx.frame.viewProjection).eye;
    f.width = w, f.height = hist.height;
    f.factored = f.in.matteIndirect != nullptr;
    f.glossy = f.factored && f.in.glossyIndirect != nullptr;
    f.frame = uint32_t(hist.frameIndex);
    maraSpiralTable(s.preTaps, maraFrameRotation(f.frame, s.seed, 4), preSpiral);
    maraSpiralTable(s.finalTaps, maraFrameRotation(f.frame, s.seed, 7), finalSpiral);
    maraTapTable(preSpiral.data(), s.preTaps * kMaraSpiralRotations, f.preRadius, f.preSigma,
                 preOffsets, preGauss);
    f.preSpiral = preSpiral.data(), f.finalSpiral = finalSpiral.data();
    f.preOffsets = preOffsets.data(), f.preGauss = preGauss.data();
    f.prevMatte = matteHistory[prev].data(), f.prevGlossy = glossyHistory[prev].data();
    f.prevPosition = position[prev].data(), f.prevNormal = normal[prev].data();
    f.prevCount = count[prev].data();
    f.matteHistory = matteHistory[cur].data(), f.glossyHistory = glossyHistory[cur].data();
    f.position = position[cur].data(), f.normal = normal[cur].data(), f.count = count[cur].data();
    f.matte = matte.data(), f.glossySignal = glossy.data(), f.expected = expected.data();
    f.previousPixel = previousPixel.data(), f.temporal = temporal.data();
    f.confidence = confidence.data(), f.glossyTemporal = glossyTemporal.data();
    f.rowMin = rowMin.data(), f.radius = radius.data(), f.median = median.data();
    f.matteOut = matteOut.data(), f.glossyRow = glossyRow.data(), f.glossyOut = glossyOut.data();
    f.composed = composed.data(), f.accept = accept.data();
    return f;
}

TaaInputs MaraBuffers::taaInputs(const MaraPassContext& ctx) const {
    const TemporalHistory& h = ctx.history;
    return bmfr::taaInputs(composed.data(), output[1 - h.cur].data(), previousPixel.data(), h.width,
                           h.height, ctx.settings, accept.data());
}

void MaraBuffers::captureDebug(int cur) {
    widenToFloat(count[cur], countF);
    widenToFloat(accept, acceptF);
}

DebugBuffers MaraBuffers::debug(int) const {
    return {view(temporal), view(matteOut), view(countF), view(acceptF)};
}

} // namespace bmfr
