// BMFR's own steps in the shared frame loop: the extra buffers its features read, and the
// visibility column it adds while the frames bring a visibility buffer.
#pragma once
#include "filters/filter_core.h"
#include <bmfr/filters/bmfr_filter.h>

namespace bmfr {

struct BmfrHooks : FilterHooks<BmfrSettings> {
    /// What the passes run with: the settings, plus the visibility column when the frames give
    /// one (visibilityFeature). It is staged as the extra after the frame's own.
    BmfrSettings active;
    int visibilityExtra = -2; ///< the visibility column's extra index; -1 none; -2 no frame yet

    int extrasNeeded(const BmfrSettings& settings) const;
    /// Within a history the visibility must come with every frame or none.
    const BmfrSettings& select(const BmfrSettings& settings, const FrameInput& frame,
                               const TemporalHistory& history, bool& changed);
    /// With visibilityFeature, the column a visibility buffer adds.
    BmfrSettings widest(const BmfrSettings& settings) const;
};

} // namespace bmfr
