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
    BmfrSettings settings; ///< as given
    /// What the passes run with: `settings`, plus the visibility column when the frames give
    /// one (visibilityFeature). It is staged as the extra after the frame's own.
    BmfrSettings active;
    int visibilityExtra = -2; ///< the visibility column's extra index; -1 none; -2 no frame yet
    std::unique_ptr<BmfrPasses> passes;
    ThreadPool pool;
    BmfrTimeline timeline;
    InputStaging staging;
    FrameStats stats;
    bool debug = false;

    explicit Impl(const BmfrSettings& s)
        : settings(s), active(s), passes(makeBmfrPasses(s.backend)), pool(s.threads) {}

    void fillNoise();
    bool selectFeatures(const FrameInput& frame);
    int extrasNeeded() const {
        int n = 0;
        for (const Feature& f : settings.features)
            if (f.source == FeatureSource::Extra && f.extraIndex + 1 > n) n = f.extraIndex + 1;
        return n;
    }
};

void BmfrDenoiser::Impl::fillNoise() {
    const int W = active.blockSize * active.blockSize, M = int(active.features.size());
    const float eps = active.noiseAmplitude;
    const uint32_t frame = uint32_t(timeline.history.frameIndex);
    timeline.noise.resize(size_t(M) * W);
    for (int f = 0; f < M; ++f) {
        const bool constant = active.features[size_t(f)].source == FeatureSource::One;
        for (int k = 0; k < W; ++k)
            timeline.noise[size_t(f) * W + k] =
                regularisationNoise(active.seed, frame, f, k, eps, constant);
    }
}

/// Sets `active` for this frame; true when its feature columns changed (the passes must be
/// allocated again). Within a history the visibility must come with every frame or none.
bool BmfrDenoiser::Impl::selectFeatures(const FrameInput& frame) {
    const bool reads = settings.visibilityFeature || settings.visibilityTaps;
    const int extra = reads && frame.visibility.data ? int(frame.extras.size()) : -1;
    if (extra == visibilityExtra) return false;
    if (visibilityExtra != -2 && timeline.history.hasHistory() && !frame.reset)
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
    return true;
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
    const bool newColumns = m.selectFeatures(frame);
    TemporalHistory& h = m.timeline.history;
    if (h.begin(frame) || newColumns)
        m.passes->allocate(h.width, h.height, m.active, m.pool.threadCount());
    if (m.passes->needsHostNoise()) m.fillNoise();

    m.stats.times.clear();
    const bool backendStages = m.settings.backend == Backend::Cuda;
    const BmfrPassContext ctx{m.active, m.staging.stage(frame, backendStages), frame, m.timeline,
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
