#include "render/bounce_guides.h"
#include <algorithm>

namespace bmfr::render {

namespace {
/// How far above the tangent plane (cosine) a guide corner must be for the guides to be aimed at.
constexpr float kMinGuideCosine = 0.05f;
/// GGX alpha from which the glossy lobe is wide enough to give the guides a share of it too.
constexpr float kRoughGlossyAlpha = 0.5f;

/// The shares of the diffuse and the glossy lobe's samples that go to the guides.
void lobeShares(const SurfacePoint& s, float share, float& diffuse, float& glossy) {
    diffuse = share;
    glossy = s.alpha >= kRoughGlossyAlpha ? share : 0.0f;
}
} // namespace

float BounceGuides::share(Vec3 p, Vec3 n) const {
    for (const Parallelogram& q : guides_.shapes())
        for (Vec3 c :
             {q.corner, q.corner + q.edgeU, q.corner + q.edgeV, q.corner + q.edgeU + q.edgeV}) {
            const Vec3 d = c - p;
            const float l = length(d);
            if (l > 0 && dot(d, n) > kMinGuideCosine * l) return kBounceGuideShare;
        }
    return 0.0f;
}

BsdfValue BounceGuides::eval(const SurfacePoint& s, Vec3 wi, float share) const {
    BsdfValue v = evalBsdf(s, wi);
    if (share <= 0 || !(v.pdf > 0)) return v;
    float toGuidesD, toGuidesG;
    lobeShares(s, share, toGuidesD, toGuidesG);
    const float glossy = glossyProbability(s), diffuse = 1 - glossy;
    const float guided = diffuse * toGuidesD + glossy * toGuidesG;
    v.pdf = diffuse * (1 - toGuidesD) * v.cosinePdf + glossy * (1 - toGuidesG) * v.ggxPdf +
            guided * guides_.pdf(wi, s.p);
    return v;
}

bool BounceGuides::sample(const SurfacePoint& s, float share, float uLobe, float u1, float u2,
                          Vec3& wi, BsdfValue& value) const {
    if (share <= 0) return sampleBsdf(s, uLobe, u1, u2, wi, value);
    if (dot(s.ns, s.wo) <= 0) return false;
    float toGuidesD, toGuidesG;
    lobeShares(s, share, toGuidesD, toGuidesG);
    // uLobe below the glossy probability picks the glossy lobe (as in sampleBsdf); the first
    // toGuides of each lobe's interval goes to the guides instead.
    const float glossy = glossyProbability(s);
    const bool guided =
        uLobe < glossy ? uLobe < glossy * toGuidesG : uLobe - glossy < (1 - glossy) * toGuidesD;
    if (!guided) {
        wi = sampleBsdfDirection(s, uLobe, u1, u2);
    } else {
        const Vec3 d = guides_.point(u1, u2) - s.p;
        const float l = length(d);
        if (!(l > 0)) return false;
        wi = d / l;
    }
    value = eval(s, wi, share);
    return value.pdf > 0;
}

} // namespace bmfr::render
