#include "backend/backend_registry.h"
#include "filters/filter_entry.h"
#include "filters/walr/walr_passes.h"
#include "filters/walr/walr_settings_table.h"
#include "temporal/frame_checks.h"
#include "temporal/input_staging.h"
#include <bmfr/error.h>

namespace bmfr {

struct __attribute__((visibility("hidden"))) WalrDenoiser::Impl {
    WalrSettings settings;
    std::unique_ptr<WalrPasses> passes;
    ThreadPool pool;
    TemporalHistory history;
    InputStaging staging;
    FrameStats stats;
    bool debug = false;
    explicit Impl(const WalrSettings& s)
        : settings(s), passes(makeWalrPasses(s.backend)), pool(s.threads) {}
};

WalrDenoiser::WalrDenoiser(const WalrSettings& s) {
    validate(s);
    impl_ = std::make_unique<Impl>(s);
}
WalrDenoiser::~WalrDenoiser() = default;
void WalrDenoiser::reset() {
    impl_->history.reset();
}
void WalrDenoiser::setDebugOutputs(bool enabled) {
    impl_->debug = enabled;
}
const FrameStats& WalrDenoiser::lastStats() const {
    return impl_->stats;
}
DebugBuffers WalrDenoiser::debug() const {
    if (!impl_->debug || impl_->history.width == 0) return {};
    return impl_->passes->debug(impl_->history.cur);
}

ImageView WalrDenoiser::denoise(const FrameInput& frame) {
    Impl& m = *impl_;
    checkFrameInput(frame, 0);
    if (m.settings.signal == WalrSignal::DiffuseIndirect && !frame.diffuseIndirect.data)
        throw Error("input buffer 'diffuseIndirect' is missing: WALR's signal=diffuse-indirect "
                    "filters the demodulated diffuse indirect light (bmfr render writes it as "
                    "diffuse_indirect)");
    TemporalHistory& h = m.history;
    if (h.begin(frame)) m.passes->allocate(h.width, h.height);
    const WalrPassContext ctx{m.settings, m.staging.stage(frame), frame, h, m.pool};
    m.stats.times.clear();
    m.stats.nonFiniteInputs = m.passes->run(ctx, m.stats.times);
    if (m.debug) m.passes->captureDebug(h.cur);
    h.end(frame);
    return m.passes->output();
}

FilterEntry walrFilterEntry() {
    return tableFilterEntry<WalrDenoiser>("walr", "WALR (Meunier and Harada 2022)",
                                          walrSettingsTable);
}

} // namespace bmfr
