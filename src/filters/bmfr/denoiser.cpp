#include "backend/cpu/bmfr_passes.h"
#include "core/hash.h"
#include "core/mat4.h"
#include "filters/bmfr/state.h"
#include "filters/frame_checks.h"
#include <bmfr/denoiser.h>
#include <bmfr/error.h>
#include <chrono>
#include <string>

namespace bmfr {

void BmfrState::allocate(int w, int h, const Settings& s, int threads) {
    width = w, height = h;
    for (int k = 0; k < 2; ++k) {
        normal[k].resize(w, h, 3);
        position[k].resize(w, h, 3);
        accumulatedNoisy[k].resize(w, h, 3);
        historyLength[k].resize(w, h, 1);
        accumulatedFitted[k].resize(w, h, 3);
        output[k].resize(w, h, 3);
    }
    previousPixel.resize(w, h, 2);
    acceptMask.resize(w, h, 1);
    fitted.resize(w, h, 3);
    remodulated.resize(w, h, 3);
    ycocg.resize(w, h, 3);
    historyLengthF.resize(w, h, 1);
    acceptMaskF.resize(w, h, 1);
    const int W = s.blockSize * s.blockSize, M = int(s.features.size());
    noise.assign(size_t(M) * W, 0.0f);
    scratch.resize(threads);
    for (FitScratch& sc : scratch) {
        sc.clean.assign(size_t(M) * W, 0.0f);
        sc.work.assign(size_t(M + 3) * W, 0.0f);
        sc.sum.assign(size_t(3) * W, 0.0f);
        sc.soa.assign(size_t(6 + 16) * W, 0.0f);
        sc.imageIndex.assign(W, -1);
    }
    hasHistory = false;
    cur = 0;
}

struct Denoiser::Impl {
    Settings settings;
    ThreadPool pool;
    BmfrState state;
    FrameStats stats;
    bool debug = false;

    explicit Impl(const Settings& s) : settings(s), pool(s.threads) {}

    void fillNoise();
};

void Denoiser::Impl::fillNoise() {
    const int W = settings.blockSize * settings.blockSize, M = int(settings.features.size());
    const float eps = settings.noiseAmplitude;
    const uint32_t frame = uint32_t(state.frameIndex);
    for (int f = 0; f < M; ++f) {
        const bool constant = settings.features[f].source == FeatureSource::One;
        for (int k = 0; k < W; ++k) {
            float u = unitFloat(hashKeys(settings.seed, frame, uint32_t(f), uint32_t(k)));
            state.noise[size_t(f) * W + k] = constant ? 0.0f : eps * (2.0f * u - 1.0f);
        }
    }
}

Denoiser::Denoiser(const Settings& settings) {
    validate(settings);
    impl_ = std::make_unique<Impl>(settings);
}
Denoiser::~Denoiser() = default;
Denoiser::Denoiser(Denoiser&&) noexcept = default;
Denoiser& Denoiser::operator=(Denoiser&&) noexcept = default;

void Denoiser::reset() {
    impl_->state.hasHistory = false;
}
void Denoiser::setDebugOutputs(bool enabled) {
    impl_->debug = enabled;
}
const FrameStats& Denoiser::lastStats() const {
    return impl_->stats;
}
const Settings& Denoiser::settings() const {
    return impl_->settings;
}

ImageView Denoiser::denoise(const FrameInput& frame) {
    using Clock = std::chrono::steady_clock;
    auto ms = [](Clock::time_point a, Clock::time_point b) {
        return std::chrono::duration<double, std::milli>(b - a).count();
    };
    Impl& m = *impl_;
    checkFrameInput(frame, m.settings.features);
    BmfrState& st = m.state;
    if (frame.color.width != st.width || frame.color.height != st.height)
        st.allocate(frame.color.width, frame.color.height, m.settings, m.pool.threadCount());
    if (frame.reset) st.hasHistory = false;
    st.cur = 1 - st.cur;

    const BmfrPassContext ctx{m.settings, frame, st, m.pool};
    auto t0 = Clock::now();
    cpu::InputCounters counters = cpu::accumulateNoisy(ctx);
    auto t1 = Clock::now();
    m.fillNoise();
    cpu::fitBlocks(ctx);
    auto t2 = Clock::now();
    cpu::accumulateFitted(ctx);
    auto t3 = Clock::now();
    cpu::temporalAntiAliasing(m.pool, st.remodulated.data(), st.output[1 - st.cur].data(),
                              st.previousPixel.data(), st.ycocg.data(), st.output[st.cur].data(),
                              st.width, st.height, m.settings.taaBlendAlpha,
                              m.settings.stages.taa && st.hasHistory);
    auto t4 = Clock::now();

    if (m.debug) {
        for (long i = 0; i < st.historyLengthF.pixelCount(); ++i) {
            st.historyLengthF.data()[i] = st.historyLength[st.cur].data()[i];
            st.acceptMaskF.data()[i] = st.acceptMask.data()[i];
        }
    }
    m.stats.times.clear();
    m.stats.times.add("accumulate", ms(t0, t1));
    m.stats.times.add("fit", ms(t1, t2));
    m.stats.times.add("accumulate_fitted", ms(t2, t3));
    m.stats.times.add("taa", ms(t3, t4));
    m.stats.nonFiniteInputs = counters.nonFinite;
    m.stats.discardedPixels = counters.discarded;
    st.hasHistory = true;
    st.previousViewProjection = frame.viewProjection;
    st.previousJitter[0] = frame.jitter[0];
    st.previousJitter[1] = frame.jitter[1];
    ++st.frameIndex;
    return view(st.output[st.cur]);
}

DebugBuffers Denoiser::debug() const {
    const BmfrState& st = impl_->state;
    if (!impl_->debug || st.width == 0) return {};
    return {view(st.accumulatedNoisy[st.cur]), view(st.fitted), view(st.historyLengthF),
            view(st.acceptMaskF)};
}

} // namespace bmfr
