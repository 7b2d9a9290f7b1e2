#include "render/lights.h"
#include "core/color.h"
#include "render/sampling.h"
#include <algorithm>
#include <cmath>

namespace bmfr::render {

float LightSet::area(int tri) const {
    const Vec3* p = &scene_.positions[3 * size_t(tri)];
    return 0.5f * length(cross(p[1] - p[0], p[2] - p[0]));
}

LightSet::LightSet(const Scene& scene, const std::vector<QuadLight>& quads, const Environment& env,
                   LightSampling sampling)
    : scene_(scene), quads_(quads), env_(env), portals_(env.portals) {
    std::vector<float> weights;
    triangleEntry_.assign(scene.triangleCount(), -1);
    float localTotal = 0;
    for (size_t t = 0; t < scene.triangleCount(); ++t) {
        const Material& m = scene.materials[size_t(scene.triangleMaterial[t])];
        float w = area(int(t)) * luminance(m.emission);
        if (w <= 0) continue;
        triangleEntry_[t] = int(entries_.size());
        entries_.push_back({Kind::Triangle, int(t), 0});
        weights.push_back(w);
        localTotal += w;
    }
    for (size_t q = 0; q < quads.size(); ++q) {
        float w = length(cross(quads[q].edgeU, quads[q].edgeV)) * luminance(quads[q].radiance);
        quadEntry_.push_back(int(entries_.size()));
        entries_.push_back({Kind::Quad, int(q), 0});
        weights.push_back(w);
        localTotal += w;
    }
    const size_t locals = entries_.size();
    // Local lights and the sun have no common power scale: each gets the local lights' weight.
    const float distantWeight = localTotal > 0 ? localTotal : 1.0f;
    if (env.sun.enabled()) {
        float r = 0.5f * env.sun.angularDiameter;
        sunCosMax_ = std::cos(r);
        sunSolidAngle_ = 2 * kPi * (1 - sunCosMax_);
        sunRadiance_ = env.sun.irradiance / sunSolidAngle_;
        sunEntry_ = int(entries_.size());
        entries_.push_back({Kind::Sun, 0, 0});
        weights.push_back(distantWeight);
    }
    if (env.sky.x + env.sky.y + env.sky.z > 0) {
        skyEntry_ = int(entries_.size());
        entries_.push_back({Kind::Sky, 0, 0});
        weights.push_back(distantWeight);
    }
    // Each strategy selects among its entries by weight; an entry's probability is its
    // selection probability within its strategy.
    auto addStrategy = [&](size_t begin, size_t end) {
        if (begin == end) return;
        Strategy st;
        float total = 0, acc = 0;
        for (size_t i = begin; i < end; ++i) total += weights[i];
        for (size_t i = begin; i < end; ++i) {
            entries_[i].probability = weights[i] / total;
            acc += entries_[i].probability;
            st.entries.push_back(int(i));
            st.cdf.push_back(acc);
        }
        st.cdf.back() = 1.0f;
        strategies_.push_back(std::move(st));
    };
    if (sampling == LightSampling::One) {
        addStrategy(0, entries_.size());
    } else {
        addStrategy(0, locals);
        for (size_t i = locals; i < entries_.size(); ++i) addStrategy(i, i + 1);
    }
}

LightSample LightSet::sample(int strategy, Vec3 p, Vec3 surfaceNormal, float uSelect, float u1,
                             float u2) const {
    LightSample s;
    if (strategy < 0 || size_t(strategy) >= strategies_.size()) return s;
    const Strategy& st = strategies_[size_t(strategy)];
    size_t i = size_t(std::lower_bound(st.cdf.begin(), st.cdf.end(), uSelect) - st.cdf.begin());
    i = std::min(i, st.entries.size() - 1);
    const Entry& e = entries_[size_t(st.entries[i])];
    Vec3 q, n;
    float a = 0;
    if (e.kind == Kind::Sky) {
        s.distance = 1e30f;
        s.radiance = env_.sky;
        if (portals_.empty()) {
            const Vec3 local = cosineHemisphere(u1, u2);
            s.wi = toWorld(local, surfaceNormal);
            s.pdf = e.probability * local.z / kPi;
            return s;
        }
        // u1 picks the half of the mixture, then is stretched back to [0, 1) within it.
        if (u1 < kSkyPortalShare) {
            const Vec3 d = portals_.point(u1 / kSkyPortalShare, u2) - p;
            const float l = length(d);
            if (!(l > 0)) return LightSample{};
            s.wi = d / l;
        } else {
            const float u = std::min((u1 - kSkyPortalShare) / (1 - kSkyPortalShare), 0.99999994f);
            s.wi = toWorld(cosineHemisphere(u, u2), surfaceNormal);
        }
        s.pdf = pdfSky(s.wi, p, surfaceNormal);
        return s;
    }
    if (e.kind == Kind::Sun) {
        s.wi = toWorld(uniformCone(u1, u2, sunCosMax_), env_.sun.direction);
        s.distance = 1e30f;
        s.radiance = sunRadiance_;
        s.pdf = e.probability / sunSolidAngle_;
        return s;
    }
    if (e.kind == Kind::Triangle) {
        const Vec3* v = &scene_.positions[3 * size_t(e.index)];
        float b1, b2;
        uniformTriangle(u1, u2, b1, b2);
        q = (1 - b1 - b2) * v[0] + b1 * v[1] + b2 * v[2];
        n = cross(v[1] - v[0], v[2] - v[0]);
        a = 0.5f * length(n);
        s.radiance = scene_.materials[size_t(scene_.triangleMaterial[size_t(e.index)])].emission;
    } else {
        const QuadLight& ql = quads_[size_t(e.index)];
        q = ql.corner + u1 * ql.edgeU + u2 * ql.edgeV;
        n = cross(ql.edgeU, ql.edgeV);
        a = length(n);
        s.radiance = ql.radiance;
    }
    Vec3 d = q - p;
    float d2 = dot(d, d);
    s.distance = std::sqrt(d2);
    s.wi = d / s.distance;
    // Triangles emit on their front (winding) side only; quads on both.
    if (e.kind == Kind::Triangle && dot(n, s.wi) >= 0) return LightSample{};
    float cosL = std::fabs(dot(n, s.wi)) / length(n);
    s.pdf = cosL > 1e-7f ? e.probability * d2 / (a * cosL) : 0.0f;
    return s;
}

float LightSet::pdfTriangle(int tri, Vec3 p, Vec3 q) const {
    int e = triangleEntry_[size_t(tri)];
    if (e < 0) return 0;
    const Vec3* v = &scene_.positions[3 * size_t(tri)];
    Vec3 n = cross(v[1] - v[0], v[2] - v[0]), d = q - p;
    float d2 = dot(d, d), cosL = std::fabs(dot(n, d)) / (length(n) * std::sqrt(d2));
    return cosL > 1e-7f ? entries_[size_t(e)].probability * d2 / (0.5f * length(n) * cosL) : 0.0f;
}

float LightSet::pdfQuad(int quad, Vec3 p, Vec3 q) const {
    const QuadLight& ql = quads_[size_t(quad)];
    Vec3 n = cross(ql.edgeU, ql.edgeV), d = q - p;
    float d2 = dot(d, d), cosL = std::fabs(dot(n, d)) / (length(n) * std::sqrt(d2));
    return cosL > 1e-7f
               ? entries_[size_t(quadEntry_[size_t(quad)])].probability * d2 / (length(n) * cosL)
               : 0.0f;
}

float LightSet::pdfSun() const {
    return sunEntry_ < 0 ? 0.0f : entries_[size_t(sunEntry_)].probability / sunSolidAngle_;
}

float LightSet::pdfSky(Vec3 d, Vec3 p, Vec3 n) const {
    if (skyEntry_ < 0) return 0.0f;
    const float probability = entries_[size_t(skyEntry_)].probability;
    // Without portals, rounded as before they existed: scenes without one keep their bits.
    if (portals_.empty()) return probability * std::fmax(dot(d, n), 0.0f) / kPi;
    const float cosine = std::fmax(dot(d, n), 0.0f) / kPi;
    return probability * ((1 - kSkyPortalShare) * cosine + kSkyPortalShare * portals_.pdf(d, p));
}

void LightSet::escaped(Vec3 d, Vec3 p, Vec3 n, Vec3& sky, float& skyPdf, Vec3& sun,
                       float& sunPdf) const {
    sky = env_.sky;
    skyPdf = pdfSky(d, p, n);
    sun = sunRadiance(d);
    sunPdf = pdfSun();
}

Vec3 LightSet::sunRadiance(Vec3 d) const {
    if (sunEntry_ < 0 || dot(d, env_.sun.direction) < sunCosMax_) return {};
    return sunRadiance_;
}

int LightSet::intersectQuads(Vec3 o, Vec3 d, float tMax, float& t) const {
    int best = -1;
    for (size_t i = 0; i < quads_.size(); ++i) {
        const QuadLight& q = quads_[i];
        float tt = 0;
        if (crossParallelogram(o, d, q.corner, q.edgeU, q.edgeV, 1e-4f, tMax, tt))
            tMax = tt, t = tt, best = int(i);
    }
    return best;
}

} // namespace bmfr::render
