// The surface model: Lambertian diffuse plus GGX microfacet reflection (metal/rough as glTF),
// evaluated and importance-sampled with the diffuse and glossy parts kept apart.
#pragma once
#include "core/color.h"
#include "render/sampling.h"

namespace bmfr::render {

/// A shaded surface point; all vectors world space, normals facing the incoming ray's side.
struct SurfacePoint {
    Vec3 p, ng, ns, wo;  ///< position, geometric and shading normal, direction to the viewer
    Vec3 baseColor;      ///< first-hit albedo feature
    Vec3 diffuse;        ///< diffuse reflectance (baseColor * (1 - metallic))
    Vec3 f0;             ///< normal-incidence Fresnel reflectance
    float alpha = 0.25f; ///< GGX alpha = roughness^2 (floored)
    float roughness = 0.5f;
    Vec3 emission;
    int material = 0;
    int triangle = -1; ///< scene triangle, -1 for analytic lights
};

struct BsdfValue {
    Vec3 diffuse, glossy;            ///< BRDF values (not multiplied by the cosine)
    float pdf = 0;                   ///< solid-angle pdf of sampleBsdf producing wi
    float cosinePdf = 0, ggxPdf = 0; ///< the diffuse and glossy lobes' own pdfs of wi
};

inline float ggxD(float cosH, float a2) {
    float d = cosH * cosH * (a2 - 1) + 1;
    return a2 / (kPi * d * d);
}
inline float smithG1(float c, float a2) {
    return 2 * c / (c + std::sqrt(a2 + (1 - a2) * c * c));
}
inline Vec3 schlick(Vec3 f0, float c) {
    float m = 1 - std::fmax(0.0f, c), m2 = m * m, k = m2 * m2 * m;
    return f0 + k * (Vec3{1, 1, 1} - f0);
}

/// Probability of sampling the glossy lobe.
inline float glossyProbability(const SurfacePoint& s) {
    float cosO = std::fmax(dot(s.ns, s.wo), 0.0f);
    float ws = luminance(schlick(s.f0, cosO)), wd = luminance(s.diffuse) * (1 - ws);
    if (ws + wd <= 0) return 0.5f;
    if (wd <= 0) return 1.0f;
    return std::fmin(0.95f, std::fmax(0.05f, ws / (ws + wd)));
}

inline BsdfValue evalBsdf(const SurfacePoint& s, Vec3 wi) {
    BsdfValue r;
    float cosI = dot(s.ns, wi), cosO = dot(s.ns, s.wo);
    if (cosI <= 0 || cosO <= 0 || dot(s.ng, wi) <= 0) return r;
    Vec3 h = normalize(wi + s.wo);
    float cosH = std::fmax(dot(s.ns, h), 0.0f), oh = std::fmax(dot(s.wo, h), 1e-6f);
    float a2 = s.alpha * s.alpha, D = ggxD(cosH, a2);
    r.diffuse = (1.0f / kPi) * s.diffuse;
    r.glossy = (D * smithG1(cosI, a2) * smithG1(cosO, a2) / (4 * cosI * cosO)) * schlick(s.f0, oh);
    float ps = glossyProbability(s);
    r.pdf = (1 - ps) * cosI / kPi + ps * D * cosH / (4 * oh);
    r.cosinePdf = cosI / kPi;
    r.ggxPdf = D * cosH / (4 * oh);
    return r;
}

/// A direction from the mixture of the cosine lobe and the GGX normal distribution: uLobe
/// below glossyProbability picks the glossy lobe. The caller checks that wo is above the surface.
inline Vec3 sampleBsdfDirection(const SurfacePoint& s, float uLobe, float u1, float u2) {
    if (uLobe < glossyProbability(s)) {
        float a2 = s.alpha * s.alpha;
        float cosH = std::sqrt((1 - u1) / (1 + (a2 - 1) * u1)),
              sinH = std::sqrt(std::fmax(0.0f, 1 - cosH * cosH));
        float phi = 2 * kPi * u2;
        Vec3 h = toWorld({sinH * std::cos(phi), sinH * std::sin(phi), cosH}, s.ns);
        return 2 * dot(s.wo, h) * h - s.wo;
    }
    return toWorld(cosineHemisphere(u1, u2), s.ns);
}

/// Samples wi by sampleBsdfDirection and evaluates the BSDF there.
inline bool sampleBsdf(const SurfacePoint& s, float uLobe, float u1, float u2, Vec3& wi,
                       BsdfValue& value) {
    if (dot(s.ns, s.wo) <= 0) return false;
    wi = sampleBsdfDirection(s, uLobe, u1, u2);
    value = evalBsdf(s, wi);
    return value.pdf > 0;
}

} // namespace bmfr::render
