#include "render/integrator.h"
#include <algorithm>

namespace bmfr::render {

Integrator::Integrator(const Scene& scene, const RayAccel& accel, const LightSet& lights,
                       int bounces)
    : scene_(scene), accel_(accel), lights_(lights), bounces_(bounces),
      guides_(lights.environment().bounceGuides) {}

void Integrator::shadeTriangle(int tri, float u, float v, Vec3 d, float coneWidth,
                               SurfacePoint& sp) const {
    const size_t b = 3 * size_t(tri);
    const Vec3* P = &scene_.positions[b];
    const Vec3* N = &scene_.normals[b];
    const Vec2f* T = &scene_.uvs[b];
    const float w = 1 - u - v;
    const Material& m = scene_.materials[size_t(scene_.triangleMaterial[size_t(tri)])];
    sp.p = w * P[0] + u * P[1] + v * P[2];
    Vec3 e1 = P[1] - P[0], e2 = P[2] - P[0];
    Vec3 ng = cross(e1, e2);
    const float worldArea2 = length(ng);
    ng = worldArea2 > 0 ? ng / worldArea2 : Vec3{0, 1, 0};
    Vec3 ns = w * N[0] + u * N[1] + v * N[2];
    ns = length(ns) > 0 ? normalize(ns) : ng;
    const float tu = w * T[0].x + u * T[1].x + v * T[2].x,
                tv = w * T[0].y + u * T[1].y + v * T[2].y;
    const float du1 = T[1].x - T[0].x, dv1 = T[1].y - T[0].y, du2 = T[2].x - T[0].x,
                dv2 = T[2].y - T[0].y;
    const float uvArea2 = std::fabs(du1 * dv2 - du2 * dv1);

    // Texture level of detail from the ray cone footprint (Akenine-Moller et al. 2019).
    auto lod = [&](const Texture& tex) {
        if (uvArea2 <= 0 || worldArea2 <= 0) return 0.0f;
        float texels = uvArea2 * float(tex.width()) * float(tex.height());
        float cosine = std::fmax(std::fabs(dot(ng, d)), 1e-3f);
        return 0.5f * std::log2(texels / worldArea2) +
               std::log2(std::fmax(coneWidth, 1e-12f) / cosine);
    };
    Vec3 base = m.baseColor;
    if (m.baseColorTexture >= 0) {
        const Texture& tex = scene_.textures[size_t(m.baseColorTexture)];
        base = base * tex.sample(tu, tv, lod(tex)).rgb;
    }
    if (m.normalTexture >= 0) {
        const Texture& tex = scene_.textures[size_t(m.normalTexture)];
        const float det = du1 * dv2 - du2 * dv1;
        if (std::fabs(det) > 1e-12f) {
            Vec3 tangent = (dv2 * e1 - dv1 * e2) / det, bitangent = (du1 * e2 - du2 * e1) / det;
            tangent = tangent - dot(tangent, ns) * ns;
            if (length(tangent) > 0) {
                tangent = normalize(tangent);
                Vec3 bi = cross(ns, tangent);
                if (dot(bi, bitangent) < 0) bi = -1.0f * bi;
                Vec3 t = tex.sample(tu, tv, lod(tex)).rgb;
                Vec3 local{(2 * t.x - 1) * m.normalScale, (2 * t.y - 1) * m.normalScale,
                           2 * t.z - 1};
                Vec3 mapped = local.x * tangent + local.y * bi + local.z * ns;
                if (length(mapped) > 0) ns = normalize(mapped);
            }
        }
    }
    // Mesh emitters are one-sided: they emit on the side their winding faces.
    const bool front = dot(ng, d) < 0;
    // Two-sided surfaces: face both normals towards the viewer.
    if (!front) ng = -1.0f * ng;
    if (dot(ns, ng) < 0) ns = ns - 2 * dot(ns, ng) * ng;
    sp.ng = ng;
    sp.ns = ns;
    sp.wo = -1.0f * d;
    sp.baseColor = base;
    sp.diffuse = (1 - m.metallic) * base;
    sp.f0 = lerp(Vec3{m.specular, m.specular, m.specular}, base, m.metallic);
    sp.roughness = m.roughness;
    sp.alpha = std::fmax(m.roughness * m.roughness, 1e-3f);
    sp.emission = front ? m.emission : Vec3{0, 0, 0};
    sp.material = scene_.triangleMaterial[size_t(tri)];
    sp.triangle = tri;
}

bool Integrator::trace(Vec3 o, Vec3 d, float width, float spread, SurfacePoint& sp, int& quad,
                       float& t, uint64_t& rays) const {
    ++rays;
    RayHit h = accel_.intersect(o, d, 1e30f);
    float tq = 0;
    quad = lights_.intersectQuads(o, d, h.triangle >= 0 ? h.t : 1e30f, tq);
    if (quad >= 0) {
        const QuadLight& q = lights_.quads()[size_t(quad)];
        Vec3 n = normalize(cross(q.edgeU, q.edgeV));
        if (dot(n, d) > 0) n = -1.0f * n;
        t = tq;
        sp = SurfacePoint{};
        sp.p = o + tq * d, sp.ng = sp.ns = n, sp.wo = -1.0f * d;
        sp.baseColor = {1, 1, 1}, sp.emission = q.radiance, sp.roughness = 1, sp.alpha = 1;
        sp.material = int(scene_.materials.size()) + quad;
        return true;
    }
    if (h.triangle < 0) return false;
    t = h.t;
    shadeTriangle(h.triangle, h.u, h.v, d, width + spread * h.t, sp);
    return true;
}

PrimaryHit Integrator::primary(Vec3 origin, Vec3 direction, float spreadAngle,
                               uint64_t& rays) const {
    PrimaryHit ph;
    ph.origin = origin, ph.direction = direction, ph.spread = spreadAngle;
    float t = 0;
    ph.hit = trace(origin, direction, 0.0f, spreadAngle, ph.surface, ph.lightQuad, t, rays);
    return ph;
}

float Integrator::sunVisibility(const PrimaryHit& first, uint64_t& rays) const {
    const Sun& sun = lights_.environment().sun;
    if (!first.hit || !sun.enabled()) return 0.0f;
    const SurfacePoint& sp = first.surface;
    const float c = dot(sp.ns, sun.direction);
    // Below the geometric surface the shadow ray would start inside the object.
    if (c <= 0 || dot(sp.ng, sun.direction) <= 0) return 0.0f;
    ++rays;
    return accel_.occluded(sp.p + offsetScale(sp.p) * sp.ng, sun.direction, 1e30f) ? 0.0f : c;
}

PathContribution Integrator::sample(const PrimaryHit& first, Rng& rng, uint64_t& rays) const {
    PathContribution out;
    const Environment& env = lights_.environment();
    if (!first.hit) {
        Vec3 L = env.sky + lights_.sunRadiance(first.direction);
        out.total = out.direct = out.diffuse = L;
        return out;
    }
    SurfacePoint sp = first.surface;
    out.direct = out.diffuse = sp.emission; // emitters seen by the camera
    Vec3 tD{1, 1, 1}, tG{0, 0, 0};          // throughput through the primary diffuse / glossy lobe
    auto add = [&](int vertex, Vec3 radianceD, Vec3 radianceG) {
        // vertex 0: light reaching the primary hit (direct); later vertices: indirect.
        (vertex == 0 ? out.direct : out.indirect) += radianceD + radianceG;
        if (vertex > 0) out.diffuseIndirect += radianceD;
        out.diffuse += radianceD;
        out.glossy += radianceG;
    };
    float width = first.spread * length(sp.p - first.origin); // ray-cone footprint here
    for (int vertex = 0; vertex <= bounces_; ++vertex) {
        const bool last = vertex == bounces_;
        const bool reflective = !isBlack(sp.diffuse) || !isBlack(sp.f0);
        const Vec3 origin = sp.p + offsetScale(sp.p) * sp.ng;
        // The guides' share of the BSDF ray; at the last vertex none follows, and light
        // samples take weight 1 without reading its pdf.
        const float guided = last || !reflective ? 0.0f : guides_.share(sp.p, sp.ns);
        // Next event estimation: one sample per strategy (one, or local, sun and sky apart).
        // (With no lights the three numbers are still drawn, so paths keep their sequence.)
        for (int strategy = 0; strategy < std::max(1, lights_.strategies()); ++strategy) {
            const float uSel = rng.next(), u1 = rng.next(), u2 = rng.next();
            if (!reflective) continue;
            const LightSample ls = lights_.sample(strategy, sp.p, sp.ns, uSel, u1, u2);
            if (!(ls.pdf > 0)) continue;
            const BsdfValue f = guides_.eval(sp, ls.wi, guided);
            const float c = dot(sp.ns, ls.wi);
            if (isBlack(f.diffuse) && isBlack(f.glossy)) continue;
            ++rays;
            const float tMax =
                ls.distance >= 1e29f ? 1e30f : ls.distance * (1 - 1e-4f) - offsetScale(sp.p);
            if (accel_.occluded(origin, ls.wi, tMax)) continue;
            // At the last vertex no BSDF ray follows: light sampling takes it all.
            const float w = last ? 1.0f : powerHeuristic(ls.pdf, f.pdf);
            const Vec3 L = (c * w / ls.pdf) * ls.radiance;
            if (vertex == 0)
                add(0, f.diffuse * L, f.glossy * L);
            else
                add(vertex, tD * ((f.diffuse + f.glossy) * L), tG * ((f.diffuse + f.glossy) * L));
        }
        const float uLobe = rng.next(), b1 = rng.next(), b2 = rng.next();
        if (last || !reflective) break;
        // BSDF-sampled secondary ray.
        Vec3 wi;
        BsdfValue f;
        if (!guides_.sample(sp, guided, uLobe, b1, b2, wi, f)) break;
        const float c = dot(sp.ns, wi) / f.pdf;
        if (vertex == 0) {
            tD = c * f.diffuse;
            tG = c * f.glossy;
        } else {
            Vec3 k = c * (f.diffuse + f.glossy);
            tD = tD * k, tG = tG * k;
        }
        SurfacePoint next;
        int quad = -1;
        float t = 0;
        // Ray cones: a bounce widens the footprint by about the lobe width (GGX alpha, ~1 rad for
        // diffuse), so indirect hits read coarse mips: less aliasing and far fewer cache misses.
        const float spread = sp.alpha;
        if (!trace(origin, wi, width, spread, next, quad, t, rays)) {
            Vec3 sky, sun;
            float skyPdf, sunPdf;
            lights_.escaped(wi, sp.p, sp.ns, sky, skyPdf, sun, sunPdf);
            Vec3 L = powerHeuristic(f.pdf, skyPdf) * sky + powerHeuristic(f.pdf, sunPdf) * sun;
            add(vertex, tD * L, tG * L);
            break;
        }
        if (!isBlack(next.emission)) {
            float lightPdf = quad >= 0 ? lights_.pdfQuad(quad, sp.p, next.p)
                                       : lights_.pdfTriangle(next.triangle, sp.p, next.p);
            Vec3 L = powerHeuristic(f.pdf, lightPdf) * next.emission;
            add(vertex, tD * L, tG * L);
        }
        width += spread * t;
        sp = next;
    }
    out.total = out.direct + out.indirect;
    return out;
}

} // namespace bmfr::render
