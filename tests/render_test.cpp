// The path tracer against analytic answers: white furnace, Lambertian plane under a distant
// light, unbiasedness of the 1-spp estimator, and feature buffers of a known camera and plane.
#include "render/frame_renderer.h"
#include "temporal/reprojection.h"
#include <cmath>
#include <gtest/gtest.h>

namespace bmfr::render {
namespace {

int addMaterial(Scene& s, Vec3 albedo, Vec3 emission) {
    Material m;
    m.baseColor = albedo, m.emission = emission, m.roughness = 1, m.specular = 0;
    s.materials.push_back(m);
    return int(s.materials.size() - 1);
}

/// Adds a quad wound so that its front faces `towards` (emitters are one-sided).
void addQuad(Scene& s, Vec3 a, Vec3 b, Vec3 c, Vec3 d, int m, Vec3 towards = {0, 0, 0}) {
    Vec3 n = cross(b - a, c - a), centre = 0.25f * (a + b + c + d);
    if (dot(n, towards - centre) < 0) std::swap(b, d);
    s.addTriangle(a, b, c, m);
    s.addTriangle(a, c, d, m);
}

Scene closedBox(float albedo, float emission) {
    Scene s;
    int m = addMaterial(s, {albedo, albedo, albedo}, {emission, emission, emission});
    Vec3 p[8];
    for (int i = 0; i < 8; ++i) p[i] = {i & 1 ? 1.f : -1.f, i & 2 ? 1.f : -1.f, i & 4 ? 1.f : -1.f};
    addQuad(s, p[0], p[1], p[3], p[2], m);
    addQuad(s, p[4], p[6], p[7], p[5], m);
    addQuad(s, p[0], p[4], p[5], p[1], m);
    addQuad(s, p[2], p[3], p[7], p[6], m);
    addQuad(s, p[0], p[2], p[6], p[4], m);
    addQuad(s, p[1], p[5], p[7], p[3], m);
    return s;
}

double meanOf(const ImageF& img) {
    double s = 0;
    for (float v : img.pixels) s += v;
    return s / double(img.pixels.size());
}

FrameData renderOnce(const Scene& scene, const CameraPose& pose, const Environment& env, int w,
                     int h, int bounces, int refSpp, int frame = 0,
                     const CameraPose* previous = nullptr, int factoredDirectSpp = 0,
                     LightSampling sampling = LightSampling::One) {
    RayAccel accel(scene);
    LightSet lights(scene, {}, env, sampling);
    FrameRenderer r(scene, accel, w, h, bounces, 7);
    if (factoredDirectSpp) r.setFactoredPaths(factoredDirectSpp);
    FrameData out;
    FrameRenderStats stats;
    EXPECT_TRUE(r.render(frame, pose, previous ? *previous : pose, previous != nullptr, lights,
                         false, refSpp, out, stats, nullptr));
    return out;
}

TEST(Render, WhiteFurnaceMatchesTheTruncatedNeumannSeries) {
    // Inside a closed Lambertian box emitting Le everywhere with albedo a, a path with B
    // secondary rays and a light sample at its last vertex sees Le * sum_{k=0}^{B+1} a^k.
    const float a = 0.5f, Le = 1.0f;
    Scene box = closedBox(a, Le);
    CameraPose pose;
    pose.position = {0.1f, -0.2f, 0.3f}, pose.target = {0.5f, 0.1f, -1.0f}, pose.fovY = 1.2f;
    for (int bounces : {0, 1, 3}) {
        FrameData f = renderOnce(box, pose, {}, 12, 10, bounces, 512);
        double expected = 0;
        for (int k = 0; k <= bounces + 1; ++k) expected += Le * std::pow(a, k);
        EXPECT_NEAR(meanOf(f.reference), expected, 0.01 * expected) << bounces << " bounces";
    }
}

TEST(Render, LambertianPlaneUnderTheSunMatchesAnalyticIrradiance) {
    Scene plane;
    const float albedo = 0.6f;
    int m = addMaterial(plane, {albedo, albedo, albedo}, {0, 0, 0});
    addQuad(plane, {-100, 0, -100}, {-100, 0, 100}, {100, 0, 100}, {100, 0, -100}, m);
    Environment env;
    const float theta = 1.0471976f; // 60 degrees from the normal
    env.sun.direction = {std::sin(theta), std::cos(theta), 0};
    env.sun.irradiance = {2, 2, 2};
    env.sun.angularDiameter = 0.00930f;
    CameraPose pose;
    pose.position = {0, 3, 2}, pose.target = {0, 0, 0}, pose.fovY = 0.5f;
    FrameData f = renderOnce(plane, pose, env, 16, 12, 1, 64);
    const double expected = albedo / 3.14159265 * 2.0 * std::cos(theta);
    for (float v : f.reference.pixels) ASSERT_NEAR(v, expected, 0.01 * expected);
    // The 1-spp frame is exact too here: the light sample alone carries it.
    EXPECT_NEAR(meanOf(f.color), expected, 0.01 * expected);
    // And its splits: all direct, all diffuse.
    EXPECT_NEAR(meanOf(f.aovs[1].second), expected, 0.01 * expected);
    EXPECT_NEAR(meanOf(f.aovs[2].second), 0.0, 1e-9);
}

TEST(Render, SunAndSkySampledApartMatchTheAnalyticIrradiance) {
    // A Lambertian plane under the sun and a constant sky: E = E_sun cos(theta) + pi L_sky, so
    // L = albedo / pi * E. Both samplings must get it, the 1-spp frame within its noise; sampled
    // apart, every pixel sees the sun and none is black.
    Scene plane;
    const float albedo = 0.6f;
    int m = addMaterial(plane, {albedo, albedo, albedo}, {0, 0, 0});
    addQuad(plane, {-100, 0, -100}, {-100, 0, 100}, {100, 0, 100}, {100, 0, -100}, m);
    Environment env;
    const float theta = 0.5f;
    env.sun.direction = {std::sin(theta), std::cos(theta), 0};
    env.sun.irradiance = {2, 2, 2};
    env.sky = {0.3f, 0.3f, 0.3f};
    CameraPose pose;
    pose.position = {0, 3, 2}, pose.target = {0, 0, 0}, pose.fovY = 0.5f;
    const double expected = albedo / 3.14159265 * (2.0 * std::cos(theta) + 3.14159265 * 0.3);
    for (LightSampling sampling : {LightSampling::One, LightSampling::Split}) {
        const char* name = sampling == LightSampling::One ? "one" : "split";
        FrameData f = renderOnce(plane, pose, env, 32, 24, 1, 256, 0, nullptr, 0, sampling);
        EXPECT_NEAR(meanOf(f.reference), expected, 0.01 * expected) << name;
        EXPECT_NEAR(meanOf(f.color), expected, 0.05 * expected) << name;
        if (sampling == LightSampling::Split) {
            for (float v : f.color.pixels) ASSERT_GT(v, 0.0f) << name;
        }
    }
}

TEST(Render, OneSppMeanEqualsTheReferenceWithinTheNoise) {
    Scene box = builtinCornellBox();
    CameraPose pose;
    pose.position = {0, 1, 3.4f}, pose.target = {0, 1, 0}, pose.fovY = 0.69f;
    const int w = 24, h = 18, frames = 300;
    RayAccel accel(box);
    LightSet lights(box, {}, {});
    FrameRenderer r(box, accel, w, h, 1, 3);
    FrameData ref, f;
    FrameRenderStats stats;
    ASSERT_TRUE(r.render(0, pose, pose, false, lights, false, 2048, ref, stats, nullptr));
    std::vector<double> sum(size_t(w) * h * 3, 0.0), sum2(sum.size(), 0.0);
    for (int k = 1; k <= frames; ++k) { // different frame index = different random numbers
        ASSERT_TRUE(r.render(k, pose, pose, false, lights, false, 0, f, stats, nullptr));
        for (size_t i = 0; i < sum.size(); ++i)
            sum[i] += f.color.pixels[i], sum2[i] += double(f.color.pixels[i]) * f.color.pixels[i];
    }
    // Compare 6x6-pixel tiles: mean of the 1-spp frames vs the reference, in standard errors.
    double worst = 0;
    for (int ty = 0; ty < h; ty += 6)
        for (int tx = 0; tx < w; tx += 6) {
            double m = 0, v = 0, refMean = 0;
            int n = 0;
            for (int y = ty; y < ty + 6; ++y)
                for (int x = tx; x < tx + 6; ++x)
                    for (int c = 0; c < 3; ++c, ++n) {
                        size_t i = (size_t(y) * w + x) * 3 + size_t(c);
                        double mean = sum[i] / frames;
                        m += mean;
                        v += (sum2[i] / frames - mean * mean) / frames;
                        refMean += ref.reference.pixels[i];
                    }
            double se = std::sqrt(v * (1.0 + double(frames) / 2048.0)) + 1e-6;
            worst = std::max(worst, std::fabs(m - refMean) / se);
        }
    EXPECT_LT(worst, 4.5) << "largest tile deviation in standard errors";
}

TEST(Render, FeatureBuffersMatchAKnownCameraAndPlane) {
    Scene wall;
    int m = addMaterial(wall, {0.3f, 0.5f, 0.7f}, {0, 0, 0});
    addQuad(wall, {-50, -50, -5}, {50, -50, -5}, {50, 50, -5}, {-50, 50, -5}, m);
    Environment env;
    env.sky = {1, 1, 1};
    CameraPose pose;
    pose.position = {0, 0, 0}, pose.target = {0, 0, -1}, pose.fovY = 1.5707963f;
    const int w = 32, h = 24;
    FrameData f = renderOnce(wall, pose, env, w, h, 1, 0);
    const double tanHalf = 1.0; // tan(45 degrees)
    const double aspect = double(w) / h;
    for (int y = 0; y < h; y += 5)
        for (int x = 0; x < w; x += 3) {
            // Ray through the pixel centre, written out by hand: rows grow downwards.
            double sx = ((x + 0.5) / w * 2 - 1) * tanHalf * aspect,
                   sy = -((y + 0.5) / h * 2 - 1) * tanHalf;
            double px = sx * 5, py = sy * 5, pz = -5;
            EXPECT_NEAR(f.position.at(x, y, 0), px, 1e-3);
            EXPECT_NEAR(f.position.at(x, y, 1), py, 1e-3);
            EXPECT_NEAR(f.position.at(x, y, 2), pz, 1e-3);
            EXPECT_NEAR(f.normal.at(x, y, 2), 1.0, 1e-6);
            EXPECT_NEAR(f.albedo.at(x, y, 1), 0.5, 1e-6);
            EXPECT_NEAR(f.aovs[0].second.at(x, y), 5.0, 1e-3); // depth along the view axis
            EXPECT_EQ(f.extras[0].at(x, y), 0.0f);             // material id
        }
}

TEST(Render, WorldPositionReprojectsToThePixelItsMotionVectorNames) {
    Scene wall;
    int m = addMaterial(wall, {0.5f, 0.5f, 0.5f}, {0, 0, 0});
    addQuad(wall, {-50, -50, -5}, {50, -50, -5}, {50, 50, -5}, {-50, 50, -5}, m);
    Environment env;
    env.sky = {1, 1, 1};
    CameraPose a, b;
    a.position = {0, 0, 0}, a.target = {0, 0, -1}, a.fovY = 1.2f;
    b = a;
    b.position = {0.3f, 0.1f, 0.2f}, b.target = {0.35f, 0.1f, -0.8f};
    const int w = 40, h = 30;
    FrameData f0 = renderOnce(wall, a, env, w, h, 1, 0, 0);
    FrameData f1 = renderOnce(wall, b, env, w, h, 1, 0, 1, &a);
    int checked = 0;
    for (int y = 2; y < h - 2; ++y)
        for (int x = 2; x < w - 2; ++x) {
            const ImageF& mv = f1.motion;
            Vec2 prev{x + mv.at(x, y, 0), y + mv.at(x, y, 1)};
            if (prev.x < 0 || prev.y < 0 || prev.x > w - 2 || prev.y > h - 2) continue;
            // Bilinear lookup of the previous frame's position buffer.
            BilinearFootprint fp = bilinearFootprint(prev);
            Vec3 p{};
            for (int t = 0; t < 4; ++t)
                p += fp.weight[t] * load3(f0.position.data(), long(tapY(fp, t)) * w + tapX(fp, t));
            Vec3 q = load3(f1.position.data(), long(y) * w + x);
            ASSERT_LT(length(p - q), 2e-3f) << x << "," << y;
            ++checked;
        }
    EXPECT_GT(checked, 500);
}

} // namespace
} // namespace bmfr::render

