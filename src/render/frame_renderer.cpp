#include "render/frame_renderer.h"
#include "core/stopwatch.h"
#include "temporal/reprojection.h"
#include <tbb/parallel_for.h>

namespace bmfr::render {

namespace {

float halton(int i, int base) {
    float f = 1, r = 0;
    for (; i > 0; i /= base) f /= float(base), r += f * float(i % base);
    return r;
}

/// Mara et al.'s sample at pixel i: writes the factorisation's buffers and returns the
/// splits as the frame's AOVs hold them (direct and indirect; diffuse and glossy are the
/// matte and glossy indirect terms; diffuse indirect the matte term).
PathContribution factoredSplits(const Integrator& integrator, const PrimaryHit& ph, Rng& rng,
                                long i, FrameData& out, uint64_t& rays, int directSpp,
                                float skyDistance) {
    const FactoredSample s = integrator.factoredSample(ph, directSpp, rng, rays);
    const Vec3 one{1, 1, 1}, m = one - s.fresnel, base = ph.hit ? ph.surface.baseColor : Vec3{};
    // albedo x M is the matte term: M is scaled by rho_L / albedo (1 - metallic in glTF).
    const Vec3 scale{base.x > 0 ? s.matteReflectance.x / base.x : 0.0f,
                     base.y > 0 ? s.matteReflectance.y / base.y : 0.0f,
                     base.z > 0 ? s.matteReflectance.z / base.z : 0.0f};
    store3(out.matteIndirect.data(), i, scale * s.matte);
    store3(out.glossyIndirect.data(), i, s.glossy);
    store3(out.directLight.data(), i, s.direct);
    store3(out.specularF0.data(), i, ph.hit ? ph.surface.f0 : Vec3{});
    out.roughness.data()[i] = ph.hit ? ph.surface.roughness : 1.0f;
    out.glossyHitDistance.data()[i] = s.glossyDistance >= 0 ? s.glossyDistance : skyDistance;
    PathContribution c;
    c.total = s.total();
    c.direct = s.emission + s.direct;
    c.diffuse = m * m * s.matteReflectance * s.matte;
    c.glossy = s.fresnel * s.glossy;
    c.indirect = c.diffuse + c.glossy;
    c.diffuseIndirect = c.diffuse;
    return c;
}

} // namespace

void frameJitter(int index, bool enabled, float jitter[2]) {
    jitter[0] = enabled ? halton(index + 1, 2) - 0.5f : 0.0f;
    jitter[1] = enabled ? halton(index + 1, 3) - 0.5f : 0.0f;
}

std::vector<std::string> FrameRenderer::extraNames() {
    return {"material_id", "roughness"};
}
std::vector<std::string> FrameRenderer::aovNames() {
    return {"depth", "direct", "indirect", "diffuse", "glossy"};
}

FrameRenderer::FrameRenderer(const Scene& scene, const RayAccel& accel, int width, int height,
                             int bounces, uint32_t seed)
    : scene_(&scene), accel_(&accel), width_(width), height_(height), bounces_(bounces),
      seed_(seed) {
    Vec3 lo, hi;
    scene.bounds(lo, hi);
    float diag = std::fmax(length(hi - lo), 1e-3f);
    zNear_ = 1e-3f * diag;
    // Escaped rays get a position a scene size away: far enough to read as background, near
    // enough not to squash the per-block feature scaling of the geometry beside them.
    skyDistance_ = 2.0f * diag;
    zFar_ = 10.0f * diag;
}

Mat4 FrameRenderer::viewProjectionOf(const CameraPose& pose) const {
    return viewProjection(pose, width_, height_, zNear_, zFar_);
}

bool FrameRenderer::render(int index, const CameraPose& pose, const CameraPose& previousPose,
                           bool hasPrevious, const LightSet& lights, bool jitterOn,
                           int referenceSpp, FrameData& out, FrameRenderStats& stats,
                           const std::atomic<bool>* cancel, const ObjectMotion* objects) const {
    const int w = width_, h = height_;
    out.viewProjection = viewProjectionOf(pose);
    frameJitter(index, jitterOn, out.jitter);
    Mat4 prevVp = viewProjectionOf(previousPose), inv;
    float prevJitter[2];
    frameJitter(index - 1, jitterOn, prevJitter);
    invert(out.viewProjection, inv);
    for (ImageF* img : {&out.color, &out.albedo, &out.normal, &out.position}) img->resize(w, h, 3);
    out.extras.assign(2, ImageF(w, h, 1));
    out.aovs.clear();
    for (const std::string& n : aovNames())
        out.aovs.emplace_back(n, ImageF(w, h, n == "depth" ? 1 : 3));
    out.motion = ImageF(w, h, 3);
    out.diffuseIndirect = ImageF(w, h, 3);
    out.previousPosition = objects ? ImageF(w, h, 3) : ImageF();
    out.previousNormal = objects ? ImageF(w, h, 3) : ImageF();
    out.reference = referenceSpp > 0 ? ImageF(w, h, 3) : ImageF();
    out.emission = ImageF(w, h, 3);
    const bool sunlit = lights.environment().sun.enabled();
    out.visibility = sunlit ? ImageF(w, h, 1) : ImageF();
    const bool factored = factoredDirectSpp_ > 0;
    for (ImageF* img : {&out.matteIndirect, &out.glossyIndirect, &out.directLight, &out.specularF0,
                        &out.roughness, &out.glossyHitDistance})
        *img = factored
                   ? ImageF(w, h, img == &out.roughness || img == &out.glossyHitDistance ? 1 : 3)
                   : ImageF();

    const Integrator integrator(*scene_, *accel_, lights, bounces_);
    const float spread = 2.0f * std::tan(0.5f * pose.fovY) / float(h);
    const Vec3 forward = normalize(pose.target - pose.position);
    const Vec3 prevForward = normalize(previousPose.target - previousPose.position);
    std::atomic<uint64_t> rays{0};
    std::atomic<bool> stopped{false};
    Stopwatch clock;
    double referenceSeconds = 0;

    auto rowLoop = [&](bool reference) {
        tbb::parallel_for(0, h, [&](int y) {
            if (stopped || (cancel && *cancel)) {
                stopped = true;
                return;
            }
            uint64_t localRays = 0;
            for (int x = 0; x < w; ++x) {
                const long i = long(y) * w + x;
                const float sx = (float(x) + 0.5f + out.jitter[0]) / float(w) * 2 - 1;
                const float sy = (float(y) + 0.5f + out.jitter[1]) / float(h) * 2 - 1;
                Vec4 a = transformPoint(inv, {sx, sy, -1}), b = transformPoint(inv, {sx, sy, 1});
                Vec3 far{b.x / b.w, b.y / b.w, b.z / b.w}, near{a.x / a.w, a.y / a.w, a.z / a.w};
                const Vec3 dir = normalize(far - near);
                PrimaryHit ph = integrator.primary(pose.position, dir, spread, localRays);
                if (reference) {
                    Vec3 sum{};
                    for (int s = 1; s <= referenceSpp; ++s) {
                        Rng rng(uint32_t(i), uint32_t(index), uint32_t(s), seed_);
                        if (factored) {
                            sum += integrator.factoredSample(ph, 1, rng, localRays).total();
                            continue;
                        }
                        const PathContribution c = integrator.sample(ph, rng, localRays);
                        sum += diffuseIndirectOnly_ ? c.diffuseIndirect : c.total;
                    }
                    store3(out.reference.data(), i, sum / float(referenceSpp));
                    continue;
                }
                Rng rng(uint32_t(i), uint32_t(index), 0u, seed_);
                PathContribution c = factored
                                         ? factoredSplits(integrator, ph, rng, i, out, localRays,
                                                          factoredDirectSpp_, skyDistance_)
                                         : integrator.sample(ph, rng, localRays);
                store3(out.color.data(), i, diffuseIndirectOnly_ ? c.diffuseIndirect : c.total);
                store3(out.aovs[1].second.data(), i, c.direct);
                store3(out.aovs[2].second.data(), i, c.indirect);
                store3(out.aovs[3].second.data(), i, c.diffuse);
                store3(out.aovs[4].second.data(), i, c.glossy);
                const SurfacePoint& s = ph.surface;
                // Demodulated, so that albedo * diffuse_indirect is the split itself.
                const Vec3 base = ph.hit ? s.baseColor : Vec3{};
                store3(out.diffuseIndirect.data(), i,
                       {base.x > 0 ? c.diffuseIndirect.x / base.x : 0.0f,
                        base.y > 0 ? c.diffuseIndirect.y / base.y : 0.0f,
                        base.z > 0 ? c.diffuseIndirect.z / base.z : 0.0f});
                Vec3 p = ph.hit ? s.p : pose.position + skyDistance_ * dir;
                store3(out.albedo.data(), i, ph.hit ? s.baseColor : Vec3{1, 1, 1});
                store3(out.emission.data(), i,
                       diffuseIndirectOnly_ ? Vec3{}
                       : ph.hit             ? s.emission
                                            : lights.environment().sky + lights.sunRadiance(dir));
                store3(out.normal.data(), i, ph.hit ? s.ns : -1.0f * dir);
                store3(out.position.data(), i, p);
                out.extras[0].data()[i] = ph.hit ? float(s.material) : -1.0f;
                out.extras[1].data()[i] = ph.hit ? s.roughness : 1.0f;
                if (sunlit) out.visibility.data()[i] = integrator.sunVisibility(ph, localRays);
                out.aovs[0].second.data()[i] = dot(p - pose.position, forward);
                // Where this point was a frame ago: objects carry it, the sky stays put.
                Vec3 pp = p, pn = ph.hit ? s.ns : -1.0f * dir;
                if (objects && ph.hit && s.triangle >= 0) {
                    const size_t o = size_t(scene_->triangleObject[size_t(s.triangle)]);
                    const Vec4 q = transformPoint(objects->points[o], p);
                    pp = {q.x, q.y, q.z};
                    const Vec3 n = transformVector(objects->normals[o], pn);
                    if (length(n) > 0) pn = normalize(n);
                }
                if (objects) {
                    store3(out.previousPosition.data(), i, pp);
                    store3(out.previousNormal.data(), i, pn);
                }
                // Off every image when the previous camera did not see the point.
                Vec2 prev{float(x), float(y)}, at;
                if (hasPrevious)
                    prev =
                        projectToPixel(prevVp, pp, prevJitter, w, h, at) ? at : Vec2{-1e6f, -1e6f};
                out.motion.data()[3 * i] = prev.x - float(x);
                out.motion.data()[3 * i + 1] = prev.y - float(y);
                // The depth offset: view depth a frame ago minus now (WALR's depth test).
                out.motion.data()[3 * i + 2] = hasPrevious
                                                   ? dot(pp - previousPose.position, prevForward) -
                                                         out.aovs[0].second.data()[i]
                                                   : 0.0f;
            }
            rays += localRays;
        });
    };
    rowLoop(false);
    stats.inputSeconds = clock.lap() / 1000.0;
    if (referenceSpp > 0 && !stopped) {
        rowLoop(true);
        referenceSeconds = clock.lap() / 1000.0;
    }
    stats.referenceSeconds = referenceSeconds;
    stats.rays = rays;
    return !stopped;
}

} // namespace bmfr::render
