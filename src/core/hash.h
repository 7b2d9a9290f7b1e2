// Deterministic per-element random numbers (no state, same bits on every thread count).
#pragma once
#include "core/host_device.h"
#include <cstdint>

namespace bmfr {

/// Wang's 32-bit integer hash, of a uint32_t or, lane by lane, of a vector of them (the CPU
/// backend's).
template <class U> BMFR_HD U wangHashOf(U s) {
    s = (s ^ 61u) ^ (s >> 16);
    s *= 9u;
    s = s ^ (s >> 4);
    s *= 0x27d4eb2du;
    s = s ^ (s >> 15);
    return s;
}
BMFR_HD uint32_t wangHash(uint32_t s) {
    return wangHashOf(s);
}

/// Hash of several keys, chained; hashKeysOf of vectors too, as wangHashOf.
template <class U> BMFR_HD U hashKeysOf(U a, U b, U c, U d) {
    return wangHashOf(d ^ wangHashOf(c ^ wangHashOf(b ^ wangHashOf(a))));
}
BMFR_HD uint32_t hashKeys(uint32_t a, uint32_t b, uint32_t c = 0, uint32_t d = 0) {
    return hashKeysOf(a, b, c, d);
}

/// Uniform float in [0, 1) from 24 bits of a hash.
BMFR_HD float unitFloat(uint32_t h) {
    return float(h >> 8) * (1.0f / 16777216.0f);
}

} // namespace bmfr
