// Border handling shared by filters, metrics and tools: reflection of an index into an image.
#pragma once
#include "core/host_device.h"

namespace bmfr {

/// Reflects an index into [0, n) with edge duplication (3 2 1 0 | 0 1 2 3 | 3 2 1 0), for any
/// distance outside (images smaller than a block included).
BMFR_HD int mirrorIndex(int i, int n) {
    int period = 2 * n;
    int m = i % period;
    if (m < 0) m += period;
    return m < n ? m : period - 1 - m;
}

} // namespace bmfr
