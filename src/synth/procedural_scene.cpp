#include "synth/procedural_scene.h"
#include "core/hash.h"
#include "core/mat4.h"
#include "temporal/reprojection.h"
#include <bmfr/error.h>
#include <cmath>
#include <tbb/parallel_for.h>

namespace bmfr {

namespace {

struct Hit {
    float t = INFINITY;
    Vec3 n;
    int material = 0;
};

constexpr float kRoom = 5.0f, kCeiling = 4.0f;
const Vec3 kSphereCentre{1.2f, 1.0f, -0.2f};
constexpr float kSphereRadius = 1.0f;
const Vec3 kBoxLo{-2.2f, 0.0f, -1.8f}, kBoxHi{-0.8f, 1.6f, -0.4f};
const Vec3 kBoxCentre = 0.5f * (kBoxLo + kBoxHi);

/// Where the moving objects are at one time: the sphere's centre and the box's turn about
/// the vertical axis through its centre.
struct Objects {
    Vec3 sphereCentre = kSphereCentre;
    float boxAngle = 0.0f; ///< radians
};

Objects objectsAt(float t) {
    return {kSphereCentre + Vec3{0.05f * t, 0.0f, 0.0f}, 0.04f * t};
}

/// Rotation about the vertical axis by `angle` radians.
Vec3 turnY(Vec3 v, float angle) {
    const float c = std::cos(angle), s = std::sin(angle);
    return {c * v.x + s * v.z, v.y, -s * v.x + c * v.z};
}
const Vec3 kLights[2] = {{0.3f, 3.6f, 1.5f}, {-3.5f, 2.2f, 3.5f}};
const Vec3 kLightPower[2] = {{9.0f, 8.5f, 8.0f}, {2.0f, 2.4f, 3.0f}};

void hitSphere(const Objects& s, Vec3 o, Vec3 d, Hit& h) {
    Vec3 oc = o - s.sphereCentre;
    float b = dot(oc, d), c = dot(oc, oc) - kSphereRadius * kSphereRadius;
    float disc = b * b - c;
    if (disc < 0) return;
    float t = -b - std::sqrt(disc);
    if (t > 1e-4f && t < h.t) h = {t, normalize(o + t * d - s.sphereCentre), 7};
}

void hitBox(const Objects& objects, Vec3 wo, Vec3 wd, Hit& h) {
    // In the box's own frame, where it is axis-aligned.
    const Vec3 o =
        objects.boxAngle == 0.0f ? wo : kBoxCentre + turnY(wo - kBoxCentre, -objects.boxAngle);
    const Vec3 d = objects.boxAngle == 0.0f ? wd : turnY(wd, -objects.boxAngle);
    float t0 = 1e-4f, t1 = h.t;
    int axis = -1;
    float sign = 0;
    for (int a = 0; a < 3; ++a) {
        float inv = 1.0f / d[a];
        float ta = (kBoxLo[a] - o[a]) * inv, tb = (kBoxHi[a] - o[a]) * inv;
        float s = -1;
        if (ta > tb) std::swap(ta, tb), s = 1;
        if (ta > t0) t0 = ta, axis = a, sign = s;
        t1 = std::fmin(t1, tb);
        if (t0 > t1) return;
    }
    if (axis < 0) return;
    Vec3 n{};
    (axis == 0 ? n.x : axis == 1 ? n.y : n.z) = sign;
    h = {t0, objects.boxAngle == 0.0f ? n : turnY(n, objects.boxAngle), 8};
}

void hitRoom(Vec3 o, Vec3 d, Hit& h) {
    // Interior of the box [-R, R] x [0, C] x [-R, R]; normals face inwards.
    struct Plane {
        int axis;
        float at;
        float normal;
        int material;
    };
    const Plane planes[6] = {{1, 0, 1, 1},      {1, kCeiling, -1, 2}, {0, -kRoom, 1, 3},
                             {0, kRoom, -1, 4}, {2, -kRoom, 1, 5},    {2, kRoom, -1, 6}};
    for (const Plane& p : planes) {
        float t = (p.at - o[p.axis]) / d[p.axis];
        if (t > 1e-4f && t < h.t) {
            Vec3 n{};
            (p.axis == 0 ? n.x : p.axis == 1 ? n.y : n.z) = p.normal;
            h = {t, n, p.material};
        }
    }
}

Hit trace(const Objects& s, Vec3 o, Vec3 d) {
    Hit h;
    hitRoom(o, d, h);
    hitSphere(s, o, d, h);
    hitBox(s, o, d, h);
    return h;
}

bool occluded(const Objects& s, Vec3 p, Vec3 light) {
    Vec3 d = light - p;
    float dist = length(d);
    d = d / dist;
    Hit h;
    h.t = dist;
    hitSphere(s, p, d, h);
    hitBox(s, p, d, h);
    return h.t < dist;
}

Vec3 albedoOf(int material, Vec3 p) {
    switch (material) {
    case 1: { // floor: 1 m checker
        int c = (int(std::floor(p.x)) + int(std::floor(p.z))) & 1;
        return c ? Vec3{0.75f, 0.72f, 0.65f} : Vec3{0.25f, 0.22f, 0.2f};
    }
    case 3:
        return {0.7f, 0.15f, 0.12f};
    case 4:
        return {0.15f, 0.6f, 0.2f};
    case 7:
        return {0.9f, 0.9f, 0.9f};
    case 8:
        return {0.45f, 0.5f, 0.85f};
    default:
        return {0.7f, 0.7f, 0.7f};
    }
}

/// Light k's cosine at p where it is unshadowed, else 0 (light 0's is FrameInput::visibility).
float litCosine(const Objects& s, Vec3 p, Vec3 n, int k) {
    const Vec3 l = kLights[k] - p;
    const float cosine = dot(n, l) / length(l);
    return cosine <= 0 || occluded(s, p + 1e-3f * n, kLights[k]) ? 0.0f : cosine;
}

/// Demodulated outgoing radiance: direct light from both lights plus a smooth ambient term.
Vec3 irradiance(const Objects& s, Vec3 p, Vec3 n) {
    Vec3 e = (0.04f + 0.03f * n.y) * Vec3{1, 1, 1};
    for (int k = 0; k < 2; ++k) {
        const Vec3 l = kLights[k] - p;
        e += (litCosine(s, p, n, k) / dot(l, l)) * kLightPower[k];
    }
    return e;
}

float halton(int i, int base) {
    float f = 1, r = 0;
    for (; i > 0; i /= base) f /= float(base), r += f * float(i % base);
    return r;
}

} // namespace

ProceduralScene::ProceduralScene(const ProceduralSceneOptions& o) : opt_(o) {
    if (o.width < 1 || o.height < 1 || o.width > 16384 || o.height > 16384)
        throw Error("procedural scene: size " + std::to_string(o.width) + "x" +
                    std::to_string(o.height) + " outside [1, 16384]");
    if (o.frames < 1 || o.frames > 100000)
        throw Error("procedural scene: frames " + std::to_string(o.frames) +
                    " outside [1, 100000]");
    if (!std::isfinite(o.cameraSpeed) || std::fabs(o.cameraSpeed) > 1000.0f)
        throw Error("procedural scene: camera speed must be a finite number in [-1000, 1000]");
    if (!std::isfinite(o.objectSpeed) || std::fabs(o.objectSpeed) > 100.0f)
        throw Error("procedural scene: object speed must be a finite number in [-100, 100]");
}

SequenceInfo ProceduralScene::info() const {
    SequenceInfo s;
    s.layout = "manifest";
    s.frameCount = opt_.frames;
    s.width = opt_.width;
    s.height = opt_.height;
    s.hasReference = true;
    s.positionLimitSquared = 0.01f;
    s.normalLimitSquared = 1.0f;
    s.extraNames = {"material_id"};
    return s;
}

namespace {

/// The camera of frame `index` (any integer: -1 is the frame before the first).
struct Camera {
    Vec3 eye;
    Mat4 viewProjection;
    float jitter[2];
};

Camera cameraOf(const ProceduralSceneOptions& o, int index) {
    const float t = float(index) * o.cameraSpeed;
    Camera c;
    c.eye = {-2.6f + 0.09f * t, 1.9f - 0.01f * t, 4.3f - 0.03f * t};
    const Vec3 target{0.0f + 0.03f * t, 0.9f, -0.5f};
    c.viewProjection =
        multiply(perspectiveYDown(1.05f, float(o.width) / float(o.height), 0.05f, 50.0f),
                 lookAt(c.eye, target, {0, 1, 0}));
    c.jitter[0] = o.jitter ? halton(index + 1, 2) - 0.5f : 0.0f;
    c.jitter[1] = o.jitter ? halton(index + 1, 3) - 0.5f : 0.0f;
    return c;
}

/// Where the point p (normal n) of `material` was in the previous frame, objects moving from
/// `was` to `now`; the room does not move.
void previousOf(int material, Vec3 p, Vec3 n, const Objects& now, const Objects& was, Vec3& pp,
                Vec3& pn) {
    pp = p, pn = n;
    if (material == 7) {
        pp = p - (now.sphereCentre - was.sphereCentre);
    } else if (material == 8) {
        const float turn = was.boxAngle - now.boxAngle;
        pp = kBoxCentre + turnY(p - kBoxCentre, turn);
        pn = turnY(n, turn);
    }
}

} // namespace

void ProceduralScene::render(int index, FrameData& f, int previous) const {
    const int w = opt_.width, h = opt_.height;
    const Camera cam = cameraOf(opt_, index), prevCam = cameraOf(opt_, previous);
    const Objects now = objectsAt(float(index) * opt_.objectSpeed);
    const Objects was = objectsAt(float(previous) * opt_.objectSpeed);
    const Vec3 eye = cam.eye;
    Mat4 inv;
    invert(cam.viewProjection, inv);
    f.viewProjection = cam.viewProjection;
    f.jitter[0] = cam.jitter[0], f.jitter[1] = cam.jitter[1];
    for (ImageF* img : {&f.color, &f.albedo, &f.normal, &f.position, &f.reference})
        img->resize(w, h, 3);
    f.extras.assign(1, ImageF(w, h, 1));
    f.visibility = ImageF(w, h, 1);
    f.motion = f.previousPosition = f.previousNormal = ImageF();
    if (opt_.motionVectors) {
        f.motion.resize(w, h, 2);
        f.previousPosition.resize(w, h, 3);
        f.previousNormal.resize(w, h, 3);
    }

    tbb::parallel_for(0, h, [&](int y) {
        for (int x = 0; x < w; ++x) {
            const float sx = (float(x) + 0.5f + f.jitter[0]) / float(w) * 2.0f - 1.0f;
            const float sy = (float(y) + 0.5f + f.jitter[1]) / float(h) * 2.0f - 1.0f;
            Vec4 a = transformPoint(inv, {sx, sy, -1.0f}), b = transformPoint(inv, {sx, sy, 1.0f});
            Vec3 pa{a.x / a.w, a.y / a.w, a.z / a.w}, pb{b.x / b.w, b.y / b.w, b.z / b.w};
            Vec3 d = normalize(pb - pa);
            Hit hit = trace(now, eye, d);
            Vec3 p = eye + hit.t * d;
            Vec3 alb = albedoOf(hit.material, p);
            Vec3 truth = alb * irradiance(now, p, hit.n);
            const long i = long(y) * w + x;
            // Unit-mean exponential noise shared by the channels, with a little chroma noise.
            uint32_t key = hashKeys(opt_.seed, uint32_t(index), uint32_t(i));
            float u = unitFloat(key);
            float common = -std::log(1.0f - u);
            Vec3 chroma{0.75f + 0.5f * unitFloat(wangHash(key + 1)),
                        0.75f + 0.5f * unitFloat(wangHash(key + 2)),
                        0.75f + 0.5f * unitFloat(wangHash(key + 3))};
            store3(f.color.data(), i, common * (truth * chroma));
            store3(f.reference.data(), i, truth);
            store3(f.albedo.data(), i, alb);
            store3(f.normal.data(), i, hit.n);
            store3(f.position.data(), i, p);
            f.extras[0].data()[i] = float(hit.material);
            f.visibility.data()[i] = litCosine(now, p, hit.n, 0);
            if (opt_.motionVectors) {
                Vec3 pp, pn;
                previousOf(hit.material, p, hit.n, now, was, pp, pn);
                store3(f.previousPosition.data(), i, pp);
                store3(f.previousNormal.data(), i, pn);
                Vec2 prev{-1e6f, -1e6f}, at; // behind the previous camera: off every image
                if (projectToPixel(prevCam.viewProjection, pp, prevCam.jitter, w, h, at)) prev = at;
                f.motion.data()[2 * i] = prev.x - float(x);
                f.motion.data()[2 * i + 1] = prev.y - float(y);
            }
        }
    });
}

} // namespace bmfr
