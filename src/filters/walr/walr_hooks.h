// WALR's own step in the shared frame loop: signal=diffuse-indirect needs its buffer.
#pragma once
#include "filters/filter_core.h"
#include <bmfr/filters/walr_filter.h>

namespace bmfr {

struct WalrHooks : FilterHooks<WalrSettings> {
    void check(const WalrSettings& s, const FrameInput& frame) const {
        if (s.signal == WalrSignal::DiffuseIndirect && !frame.diffuseIndirect.data)
            throw Error("input buffer 'diffuseIndirect' is missing: WALR's signal=diffuse-indirect "
                        "filters the demodulated diffuse indirect light (bmfr render writes it as "
                        "diffuse_indirect)");
    }
};

} // namespace bmfr
