#include "backend/backend_registry.h"
#include "filters/filter_entry.h"
#include "filters/svgf/svgf_passes.h"
#include "filters/svgf/svgf_settings_table.h"
#include "temporal/frame_checks.h"
#include "temporal/input_staging.h"
#include <bmfr/error.h>

namespace bmfr {

struct __attribute__((visibility("hidden"))) SvgfDenoiser::Impl {
    SvgfSettings settings;
    std::unique_ptr<SvgfPasses> passes;
    ThreadPool pool;
    TemporalHistory history;
    InputStaging staging;
    FrameStats stats;
    bool debug = false;
    explicit Impl(const SvgfSettings& s)
        : settings(s), passes(makeSvgfPasses(s.backend)), pool(s.threads) {}
};

SvgfDenoiser::SvgfDenoiser(const SvgfSettings& s) {
    validate(s);
    impl_ = std::make_unique<Impl>(s);
}
SvgfDenoiser::~SvgfDenoiser() = default;
void SvgfDenoiser::reset() {
    impl_->history.reset();
}
void SvgfDenoiser::setDebugOutputs(bool enabled) {
    impl_->debug = enabled;
}
const FrameStats& SvgfDenoiser::lastStats() const {
    return impl_->stats;
}
ImageView SvgfDenoiser::variance() const {
    return impl_->passes->variance();
}
DebugBuffers SvgfDenoiser::debug() const {
    if (!impl_->debug || impl_->history.width == 0) return {};
    return impl_->passes->debug(impl_->history.cur);
}

ImageView SvgfDenoiser::denoise(const FrameInput& frame) {
    Impl& m = *impl_;
    checkFrameInput(frame, 0);
    TemporalHistory& h = m.history;
    if (h.begin(frame)) m.passes->allocate(h.width, h.height);
    const SvgfPassContext ctx{m.settings, m.staging.stage(frame), frame, h, m.pool};
    m.stats.times.clear();
    m.stats.nonFiniteInputs = m.passes->run(ctx, m.stats.times);
    if (m.debug) m.passes->captureDebug(h.cur);
    const int slot = h.cur;
    h.end(frame);
    return m.passes->output(slot);
}

FilterEntry svgfFilterEntry() {
    return tableFilterEntry<SvgfDenoiser>("svgf", "SVGF (Schied et al. 2017)", svgfSettingsTable);
}

} // namespace bmfr
