// Mara et al. 2017's factored Monte Carlo estimator (their section 3.2 and 3.3): the BRDF split
// into a matte and a glossy term combined by Fresnel, evaluated once at the mirror direction,
// with one path for each term and direct light apart.
#include "render/integrator.h"

namespace bmfr::render {

Vec3 FactoredSample::total() const {
    const Vec3 one{1, 1, 1}, m = one - fresnel;
    return emission + direct + m * m * matteReflectance * matte + fresnel * glossy;
}

Integrator::Along Integrator::along(const SurfacePoint& sp, Vec3 wi, Rng& rng,
                                    uint64_t& rays) const {
    Along r;
    const Vec3 origin = sp.p + offsetScale(sp.p) * sp.ng;
    PrimaryHit next;
    float t = 0;
    next.origin = origin, next.direction = wi, next.spread = sp.alpha;
    next.hit = trace(origin, wi, 0.0f, sp.alpha, next.surface, next.lightQuad, t, rays);
    if (!next.hit) {
        lights_.escaped(wi, sp.p, sp.ns, r.emitted, r.emittedPdf, r.sun, r.sunPdf);
        return r;
    }
    r.distance = t;
    const SurfacePoint& q = next.surface;
    if (!isBlack(q.emission)) {
        r.emitted = q.emission;
        r.emittedPdf = next.lightQuad >= 0 ? lights_.pdfQuad(next.lightQuad, sp.p, q.p)
                                           : lights_.pdfTriangle(q.triangle, sp.p, q.p);
    }
    // The next surface's own sample, one BSDF ray fewer, is the light it reflects towards sp.
    const Integrator inner(scene_, accel_, lights_, bounces_ > 0 ? bounces_ - 1 : 0);
    const PathContribution c = inner.sample(next, rng, rays);
    r.indirect = vmax(c.total - q.emission, Vec3{});
    return r;
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
    if (cosO <= 0 || (isBlack(sp.diffuse) && isBlack(sp.f0))) return s;
    s.fresnel = schlick(sp.f0, cosO);
    const Vec3 origin = sp.p + offsetScale(sp.p) * sp.ng;
    const float a2 = sp.alpha * sp.alpha;
    // The three strategies for the direct light and their densities (balance heuristic): N light
    // samples, the matte path's cosine direction and the glossy path's GGX one.
    const bool matteRay = bounces_ > 0, glossyRay = bounces_ > 0 && !isBlack(sp.f0);
    const int n = lights_.empty() ? 0 : directSamples;
    auto pathPdfs = [&](Vec3 wi) {
        const float cosI = dot(sp.ns, wi);
        if (cosI <= 0) return 0.0f;
        float p = matteRay ? cosI / kPi : 0.0f;
        const Vec3 h = normalize(wi + sp.wo);
        const float cosH = dot(sp.ns, h), oh = dot(sp.wo, h);
        if (glossyRay && cosH > 0 && oh > 0) p += ggxD(cosH, a2) * cosH / (4 * oh);
        return p;
    };
    auto directAlong = [&](Vec3 wi, const Along& r) {
        const BsdfValue f = evalBsdf(sp, wi);
        const Vec3 fr = f.diffuse + f.glossy;
        if (isBlack(fr)) return;
        const float cosI = dot(sp.ns, wi), paths = pathPdfs(wi);
        s.direct += (cosI / (float(n) * r.emittedPdf + paths)) * (fr * r.emitted);
        if (!isBlack(r.sun)) s.direct += (cosI / (float(n) * r.sunPdf + paths)) * (fr * r.sun);
    };
    for (int k = 0; k < n; ++k) {
        const float uSel = rng.next(), u1 = rng.next(), u2 = rng.next();
        const LightSample ls = lights_.sample(sp.p, sp.ns, uSel, u1, u2);
        if (!(ls.pdf > 0)) continue;
        const BsdfValue f = evalBsdf(sp, ls.wi);
        const Vec3 fr = f.diffuse + f.glossy;
        if (isBlack(fr)) continue;
        ++rays;
        const float tMax =
            ls.distance >= 1e29f ? 1e30f : ls.distance * (1 - 1e-4f) - offsetScale(sp.p);
        if (accel_.occluded(origin, ls.wi, tMax)) continue;
        const float cosI = dot(sp.ns, ls.wi);
        s.direct += (cosI / (float(n) * ls.pdf + pathPdfs(ls.wi))) * (fr * ls.radiance);
    }
    // Matte: a cosine-sampled direction, whose pdf cancels the cosine (their Eq. 6 and 9).
    {
        const float u1 = rng.next(), u2 = rng.next();
        const Vec3 wi = toWorld(cosineHemisphere(u1, u2), sp.ns);
        if (dot(sp.ng, wi) > 0 && matteRay) {
            const Along r = along(sp, wi, rng, rays);
            s.matte = r.indirect;
            directAlong(wi, r);
        }
    }
    // Glossy: a GGX-sampled half vector; g cos / pdf = G1(i) G1(o) (o.h) / (cos_o cos_h).
    {
        const float u1 = rng.next(), u2 = rng.next();
        const float cosH = std::sqrt((1 - u1) / (1 + (a2 - 1) * u1)),
                    sinH = std::sqrt(std::fmax(0.0f, 1 - cosH * cosH)), phi = 2 * kPi * u2;
        const Vec3 h = toWorld({sinH * std::cos(phi), sinH * std::sin(phi), cosH}, sp.ns);
        const float oh = dot(sp.wo, h);
        const Vec3 wi = 2 * oh * h - sp.wo;
        const float cosI = dot(sp.ns, wi);
        if (oh > 0 && cosI > 0 && dot(sp.ng, wi) > 0 && glossyRay) {
            const float weight =
                smithG1(cosI, a2) * smithG1(cosO, a2) * oh / (cosO * std::fmax(cosH, 1e-6f));
            const Along r = along(sp, wi, rng, rays);
            s.glossy = weight * r.indirect;
            s.glossyDistance = r.distance;
            directAlong(wi, r);
        }
    }
    return s;
}

} // namespace bmfr::render
