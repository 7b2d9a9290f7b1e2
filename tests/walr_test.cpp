// WALR (Meunier and Harada 2022): tests W1 to W11 of the implementation notes, the solver
// against an exact double-precision solve, WALR against REFWLR, the CPU backend against the
// reference, and the filter end to end on a path-traced Cornell box.
#include "backend/cpu/walr/cpu_walr_spatial.h"
#include "core/hash.h"
#include "filters/walr/refwlr.h"
#include "filters/walr/walr_passes.h"
#include "filters/walr/walr_temporal_kernels.h"
#include "metrics/basic_metrics.h"
#include "render/scene_description.h"
#include "render/sequence_renderer.h"
#include "synth/procedural_scene.h"
#include "test_scenes.h"
#include "test_support.h"
#include <Eigen/Dense>
#include <bmfr/bmfr.hpp>
#include <bmfr/error.h>
#include <cmath>
#include <cstring>
#include <gtest/gtest.h>

namespace bmfr {
namespace {

using testing::errorOf;

/// A synthetic G-buffer: positions, normals (for the edge weights), depth, features and signal.
struct WalrGBuffer {
    int w = 0, h = 0;
    std::vector<float> pos, nrm, depth, feat, sig;
    WalrGBuffer(int width, int height)
        : w(width), h(height), pos(size_t(3 * w * h)), nrm(size_t(3 * w * h)),
          depth(size_t(w * h), 10.0f), feat(size_t(2 * w * h), 0.5f), sig(size_t(3 * w * h)) {
        for (long i = 0; i < long(w) * h; ++i) {
            setPosition(i, {float(i % w) * 0.01f, float(i / w) * 0.01f, 10.0f});
            store3(nrm.data(), i, {0, 0, 1});
        }
    }
    long size() const { return long(w) * h; }
    void setPosition(long i, Vec3 p) {
        store3(pos.data(), i, p);
        depth[size_t(i)] = p.z;
    }
    EdgeGuide guide(bool tracing = true, bool replacement = true, float nearF = 0.005f,
                    float farF = 0.02f) const {
        EdgeGuide g;
        g.position = pos.data(), g.normal = nrm.data(), g.depth = depth.data();
        g.width = w, g.height = h, g.nearFraction = nearF, g.farFraction = farF;
        g.tracing = tracing, g.replacement = replacement;
        return g;
    }
};

struct WalrRun {
    std::vector<float> out;   ///< 3 per pixel
    std::vector<float> means; ///< the final averages' mean colour YX_c0, 3 per pixel
};

/// WALR's spatial filter through the kernels: T iterations, then the solve; with `eightWide`,
/// the CPU backend's interleaved iterations and solve instead of the scalar kernels on planes;
/// with `half`, half averages between iterations.
WalrRun runWalr(const WalrGBuffer& f, const EdgeGuide& g, int iterations, bool keepW = false,
                float eps = 1e-4f, uint32_t frame = 0, bool eightWide = false,
                long* skippedTaps = nullptr, bool half = false) {
    const long n = f.size();
    const AverageLayout layout = eightWide ? AverageLayout{1, 16} : AverageLayout{n, 1};
    std::vector<float> a(size_t(16 * n)), b(a.size());
    std::vector<float> wa(static_cast<size_t>(n)), wb(static_cast<size_t>(n));
    for (long i = 0; i < n; ++i) {
        float s[kWalrAverages];
        walrSampleProducts(load3(f.sig.data(), i), {f.feat[2 * i], f.feat[2 * i + 1]}, s);
        for (int k = 0; k < kWalrAverages; ++k) a[size_t(layout.at(k, i))] = s[k];
    }
    ThreadPool pool(2);
    cpu::EdgePlanes planes;
    if (eightWide) planes.fill(pool, g);
    SteppedTraceBuffers trace; // for the scalar kernel
    trace.resize(n);
    int step = 1;
    for (int t = 0; t < iterations; ++t, step *= 3) {
        WalrLevel l;
        l.in = a.data(), l.out = b.data(), l.layout = layout, l.iteration = t, l.step = step;
        l.weightIn = keepW && t > 0 ? wa.data() : nullptr;
        l.weightOut = keepW ? wb.data() : nullptr;
        l.frame = frame;
        l.halfIn = half && t > 0, l.halfOut = half && t < iterations - 1;
        l.trace = trace.at(t);
        if (eightWide)
            cpu::walrAtrousIteration(pool, g, planes, l, t + 1 == iterations);
        else
            for (int y = 0; y < f.h; ++y)
                for (int x = 0; x < f.w; ++x) walrAtrousPixel(g, l, x, y);
        std::swap(a, b);
        std::swap(wa, wb);
    }
    if (skippedTaps) *skippedTaps = planes.skippedTaps;
    WalrRun r;
    r.out.resize(size_t(3 * n));
    r.means.resize(size_t(3 * n));
    if (eightWide) cpu::walrSolveImage(pool, f.w, f.h, a.data(), f.feat.data(), eps, r.out.data());
    for (long i = 0; i < n; ++i) {
        if (!eightWide)
            store3(r.out.data(), i,
                   walrSolvePixel(a.data(), layout, i, {f.feat[2 * i], f.feat[2 * i + 1]}, eps));
        store3(
            r.means.data(), i,
            {a[size_t(layout.at(5, i))], a[size_t(layout.at(8, i))], a[size_t(layout.at(11, i))]});
    }
    return r;
}

float rnd(uint32_t a, uint32_t b) {
    return unitFloat(hashKeys(a, b, 77u));
}

/// Smoothly varying features (no pivot clamp fires) and normals tilted with them.
void varyFeatures(WalrGBuffer& f) {
    for (long i = 0; i < f.size(); ++i) {
        const float x = float(i % f.w) / float(f.w), y = float(i / f.w) / float(f.h);
        f.feat[size_t(2 * i)] = 0.5f + 0.3f * std::sin(9.0f * x + 2.0f * y);
        f.feat[size_t(2 * i + 1)] = 0.5f + 0.3f * std::cos(7.0f * y - 3.0f * x);
    }
}

// W1: a signal that is exactly linear in the features is reproduced, for any weights.
TEST(Walr, W1ReproducesASignalLinearInTheFeatures) {
    WalrGBuffer f(121, 121);
    varyFeatures(f);
    for (long i = 0; i < f.size(); ++i) {
        // A tilted normal field, so that the edge weights are not all 1.
        const float x = float(i % f.w) / float(f.w);
        store3(f.nrm.data(), i, normalize(Vec3{0.3f * std::sin(5.0f * x), 0.1f, 1.0f}));
        const float u = f.feat[size_t(2 * i)], v = f.feat[size_t(2 * i + 1)];
        store3(f.sig.data(), i, {0.2f + 0.5f * u - 0.3f * v, 1.0f - u, 0.3f + 2.0f * v});
    }
    for (bool keepW : {false, true}) {
        const WalrRun r = runWalr(f, f.guide(true, true, 0.0f, 0.5f), 4, keepW);
        float worst = 0;
        for (size_t k = 0; k < r.out.size(); ++k)
            worst = std::fmax(worst, std::fabs(r.out[k] - f.sig[k]));
        EXPECT_LT(worst, 2e-4f) << "keepW " << keepW;
    }
}

// W2 and W3: constant normals make the ε clamp fire; a constant stays constant and any signal
// reduces to the edge-aware mean.
TEST(Walr, W2W3FlatNormalsGiveTheEdgeAwareMean) {
    WalrGBuffer f(90, 70);
    for (long i = 0; i < f.size(); ++i) store3(f.sig.data(), i, {2.5f, 2.5f, 2.5f});
    WalrRun r = runWalr(f, f.guide(), 4);
    for (float v : r.out) ASSERT_NEAR(v, 2.5f, 2e-5f);
    for (long i = 0; i < f.size(); ++i)
        store3(f.sig.data(), i,
               {rnd(uint32_t(i), 1), rnd(uint32_t(i), 2), 3 * rnd(uint32_t(i), 3)});
    r = runWalr(f, f.guide(), 4);
    for (size_t k = 0; k < r.out.size(); ++k) ASSERT_NEAR(r.out[k], r.means[k], 2e-5f) << k;
}

// W4: the output is linear in the signal (the weights depend only on geometry).
TEST(Walr, W4OutputIsLinearInTheSignal) {
    WalrGBuffer a(80, 60);
    varyFeatures(a);
    WalrGBuffer b = a, c = a;
    for (long i = 0; i < a.size(); ++i) {
        const Vec3 va{rnd(uint32_t(i), 4), rnd(uint32_t(i), 5), rnd(uint32_t(i), 6)};
        const Vec3 vb{rnd(uint32_t(i), 7), rnd(uint32_t(i), 8), rnd(uint32_t(i), 9)};
        store3(a.sig.data(), i, va);
        store3(b.sig.data(), i, vb);
        store3(c.sig.data(), i, 2.0f * va + 3.0f * vb);
    }
    const WalrRun ra = runWalr(a, a.guide(), 3), rb = runWalr(b, b.guide(), 3),
                  rc = runWalr(c, c.guide(), 3);
    for (size_t k = 0; k < ra.out.size(); ++k) {
        if (ra.out[k] <= 0 || rb.out[k] <= 0) continue; // the >= 0 clamp is not linear
        ASSERT_NEAR(rc.out[k], 2.0f * ra.out[k] + 3.0f * rb.out[k], 2e-4f) << k;
    }
    // An affine remap of the features ([0, 1] to [-1, 1], as the paper allows either) changes
    // nothing while no pivot clamp fires.
    WalrGBuffer d = a;
    for (float& v : d.feat) v = 2.0f * v - 1.0f;
    const WalrRun rd = runWalr(d, d.guide(), 3);
    for (size_t k = 0; k < ra.out.size(); ++k) {
        if (ra.out[k] <= 0) continue;
        ASSERT_NEAR(rd.out[k], ra.out[k], 2e-4f) << k;
    }
}

// W5: with every weight 1, T = 4 averages each pixel of the 81x81 window exactly once.
TEST(Walr, W5ImpulseCoversTheWindowExactlyOnce) {
    for (int T : {3, 4}) {
        WalrGBuffer f(161, 161); // every pixel whose window holds the impulse is inside
        const long centre = 80 * 161 + 80;
        store3(f.sig.data(), centre, {1, 1, 1});
        const WalrRun r = runWalr(f, f.guide(true, true, 1.0f, 2.0f), T);
        const int window = T == 3 ? 27 : 81;
        const float expected = 1.0f / float(window * window);
        long nonzero = 0;
        for (long i = 0; i < f.size(); ++i) {
            const int dx = int(i % f.w) - 80, dy = int(i / f.w) - 80;
            const bool inside = std::abs(dx) <= window / 2 && std::abs(dy) <= window / 2;
            const float m = r.means[size_t(3 * i)];
            if (m != 0) ++nonzero;
            if (inside) {
                ASSERT_NEAR(m, expected, expected * 1e-4f) << dx << "," << dy;
            } else {
                ASSERT_EQ(m, 0.0f) << dx << "," << dy;
            }
        }
        EXPECT_EQ(nonzero, long(window) * window);
    }
}

// W5 (second part) and the oracle: with every weight 1, WALR equals REFWLR in the interior.
TEST(Walr, EqualsRefwlrInTheInteriorWhenAllWeightsAreOne) {
    WalrGBuffer f(101, 97);
    varyFeatures(f);
    for (long i = 0; i < f.size(); ++i) {
        store3(f.pos.data(), i, {0, 0, 10}); // one point: every plane distance is 0
        store3(f.sig.data(), i, {rnd(uint32_t(i), 10), rnd(uint32_t(i), 11), rnd(uint32_t(i), 12)});
    }
    const EdgeGuide g = f.guide();
    const WalrRun r = runWalr(f, g, 4);
    for (int y = 40; y <= 56; y += 4)
        for (int x = 40; x <= 60; x += 5) {
            const Vec3 ref = refwlrPixel(g, f.sig.data(), f.feat.data(), 40, 1e-4, x, y);
            const Vec3 got = load3(r.out.data(), long(y) * f.w + x);
            for (int c = 0; c < 3; ++c) ASSERT_NEAR(got[c], ref[c], 1e-4f) << x << "," << y;
        }
}

// W6: two parallel planes further apart than the ramp: what happens on B never reaches A.
TEST(Walr, W6DepthStepSeparatesThePlanesExactly) {
    WalrGBuffer f(120, 60);
    varyFeatures(f);
    for (long i = 0; i < f.size(); ++i) {
        const int x = int(i % f.w);
        f.setPosition(i, {float(x) * 0.01f, float(i / f.w) * 0.01f, x < 60 ? 10.0f : 12.0f});
        store3(f.sig.data(), i, {rnd(uint32_t(i), 13), 0.5f, 0.5f});
    }
    WalrGBuffer g = f;
    for (long i = 0; i < f.size(); ++i)
        if (i % f.w >= 60) store3(g.sig.data(), i, {5.0f * rnd(uint32_t(i), 14), 9.0f, 0.0f});
    const WalrRun a = runWalr(f, f.guide(), 4), b = runWalr(g, g.guide(), 4);
    for (long i = 0; i < f.size(); ++i) {
        if (i % f.w >= 60) continue;
        for (int c = 0; c < 3; ++c) ASSERT_EQ(a.out[size_t(3 * i + c)], b.out[size_t(3 * i + c)]);
    }
}

// W7: a 1-pixel strip in front of a wall stops every tap that crosses it when tracing; testing
// only the tap's end leaks the right side's light into the left.
TEST(Walr, W7EdgeTracingStopsLeaksPastAThinOccluder) {
    const int strip = 60;
    WalrGBuffer f(121, 60);
    for (long i = 0; i < f.size(); ++i) {
        const int x = int(i % f.w);
        f.setPosition(i, {float(x) * 0.01f, float(i / f.w) * 0.01f, x == strip ? 9.0f : 10.0f});
        const float v = x > strip ? 1.0f : 0.0f;
        store3(f.sig.data(), i, {v, v, v});
    }
    auto leak = [&](bool tracing, float stepFraction = 0, bool eightWide = false) {
        EdgeGuide g = f.guide(tracing, true);
        g.stepFraction = stepFraction;
        const WalrRun r = runWalr(f, g, 4, false, 1e-4f, 0, eightWide);
        float worst = 0;
        for (long i = 0; i < f.size(); ++i)
            if (i % f.w < strip) worst = std::fmax(worst, r.out[size_t(3 * i)]);
        return worst;
    };
    EXPECT_EQ(leak(true), 0.0f);
    EXPECT_GT(leak(false), 0.2f);
    // A stepped trace skips no edge that the last iteration's trace from where a stretch begins
    // saw: the strip stops every tap here too.
    for (float stepFraction : {0.5f, 1.0f})
        for (bool eightWide : {false, true})
            EXPECT_EQ(leak(true, stepFraction, eightWide), 0.0f) << stepFraction << eightWide;
}

// A stepped trace whose skips are all 0 (a share of 0.01 of runs of at most 27 steps) tests every
// step, and carries its minimum and first zero from one iteration to the next, so it gives the
// exact trace's bits, replacements included, on the scalar kernel and eight wide.
TEST(Walr, SteppedTraceThatSkipsNothingIsTheExactTrace) {
    WalrGBuffer f(150, 90);
    varyFeatures(f);
    for (long i = 0; i < f.size(); ++i) {
        const int x = int(i % f.w), y = int(i / f.w);
        const bool raised = x > 60 && x < 80 && y > 30 && y < 60;
        const float z = 10.0f + 0.6f * std::sin(float(x) / 40.0f) * std::cos(float(y) / 30.0f) -
                        (raised ? 1.0f : 0.0f);
        f.setPosition(i, {float(x) * 0.01f, float(y) * 0.01f, z});
        store3(f.nrm.data(), i, normalize(Vec3{0.01f * float(x % 5), 0.0f, 1.0f}));
        store3(f.sig.data(), i, {rnd(uint32_t(i), 40), rnd(uint32_t(i), 41), 0.5f});
    }
    const WalrRun exact = runWalr(f, f.guide(), 4, false, 1e-4f, 2);
    EdgeGuide g = f.guide();
    g.stepFraction = 0.01f;
    for (bool eightWide : {false, true}) {
        const WalrRun stepped = runWalr(f, g, 4, false, 1e-4f, 2, eightWide);
        for (size_t k = 0; k < exact.out.size(); ++k)
            ASSERT_EQ(exact.out[k], stepped.out[k]) << k << " eight wide " << eightWide;
    }
}

// W8: the pivot-clamped Cholesky with three right-hand sides solves XX + diag(delta) exactly,
// and stays finite for rank-deficient matrices.
TEST(Walr, W8ClampedCholeskySolvesTheRidgedSystem) {
    for (uint32_t trial = 0; trial < 200; ++trial) {
        // Averages of a few random samples: positive semi-definite, often nearly singular.
        const int samples = 1 + int(trial % 6);
        Eigen::Matrix3d xx = Eigen::Matrix3d::Zero();
        for (int s = 0; s < samples; ++s) {
            const Eigen::Vector3d x{1.0, rnd(trial, 100 + s), rnd(trial, 200 + s)};
            xx += x * x.transpose() / samples;
        }
        const double eps = 1e-4;
        const Cholesky3<double> c =
            choleskyClamped<double>(xx(0, 1), xx(0, 2), xx(1, 1), xx(1, 2), xx(2, 2), eps);
        // delta from the pivots as the algorithm meets them.
        const double p1 = xx(1, 1) - xx(0, 1) * xx(0, 1);
        const double d1 = std::max(0.0, eps - p1);
        const double c21 = (xx(1, 2) - xx(0, 2) * xx(0, 1)) / std::sqrt(p1 + d1);
        const double p2 = xx(2, 2) - xx(0, 2) * xx(0, 2) - c21 * c21;
        const double d2 = std::max(0.0, eps - p2);
        Eigen::Matrix3d ridged = xx;
        ridged(1, 1) += d1;
        ridged(2, 2) += d2;
        const Eigen::Vector3d rhs{rnd(trial, 1), rnd(trial, 2), rnd(trial, 3)};
        const Eigen::Vector3d exact = ridged.ldlt().solve(rhs);
        const double r[3] = {rhs[0], rhs[1], rhs[2]};
        double beta[3];
        choleskySolve(c, r, beta);
        for (int k = 0; k < 3; ++k) {
            ASSERT_TRUE(std::isfinite(beta[k]));
            ASSERT_NEAR(beta[k], exact[k], 1e-8 * (1 + std::fabs(exact[k]))) << trial;
        }
        if (d1 == 0 && d2 == 0) { // no clamp: C C^T is XX itself
            Eigen::Matrix3d cm;
            cm << c.c00, 0, 0, c.c10, c.c11, 0, c.c20, c.c21, c.c22;
            ASSERT_LT((cm * cm.transpose() - xx).norm(), 1e-12);
        }
    }
}

// W9: on a curved surface with normal-dependent light, the regression keeps the gradient that
// the same-sized edge-aware mean flattens.
TEST(Walr, W9KeepsGradientsTheMeanFlattens) {
    WalrGBuffer f(121, 121);
    const ViewBasis view; // camera at the origin looking down -z
    const Vec3 light = normalize(Vec3{0.6f, -0.3f, 1.0f});
    double errWalr = 0, errMean = 0;
    // The sphere fills the image: every pixel sees it.
    for (long i = 0; i < f.size(); ++i) {
        const float x = (float(i % f.w) - 60.0f) / 90.0f, y = (float(i / f.w) - 60.0f) / 90.0f;
        const float zz = std::sqrt(std::fmax(0.0f, 1.0f - x * x - y * y));
        const Vec3 n = normalize(Vec3{x, y, zz + 1e-3f});
        f.setPosition(i, {x, y, 10.0f - zz});
        store3(f.nrm.data(), i, n);
        const Vec2 o = walrNormalFeatures(n, {x, y, -10.0f + zz}, view);
        f.feat[size_t(2 * i)] = o.x, f.feat[size_t(2 * i + 1)] = o.y;
        const float v = std::fmax(0.0f, dot(n, light));
        store3(f.sig.data(), i, {v, v, v});
    }
    const WalrRun r = runWalr(f, f.guide(true, true, 0.05f, 0.2f), 4);
    for (long i = 0; i < f.size(); ++i) {
        errWalr += std::pow(r.out[size_t(3 * i)] - f.sig[size_t(3 * i)], 2);
        errMean += std::pow(r.means[size_t(3 * i)] - f.sig[size_t(3 * i)], 2);
    }
    EXPECT_LT(errWalr, 0.5 * errMean); // measured: 0.29
}

// W11: camera-facing normals give continuous features, also at grazing angles.
TEST(Walr, W11OctahedralFeaturesAreContinuousOverVisibleNormals) {
    const ViewBasis view;
    const Vec3 p{0, 0, -5}; // in front of the camera at the origin
    float worst = 0;
    for (int a = 0; a < 360; ++a)
        for (int e = 0; e < 89; ++e) {
            auto dir = [](float az, float el) {
                const float r = std::cos(el);
                return Vec3{r * std::cos(az), r * std::sin(az), std::sin(el)};
            };
            const float az = float(a) * 0.01745f, el = float(e) * 0.01745f + 0.001f;
            const Vec3 n0 = dir(az, el), n1 = dir(az + 0.001f, el + 0.001f);
            const Vec2 f0 = walrNormalFeatures(n0, p, view), f1 = walrNormalFeatures(n1, p, view);
            const float df = std::hypot(f1.x - f0.x, f1.y - f0.y), dn = length(n1 - n0);
            worst = std::fmax(worst, df / dn);
        }
    EXPECT_LT(worst, 3.0f); // a fold would give a jump, far above any Lipschitz bound
    // Back-facing normals are flipped towards the camera first.
    const Vec2 a = walrNormalFeatures({0, 0, 1}, p, view),
               b = walrNormalFeatures({0, 0, -1}, p, view);
    EXPECT_EQ(a.x, b.x);
    EXPECT_EQ(a.y, b.y);
}

// The CPU backend skips the steps of taps whose chord bound proves them all of weight 1, and
// still gives the reference's bits: on a curved surface whose plane distances cross the ramp's
// start within the segments, with a raised square (edges) and with coordinates far from 0.
TEST(Walr, SkippedStepsKeepTheScalarKernelsBits) {
    for (float amplitude : {0.05f, 0.6f, 2.0f})
        for (float offset : {0.0f, 1000.0f}) {
            WalrGBuffer f(190, 170);
            varyFeatures(f);
            for (long i = 0; i < f.size(); ++i) {
                const int x = int(i % f.w), y = int(i / f.w);
                const float sx = std::sin(float(x) / 40.0f), cy = std::cos(float(y) / 30.0f);
                const bool raised = x > 120 && x < 150 && y > 40 && y < 90;
                const float z = 10.0f + amplitude * sx * cy - (raised ? 1.0f : 0.0f);
                f.setPosition(i, {offset + float(x) * 0.01f, float(y) * 0.01f, z});
                // The surface's normal, from dz/dX and dz/dY (X = 0.01 x, Y = 0.01 y).
                const float dzdx = amplitude * std::cos(float(x) / 40.0f) / 40.0f * cy / 0.01f;
                const float dzdy = -amplitude * sx * std::sin(float(y) / 30.0f) / 30.0f / 0.01f;
                store3(f.nrm.data(), i, normalize(Vec3{-dzdx, -dzdy, 1.0f}));
                store3(f.sig.data(), i, {rnd(uint32_t(i), 30), rnd(uint32_t(i), 31), 0.5f});
            }
            for (int iterations : {4, 5}) {
                const EdgeGuide g = f.guide(true, true);
                long skipped = 0;
                const WalrRun a = runWalr(f, g, iterations, true, 1e-4f, 5, false);
                const WalrRun b = runWalr(f, g, iterations, true, 1e-4f, 5, true, &skipped);
                const std::string where = "amplitude " + std::to_string(amplitude) + " offset " +
                                          std::to_string(offset) + " T " +
                                          std::to_string(iterations);
                for (size_t k = 0; k < a.means.size(); ++k) {
                    ASSERT_EQ(a.means[k], b.means[k]) << k << " " << where;
                    ASSERT_EQ(a.out[k], b.out[k]) << k << " " << where;
                }
                // Iterations 2 and on may skip: 24 x 170 blocks of eight, 8 taps each. Measured:
                // 76% to 81% at amplitude 0.05, 29% to 39% at 2 (fewer at T 5: taps leave the
                // image).
                const long taps = long(iterations - 2) * 24 * 170 * 8;
                EXPECT_GT(skipped, taps / 5) << where;
                if (amplitude < 0.1f) {
                    EXPECT_GT(skipped, taps / 2) << where;
                }
            }
        }
}

// The CPU backend's eight-wide iterations and solve are the reference's bit for bit, edges,
// tracing, replacement and W included.
TEST(Walr, EightWideIterationsMatchTheScalarKernelBitForBit) {
    WalrGBuffer f(133, 71);
    varyFeatures(f);
    for (long i = 0; i < f.size(); ++i) {
        const int x = int(i % f.w), y = int(i / f.w);
        const float z = (x / 17 + y / 13) % 3 == 0 ? 9.0f : 10.0f + 0.002f * float(x);
        f.setPosition(i, {float(x) * 0.01f, float(y) * 0.01f, z});
        store3(f.nrm.data(), i, normalize(Vec3{0.01f * float(x % 7), 0.0f, 1.0f}));
        store3(f.sig.data(), i, {rnd(uint32_t(i), 20), rnd(uint32_t(i), 21), rnd(uint32_t(i), 22)});
    }
    for (bool half : {false, true})
        for (bool keepW : {false, true})
            for (float stepFraction : {-1.0f, 0.0f, 0.5f, 1.0f}) { // -1: no tracing
                EdgeGuide g = f.guide(stepFraction >= 0, true);
                g.stepFraction = stepFraction > 0 ? stepFraction : 0.0f;
                const WalrRun a = runWalr(f, g, 4, keepW, 1e-4f, 3, false, nullptr, half);
                const WalrRun b = runWalr(f, g, 4, keepW, 1e-4f, 3, true, nullptr, half);
                const std::string what = std::string(half ? "half" : "float") + " keepW " +
                                         std::to_string(keepW) + " step " +
                                         std::to_string(stepFraction);
                for (size_t k = 0; k < a.means.size(); ++k) {
                    ASSERT_EQ(a.means[k], b.means[k]) << k << " " << what;
                    ASSERT_EQ(a.out[k], b.out[k]) << k << " " << what;
                }
            }
}

TEST(Walr, VarianceClipLeavesAHistoryInsideTheBoxAlone) {
    NeighbourhoodMoments m{{1, 2, 3}, {0.5f, 0.5f, 1.0f}};
    const Vec3 inside{1.2f, 1.7f, 3.9f}, outside{3.0f, 2.0f, 3.0f};
    const Vec3 a = varianceClip(inside, m, 1.0f), b = varianceClip(outside, m, 1.0f);
    EXPECT_EQ(a.x, inside.x);
    EXPECT_EQ(a.y, inside.y);
    EXPECT_EQ(a.z, inside.z);
    EXPECT_NEAR(b.x, 1.5f, 1e-6f); // pulled along the line to the mean onto the box
    EXPECT_NEAR(b.y, 2.0f, 1e-6f);
}

Vec3 catmullRom(const std::vector<float>& img, Vec2 p) {
    Vec3 v, unused;
    sampleCatmullRom2(img.data(), nullptr, 8, 8, p, v, unused);
    return v;
}

TEST(Walr, CatmullRomIsExactAtPixelCentresAndClampedAtZero) {
    std::vector<float> img(3 * 8 * 8);
    for (size_t k = 0; k < img.size(); ++k) img[k] = float(k % 5);
    const Vec3 v = catmullRom(img, {3, 4});
    EXPECT_EQ(v.x, img[3 * (4 * 8 + 3)]);
    std::vector<float> step(3 * 8 * 8, 0.0f);
    for (int x = 4; x < 8; ++x)
        for (int y = 0; y < 8; ++y) store3(step.data(), y * 8 + x, {1, 1, 1});
    EXPECT_GE(catmullRom(step, {3.3f, 2}).x, 0.0f); // the undershoot is cut
    EXPECT_LE(catmullRom(step, {3.3f, 2}).x, 0.5f);
}

/// A static camera on the procedural room, pixel centres, no emission buffer, zero motion.
std::vector<FrameData> staticFrames(int w, int h, int n) {
    ProceduralSceneOptions o;
    o.width = w, o.height = h, o.frames = n, o.jitter = false, o.cameraSpeed = 0.0f;
    ProceduralScene scene(o);
    std::vector<FrameData> frames(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) {
        scene.render(i, frames[size_t(i)]);
        frames[size_t(i)].emission = ImageF();
        // Zero motion: the history is read at exactly the same pixel (no round-off of a
        // reprojection through the camera).
        frames[size_t(i)].motion = ImageF(w, h, 2);
    }
    return frames;
}

Vec3 demodulated(const FrameData& f, long i) {
    const Vec3 c = load3(f.color.data(), i), a = guardAlbedo(load3(f.albedo.data(), i), 0.001f);
    return {c.x / a.x, c.y / a.y, c.z / a.z};
}

// W10: with a static camera the preprocess is the exact mean of up to 1 / preAlpha samples; a
// depth change beyond the tolerance restarts it; the same seed gives the same bits.
TEST(Walr, W10TemporalRules) {
    const int w = 48, h = 32, n = 5;
    std::vector<FrameData> frames = staticFrames(w, h, n + 1);
    WalrDenoiser d;
    d.setDebugOutputs(true);
    for (int k = 0; k < n; ++k) {
        d.denoise(frames[size_t(k)].input());
        const DebugBuffers dbg = d.debug();
        for (long i = 0; i < long(w) * h; ++i) {
            if (dbg.historyLength.data[i] != float(k + 1)) continue; // a border pixel or miss
            Vec3 mean{};
            for (int j = 0; j <= k; ++j) mean += demodulated(frames[size_t(j)], i);
            mean = mean / float(k + 1);
            for (int c = 0; c < 3; ++c)
                ASSERT_NEAR(dbg.accumulatedNoisy.data[3 * i + c], mean[c], 1e-5f * (1 + mean[c]))
                    << "frame " << k << " pixel " << i;
        }
    }
    long full = 0;
    for (long i = 0; i < long(w) * h; ++i) full += d.debug().historyLength.data[i] == float(n);
    EXPECT_GT(full, long(w) * h * 9 / 10);
    // Every surface 10% further away along its view ray: the depth test rejects every history.
    FrameData moved = frames[size_t(n)];
    const Vec3 eye = viewBasisOf(moved.viewProjection).eye;
    for (long i = 0; i < long(w) * h; ++i)
        store3(moved.position.data(), i, eye + 1.1f * (load3(moved.position.data(), i) - eye));
    d.denoise(moved.input());
    for (long i = 0; i < long(w) * h; ++i) {
        ASSERT_EQ(d.debug().historyLength.data[i], 1.0f) << i;
        const Vec3 y = demodulated(moved, i);
        for (int c = 0; c < 3; ++c) ASSERT_EQ(d.debug().accumulatedNoisy.data[3 * i + c], y[c]);
    }
    // Determinism: the same frames and seed give the same bits.
    auto run = [&](uint32_t seed) {
        WalrSettings s;
        s.seed = seed;
        WalrDenoiser f(s);
        ImageView out;
        for (int k = 0; k < n; ++k) out = f.denoise(frames[size_t(k)].input());
        return std::vector<float>(out.data, out.data + 3 * w * h);
    };
    EXPECT_EQ(run(7), run(7));
}

// The paper's own use: only the diffuse indirect light is filtered and the rest of the colour
// comes back untouched.
TEST(Walr, DiffuseIndirectSignalAddsTheRestBackUnfiltered) {
    const int w = 40, h = 30;
    std::vector<FrameData> frames = staticFrames(w, h, 1);
    FrameData& f = frames[0];
    WalrSettings s;
    s.signal = WalrSignal::DiffuseIndirect;
    WalrDenoiser d(s);
    EXPECT_NE(errorOf([&] { d.denoise(f.input()); }).find("'diffuseIndirect' is missing"),
              std::string::npos);
    // A constant diffuse indirect (what the spatial filter keeps exactly) under noisy colour.
    f.diffuseIndirect = ImageF(w, h, 3);
    for (float& v : f.diffuseIndirect.pixels) v = 0.25f;
    const ImageView out = d.denoise(f.input());
    for (long k = 0; k < 3L * w * h; ++k)
        ASSERT_NEAR(out.data[k], f.color.pixels[size_t(k)], 1e-5f);
    // A non-finite value in the buffer is counted and replaced, never passed on.
    f.diffuseIndirect.pixels[7] = NAN;
    const ImageView poisoned = d.denoise(f.input());
    EXPECT_EQ(d.lastStats().nonFiniteInputs, 1);
    for (long k = 0; k < 3L * w * h; ++k) ASSERT_TRUE(std::isfinite(poisoned.data[k])) << k;
    s.colorIsDemodulated = true;
    EXPECT_NE(errorOf([&] { WalrDenoiser bad(s); }).find("colorIsDemodulated"), std::string::npos);
}

TEST(Walr, CpuBackendGivesTheReferenceBits) {
    // The CPU's eight-wide preprocess, spatial filter and postprocess keep the reference's bits:
    // moving objects with motion vectors, an odd width (tails of 8 pixels), a non-finite input,
    // the diffuse-indirect signal and the world-space history test.
    ProceduralSceneOptions o;
    o.width = 83, o.height = 61, o.frames = 5, o.cameraSpeed = 1.0f, o.jitter = true;
    o.objectSpeed = 2.0f, o.motionVectors = true;
    ProceduralScene scene(o);
    std::vector<FrameData> frames(5);
    for (int i = 0; i < 5; ++i) {
        scene.render(i, frames[size_t(i)]);
        FrameData& f = frames[size_t(i)];
        f.diffuseIndirect = f.color;
        for (float& v : f.diffuseIndirect.pixels) v *= 0.5f;
    }
    frames[2].color.pixels[333] = NAN;
    // At this size T is 1 by default; three iterations pass two levels through half averages.
    for (const SettingValues& extra :
         std::vector<SettingValues>{{},
                                    {{"historyTest", "world"}},
                                    {{"signal", "diffuse-indirect"}},
                                    {{"iterations", "3"}},
                                    {{"iterations", "3"}, {"halfAverages", "false"}},
                                    {{"iterations", "4"}, {"edgeStep", "0.5"}}}) {
        SettingValues cpuValues = extra, refValues = extra;
        cpuValues.push_back({"backend", "cpu"});
        refValues.push_back({"backend", "reference"});
        auto cpu = makeFilter("walr", cpuValues), ref = makeFilter("walr", refValues);
        cpu->setDebugOutputs(true);
        ref->setDebugOutputs(true);
        for (size_t k = 0; k < frames.size(); ++k) {
            const ImageView a = cpu->denoise(frames[k].input());
            const ImageView b = ref->denoise(frames[k].input());
            const size_t n = size_t(3 * a.width * a.height);
            ASSERT_EQ(0, std::memcmp(a.data, b.data, n * sizeof(float))) << "frame " << k;
            ASSERT_EQ(cpu->lastStats().nonFiniteInputs, ref->lastStats().nonFiniteInputs);
            const DebugBuffers da = cpu->debug(), db = ref->debug();
            ASSERT_EQ(0, std::memcmp(da.accumulatedNoisy.data, db.accumulatedNoisy.data,
                                     n * sizeof(float)))
                << "the preprocess average, frame " << k;
            ASSERT_EQ(0, std::memcmp(da.historyLength.data, db.historyLength.data,
                                     size_t(a.width * a.height) * sizeof(float)))
                << "frame " << k;
        }
    }
}

// End to end on a path-traced Cornell box with a moving camera, in the paper's own signal
// (the diffuse indirect light): WALR's error is at most a quarter of the noisy input's.
TEST(Walr, PathTracedCornellErrorIsAtMostAQuarterOfNoisy) {
    render::SceneDescription d = render::loadSceneDescription("cornell-moving", ".");
    d.width = 160, d.height = 120, d.frames = 10, d.referenceSpp = 128;
    d.diffuseIndirectOnly = true;
    const std::string dir = testing::freshDir("Walr", "cornell").string();
    render::SequenceRenderOptions o;
    o.output = dir, o.quiet = true;
    render::renderSequence(
        d, o, nullptr, [](int, int) {}, [](const std::string&) {});
    auto reader = SequenceReader::open(dir);
    WalrDenoiser walr;
    double out = 0, in = 0;
    FrameData f;
    for (int i = 0; i < d.frames; ++i) {
        reader->load(i, f);
        const ImageView v = walr.denoise(f.input());
        ImageF img(v.width, v.height, 3);
        std::copy(v.data, v.data + 3 * v.width * v.height, img.data());
        if (i < 3) continue; // the first frames have little history
        out += rmseToneMapped(img, f.reference);
        in += rmseToneMapped(f.color, f.reference);
    }
    EXPECT_LE(out, 0.25 * in) << "mean RMSE denoised " << out / 7 << " noisy " << in / 7;
}

TEST(Walr, IterationsByImageSizeKeepThePapersShareOfTheFrame) {
    WalrSettings s;
    EXPECT_EQ(walrIterations(s, 1920, 1080), 4); // the paper's own configuration
    EXPECT_EQ(walrIterations(s, 1280, 720), 4);
    EXPECT_EQ(walrIterations(s, 640, 360), 3);
    EXPECT_EQ(walrIterations(s, 320, 240), 3);
    EXPECT_EQ(walrIterations(s, 3840, 2160), 5);
    EXPECT_EQ(walrIterations(s, 160, 120), 2);
    EXPECT_EQ(walrIterations(s, 8, 8), 1);
    EXPECT_EQ(walrIterations(s, 1080, 1920), 4); // portrait: the shorter side
    s.iterations = 2;
    EXPECT_EQ(walrIterations(s, 1920, 1080), 2);
}

TEST(Walr, SettingsAreChecked) {
    EXPECT_NE(errorOf([] {
                  makeFilter("walr", {{"iterations", "6"}});
              }).find("iterations"),
              std::string::npos);
    EXPECT_NE(errorOf([] {
                  makeFilter("walr", {{"edgeNear", "0.05"}});
              }).find("edgeFar"),
              std::string::npos);
    EXPECT_NE(errorOf([] {
                  makeFilter("walr", {{"solver", "qr"}});
              }).find("walr, refwlr"),
              std::string::npos);
}

} // namespace
} // namespace bmfr
