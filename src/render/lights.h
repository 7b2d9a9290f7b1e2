// Light sources and their sampling: emissive triangles (one-sided, front = winding), analytic
// two-sided quads (may move per frame), a constant sky (cosine-sampled around the normal, and
// through its portals when it has them), and a sun with angular size.
#pragma once
#include "render/parallelograms.h"
#include "render/scene.h"
#include <vector>

namespace bmfr::render {

/// Two-sided emitting parallelogram corner + s*edgeU + t*edgeV, s, t in [0, 1].
struct QuadLight {
    Vec3 corner, edgeU, edgeV;
    Vec3 radiance; ///< W/(sr m^2)
};

struct Sun {
    Vec3 direction{0, 1, 0};          ///< unit vector towards the sun
    float angularDiameter = 0.00930f; ///< radians (0.53 degrees)
    Vec3 irradiance{0, 0, 0};         ///< W/m^2 on a surface facing the sun
    bool enabled() const { return irradiance.x + irradiance.y + irradiance.z > 0; }
};

/// An opening through which the sky reaches an enclosed space (a courtyard's roof, a window).
/// Sky samples aim at it, so a point that sees the sky only through it finds the sky far more
/// often than by cosine sampling. It changes the noise, not the expected image: directions off
/// the portal are still sampled, by the cosine half of the mixture.
using SkyPortal = Parallelogram;

struct Environment {
    Sun sun;
    Vec3 sky{0, 0, 0};              ///< constant radiance of directions that escape the scene
    std::vector<SkyPortal> portals; ///< where the sky gets in; empty: sampled by cosine alone
    /// Where the indirect light mostly comes from (render/bounce_guides.h); empty: diffuse
    /// bounces are cosine-sampled alone.
    std::vector<Parallelogram> bounceGuides;
};

/// With portals, the share of sky samples aimed at them; the rest are cosine-weighted, and keep
/// the sky outside the portals sampled. On Sponza's atrium 0.9 leaves 41% of 1-spp pixels
/// black where 0.5 leaves 51% (66.7% without the portal).
inline constexpr float kSkyPortalShare = 0.9f;

struct LightSample {
    Vec3 wi;
    float distance = 0; ///< to the sampled point (1e30 for the sun)
    Vec3 radiance;
    float pdf = 0; ///< solid angle, selection included
};

/// How a path vertex samples the lights.
enum class LightSampling {
    /// One sample per vertex from all lights (the BMFR paper's paths): selection proportional
    /// to power among local lights; the sun and the sky each weigh as much as all local lights.
    One,
    /// Up to three samples per vertex: one local light, the sun and the sky, each with its own
    /// shadow ray. Far fewer black pixels where one of them is mostly occluded (Sponza's atrium).
    Split,
};

/// The scene's lights and their sampling strategies (see LightSampling).
class LightSet {
  public:
    LightSet(const Scene& scene, const std::vector<QuadLight>& quads, const Environment& env,
             LightSampling sampling = LightSampling::One);
    bool empty() const { return entries_.empty(); }
    /// How many light samples each vertex takes: 1, or with Split one per kind present.
    int strategies() const { return int(strategies_.size()); }
    /// Light sample `strategy` (< strategies()) seen from p with surface normal n (the sky is
    /// sampled cosine-weighted around n); uSelect picks among the strategy's lights.
    LightSample sample(int strategy, Vec3 p, Vec3 n, float uSelect, float u1, float u2) const;
    /// The single strategy of LightSampling::One.
    LightSample sample(Vec3 p, Vec3 n, float uSelect, float u1, float u2) const {
        return sample(0, p, n, uSelect, u1, u2);
    }
    /// Solid-angle pdf of sample() returning the point q on emissive triangle `tri`.
    float pdfTriangle(int tri, Vec3 p, Vec3 q) const;
    float pdfQuad(int quad, Vec3 p, Vec3 q) const;
    float pdfSun() const;
    /// Solid-angle pdf of sample() returning sky direction d at point p with normal n.
    float pdfSky(Vec3 d, Vec3 p, Vec3 n) const;
    /// Radiance and light pdf of a direction escaping from p (sky plus sun disk), for MIS
    /// weighting: returns the radiance split into its sky and sun parts.
    void escaped(Vec3 d, Vec3 p, Vec3 n, Vec3& sky, float& skyPdf, Vec3& sun, float& sunPdf) const;
    const std::vector<QuadLight>& quads() const { return quads_; }
    const Environment& environment() const { return env_; }
    /// Closest analytic quad light hit before tMax; returns its index or -1.
    int intersectQuads(Vec3 o, Vec3 d, float tMax, float& t) const;
    /// Sun radiance seen along an escaping direction (0 outside the disk).
    Vec3 sunRadiance(Vec3 d) const;

  private:
    enum class Kind { Triangle, Quad, Sun, Sky };
    struct Entry {
        Kind kind;
        int index;
        float probability;
    };
    const Scene& scene_;
    std::vector<QuadLight> quads_;
    Environment env_;
    std::vector<Entry> entries_;
    /// Per strategy: its entries and their cumulative probabilities.
    struct Strategy {
        std::vector<int> entries;
        std::vector<float> cdf;
    };
    std::vector<Strategy> strategies_;
    std::vector<int> triangleEntry_; ///< scene triangle -> entry, -1 when not emissive
    std::vector<int> quadEntry_;
    int sunEntry_ = -1, skyEntry_ = -1;
    float sunCosMax_ = 1, sunSolidAngle_ = 0;
    ParallelogramSet portals_; ///< the environment's sky portals
    Vec3 sunRadiance_;
    float area(int tri) const;
};

} // namespace bmfr::render
