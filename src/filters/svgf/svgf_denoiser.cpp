#include "backend/backend_registry.h"
#include "filters/filter_entry.h"
#include "filters/svgf/svgf_passes.h"
#include "filters/svgf/svgf_settings_table.h"
#include <bmfr/error.h>

namespace bmfr {

struct __attribute__((visibility("hidden"))) SvgfDenoiser::Impl
    : FilterCore<SvgfSettings, SvgfPasses> {
    explicit Impl(const SvgfSettings& s) : FilterCore(s, makeSvgfPasses(s.backend)) {}
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
    return impl_->debugBuffers();
}

ImageView SvgfDenoiser::denoise(const FrameInput& frame) {
    return impl_->passes->output(impl_->runFrame(frame));
}

FilterEntry svgfFilterEntry() {
    return tableFilterEntry<SvgfDenoiser>("svgf", "SVGF (Schied et al. 2017)", svgfSettingsTable);
}

} // namespace bmfr
