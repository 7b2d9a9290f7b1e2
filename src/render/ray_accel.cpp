#include "render/ray_accel.h"
#include <bmfr/error.h>
#include <cmath>
#include <embree3/rtcore.h>
#include <vector>

namespace bmfr::render {

struct AlphaContext;

struct RayAccel::Impl {
    const Scene* scene = nullptr;
    RTCDevice device = nullptr;
    RTCScene rtc = nullptr;
    std::vector<std::vector<int>> geometryTriangles; ///< [geomID][primID] -> scene triangle
    std::vector<std::unique_ptr<struct AlphaContext>> alphaContexts;

    float alphaAt(int tri, float u, float v) const {
        const Material& m = scene->materials[size_t(scene->triangleMaterial[size_t(tri)])];
        if (m.baseColorTexture < 0) return 1.0f;
        const Vec2f* uv = &scene->uvs[3 * size_t(tri)];
        float w = 1 - u - v;
        return scene->textures[size_t(m.baseColorTexture)].alphaNearest(
            w * uv[0].x + u * uv[1].x + v * uv[2].x, w * uv[0].y + u * uv[1].y + v * uv[2].y);
    }
};

struct AlphaContext {
    const RayAccel::Impl* impl;
    unsigned geomID;
};

namespace {

void alphaFilter(const RTCFilterFunctionNArguments* args) {
    auto* ctx = static_cast<const AlphaContext*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        unsigned prim = RTCHitN_primID(args->hit, args->N, i);
        int tri = ctx->impl->geometryTriangles[ctx->geomID][prim];
        const Material& m =
            ctx->impl->scene->materials[size_t(ctx->impl->scene->triangleMaterial[size_t(tri)])];
        if (ctx->impl->alphaAt(tri, RTCHitN_u(args->hit, args->N, i),
                               RTCHitN_v(args->hit, args->N, i)) < m.alphaCutoff)
            args->valid[i] = 0;
    }
}

} // namespace

RayAccel::RayAccel(const Scene& scene) : impl_(std::make_unique<Impl>()) {
    Impl& m = *impl_;
    m.scene = &scene;
    m.device = rtcNewDevice(nullptr);
    if (!m.device) throw Error("Embree: cannot create a device");
    m.rtc = rtcNewScene(m.device);
    rtcSetSceneBuildQuality(m.rtc, RTC_BUILD_QUALITY_HIGH); // built once, traced millions of times
    std::vector<int> opaque, masked;
    for (size_t t = 0; t < scene.triangleCount(); ++t)
        (scene.materials[size_t(scene.triangleMaterial[t])].alphaMask ? masked : opaque)
            .push_back(int(t));
    for (int pass = 0; pass < 2; ++pass) {
        const std::vector<int>& tris = pass == 0 ? opaque : masked;
        if (tris.empty()) continue;
        RTCGeometry g = rtcNewGeometry(m.device, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
            g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), tris.size() * 3));
        auto* ix = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
            g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), tris.size()));
        for (size_t k = 0; k < tris.size(); ++k)
            for (int j = 0; j < 3; ++j) {
                Vec3 p = scene.positions[3 * size_t(tris[k]) + size_t(j)];
                v[9 * k + 3 * size_t(j)] = p.x;
                v[9 * k + 3 * size_t(j) + 1] = p.y;
                v[9 * k + 3 * size_t(j) + 2] = p.z;
                ix[3 * k + size_t(j)] = unsigned(3 * k + size_t(j));
            }
        const unsigned id = unsigned(m.geometryTriangles.size());
        if (pass == 1) {
            m.alphaContexts.push_back(std::make_unique<AlphaContext>(AlphaContext{&m, id}));
            rtcSetGeometryUserData(g, m.alphaContexts.back().get());
            rtcSetGeometryIntersectFilterFunction(g, alphaFilter);
            rtcSetGeometryOccludedFilterFunction(g, alphaFilter);
        }
        rtcCommitGeometry(g);
        rtcAttachGeometryByID(m.rtc, g, id);
        rtcReleaseGeometry(g);
        m.geometryTriangles.push_back(tris);
    }
    rtcCommitScene(m.rtc);
    // Checked here rather than thrown from an Embree callback (no exceptions through C frames).
    if (RTCError e = rtcGetDeviceError(m.device); e != RTC_ERROR_NONE)
        throw Error("Embree failed to build the scene (error " + std::to_string(int(e)) + ")");
}

RayAccel::~RayAccel() {
    if (impl_->rtc) rtcReleaseScene(impl_->rtc);
    if (impl_->device) rtcReleaseDevice(impl_->device);
}

RayHit RayAccel::intersect(Vec3 o, Vec3 d, float tMax) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh{};
    rh.ray.org_x = o.x, rh.ray.org_y = o.y, rh.ray.org_z = o.z;
    rh.ray.dir_x = d.x, rh.ray.dir_y = d.y, rh.ray.dir_z = d.z;
    rh.ray.tnear = 0, rh.ray.tfar = tMax, rh.ray.mask = 0xffffffffu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(impl_->rtc, &ctx, &rh);
    RayHit h;
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return h;
    h.t = rh.ray.tfar;
    h.triangle = impl_->geometryTriangles[rh.hit.geomID][rh.hit.primID];
    h.u = rh.hit.u, h.v = rh.hit.v;
    return h;
}

bool RayAccel::occluded(Vec3 o, Vec3 d, float tMax) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRay r{};
    r.org_x = o.x, r.org_y = o.y, r.org_z = o.z;
    r.dir_x = d.x, r.dir_y = d.y, r.dir_z = d.z;
    r.tnear = 0, r.tfar = tMax, r.mask = 0xffffffffu;
    rtcOccluded1(impl_->rtc, &ctx, &r);
    return r.tfar < 0;
}

} // namespace bmfr::render
