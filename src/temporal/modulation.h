// The way back from demodulated filtering to radiance: re-multiply by the albedo and add the
// noise-free emission that was taken out on input (temporal/pixel_input.h). Every filter ends
// its spatial and temporal work with this, before TAA.
#pragma once
#include "temporal/pixel_input.h"

namespace bmfr {

/// c * guarded albedo when `remodulate`, plus the emission when given and finite.
BMFR_HD Vec3 remodulate(Vec3 c, Vec3 albedo, const float* emission, bool remodulateAlbedo,
                        float albedoEpsilon) {
    if (remodulateAlbedo) c = c * guardAlbedo(albedo, albedoEpsilon);
    if (emission) {
        const Vec3 e{emission[0], emission[1], emission[2]};
        if (std::isfinite(e.x) && std::isfinite(e.y) && std::isfinite(e.z)) c = c + e;
    }
    return c;
}

/// remodulate() of pixel i of a frame's input planes.
BMFR_HD Vec3 remodulatePixel(Vec3 c, const InputPlanes& in, long i, bool remodulateAlbedo,
                             float albedoEpsilon) {
    return remodulate(c, load3(in.albedo, i), in.emission ? in.emission + 3 * i : nullptr,
                      remodulateAlbedo, albedoEpsilon);
}

} // namespace bmfr
