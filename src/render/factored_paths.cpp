// Mara et al. 2017's factored Monte Carlo estimator (their section 3.2 and 3.3): the BRDF split
// into a matte and a glossy term combined by Fresnel, evaluated once at the mirror direction,
// with one path for each term and direct light apart.
#include "render/integrator.h"

namespace bmfr::render {

namespace {

float offsetScale(Vec3 p) {
    return 1e-4f * (1.0f + std::fmax(std::fabs(p.x), std::fmax(std::fabs(p.y), std::fabs(p.z))));
}

} // namespace

Vec3 FactoredSample::total() const {
    const Vec3 one{1, 1, 1}, m = one - fresnel;
    return emission + direct + m * m * matteReflectance * matte + fresnel * glossy;
}

Vec3 Integrator::indirectAlong(const SurfacePoint& sp, Vec3 wi, Rng& rng, float& distance,
                               uint64_t& rays) const {
    distance = -1;
    const Vec3 origin = sp.p + offsetScale(sp.p) * sp.ng;
    PrimaryHit next;
    float t = 0;
    next.origin = origin, next.direction = wi, next.spread = sp.alpha;
    next.hit = trace(origin, wi, 0.0f, sp.alpha, next.surface, next.lightQuad, t, rays);
    if (!next.hit) return {}; // the sky and the sun are direct light
    distance = t;
    // The next surface's own sample, one BSDF ray fewer, is the light it reflects towards sp.
    const Integrator inner(scene_, accel_, lights_, bounces_ > 0 ? bounces_ - 1 : 0);
    const PathContribution c = inner.sample(next, rng, rays);
    return vmax(c.total - next.surface.emission, Vec3{});
}

FactoredSample Integrator::factoredSample(const PrimaryHit& first, int directSamples, Rng& rng,
                                          uint64_t& rays) const {
    FactoredSample s;
    s.fresnel = {}, s.matteReflectance = {};
    if (!first.hit) {
        s.emission = lights_.environment().sky + lights_.sunRadiance(first.direction);
        return s;
    }
    const SurfacePoint& sp = first.surface;
    s.emission = sp.emission;
    s.matteReflectance = sp.diffuse;
    const float cosO = dot(sp.ns, sp.wo);
    if (cosO <= 0 || (sp.diffuse.x <= 0 && sp.diffuse.y <= 0 && sp.diffuse.z <= 0 && sp.f0.x <= 0 &&
                      sp.f0.y <= 0 && sp.f0.z <= 0))
        return s;
    s.fresnel = schlick(sp.f0, cosO);
    const Vec3 origin = sp.p + offsetScale(sp.p) * sp.ng;
    // Direct light: light sampling alone, so a path that reaches a light adds nothing later.
    if (!lights_.empty() && directSamples > 0) {
        for (int k = 0; k < directSamples; ++k) {
            const float uSel = rng.next(), u1 = rng.next(), u2 = rng.next();
            const LightSample ls = lights_.sample(sp.p, sp.ns, uSel, u1, u2);
            if (!(ls.pdf > 0)) continue;
            const BsdfValue f = evalBsdf(sp, ls.wi);
            const Vec3 fr = f.diffuse + f.glossy;
            if (fr.x <= 0 && fr.y <= 0 && fr.z <= 0) continue;
            ++rays;
            const float tMax =
                ls.distance >= 1e29f ? 1e30f : ls.distance * (1 - 1e-4f) - offsetScale(sp.p);
            if (accel_.occluded(origin, ls.wi, tMax)) continue;
            s.direct += (dot(sp.ns, ls.wi) / ls.pdf) * (fr * ls.radiance);
        }
        s.direct = s.direct / float(directSamples);
    }
    float unused = 0;
    // Matte: a cosine-sampled direction, whose pdf cancels the cosine (their Eq. 6 and 9).
    {
        const float u1 = rng.next(), u2 = rng.next();
        const Vec3 wi = toWorld(cosineHemisphere(u1, u2), sp.ns);
        if (dot(sp.ng, wi) > 0 && bounces_ > 0) s.matte = indirectAlong(sp, wi, rng, unused, rays);
    }
    // Glossy: a GGX-sampled half vector; g cos / pdf = G1(i) G1(o) (o.h) / (cos_o cos_h).
    {
        const float u1 = rng.next(), u2 = rng.next();
        const float a2 = sp.alpha * sp.alpha;
        const float cosH = std::sqrt((1 - u1) / (1 + (a2 - 1) * u1)),
                    sinH = std::sqrt(std::fmax(0.0f, 1 - cosH * cosH)), phi = 2 * kPi * u2;
        const Vec3 h = toWorld({sinH * std::cos(phi), sinH * std::sin(phi), cosH}, sp.ns);
        const float oh = dot(sp.wo, h);
        const Vec3 wi = 2 * oh * h - sp.wo;
        const float cosI = dot(sp.ns, wi);
        if (oh > 0 && cosI > 0 && dot(sp.ng, wi) > 0 && bounces_ > 0 &&
            (sp.f0.x > 0 || sp.f0.y > 0 || sp.f0.z > 0)) {
            const float weight =
                smithG1(cosI, a2) * smithG1(cosO, a2) * oh / (cosO * std::fmax(cosH, 1e-6f));
            s.glossy = weight * indirectAlong(sp, wi, rng, s.glossyDistance, rays);
        }
    }
    return s;
}

} // namespace bmfr::render
