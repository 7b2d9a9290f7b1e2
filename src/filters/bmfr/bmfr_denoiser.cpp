#include "backend/backend_registry.h"
#include "core/settings_table.h"
#include "filters/bmfr/bmfr_passes.h"
#include "filters/bmfr/bmfr_settings_table.h"
#include "filters/bmfr/regularisation_noise.h"
#include "filters/filter_entry.h"
#include "temporal/frame_checks.h"
#include "temporal/input_staging.h"
#include <bmfr/error.h>

namespace bmfr {

struct __attribute__((visibility("hidden"))) BmfrDenoiser::Impl {
    BmfrSettings settings;
    std::unique_ptr<BmfrPasses> passes;
    ThreadPool pool;
    BmfrTimeline timeline;
    InputStaging staging;
    FrameStats stats;
    bool debug = false;

    explicit Impl(const BmfrSettings& s)
        : settings(s), passes(makeBmfrPasses(s.backend)), pool(s.threads) {}

    void fillNoise();
    int extrasNeeded() const {
        int n = 0;
        for (const Feature& f : settings.features)
            if (f.source == FeatureSource::Extra && f.extraIndex + 1 > n) n = f.extraIndex + 1;
        return n;
    }
};

void BmfrDenoiser::Impl::fillNoise() {
    const int W = settings.blockSize * settings.blockSize, M = int(settings.features.size());
    const float eps = settings.noiseAmplitude;
    const uint32_t frame = uint32_t(timeline.history.frameIndex);
    timeline.noise.resize(size_t(M) * W);
    for (int f = 0; f < M; ++f) {
        const bool constant = settings.features[size_t(f)].source == FeatureSource::One;
        for (int k = 0; k < W; ++k)
            timeline.noise[size_t(f) * W + k] =
                regularisationNoise(settings.seed, frame, f, k, eps, constant);
    }
}

BmfrDenoiser::BmfrDenoiser(const BmfrSettings& settings) {
    validate(settings);
    impl_ = std::make_unique<Impl>(settings);
}
BmfrDenoiser::~BmfrDenoiser() = default;
BmfrDenoiser::BmfrDenoiser(BmfrDenoiser&&) noexcept = default;
BmfrDenoiser& BmfrDenoiser::operator=(BmfrDenoiser&&) noexcept = default;

void BmfrDenoiser::reset() {
    impl_->timeline.history.reset();
}
void BmfrDenoiser::setDebugOutputs(bool enabled) {
    impl_->debug = enabled;
}
const FrameStats& BmfrDenoiser::lastStats() const {
    return impl_->stats;
}
const BmfrSettings& BmfrDenoiser::settings() const {
    return impl_->settings;
}

ImageView BmfrDenoiser::denoise(const FrameInput& frame) {
    Impl& m = *impl_;
    checkFrameInput(frame, m.extrasNeeded(), m.settings.backend);
    TemporalHistory& h = m.timeline.history;
    if (h.begin(frame)) m.passes->allocate(h.width, h.height, m.settings, m.pool.threadCount());
    if (m.passes->needsHostNoise()) m.fillNoise();

    m.stats.times.clear();
    const bool backendStages = m.settings.backend == Backend::Cuda;
    const BmfrPassContext ctx{m.settings, m.staging.stage(frame, backendStages), frame, m.timeline,
                              m.pool};
    const InputCounters counters = m.passes->run(ctx, m.stats.times);
    if (m.debug) m.passes->captureDebug(m.timeline);
    m.stats.nonFiniteInputs = counters.nonFinite;
    m.stats.discardedPixels = counters.discarded;
    const int slot = h.cur;
    h.end(frame);
    return m.passes->output(slot);
}

DebugBuffers BmfrDenoiser::debug() const {
    if (!impl_->debug || impl_->timeline.history.width == 0) return {};
    return impl_->passes->debug(impl_->timeline);
}

FilterEntry bmfrFilterEntry() {
    return tableFilterEntry<BmfrDenoiser>("bmfr", "BMFR (Koskela et al. 2019)", bmfrSettingsTable);
}

} // namespace bmfr
