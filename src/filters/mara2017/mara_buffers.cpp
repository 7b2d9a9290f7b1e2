#include "core/view_basis.h"
#include "filters/mara2017/mara_passes.h"
#include <cmath>

namespace bmfr {

void MaraTables::reserve(const Mara2017Settings& s) {
    preSpiral.reserve(size_t(2 * s.preTaps * kMaraSpiralRotations));
    finalSpiral.reserve(size_t(2 * s.finalTaps * kMaraSpiralRotations));
    preOffsets.reserve(size_t(2 * s.preTaps * kMaraSpiralRotations));
    preGauss.reserve(size_t(s.preTaps * kMaraSpiralRotations));
}

void MaraTables::build(const Mara2017Settings& s, MaraFrame& f) {
    maraSpiralTable(s.preTaps, maraFrameRotation(f.frame, s.seed, 4), preSpiral);
    maraSpiralTable(s.finalTaps, maraFrameRotation(f.frame, s.seed, 7), finalSpiral);
    maraTapTable(preSpiral.data(), s.preTaps * kMaraSpiralRotations, f.preRadius, f.preSigma,
                 preOffsets, preGauss);
    f.preSpiral = preSpiral.data(), f.finalSpiral = finalSpiral.data();
    f.preOffsets = preOffsets.data(), f.preGauss = preGauss.data();
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

} // namespace bmfr
