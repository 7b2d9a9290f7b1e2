#include "backend/backend_registry.h"
#include "filters/filter_entry.h"
#include "filters/mara2017/mara_passes.h"
#include "filters/mara2017/mara_settings_table.h"
#include <bmfr/error.h>

namespace bmfr {

struct __attribute__((visibility("hidden"))) Mara2017Denoiser::Impl
    : FilterCore<Mara2017Settings, MaraPasses> {
    explicit Impl(const Mara2017Settings& s) : FilterCore(s, makeMaraPasses(s.backend)) {}
};

Mara2017Denoiser::Mara2017Denoiser(const Mara2017Settings& s) {
    validate(s);
    impl_ = std::make_unique<Impl>(s);
}
Mara2017Denoiser::~Mara2017Denoiser() = default;
void Mara2017Denoiser::reset() {
    impl_->history.reset();
}
void Mara2017Denoiser::setDebugOutputs(bool enabled) {
    impl_->debug = enabled;
}
const FrameStats& Mara2017Denoiser::lastStats() const {
    return impl_->stats;
}
DebugBuffers Mara2017Denoiser::debug() const {
    return impl_->debugBuffers();
}

ImageView Mara2017Denoiser::denoise(const FrameInput& frame) {
    if (frame.glossyIndirect.data && !frame.matteIndirect.data)
        throw Error("input buffer 'glossyIndirect' is given without 'matteIndirect': Mara 2017's "
                    "factorisation needs both (bmfr render --paths mara writes them)");
    return impl_->passes->output(impl_->runFrame(frame));
}

FilterEntry mara2017FilterEntry() {
    return tableFilterEntry<Mara2017Denoiser>("mara2017", "Mara et al. 2017",
                                              mara2017SettingsTable);
}

} // namespace bmfr
