// The paper's 1-spp light transport (section 3.1): primary hit, next event estimation (one shadow
// ray to a random point on a random light), one BSDF-sampled secondary ray combined by multiple
// importance sampling, and a second shadow ray from the secondary hit; `bounces` secondary rays
// in general. The reference averages the same estimator over many samples.
#pragma once
#include "render/bsdf.h"
#include "render/lights.h"
#include "render/ray_accel.h"
#include "render/sampling.h"
#include <cstdint>

namespace bmfr::render {

/// The deterministic first hit of a camera ray, with its feature values.
struct PrimaryHit {
    bool hit = false;
    Vec3 origin, direction;
    float spread = 0; ///< radians per pixel of the camera ray cone
    SurfacePoint surface;
    int lightQuad = -1; ///< the hit is analytic quad light k
};

/// One sample's radiance and its splits (direct + indirect = diffuse + glossy = total), and
/// the indirect light through the primary hit's diffuse lobe (part of indirect and of diffuse).
struct PathContribution {
    Vec3 total, direct, indirect, diffuse, glossy, diffuseIndirect;
};

/// One sample of Mara et al. 2017's factored estimator (their Eq. 9 and 10): direct light by
/// light sampling alone, one cosine-sampled matte path and one GGX-sampled glossy path. The
/// sky and the sun are direct light, so paths that escape add nothing to M or G.
struct FactoredSample {
    Vec3 emission; ///< seen at the first hit (or the sky and sun for a miss)
    Vec3 direct;   ///< reflected direct light, the full BRDF, mean of the light samples
    Vec3 matte;    ///< M: indirect radiance along the cosine-sampled direction
    Vec3 glossy;   ///< G: indirect radiance along the GGX direction times g cos / pdf
    Vec3 fresnel;  ///< F_s = Schlick(F0, n . wo), the Fresnel factor at the mirror direction
    Vec3 matteReflectance;     ///< rho_L, the diffuse reflectance
    float glossyDistance = -1; ///< to the glossy path's next hit; -1 when it escaped
    /// The estimate: emission + direct + (1 - F_s)^2 rho_L M + F_s G.
    Vec3 total() const;
};

class Integrator {
  public:
    /// bounces = number of BSDF-sampled secondary rays per path; [0, 64]; the paper uses 1.
    Integrator(const Scene& scene, const RayAccel& accel, const LightSet& lights, int bounces);

    /// spreadAngle: radians per pixel, for the texture level of detail (ray cones).
    PrimaryHit primary(Vec3 origin, Vec3 direction, float spreadAngle, uint64_t& rays) const;
    PathContribution sample(const PrimaryHit& first, Rng& rng, uint64_t& rays) const;
    /// Mara et al.'s factored sample with `directSamples` light samples at the first hit
    /// (render/factored_paths.cpp).
    FactoredSample factoredSample(const PrimaryHit& first, int directSamples, Rng& rng,
                                  uint64_t& rays) const;

  private:
    const Scene& scene_;
    const RayAccel& accel_;
    const LightSet& lights_;
    int bounces_;

    /// Closest surface (mesh or quad light) along a ray; fills the shading point.
    /// width: ray-cone footprint at o; spread: its growth per unit distance (radians).
    bool trace(Vec3 o, Vec3 d, float width, float spread, SurfacePoint& sp, int& quad, float& t,
               uint64_t& rays) const;
    /// Light arriving at sp along wi from the next surface, its emission left out (that is
    /// direct light): the next surface's reflected light with bounces_ - 1 further BSDF rays.
    Vec3 indirectAlong(const SurfacePoint& sp, Vec3 wi, Rng& rng, float& distance,
                       uint64_t& rays) const;
    void shadeTriangle(int tri, float u, float v, Vec3 d, float coneWidth, SurfacePoint& sp) const;
};

} // namespace bmfr::render
