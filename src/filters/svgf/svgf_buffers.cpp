#include "filters/svgf/svgf_passes.h"

namespace bmfr {

void SvgfBuffers::allocate(int w, int h) {
    for (int k = 0; k < 2; ++k) {
        normal[k].resize(w, h, 3), position[k].resize(w, h, 3), color[k].resize(w, h, 3);
        moments[k].resize(w, h, 2), historyLength[k].resize(w, h, 1), output[k].resize(w, h, 3, 24);
        filtered[k].resize(w, h, 4);
    }
    integrated.resize(w, h, 3), integratedMoments.resize(w, h, 2), depth.resize(w, h, 1);
    depthGradient.resize(w, h, 2), variance.resize(w, h, 1), previousPixel.resize(w, h, 2);
    accept.resize(w, h, 1), remodulated.resize(w, h, 3);
}

SvgfFrame SvgfBuffers::frame(const SvgfPassContext& ctx) {
    const SvgfSettings& s = ctx.settings;
    const int cur = ctx.history.cur, prev = 1 - cur;
    SvgfFrame f;
    f.in = ctx.input;
    f.modes = {s.colorIsDemodulated, true, s.albedoEpsilon};
    f.previous = ctx.history.previous;
    f.viewProjection = ctx.frame.viewProjection;
    f.limits = {s.positionLimitSquared, s.normalLimitSquared};
    f.colorAlpha = s.colorAlpha, f.momentsAlpha = s.momentsAlpha;
    f.width = ctx.history.width, f.height = ctx.history.height;
    f.prevNormal = normal[prev].data(), f.prevPosition = position[prev].data();
    f.prevColor = color[prev].data(), f.prevMoments = moments[prev].data();
    f.prevLength = historyLength[prev].data();
    f.normal = normal[cur].data(), f.position = position[cur].data();
    f.color = color[cur].data(), f.moments = moments[cur].data();
    f.length = historyLength[cur].data();
    f.integrated = integrated.data(), f.integratedMoments = integratedMoments.data();
    f.depth = depth.data(), f.depthGradient = depthGradient.data();
    f.previousPixel = previousPixel.data(), f.accept = accept.data();
    return f;
}

void SvgfBuffers::captureDebug(int cur) {
    const ImageF& last = filtered[outputLevel];
    if (historyLengthF.width != last.width || historyLengthF.height != last.height) {
        historyLengthF.resize(last.width, last.height, 1);
        acceptF.resize(last.width, last.height, 1);
        finalLevel.resize(last.width, last.height, 3);
    }
    for (long i = 0; i < last.pixelCount(); ++i) {
        historyLengthF.data()[i] = historyLength[cur].data()[i];
        acceptF.data()[i] = accept.data()[i];
        store3(finalLevel.data(), i, load3Stride4(last.data(), i));
    }
}

DebugBuffers SvgfBuffers::debug(int) const {
    return {view(integrated), view(finalLevel), view(historyLengthF), view(acceptF)};
}

} // namespace bmfr
