// Bounce guides: parallelograms where a scene's indirect light mostly comes from (a sunlit
// floor in a courtyard). Diffuse bounces aim part of their samples at them, so points that see
// the lit part of the scene only through a small solid angle (Sponza's galleries) find it far
// more often than by cosine sampling. Like sky portals they change the noise, not the expected
// image: the BSDF ray's pdf is the mixture's, for its throughput and its MIS weights alike.
#pragma once
#include "render/bsdf.h"
#include "render/parallelograms.h"

namespace bmfr::render {

/// The share of a diffuse or rough glossy lobe's samples aimed at the guides, where a guide is
/// in view. On sponza-static's first frame 0.7 leaves 31.8% of 1-spp pixels black, 0.5 35.2%
/// and no guide 43.7%.
inline constexpr float kBounceGuideShare = 0.7f;

class BounceGuides {
  public:
    BounceGuides() = default;
    explicit BounceGuides(std::vector<Parallelogram> guides) : guides_(std::move(guides)) {}
    bool empty() const { return guides_.empty(); }
    /// The share of lobe samples aimed at the guides from p with shading normal n:
    /// kBounceGuideShare when a guide corner stands clearly above the tangent plane, else 0 (the
    /// guided floor itself, and points behind a guide, would waste them).
    float share(Vec3 p, Vec3 n) const;
    /// evalBsdf with the pdf of sample() at this share: the mixture of the glossy lobe, the
    /// cosine and the guides.
    BsdfValue eval(const SurfacePoint& s, Vec3 wi, float share) const;
    /// sampleBsdf whose diffuse lobe, and glossy lobe when rough (GGX alpha >= 0.5), aim at the
    /// guides with probability `share` (uLobe picks the lobe and then the part, so no extra
    /// random number is drawn); value.pdf is eval()'s.
    bool sample(const SurfacePoint& s, float share, float uLobe, float u1, float u2, Vec3& wi,
                BsdfValue& value) const;

  private:
    ParallelogramSet guides_;
};

} // namespace bmfr::render
