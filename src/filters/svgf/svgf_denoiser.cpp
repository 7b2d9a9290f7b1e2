#include "backend/cpu/svgf_passes.h"
#include "backend/cpu/taa.h"
#include "core/mat4.h"
#include "filters/frame_checks.h"
#include "filters/pixel_input.h"
#include <bmfr/error.h>
#include <bmfr/svgf.h>
#include <chrono>
#include <string>

namespace bmfr {

void validate(const SvgfSettings& s) {
    auto check = [](const char* name, double v, double lo, double hi, bool loOpen) {
        if (!std::isfinite(v) || (loOpen ? v <= lo : v < lo) || v > hi)
            throw Error(std::string("SVGF setting ") + name + " = " + std::to_string(v) +
                        " is out of range");
    };
    check("colorAlpha", s.colorAlpha, 0, 1, true);
    check("momentsAlpha", s.momentsAlpha, 0, 1, true);
    check("iterations", s.iterations, 1, 8, false);
    check("kernelRadius", s.kernelRadius, 1, 2, false);
    check("phiDepth", s.phiDepth, 0, 1e6, true);
    check("phiNormal", s.phiNormal, 1, 1024, false);
    check("phiLuminance", s.phiLuminance, 0, 1e6, true);
    check("spatialVarianceFrames", s.spatialVarianceFrames, 0, 255, false);
    validate(static_cast<const TemporalSettings&>(s), "SVGF setting");
}

void SvgfState::allocate(int w, int h) {
    width = w, height = h, cur = 0, hasHistory = false;
    for (int k = 0; k < 2; ++k) {
        normal[k].resize(w, h, 3), position[k].resize(w, h, 3), color[k].resize(w, h, 3);
        moments[k].resize(w, h, 2), historyLength[k].resize(w, h, 1), output[k].resize(w, h, 3, 4);
        filtered[k].resize(w, h, 4);
    }
    integrated.resize(w, h, 3), integratedMoments.resize(w, h, 2), depth.resize(w, h, 1);
    depthGradient.resize(w, h, 2), variance.resize(w, h, 1), previousPixel.resize(w, h, 2);
    accept.resize(w, h, 1), remodulated.resize(w, h, 3),
        taaRecords.resize(int(cpu::taaScratchFloats(w, h)), 1, 1);
}

struct SvgfDenoiser::Impl {
    SvgfSettings settings;
    ThreadPool pool;
    SvgfState state;
    FrameStats stats;
    explicit Impl(const SvgfSettings& s) : settings(s), pool(s.threads) {}
};

SvgfDenoiser::SvgfDenoiser(const SvgfSettings& s) {
    validate(s);
    impl_ = std::make_unique<Impl>(s);
}
SvgfDenoiser::~SvgfDenoiser() = default;
void SvgfDenoiser::reset() {
    impl_->state.hasHistory = false;
}
const FrameStats& SvgfDenoiser::lastStats() const {
    return impl_->stats;
}
ImageView SvgfDenoiser::variance() const {
    return view(impl_->state.variance);
}

ImageView SvgfDenoiser::denoise(const FrameInput& frame) {
    using Clock = std::chrono::steady_clock;
    auto ms = [](Clock::time_point a, Clock::time_point b) {
        return std::chrono::duration<double, std::milli>(b - a).count();
    };
    Impl& m = *impl_;
    checkFrameInput(frame, {});
    SvgfState& st = m.state;
    if (frame.color.width != st.width || frame.color.height != st.height)
        st.allocate(frame.color.width, frame.color.height);
    if (frame.reset) st.hasHistory = false;
    st.cur = 1 - st.cur;
    const SvgfPassContext ctx{m.settings, frame, st, m.pool};

    auto t0 = Clock::now();
    m.stats.nonFiniteInputs = cpu::svgfAccumulate(ctx);
    auto t1 = Clock::now();
    cpu::svgfEstimateVariance(ctx);
    auto t2 = Clock::now();
    const int levels = m.settings.iterations;
    int src = 0;
    for (int k = 0; k < levels; ++k) {
        const int level = m.settings.reverseLevels ? levels - 1 - k : k;
        cpu::svgfAtrous(m.pool, m.settings, st.filtered[src], st.filtered[1 - src],
                        st.normal[st.cur], st.depth, st.depthGradient, st.historyLength[st.cur],
                        1 << level);
        src = 1 - src;
        if (level == 0) // the step-1 level becomes the next frame's colour history
            for (long i = 0; i < st.integrated.pixelCount(); ++i)
                store3(st.color[st.cur].data(), i, load3Stride4(st.filtered[src].data(), i));
    }
    const bool remodulate = true;
    for (long i = 0; i < st.integrated.pixelCount(); ++i) {
        Vec3 c = load3Stride4(st.filtered[src].data(), i);
        if (remodulate) c = c * guardAlbedo(load3(frame.albedo.data, i), m.settings.albedoEpsilon);
        if (frame.emission.data) {
            Vec3 e = load3(frame.emission.data, i);
            if (std::isfinite(e.x) && std::isfinite(e.y) && std::isfinite(e.z)) c = c + e;
        }
        store3(st.remodulated.data(), i, c);
    }
    auto t3 = Clock::now();
    cpu::temporalAntiAliasing(m.pool, st.remodulated.data(), st.output[1 - st.cur].data(),
                              st.previousPixel.data(), st.taaRecords.data(),
                              st.output[st.cur].data(), st.width, st.height,
                              m.settings.taaBlendAlpha, m.settings.taa && st.hasHistory);
    auto t4 = Clock::now();
    m.stats.times.clear();
    m.stats.times.add("accumulate", ms(t0, t1));
    m.stats.times.add("variance", ms(t1, t2));
    m.stats.times.add("atrous", ms(t2, t3));
    m.stats.times.add("taa", ms(t3, t4));
    st.hasHistory = true;
    st.previousViewProjection = frame.viewProjection;
    st.previousJitter[0] = frame.jitter[0], st.previousJitter[1] = frame.jitter[1];
    return view(st.output[st.cur]);
}

} // namespace bmfr
