// Mara 2017's own step in the shared frame loop: its factorisation needs both indirect paths.
#pragma once
#include "filters/filter_core.h"
#include <bmfr/filters/mara2017_filter.h>

namespace bmfr {

struct MaraHooks : FilterHooks<Mara2017Settings> {
    void check(const Mara2017Settings&, const FrameInput& frame) const {
        if (frame.glossyIndirect.data && !frame.matteIndirect.data)
            throw Error("input buffer 'glossyIndirect' is given without 'matteIndirect': Mara "
                        "2017's factorisation needs both (bmfr render --paths mara writes them)");
    }
};

} // namespace bmfr
