// Deterministic per-element random numbers (no state, same bits on every thread count).
#pragma once
#include "core/host_device.h"
#include <cstdint>

namespace bmfr {

/// Wang's 32-bit integer hash.
BMFR_HD uint32_t wangHash(uint32_t s) {
    s = (s ^ 61u) ^ (s >> 16);
    s *= 9u;
    s = s ^ (s >> 4);
    s *= 0x27d4eb2du;
    s = s ^ (s >> 15);
    return s;
}

/// Hash of several keys, chained.
BMFR_HD uint32_t hashKeys(uint32_t a, uint32_t b, uint32_t c = 0, uint32_t d = 0) {
    return wangHash(d ^ wangHash(c ^ wangHash(b ^ wangHash(a))));
}

/// Uniform float in [0, 1) from 24 bits of a hash.
BMFR_HD float unitFloat(uint32_t h) {
    return float(h >> 8) * (1.0f / 16777216.0f);
}

} // namespace bmfr