namespace bmfr::render {
namespace {

/// A Lambertian plane y = 0, 2 km across, facing up.
Scene openPlane(float albedo) {
    Scene plane;
    int m = addMaterial(plane, {albedo, albedo, albedo}, {0, 0, 0});
    addQuad(plane, {-1000, 0, -1000}, {-1000, 0, 1000}, {1000, 0, 1000}, {1000, 0, -1000}, m,
            {0, 1, 0});
    return plane;
}

TEST(Render, LambertianPlaneUnderAConstantSkyReflectsAlbedoTimesSky) {
    // Irradiance pi L from the whole upper hemisphere: radiance a / pi * pi L = a L.
    const float albedo = 0.7f;
    const Scene plane = openPlane(albedo);
    Environment env;
    env.sky = {0.5f, 1.0f, 2.0f};
    CameraPose pose;
    pose.position = {0, 2, 1}, pose.target = {0, 0, 0}, pose.fovY = 0.4f;
    FrameData f = renderOnce(plane, pose, env, 12, 10, 1, 1024);
    for (long i = 0; i < f.reference.pixelCount(); ++i)
        for (int c = 0; c < 3; ++c)
            ASSERT_NEAR(f.reference.data()[3 * i + c], albedo * env.sky[c],
                        0.02 * albedo * env.sky[c]);
}

/// The fraction of a point's cosine-weighted hemisphere covered by the rectangle [x1, x2] x
/// [z1, z2] at height h above it (Lambert's formula for a parallel rectangle, by corners).
double rectangleFormFactor(double x0, double z0, double x1, double x2, double z1, double z2,
                           double h) {
    auto corner = [&](double x, double z) {
        const double X = (x - x0) / h, Z = (z - z0) / h;
        const double a = std::sqrt(1 + X * X), b = std::sqrt(1 + Z * Z);
        return (X / a * std::atan(Z / a) + Z / b * std::atan(X / b)) / (2 * 3.14159265358979);
    };
    return corner(x2, z2) - corner(x1, z2) - corner(x2, z1) + corner(x1, z1);
}

TEST(Render, SkyThroughAPortalMatchesLambertsRectangleAndFindsTheSkyMoreOften) {
    // A floor (albedo a) under a black ceiling at height 1 with a 1 x 1 hole: a floor point's
    // radiance is a L F, F the hole's form factor. Aiming sky samples at a portal over the hole
    // must keep that expectation (the cosine half covers the rest of the sky) and leave far
    // fewer 1-spp pixels black than cosine sampling, which finds the hole a quarter of the time.
    const float a = 0.6f, h = 1.0f;
    Scene s;
    const int floor = addMaterial(s, {a, a, a}, {0, 0, 0}), black = addMaterial(s, {}, {});
    addQuad(s, {-100, 0, -100}, {-100, 0, 100}, {100, 0, 100}, {100, 0, -100}, floor, {0, 1, 0});
    // The ceiling: four quads around the hole [-0.5, 0.5]^2.
    addQuad(s, {-100, h, -100}, {-100, h, -0.5f}, {100, h, -0.5f}, {100, h, -100}, black);
    addQuad(s, {-100, h, 0.5f}, {-100, h, 100}, {100, h, 100}, {100, h, 0.5f}, black);
    addQuad(s, {-100, h, -0.5f}, {-100, h, 0.5f}, {-0.5f, h, 0.5f}, {-0.5f, h, -0.5f}, black);
    addQuad(s, {0.5f, h, -0.5f}, {0.5f, h, 0.5f}, {100, h, 0.5f}, {100, h, -0.5f}, black);
    Environment env;
    env.sky = {1.0f, 1.0f, 1.0f};
    CameraPose pose; // looking down through the hole
    pose.position = {0, 3, 0}, pose.target = {0, 0, 0}, pose.up = {1, 0, 0}, pose.fovY = 0.25f;
    double black0 = 0;
    for (bool portal : {false, true}) {
        env.portals.clear();
        if (portal) env.portals.push_back({{-0.5f, h + 0.01f, -0.5f}, {1, 0, 0}, {0, 0, 1}});
        for (LightSampling sampling : {LightSampling::One, LightSampling::Split}) {
            const FrameData f = renderOnce(s, pose, env, 16, 16, 1, 256, 0, nullptr, 0, sampling);
            double expected = 0, reference = 0, noisy = 0, blackShare = 0;
            const long n = f.reference.pixelCount();
            for (long i = 0; i < n; ++i) {
                const float* p = f.position.data() + 3 * i;
                ASSERT_NEAR(p[1], 0.0f, 1e-4f); // every pixel sees the floor
                expected += a * rectangleFormFactor(p[0], p[2], -0.5, 0.5, -0.5, 0.5, h);
                reference += f.reference.data()[3 * i];
                noisy += f.color.data()[3 * i];
                blackShare += f.color.data()[3 * i] <= 0.0f;
            }
            const std::string what = std::string(portal ? "portal" : "cosine") +
                                     (sampling == LightSampling::One ? ", one" : ", split");
            EXPECT_NEAR(reference / double(n), expected / double(n), 0.01 * expected / n) << what;
            EXPECT_NEAR(noisy / double(n), expected / double(n), 0.1 * expected / n) << what;
            blackShare /= double(n);
            if (!portal && sampling == LightSampling::Split) black0 = blackShare;
            if (portal && sampling == LightSampling::Split) {
                EXPECT_GT(black0, 0.4) << what;
                EXPECT_LT(blackShare, 0.25 * black0) << what;
            }
        }
    }
}

TEST(Render, BounceGuidesKeepTheExpectationAndFindTheLitPatchMoreOften) {
    // A ceiling (albedo a) at height 1 over a 1 x 1 patch (albedo b) that a low sun lights from
    // under the ceiling's edge, or that emits: a ceiling point's radiance is a L F, L the patch's
    // radiance and F its form factor. Guiding the ceiling's bounces at the patch must keep that
    // (the throughput and both MIS weights use the mixture's pdf) and find the patch far more
    // often than the cosine, which finds it about a fifth of the time.
    const float a = 0.6f, b = 0.8f, h = 1.0f, emitted = 2.0f;
    const Vec3 sunDirection = normalize(Vec3{1, 0.3f, 0});
    const float sunIrradiance = 2.0f;
    for (bool emitting : {false, true}) {
        Scene s;
        const int ceiling = addMaterial(s, {a, a, a}, {}),
                  patch = emitting ? addMaterial(s, {}, {emitted, emitted, emitted})
                                   : addMaterial(s, {b, b, b}, {});
        addQuad(s, {-1.5f, h, -3}, {-1.5f, h, 3}, {1.5f, h, 3}, {1.5f, h, -3}, ceiling, {0, 0, 0});
        addQuad(s, {-0.5f, 0, -0.5f}, {-0.5f, 0, 0.5f}, {0.5f, 0, 0.5f}, {0.5f, 0, -0.5f}, patch,
                {0, 1, 0});
        Environment env;
        if (!emitting) {
            env.sun.direction = sunDirection;
            env.sun.irradiance = {sunIrradiance, sunIrradiance, sunIrradiance};
        }
        const float patchRadiance =
            emitting ? emitted : b / 3.14159265f * sunIrradiance * sunDirection.y;
        CameraPose pose; // looking up at the ceiling over the patch
        pose.position = {0, 0.5f, 0}, pose.target = {0, h, 0}, pose.up = {1, 0, 0};
        pose.fovY = 0.6f;
        double black[2] = {};
        for (bool guided : {false, true}) {
            env.bounceGuides.clear();
            if (guided) env.bounceGuides.push_back({{-0.5f, 0, -0.5f}, {1, 0, 0}, {0, 0, 1}});
            const FrameData f = renderOnce(s, pose, env, 16, 16, 1, 256);
            double expected = 0, reference = 0, noisy = 0;
            const long n = f.reference.pixelCount();
            for (long i = 0; i < n; ++i) {
                const float* p = f.position.data() + 3 * i;
                ASSERT_NEAR(p[1], h, 1e-4f); // every pixel sees the ceiling
                expected +=
                    a * patchRadiance * rectangleFormFactor(p[0], p[2], -0.5, 0.5, -0.5, 0.5, h);
                reference += f.reference.data()[3 * i];
                noisy += f.color.data()[3 * i];
                black[guided] += f.color.data()[3 * i] <= 0.0f;
            }
            const std::string what = std::string(emitting ? "emitting" : "sunlit") +
                                     (guided ? " patch, guided" : " patch, cosine");
            EXPECT_NEAR(reference / double(n), expected / double(n), 0.01 * expected / n) << what;
            EXPECT_NEAR(noisy / double(n), expected / double(n), 0.1 * expected / n) << what;
            black[guided] /= double(n);
        }
        if (!emitting) {
            EXPECT_GT(black[0], 0.6);
            EXPECT_LT(black[1], 0.45 * black[0]);
        }
    }
}

/// A glossy floor (F0 0.5, roughness 0.3) and a matte wall under a sky and a sun.
Scene glossyFloorAndWall(Environment& env) {
    Scene s;
    Material floor, wall;
    floor.baseColor = {0.6f, 0.5f, 0.4f}, floor.roughness = 0.3f, floor.specular = 0.5f;
    wall.baseColor = {0.3f, 0.6f, 0.3f}, wall.roughness = 1.0f, wall.specular = 0.0f;
    s.materials = {floor, wall};
    addQuad(s, {-3, 0, -3}, {-3, 0, 3}, {3, 0, 3}, {3, 0, -3}, 0, {0, 1, 0});
    addQuad(s, {-3, 0, -1}, {3, 0, -1}, {3, 2, -1}, {-3, 2, -1}, 1, {0, 1, 1});
    env.sky = {0.4f, 0.5f, 0.7f};
    env.sun.direction = normalize(Vec3{0.3f, 1.0f, 0.6f});
    env.sun.irradiance = {3, 3, 2.5f};
    env.sun.angularDiameter = 0.0093f;
    return s;
}

// Mara et al.'s factored paths on an open Lambertian plane, where every matte and glossy path
// escapes: the sky and the sun are direct light, so the direct buffer alone carries the
// analytic radiance (albedo x sky; albedo / pi x sun irradiance x cosine) and M and G are 0.
// (Elsewhere the factored BRDF, m (1 - F_s)^2 + g F_s, is not our material's, so the two
// estimators' references differ by design: 5 to 15% darker in the Cornell box's corners.)
TEST(Render, FactoredPathsOnAnOpenPlaneGiveTheAnalyticRadianceAsDirectLight) {
    const float albedo = 0.7f;
    const Scene plane = openPlane(albedo);
    Environment sky, sun;
    sky.sky = {0.5f, 1.0f, 2.0f};
    const float theta = 1.0471976f;
    sun.sun.direction = {std::sin(theta), std::cos(theta), 0};
    sun.sun.irradiance = {2, 2, 2};
    sun.sun.angularDiameter = 0.00930f;
    CameraPose pose;
    pose.position = {0, 2, 1}, pose.target = {0, 0, 0}, pose.fovY = 0.4f;
    for (const Environment* env : {&sky, &sun}) {
        const FrameData f = renderOnce(plane, pose, *env, 12, 10, 2, 1024, 0, nullptr, 16);
        for (long i = 0; i < f.reference.pixelCount(); ++i)
            for (int c = 0; c < 3; ++c) {
                const double want =
                    env == &sky ? albedo * sky.sky[c] : albedo / 3.14159265 * 2.0 * std::cos(theta);
                ASSERT_NEAR(f.reference.data()[3 * i + c], want, 0.02 * want) << i;
                ASSERT_EQ(f.matteIndirect.data()[3 * i + c], 0.0f);
                ASSERT_EQ(f.glossyIndirect.data()[3 * i + c], 0.0f);
            }
        EXPECT_NEAR(meanOf(f.directLight), meanOf(f.reference), 0.03 * meanOf(f.reference));
    }
}

// The factored direct light on a glossy plane under a constant sky: the light samples and the
// two paths' rays, weighted by multiple importance sampling, give the sky times the BRDF's
// cosine-weighted integral, here by quadrature of evalBsdf over the hemisphere.
TEST(Render, FactoredDirectLightOnAGlossyPlaneMatchesQuadrature) {
    Scene plane;
    Material m;
    m.baseColor = {0.3f, 0.3f, 0.3f}, m.roughness = 0.3f, m.specular = 0.5f;
    plane.materials = {m};
    addQuad(plane, {-1000, 0, -1000}, {-1000, 0, 1000}, {1000, 0, 1000}, {1000, 0, -1000}, 0,
            {0, 1, 0});
    Environment env;
    env.sky = {1, 1, 1};
    CameraPose pose;
    pose.position = {0, 1, 1.5f}, pose.target = {0, 0, -0.5f}, pose.fovY = 0.6f;
    const int w = 8, h = 6;
    const FrameData f = renderOnce(plane, pose, env, w, h, 1, 2048, 0, nullptr, 4);
    SurfacePoint sp;
    sp.ng = sp.ns = {0, 1, 0};
    sp.diffuse = m.baseColor, sp.f0 = {m.specular, m.specular, m.specular};
    sp.alpha = m.roughness * m.roughness, sp.roughness = m.roughness;
    for (long i : {long(w / 2), long(w * h / 2 + 1), long(w * h - 2)}) {
        sp.p = load3(f.position.data(), i);
        sp.wo = normalize(pose.position - sp.p);
        // Midpoint rule in (cos theta, phi), fine enough for a lobe of alpha 0.09.
        const int nt = 1500, np = 1500;
        double sum = 0;
        for (int a = 0; a < nt; ++a)
            for (int b = 0; b < np; ++b) {
                const float ct = (float(a) + 0.5f) / float(nt), st = std::sqrt(1 - ct * ct);
                const float phi = 6.2831853f * (float(b) + 0.5f) / float(np);
                const Vec3 wi{st * std::cos(phi), ct, st * std::sin(phi)};
                const BsdfValue v = evalBsdf(sp, wi);
                sum += double(v.diffuse.x + v.glossy.x) * ct;
            }
        const double want = sum * (1.0 / nt) * (6.283185307 / np);
        EXPECT_NEAR(f.reference.data()[3 * i], want, 0.02 * want) << "pixel " << i;
    }
}

// The factored buffers compose to the colour (L = direct + (1 - F)^2 rho M + F G + emission,
// F Schlick's at the view angle), and each is in its range.
TEST(Render, FactoredBuffersComposeToTheColour) {
    Environment env;
    const Scene s = glossyFloorAndWall(env);
    CameraPose pose;
    pose.position = {0, 1.2f, 2.5f}, pose.target = {0, 0.3f, -1}, pose.fovY = 0.9f;
    const FrameData f = renderOnce(s, pose, env, 32, 24, 2, 0, 0, nullptr, 8);
    int glossy = 0;
    for (long i = 0; i < f.color.pixelCount(); ++i) {
        const Vec3 p = load3(f.position.data(), i), n = load3(f.normal.data(), i);
        const Vec3 v = normalize(pose.position - p);
        const Vec3 F0 = load3(f.specularF0.data(), i), rho = load3(f.albedo.data(), i);
        const Vec3 M = load3(f.matteIndirect.data(), i), G = load3(f.glossyIndirect.data(), i);
        const Vec3 D = load3(f.directLight.data(), i), E = load3(f.emission.data(), i);
        const float cosine = std::fmax(0.0f, dot(n, v));
        for (int c = 0; c < 3; ++c) {
            ASSERT_GE(M[c], 0.0f);
            ASSERT_GE(G[c], 0.0f);
            ASSERT_GE(D[c], 0.0f);
            ASSERT_GE(F0[c], 0.0f);
            ASSERT_LE(F0[c], 1.0f);
            const double F = F0[c] + (1 - F0[c]) * std::pow(1.0 - cosine, 5.0);
            const double want = D[c] + (1 - F) * (1 - F) * rho[c] * M[c] + F * G[c] + E[c];
            ASSERT_NEAR(f.color.data()[3 * i + c], want, 1e-3 * want + 1e-5) << i << " " << c;
        }
        const float r = f.roughness.data()[i], d = f.glossyHitDistance.data()[i];
        ASSERT_GE(r, 0.0f);
        ASSERT_LE(r, 1.0f);
        ASSERT_TRUE(std::isfinite(d) && d >= 0.0f) << d;
        glossy += G[0] > 0;
    }
    EXPECT_GT(glossy, 20) << "glossy paths reach the wall";
}

} // namespace
} // namespace bmfr::render
