// The paper's 1-spp light transport (section 3.1): primary hit, next event estimation (one shadow
// ray to a random point on a random light), one BSDF-sampled secondary ray combined by multiple
// importance sampling, and a second shadow ray from the secondary hit; `bounces` secondary rays
// in general. The reference averages the same estimator over many samples.
#pragma once
#include "render/bounce_guides.h"
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
/// How far a ray leaving p starts from it, scene units: relative to p's magnitude, so that
/// float positions far from the origin do not hit their own surface.
inline float offsetScale(Vec3 p) {
    return 1e-4f * (1.0f + std::fmax(std::fabs(p.x), std::fmax(std::fabs(p.y), std::fabs(p.z))));
}
inline bool isBlack(Vec3 v) {
    return v.x <= 0 && v.y <= 0 && v.z <= 0;
}

struct PathContribution {
    Vec3 total, direct, indirect, diffuse, glossy, diffuseIndirect;
};

/// One sample of Mara et al. 2017's factored estimator (their Eq. 9 and 10): one cosine-sampled
/// matte path, one GGX-sampled glossy path and the direct light apart. The sky, the sun and
/// emitters are direct light: the light samples and the two paths' first rays, combined by
/// multiple importance sampling (balance heuristic), so M and G hold indirect light only.
struct FactoredSample {
    Vec3 emission; ///< seen at the first hit (or the sky and sun for a miss)
    Vec3 direct;   ///< reflected direct light, the full BRDF (light samples and both paths)
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
    /// The sun's noise-free visibility at the first hit times its cosine: max(0, n . l) when
    /// the ray towards the sun's centre escapes, else 0 (also for misses and a scene without
    /// a sun). FrameInput::visibility.
    float sunVisibility(const PrimaryHit& first, uint64_t& rays) const;
    /// Mara et al.'s factored sample with `directSamples` light samples at the first hit
    /// (render/factored_paths.cpp).
    FactoredSample factoredSample(const PrimaryHit& first, int directSamples, Rng& rng,
                                  uint64_t& rays) const;

  private:
    const Scene& scene_;
    const RayAccel& accel_;
    const LightSet& lights_;
    int bounces_;
    BounceGuides guides_; ///< the environment's, for the BSDF rays of sample()

    /// Closest surface (mesh or quad light) along a ray; fills the shading point.
    /// width: ray-cone footprint at o; spread: its growth per unit distance (radians).
    bool trace(Vec3 o, Vec3 d, float width, float spread, SurfacePoint& sp, int& quad, float& t,
               uint64_t& rays) const;
    /// What a ray from sp along wi brings: the next surface's reflected light with bounces_ - 1
    /// further BSDF rays (indirect), and apart what it emits or the sky and sun (direct).
    struct Along {
        Vec3 indirect;
        Vec3 emitted;         ///< the next surface's emission towards sp, or the sky's
        float emittedPdf = 0; ///< the light sampler's pdf of that direction
        Vec3 sun;             ///< the sun disk, when the ray escaped
        float sunPdf = 0;
        float distance = -1; ///< to the next hit; -1 when the ray escaped
    };
    Along along(const SurfacePoint& sp, Vec3 wi, Rng& rng, uint64_t& rays) const;
    void shadeTriangle(int tri, float u, float v, Vec3 d, float coneWidth, SurfacePoint& sp) const;
};

} // namespace bmfr::render
