// The public filter classes' constructors and extras: each filter's frame loop over the passes
// of the backend its settings name.
#include "backend/backend_registry.h"
#include "filters/bmfr/bmfr_hooks.h"
#include "filters/mara2017/mara_hooks.h"
#include "filters/walr/walr_hooks.h"

namespace bmfr {

namespace {

template <class S, class Hooks = FilterHooks<S>>
std::unique_ptr<FrameLoop> frameLoop(const char* name, const S& settings) {
    validate(settings);
    return std::make_unique<FilterCore<S, Hooks>>(name, settings,
                                                  makePasses<S>(settings.backend, name));
}

template <class S, class Hooks = FilterHooks<S>> const auto& core(const FrameLoop& loop) {
    return static_cast<const FilterCore<S, Hooks>&>(loop);
}

} // namespace

BmfrDenoiser::BmfrDenoiser(const BmfrSettings& s)
    : TemporalFilter(frameLoop<BmfrSettings, BmfrHooks>("bmfr", s)) {}
const BmfrSettings& BmfrDenoiser::settings() const {
    return core<BmfrSettings, BmfrHooks>(loop()).settings;
}

SvgfDenoiser::SvgfDenoiser(const SvgfSettings& s) : TemporalFilter(frameLoop("svgf", s)) {}
ImageView SvgfDenoiser::variance() const {
    return core<SvgfSettings>(loop()).passes->variance();
}

WalrDenoiser::WalrDenoiser(const WalrSettings& s)
    : TemporalFilter(frameLoop<WalrSettings, WalrHooks>("walr", s)) {}

Mara2017Denoiser::Mara2017Denoiser(const Mara2017Settings& s)
    : TemporalFilter(frameLoop<Mara2017Settings, MaraHooks>("mara2017", s)) {}

} // namespace bmfr
