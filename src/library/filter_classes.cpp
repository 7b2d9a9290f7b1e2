// The public filter classes' constructors and extras: each filter's frame loop over the passes
// of its device's backend, on the device's threads.
#include "backend/backend_registry.h"
#include "filters/bmfr/bmfr_hooks.h"
#include "filters/mara2017/mara_hooks.h"
#include "filters/walr/walr_hooks.h"
#include "library/device_state.h"
#include <bmfr/error.h>

namespace bmfr {

namespace {

template <class S, class Hooks = FilterHooks<S>>
std::unique_ptr<FrameLoop> frameLoop(const char* name, const S& settings, const Device& device) {
    validate(settings);
    const Device::State& d = DeviceAccess::state(device);
    if (settings.backend != d.backend)
        throw Error(std::string("the ") + name + " settings say backend " +
                    backendName(settings.backend) + ", the device is " + backendName(d.backend));
    auto core = std::make_unique<FilterCore<S, Hooks>>(
        name, settings, makePasses<S>(settings.backend, d.cudaDevice), d.pool);
    if (d.reservedWidth > 0) core->reserve(d.reservedWidth, d.reservedHeight);
    return core;
}

/// The device of a filter made without one: its own threads. Its settings are checked first, so
/// that a setting out of range is reported as such.
template <class S> Device ownDevice(const S& settings) {
    validate(settings);
    return Device(settings.backend, settings.threads);
}

template <class S, class Hooks = FilterHooks<S>> const auto& core(const FrameLoop& loop) {
    return static_cast<const FilterCore<S, Hooks>&>(loop);
}

} // namespace

BmfrDenoiser::BmfrDenoiser(const BmfrSettings& s) : BmfrDenoiser(s, ownDevice(s)) {}
BmfrDenoiser::BmfrDenoiser(const BmfrSettings& s, const Device& device)
    : TemporalFilter(frameLoop<BmfrSettings, BmfrHooks>("bmfr", s, device)) {}
const BmfrSettings& BmfrDenoiser::settings() const {
    return core<BmfrSettings, BmfrHooks>(loop()).settings;
}

SvgfDenoiser::SvgfDenoiser(const SvgfSettings& s) : SvgfDenoiser(s, ownDevice(s)) {}
SvgfDenoiser::SvgfDenoiser(const SvgfSettings& s, const Device& device)
    : TemporalFilter(frameLoop("svgf", s, device)) {}
ImageView SvgfDenoiser::variance() const {
    return core<SvgfSettings>(loop()).passes->variance();
}

WalrDenoiser::WalrDenoiser(const WalrSettings& s) : WalrDenoiser(s, ownDevice(s)) {}
WalrDenoiser::WalrDenoiser(const WalrSettings& s, const Device& device)
    : TemporalFilter(frameLoop<WalrSettings, WalrHooks>("walr", s, device)) {}

Mara2017Denoiser::Mara2017Denoiser(const Mara2017Settings& s) : Mara2017Denoiser(s, ownDevice(s)) {}
Mara2017Denoiser::Mara2017Denoiser(const Mara2017Settings& s, const Device& device)
    : TemporalFilter(frameLoop<Mara2017Settings, MaraHooks>("mara2017", s, device)) {}

} // namespace bmfr
