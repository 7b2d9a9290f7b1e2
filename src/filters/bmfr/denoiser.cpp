#include "core/hash.h"
#include "core/mat4.h"
#include "filters/bmfr/state.h"
#include "filters/frame_checks.h"
#include <bmfr/denoiser.h>
#include <bmfr/error.h>
#include <string>

namespace bmfr {

struct Denoiser::Impl {
    Settings settings;
    ThreadPool pool;
    BmfrTimeline timeline;
    std::unique_ptr<BmfrPasses> passes;
    FrameStats stats;
    bool debug = false;

    explicit Impl(const Settings& s)
        : settings(s), pool(s.threads),
          passes(s.implementation == Implementation::Reference ? makeReferencePasses()
                                                               : makeFastPasses()) {}

    void fillNoise();
};

void Denoiser::Impl::fillNoise() {
    const int W = settings.blockSize * settings.blockSize, M = int(settings.features.size());
    const float eps = settings.noiseAmplitude;
    const uint32_t frame = uint32_t(timeline.frameIndex);
    timeline.noise.resize(size_t(M) * W);
    for (int f = 0; f < M; ++f) {
        const bool constant = settings.features[f].source == FeatureSource::One;
        for (int k = 0; k < W; ++k) {
            float u = unitFloat(hashKeys(settings.seed, frame, uint32_t(f), uint32_t(k)));
            timeline.noise[size_t(f) * W + k] = constant ? 0.0f : eps * (2.0f * u - 1.0f);
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
    impl_->timeline.hasHistory = false;
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
    Impl& m = *impl_;
    checkFrameInput(frame, m.settings.features);
    BmfrTimeline& t = m.timeline;
    if (frame.color.width != t.width || frame.color.height != t.height) {
        t.width = frame.color.width, t.height = frame.color.height;
        t.hasHistory = false;
        t.cur = 0;
        m.passes->allocate(t.width, t.height, m.settings, m.pool.threadCount());
    }
    if (frame.reset) t.hasHistory = false;
    t.cur = 1 - t.cur;
    m.fillNoise();

    m.stats.times.clear();
    const BmfrPassContext ctx{m.settings, frame, t, m.pool};
    const InputCounters counters = m.passes->run(ctx, m.stats.times);
    if (m.debug) m.passes->captureDebug(t);
    m.stats.nonFiniteInputs = counters.nonFinite;
    m.stats.discardedPixels = counters.discarded;
    t.hasHistory = true;
    t.previousViewProjection = frame.viewProjection;
    t.previousJitter[0] = frame.jitter[0];
    t.previousJitter[1] = frame.jitter[1];
    ++t.frameIndex;
    return m.passes->output(t.cur);
}

DebugBuffers Denoiser::debug() const {
    if (!impl_->debug || impl_->timeline.width == 0) return {};
    return impl_->passes->debug(impl_->timeline);
}

} // namespace bmfr
