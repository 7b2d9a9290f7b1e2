#include "backend/backend_registry.h"
#include "filters/filter_entry.h"
#include "filters/walr/walr_passes.h"
#include "filters/walr/walr_settings_table.h"
#include <bmfr/error.h>

namespace bmfr {

struct __attribute__((visibility("hidden"))) WalrDenoiser::Impl
    : FilterCore<WalrSettings, WalrPasses> {
    explicit Impl(const WalrSettings& s) : FilterCore(s, makeWalrPasses(s.backend)) {}
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
    return impl_->debugBuffers();
}

ImageView WalrDenoiser::denoise(const FrameInput& frame) {
    if (impl_->settings.signal == WalrSignal::DiffuseIndirect && !frame.diffuseIndirect.data)
        throw Error("input buffer 'diffuseIndirect' is missing: WALR's signal=diffuse-indirect "
                    "filters the demodulated diffuse indirect light (bmfr render writes it as "
                    "diffuse_indirect)");
    impl_->runFrame(frame);
    return impl_->passes->output();
}

FilterEntry walrFilterEntry() {
    return tableFilterEntry<WalrDenoiser>("walr", "WALR (Meunier and Harada 2022)",
                                          walrSettingsTable);
}

} // namespace bmfr
