// Mara et al. 2017: tests M1 to M12 of the implementation notes on the stage kernels and the
// whole filter, the CPU backend's running minimum against a brute-force one, and the filter end
// to end on a Cornell box path traced with the paper's factored paths.
#include "backend/cpu/isa.h"
#include "backend/cpu/mara2017/cpu_mara_glossy.h"
#include "backend/cpu/mara2017/cpu_mara_rows.h"
#include "backend/cpu/mara2017/cpu_running_min.h"
#include "filters/mara2017/mara_passes.h"
#include "metrics/basic_metrics.h"
#include "path_traced_box.h"
#include "render/frame_renderer.h"
#include "render/lights.h"
#include "render/ray_accel.h"
#include "render/scene_description.h"
#include "render/sequence_renderer.h"
#include "test_scenes.h"
#include "test_support.h"
#include <bmfr/bmfr.hpp>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <gtest/gtest.h>
#include <random>
#include <set>
#include <tuple>
#include <utility>

namespace bmfr {
namespace {

using testing::errorOf;

/// One frame's stage buffers over a plane z = 0 facing +z, 1 cm per pixel, wired into a
/// MaraFrame with the default settings at this width.
struct MaraPlane {
    int w, h;
    std::vector<float> pos, nrm, matte, glossy, expected, prevPixel, temporal, conf, rowMin, radius,
        median, matteOut, history, prevMatte, prevGlossy, prevPos, glossyTemporal, glossyHistory,
        glossyRow, glossyOut, rough, hitDistance, preSpiral, finalSpiral;
    std::vector<int> preOffsets;
    std::vector<uint8_t> prevCount, count, accept;
    MaraFrame f;

    MaraPlane(int width, int height, const Mara2017Settings& s = {})
        : w(width), h(height), f(maraFrameSettings(s, width)) {
        const size_t n = size_t(w) * size_t(h);
        for (auto* v : {&pos, &nrm, &matte, &glossy, &expected, &temporal, &median, &matteOut,
                        &history, &prevMatte, &prevGlossy, &prevPos, &glossyTemporal,
                        &glossyHistory, &glossyRow, &glossyOut})
            v->assign(3 * n + 1, 0.0f); // one float past the end, as MaraBuffers
        for (auto* v : {&conf, &rowMin, &radius, &rough, &hitDistance}) v->assign(n, 0.0f);
        prevPixel.assign(2 * n, -1e6f);
        prevCount.assign(n, 0), count.assign(n, 0), accept.assign(n, 0);
        for (long i = 0; i < long(n); ++i) {
            setPosition(i, {float(i % w) * 0.01f, float(i / w) * 0.01f, 0.0f});
            store3(nrm.data(), i, {0, 0, 1});
        }
        maraSpiralTable(f.preTaps, 0.3f, preSpiral);
        maraSpiralTable(f.finalTaps, 1.1f, finalSpiral);
        for (float u : preSpiral) preOffsets.push_back(maraTapOffset(u, f.preRadius));
        wire();
    }
    /// Points the frame at the buffers (again, after a test replaced one).
    void wire() {
        f.width = w, f.height = h;
        f.position = pos.data(), f.normal = nrm.data(), f.matte = matte.data();
        f.glossySignal = glossy.data(), f.expected = expected.data();
        f.previousPixel = prevPixel.data(), f.temporal = temporal.data();
        f.confidence = conf.data(), f.rowMin = rowMin.data(), f.radius = radius.data();
        f.median = median.data(), f.matteOut = matteOut.data(), f.matteHistory = history.data();
        f.prevMatte = prevMatte.data(), f.prevGlossy = prevGlossy.data();
        f.prevPosition = prevPos.data(), f.prevCount = prevCount.data(), f.count = count.data();
        f.accept = accept.data(), f.glossyTemporal = glossyTemporal.data();
        f.glossyHistory = glossyHistory.data(), f.glossyRow = glossyRow.data();
        f.glossyOut = glossyOut.data();
        f.preSpiral = preSpiral.data(), f.finalSpiral = finalSpiral.data();
        f.preOffsets = preOffsets.data();
        f.in.roughness = rough.data(), f.in.glossyHitDistance = hitDistance.data();
        f.in.width = w, f.in.height = h;
    }
    long size() const { return long(w) * h; }
    /// A 3-channel buffer's pixels, without the float past the end.
    std::vector<float> pixels(const std::vector<float>& v) const {
        return {v.begin(), v.begin() + 3 * size()};
    }
    void setPosition(long i, Vec3 p) { store3(pos.data(), i, p); }
    /// Every pixel's history valid and perfectly reprojected: the previous frame saw the same
    /// point through the same pixel, with `frames` of history.
    void perfectHistory(int frames) {
        for (long i = 0; i < size(); ++i) {
            prevPixel[2 * size_t(i)] = float(i % w), prevPixel[2 * size_t(i) + 1] = float(i / w);
            store3(expected.data(), i, load3(pos.data(), i));
            store3(prevPos.data(), i, load3(pos.data(), i));
            prevCount[size_t(i)] = uint8_t(frames);
        }
    }
    template <class Fn> void each(Fn fn) {
        wire();
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) fn(x, y);
    }
};

std::vector<float> randomValues(size_t n, float lo, float hi, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(lo, hi);
    std::vector<float> v(n);
    for (float& x : v) x = u(rng);
    return v;
}

TEST(Mara2017, M1ConfidenceFallsFromHAtD0ToZeroAtD1) {
    const float h = 0.98f, d0 = 0.05f, d1 = 0.07f;
    EXPECT_FLOAT_EQ(maraConfidence(0.0f, h, d0, d1), h);
    EXPECT_FLOAT_EQ(maraConfidence(0.05f, h, d0, d1), h);
    EXPECT_NEAR(maraConfidence(0.06f, h, d0, d1), h / 2, 1e-5f);
    EXPECT_EQ(maraConfidence(0.07f, h, d0, d1), 0.0f);
    EXPECT_EQ(maraConfidence(3.0f, h, d0, d1), 0.0f);
    EXPECT_EQ(maraConfidence(NAN, h, d0, d1), 0.0f);
    float last = h;
    for (int k = 0; k <= 200; ++k) {
        const float c = maraConfidence(0.0005f * float(k), h, d0, d1);
        ASSERT_LE(c, last) << k;
        last = c;
    }
}

TEST(Mara2017, M3DisoccludedPixelTakesTheCurrentSample) {
    MaraPlane a(12, 10);
    a.matte = randomValues(a.matte.size(), 0, 1, 1);
    a.prevMatte.assign(a.prevMatte.size(), 7.0f);
    a.perfectHistory(20);
    a.prevPixel[2 * 15] = -1e6f; // pixel 15: no previous pixel at all
    // Pixel 40: the previous pixel saw a surface 8 cm from where the point was (beyond d1).
    store3(a.prevPos.data(), 40, load3(a.pos.data(), 40) + Vec3{0.08f, 0, 0});
    a.each([&](int x, int y) { maraMatteTemporalPixel(a.f, x, y); });
    for (long i : {15L, 40L}) {
        EXPECT_EQ(a.conf[size_t(i)], 0.0f) << i;
        EXPECT_EQ(a.count[size_t(i)], 1) << i;
        for (int c = 0; c < 3; ++c)
            EXPECT_EQ(a.temporal[3 * size_t(i) + c], a.matte[3 * size_t(i) + c]);
    }
    EXPECT_FLOAT_EQ(a.conf[16], 0.98f);
    EXPECT_EQ(a.count[16], 21);
}

TEST(Mara2017, M4ClampedHistoryLiesInTheNew3x3) {
    for (bool clamp : {true, false}) {
        Mara2017Settings s;
        s.hysteresis = 1.0f, s.cumulativeStart = false, s.clampHistory = clamp;
        MaraPlane a(16, 12, s);
        a.matte = randomValues(a.matte.size(), 0, 1, 2);
        a.prevMatte = randomValues(a.prevMatte.size(), -1, 3, 3);
        a.perfectHistory(30);
        a.each([&](int x, int y) { maraMatteTemporalPixel(a.f, x, y); });
        int clamped = 0;
        a.each([&](int x, int y) {
            const long i = long(y) * a.w + x;
            Vec3 lo, hi;
            maraBox(a.matte.data(), a.w, a.h, x, y, 1, lo, hi);
            const Vec3 t = load3(a.temporal.data(), i), was = load3(a.prevMatte.data(), i);
            for (int c = 0; c < 3; ++c) {
                if (!clamp) {
                    ASSERT_EQ(t[c], was[c]);
                    continue;
                }
                ASSERT_GE(t[c], lo[c]) << x << "," << y;
                ASSERT_LE(t[c], hi[c]) << x << "," << y;
                clamped += t[c] != was[c];
            }
        });
        if (clamp) {
            EXPECT_GT(clamped, a.w * a.h); // most of a history out of range is clamped
        }
    }
}

TEST(Mara2017, CumulativeStartAveragesUntilTheHysteresisTakesOver) {
    for (bool cumulative : {true, false}) {
        Mara2017Settings s;
        s.cumulativeStart = cumulative, s.clampHistory = false;
        MaraPlane a(4, 4, s);
        a.matte.assign(a.matte.size(), 1.0f);
        a.perfectHistory(3); // three frames of history averaging 0
        a.each([&](int x, int y) { maraMatteTemporalPixel(a.f, x, y); });
        // The fourth sample's share: 1/4 as a running mean, 1 - h without the cumulative start.
        EXPECT_FLOAT_EQ(a.temporal[0], cumulative ? 0.25f : 1.0f - 0.98f);
        a.perfectHistory(200);
        a.each([&](int x, int y) { maraMatteTemporalPixel(a.f, x, y); });
        EXPECT_NEAR(a.temporal[0], 1.0f - 0.98f, 1e-6f); // h once the history is long
    }
}

/// Stage 5 by brute force: the min of c over the (2R + 1)^2 box inside the image.
float bruteRadius(MaraPlane& a, int x, int y) {
    float m = INFINITY;
    for (int qy = std::max(0, y - a.f.maxRadius); qy <= std::min(a.h - 1, y + a.f.maxRadius); ++qy)
        for (int qx = std::max(0, x - a.f.maxRadius); qx <= std::min(a.w - 1, x + a.f.maxRadius);
             ++qx)
            m = std::fmin(m, a.conf[size_t(qy) * size_t(a.w) + size_t(qx)]);
    float r = (1.0f - m) * float(a.f.maxRadius);
    return a.conf[size_t(y) * size_t(a.w) + size_t(x)] < 0.5f ? 6.0f * r : r;
}

void runStage5(MaraPlane& a) {
    a.each([&](int x, int y) { maraRowMinPixel(a.f, x, y); });
    a.each([&](int x, int y) { maraColumnMinPixel(a.f, x, y); });
}

TEST(Mara2017, M5DisocclusionRadiusIsTheSeparableMinOfTheBox) {
    MaraPlane a(60, 40); // R = W/20 = 3
    ASSERT_EQ(a.f.maxRadius, 3);
    const int R = a.f.maxRadius;
    // All confident: r = (1 - h) R everywhere.
    a.conf.assign(a.conf.size(), 0.98f);
    runStage5(a);
    for (float r : a.radius) ASSERT_FLOAT_EQ(r, (1.0f - 0.98f) * float(R));
    // One pixel with c = 0: R within R of it (Chebyshev), 6R on it, (1 - h) R beyond.
    const int px = 20, py = 15;
    a.conf[size_t(py * a.w + px)] = 0.0f;
    runStage5(a);
    a.each([&](int x, int y) {
        const float r = a.radius[size_t(y * a.w + x)];
        if (x == px && y == py)
            ASSERT_FLOAT_EQ(r, 6.0f * float(R));
        else if (std::abs(x - px) <= R && std::abs(y - py) <= R)
            ASSERT_FLOAT_EQ(r, float(R)) << x << "," << y;
        else
            ASSERT_FLOAT_EQ(r, (1.0f - 0.98f) * float(R)) << x << "," << y;
    });
    // Random confidences: the two 1D passes equal the brute-force 2D min bit for bit.
    a.conf = randomValues(a.conf.size(), 0, 0.98f, 4);
    runStage5(a);
    a.each([&](int x, int y) { ASSERT_EQ(a.radius[size_t(y * a.w + x)], bruteRadius(a, x, y)); });
}

TEST(Mara2017, CpuRunningMinEqualsTheBruteForceMin) {
    for (int n : {1, 2, 7, 64, 129})
        for (int r : {0, 1, 3, 31, 64, 200}) {
            std::vector<float> in = randomValues(size_t(n), 0, 1, unsigned(n * 1000 + r));
            // NaNs, as std::fmin skips them (every window of three or more holds a number).
            for (int k = 3; r > 0 && k < n; k += 7) in[size_t(k)] = NAN;
            std::vector<float> out(static_cast<size_t>(n));
            std::vector<float> g(size_t(2 * (n + 4 * r + 2))), h(g.size());
            cpu::runningMin(in.data(), 1, n, r, out.data(), 1, g.data(), h.data());
            for (int k = 0; k < n; ++k) {
                float m = INFINITY;
                for (int j = std::max(0, k - r); j <= std::min(n - 1, k + r); ++j)
                    m = std::fmin(m, in[size_t(j)]);
                ASSERT_EQ(out[size_t(k)], m) << "n " << n << " r " << r << " k " << k;
            }
            // Eight columns at once (stage 5's column pass): each lane as the scalar min, with
            // NaNs at other places in each column.
            std::vector<float> in8 = randomValues(size_t(8 * n), 0, 1, unsigned(n * 7 + r));
            for (int c = 0; c < 8; ++c)
                for (int k = c % 5; r > 0 && k < n; k += 5 + c) in8[size_t(8 * k + c)] = NAN;
            std::vector<float> out8(in8.size());
            // Its lines on 32 bytes, as the stage keeps them.
            std::vector<float> lines(16 * g.size() + 8);
            auto* g8 = reinterpret_cast<simd::f8*>(
                (reinterpret_cast<uintptr_t>(lines.data()) + 31) & ~uintptr_t(31));
            cpu::runningMin(in8.data(), 8, n, r, out8.data(), 8, g8, g8 + g.size());
            for (int c = 0; c < 8; ++c)
                for (int k = 0; k < n; ++k) {
                    float m = INFINITY;
                    for (int j = std::max(0, k - r); j <= std::min(n - 1, k + r); ++j)
                        m = std::fmin(m, in8[size_t(8 * j + c)]);
                    ASSERT_EQ(out8[size_t(8 * k + c)], m)
                        << "n " << n << " r " << r << " k " << k << " column " << c;
                }
        }
}

TEST(Mara2017, CpuVectorStagesGiveTheReferenceBits) {
    const int w = 101, h = 23; // tails and borders on both sides
    MaraPlane a(w, h);
    std::vector<float> bump = randomValues(size_t(w * h), -0.02f, 0.02f, 7);
    std::vector<float> tilt = randomValues(size_t(2 * w * h), -0.3f, 0.3f, 8);
    a.temporal = randomValues(a.temporal.size(), 0, 2, 9);
    a.glossy = randomValues(a.glossy.size(), 0, 2, 10);
    for (long i = 0; i < a.size(); ++i) {
        a.setPosition(i, {float(i % w) * 0.01f, float(i / w) * 0.01f, bump[size_t(i)]});
        const Vec3 n{tilt[2 * size_t(i)], tilt[2 * size_t(i) + 1], 1.0f};
        store3(a.nrm.data(), i, n / length(n));
        // Mostly shared roughness in runs, some pixels of their own, one NaN.
        a.rough[size_t(i)] = (i / 40) % 3 == 0 ? 0.01f : (i % 17 == 0 ? 0.7f : 0.4f);
    }
    a.rough[333] = NAN;
    // Stage 4 with a 3-pixel disk and its Gaussian table; stage 7 with radii from 0 to 12.
    a.f.preRadius = 3, a.f.preSigma = 1.5f;
    std::vector<float> gauss;
    maraTapTable(a.preSpiral.data(), a.f.preTaps * kMaraSpiralRotations, 3, a.f.preSigma,
                 a.preOffsets, gauss);
    a.f.preGauss = gauss.data();
    a.radius = randomValues(a.radius.size(), -2, 12, 11);
    a.f.frame = 5;
    // A third of the pixels at the radii stage 7's tables hold (as the stage computes them), and
    // runs of eight sharing one of them or a radius of their own.
    cpu::MaraTapTables tables;
    tables.buildFinal(a.f);
    for (size_t k = 0; k < a.radius.size(); k += 3) a.radius[k] = tables.radius[k % 4];
    for (size_t k = 16; k + 8 < a.radius.size(); k += 40)
        for (size_t l = 0; l < 8; ++l) a.radius[k + l] = k % 80 == 16 ? tables.radius[1] : 2.5f;
    // Runs of eight with two radii, which take each radius's taps in turn: a table's and one of
    // their own, and two of their own.
    for (int y = 1; y < h; y += 4)
        for (size_t l = 0; l < 8; ++l) {
            a.radius[size_t(y * w + 24) + l] = l < 3 ? tables.radius[0] : 7.5f;
            a.radius[size_t(y * w + 64) + l] = l % 2 ? 3.5f : 9.0f;
        }
    // Runs of sixteen, which the AVX-512 path takes as one vector at rotationWidth 16: one radius
    // of the tables, one of their own, and two radii.
    for (int y = 2; y < h; y += 4)
        for (size_t l = 0; l < 16; ++l) {
            a.radius[size_t(y * w) + l] = 5.5f;
            a.radius[size_t(y * w + 32) + l] = tables.radius[1];
            a.radius[size_t(y * w + 80) + l] = l < 5 ? tables.radius[0] : 6.5f;
        }
    // Stages 4 and 7 on the CPU backend's active path, in tiles.
    auto cpuStages = [&](const MaraPlane& from) {
        MaraPlane p = from;
        p.wire();
        tables.buildPre(p.f);
        tables.buildFinal(p.f);
        cpu::maraSparseTile(p.f, p.temporal.data(), false, 0, 48, 0, h, tables);
        cpu::maraSparseTile(p.f, p.temporal.data(), false, 48, w, 0, h, tables);
        cpu::maraSparseTile(p.f, p.glossy.data(), true, 0, w, 0, 9, tables);
        cpu::maraSparseTile(p.f, p.glossy.data(), true, 0, w, 9, h, tables);
        return std::make_pair(p.history, p.matteOut);
    };
    // Each pixel its own rotation: the reference's bits. Runs of eight or sixteen: the taps that
    // land on one pixel are merged, so the sums round differently.
    for (const int across : {1, 8, 16}) {
        a.f.rotationWidth = across;
        MaraPlane b = a;
        std::tie(b.history, b.matteOut) = cpuStages(a);
        // Every path the same bits: eight lanes, and sixteen on AVX-512 (at width 16).
        if (cpu::bestIsa() != cpu::Isa::Avx512)
            std::printf("no AVX-512 here: the sixteen-lane path is not compared\n");
        for (int k = 0; k < int(cpu::bestIsa()); ++k) {
            cpu::setActiveIsa(cpu::Isa(k));
            const auto path = cpuStages(a);
            cpu::setActiveIsa(cpu::bestIsa());
            EXPECT_EQ(path.first, b.history) << across << ", " << cpu::isaName(cpu::Isa(k));
            EXPECT_EQ(path.second, b.matteOut) << across << ", " << cpu::isaName(cpu::Isa(k));
        }
        a.each([&](int x, int y) { maraPreBilateralPixel(a.f, x, y); });
        a.each([&](int x, int y) { maraFinalBilateralPixel(a.f, a.glossy.data(), x, y); });
        if (across == 1) {
            EXPECT_EQ(a.history, b.history);
            EXPECT_EQ(a.matteOut, b.matteOut);
            continue;
        }
        for (size_t k = 0; k < a.history.size(); ++k) {
            ASSERT_NEAR(b.history[k], a.history[k], 2e-6f * (1 + std::fabs(a.history[k]))) << k;
            ASSERT_NEAR(b.matteOut[k], a.matteOut[k], 2e-6f * (1 + std::fabs(a.matteOut[k]))) << k;
        }
        EXPECT_NE(a.matteOut, b.matteOut) << "the merged taps are not exercised";
    }
    // A non-finite colour beside runs of sixteen with two radii, and a -0 centre: a lane's taps
    // of the other radius (weight 0) leave its sums alone, so every path still gives the same
    // bytes (NaN included).
    MaraPlane odd = a;
    odd.f.rotationWidth = 16;
    for (int y = 2; y < h; y += 4) {
        store3(odd.temporal.data(), long(y) * w + 90, {INFINITY, 1.0f, NAN});
        store3(odd.glossy.data(), long(y) * w + 90, {INFINITY, 1.0f, NAN});
        store3(odd.temporal.data(), long(y) * w + 84, {-0.0f, -0.0f, -0.0f});
        store3(odd.glossy.data(), long(y) * w + 84, {-0.0f, -0.0f, -0.0f});
    }
    const auto best = cpuStages(odd);
    auto sameBytes = [](const std::vector<float>& x, const std::vector<float>& y) {
        return x.size() == y.size() && std::memcmp(x.data(), y.data(), x.size() * 4) == 0;
    };
    for (int k = 0; k < int(cpu::bestIsa()); ++k) {
        cpu::setActiveIsa(cpu::Isa(k));
        const auto path = cpuStages(odd);
        cpu::setActiveIsa(cpu::bestIsa());
        EXPECT_TRUE(sameBytes(path.first, best.first)) << cpu::isaName(cpu::Isa(k));
        EXPECT_TRUE(sameBytes(path.second, best.second)) << cpu::isaName(cpu::Isa(k));
    }
    MaraPlane b = a;
    b.wire();
    a.each([&](int x, int y) { maraMedianPixel(a.f, x, y); });
    a.each([&](int x, int y) {
        maraGlossyPassPixel(a.f, a.glossy.data(), a.glossyRow.data(), x, y, 1, 0);
    });
    a.each([&](int x, int y) {
        maraGlossyPassPixel(a.f, a.glossyRow.data(), a.glossyOut.data(), x, y, 0, 1);
    });
    cpu::maraMedianRows(b.f, 0, h);
    // The pair weights' rows reach into the band above: bands of 5 and 18 rows.
    const int reach = cpu::maraGlossyReach(b.f);
    // The scratch filled with NaN (which a weight turns into 0) and with 0.5 (a weight or a
    // colour) where the passes have not written: a read of it would show in the outputs.
    for (const float stale : {NAN, 0.5f}) {
        std::vector<float> scratch(cpu::maraGlossyScratch(w, reach), stale);
        cpu::maraGlossyRows(b.f, b.glossy.data(), b.glossyRow.data(), 0, h, false, reach,
                            scratch.data());
        cpu::maraGlossyRows(b.f, b.glossyRow.data(), b.glossyOut.data(), 0, 5, true, reach,
                            scratch.data());
        cpu::maraGlossyRows(b.f, b.glossyRow.data(), b.glossyOut.data(), 5, h, true, reach,
                            scratch.data());
        EXPECT_EQ(a.glossyRow, b.glossyRow) << stale;
        EXPECT_EQ(a.glossyOut, b.glossyOut) << stale;
    }
    EXPECT_EQ(a.median, b.median);
}

TEST(Mara2017, M6MedianRemovesAFireflyAndKeepsAStep) {
    MaraPlane a(9, 9);
    a.temporal.assign(a.temporal.size(), 0.5f);
    store3(a.temporal.data(), 4 * 9 + 4, {100, 100, 100});
    a.each([&](int x, int y) { maraMedianPixel(a.f, x, y); });
    for (float v : a.pixels(a.median)) ASSERT_EQ(v, 0.5f);
    a.each([&](int x, int y) {
        store3(a.temporal.data(), y * 9 + x, Vec3{1, 1, 1} * (x < 4 ? 0.2f : 0.8f));
    });
    a.each([&](int x, int y) { maraMedianPixel(a.f, x, y); });
    EXPECT_EQ(a.pixels(a.median), a.pixels(a.temporal));
}

/// A static camera looking down -z at a plane at z = -2, colour `c` (albedo 1).
std::vector<FrameData> planeFrames(int w, int h, int n, Vec3 c, float dx = 0) {
    std::vector<FrameData> frames;
    for (int k = 0; k < n; ++k) {
        const Mat4 vp = test::cameraAt({dx * float(k), 0, 0}, w, h);
        frames.push_back(test::planeFrame(vp, w, h, c, [](int, int) { return -2.0f; }));
    }
    return frames;
}

TEST(Mara2017, M6FireflyIsNotShownButEntersTheHistory) {
    const int w = 32, h = 24;
    std::vector<FrameData> frames = planeFrames(w, h, 6, {0.5f, 0.5f, 0.5f});
    const long p = 12L * w + 16;
    store3(frames[5].color.data(), p, {100, 100, 100});
    Mara2017Denoiser d;
    d.setDebugOutputs(true);
    for (int k = 0; k < 6; ++k) {
        const ImageView out = d.denoise(frames[size_t(k)].input());
        const ImageView t = d.debug().accumulatedNoisy; // stage 3's T, the history loop
        if (k == 5) {
            EXPECT_NEAR(out.data[3 * p], 0.5f, 1e-4f) << "the firefly is shown";
            EXPECT_GT(t.data[3 * p], 10.0f) << "the firefly left the loop";
        }
    }
}

/// The CPU backend's output and debug buffers are the reference's, bit for bit, with each pixel
/// its own rotation.
void expectCpuGivesTheReferenceBits(const std::vector<FrameData>& frames) {
    auto cpu = makeFilter("mara2017", {{"backend", "cpu"}, {"rotationWidth", "1"}});
    auto ref = makeFilter("mara2017", {{"backend", "reference"}, {"rotationWidth", "1"}});
    cpu->setDebugOutputs(true);
    ref->setDebugOutputs(true);
    for (size_t k = 0; k < frames.size(); ++k) {
        const ImageView a = cpu->denoise(frames[k].input()), b = ref->denoise(frames[k].input());
        const size_t n = size_t(3 * a.width * a.height);
        ASSERT_EQ(0, std::memcmp(a.data, b.data, n * sizeof(float))) << "frame " << k;
        const DebugBuffers da = cpu->debug(), db = ref->debug();
        ASSERT_EQ(
            0, std::memcmp(da.accumulatedNoisy.data, db.accumulatedNoisy.data, n * sizeof(float)))
            << "stage 3's T, frame " << k;
        ASSERT_EQ(0, std::memcmp(da.historyLength.data, db.historyLength.data,
                                 size_t(a.width * a.height) * sizeof(float)))
            << "frame " << k;
    }
}

TEST(Mara2017, CpuBackendGivesTheReferenceBitsWithEachPixelItsOwnRotation) {
    // Every CPU stage but the merged taps of shared rotations keeps the reference's bits: the
    // whole filter, factored paths and glossy included (and the plain colour: the composition
    // re-modulates it), on an odd width (tails of 8 pixels).
    for (const bool factored : {true, false}) {
        const std::vector<FrameData> frames =
            test::pathTracedBox(83, 61, 5, 3, 0.04f, 0, factored ? 2 : 0);
        ASSERT_EQ(frames[0].matteIndirect.pixels.empty(), !factored);
        expectCpuGivesTheReferenceBits(frames);
    }
}

TEST(Mara2017, M7SparseTapsStayInTheDiskAndTurnEveryFrame) {
    const Mara2017Settings s;
    const MaraFrame f = maraFrameSettings(s, 1280);
    ASSERT_FLOAT_EQ(f.preRadius, 6.4f); // 1% of the width across
    std::vector<float> spiral;
    maraSpiralTable(f.preTaps, 0.0f, spiral);
    ASSERT_EQ(spiral.size(), size_t(2 * 50 * kMaraSpiralRotations));
    for (size_t k = 0; k < spiral.size(); k += 2) {
        const float r = std::hypot(spiral[k], spiral[k + 1]);
        ASSERT_LT(r, 1.0f);
        const int dx = maraTapOffset(spiral[k], f.preRadius),
                  dy = maraTapOffset(spiral[k + 1], f.preRadius);
        ASSERT_LE(std::hypot(float(dx), float(dy)), f.preRadius + 0.7072f);
    }
    EXPECT_NE(maraFrameRotation(0, 0, 4), maraFrameRotation(1, 0, 4));
    // Each pixel its own rotation (rotationWidth 1), or runs of eight or sixteen (the default)
    // sharing one: neighbouring runs differ, the 16 rotations are used alike, and a pixel's
    // changes with the frame.
    for (const int across : {1, 8, 16}) {
        int differ = 0, sameInRun = 0, changes = 0;
        for (int x = 0; x < 64 * across; x += across)
            differ += maraPixelRotation(x, 0, across, 0, 0, 4) !=
                      maraPixelRotation(x + across, 0, across, 0, 0, 4);
        for (int x = 0; x < 64; ++x)
            sameInRun += maraPixelRotation(x, 3, across, 0, 0, 4) ==
                         maraPixelRotation(x / across * across, 3, across, 0, 0, 4);
        for (uint32_t frame = 0; frame < 64; ++frame)
            changes += maraPixelRotation(13, 7, across, frame, 0, 4) !=
                       maraPixelRotation(13, 7, across, frame + 1, 0, 4);
        EXPECT_GT(differ, 48) << across;
        EXPECT_EQ(sameInRun, 64) << across;
        EXPECT_GT(changes, 48) << across;
        int histogram[kMaraSpiralRotations] = {};
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 64; ++x)
                ++histogram[maraPixelRotation(x * across, y, across, 0, 0, 4)];
        for (int r = 0; r < kMaraSpiralRotations; ++r) {
            EXPECT_GT(histogram[r], 256 * 7 / 10) << across << ", rotation " << r;
            EXPECT_LT(histogram[r], 256 * 13 / 10) << across << ", rotation " << r;
        }
        // Over many frames one pixel's own taps (its rotation each frame) cover the whole disk:
        // the time average is a dense filter.
        std::set<std::pair<int, int>> hit;
        for (uint32_t frame = 0; frame < 64; ++frame) {
            maraSpiralTable(f.preTaps, maraFrameRotation(frame, 0, 4), spiral);
            const int r = maraPixelRotation(13, 7, across, frame, 0, 4);
            for (int k = 0; k < f.preTaps; ++k)
                hit.insert(
                    {maraTapOffset(spiral[size_t(2 * (r * f.preTaps + k))], f.preRadius),
                     maraTapOffset(spiral[size_t(2 * (r * f.preTaps + k) + 1)], f.preRadius)});
        }
        int inside = 0, missed = 0;
        for (int dy = -6; dy <= 6; ++dy)
            for (int dx = -6; dx <= 6; ++dx)
                if (std::hypot(float(dx), float(dy)) <= f.preRadius - 0.5f && (dx || dy))
                    ++inside, missed += !hit.count({dx, dy});
        EXPECT_EQ(missed, 0) << "of " << inside << ", rotation width " << across;
    }
}

TEST(Mara2017, M8GlossySigmaLimitsAndSeparability) {
    EXPECT_FLOAT_EQ(maraGlossySigma(1.0f, 7, 0.1f, 1e-4f), 7.0f + 1e-4f);
    EXPECT_FLOAT_EQ(maraGlossySigma(0.0f, 7, 0.1f, 1e-4f), 1e-4f);
    EXPECT_NEAR(maraGlossySigma(0.01f, 7, 0.1f, 1e-4f), 4.4f, 0.05f); // the notes' table
    EXPECT_NEAR(maraGlossySigma(0.5f, 7, 0.1f, 1e-4f), 6.5f, 0.05f);
    // Roughness 0: the identity.
    MaraPlane a(20, 10);
    a.glossy = randomValues(a.glossy.size(), 0, 1, 5);
    a.each([&](int x, int y) {
        maraGlossyPassPixel(a.f, a.glossy.data(), a.glossyRow.data(), x, y, 1, 0);
    });
    EXPECT_EQ(a.pixels(a.glossyRow), a.pixels(a.glossy));
    // H then V of an impulse with unit edge weights is the normalised 2D Gaussian.
    MaraPlane b(81, 81);
    b.rough.assign(b.rough.size(), 0.5f);
    const float sigma = maraGlossySigma(0.5f, 7, 0.1f, 1e-4f);
    store3(b.glossy.data(), 40L * 81 + 40, {1, 1, 1});
    b.each([&](int x, int y) {
        maraGlossyPassPixel(b.f, b.glossy.data(), b.glossyRow.data(), x, y, 1, 0);
    });
    b.each([&](int x, int y) {
        maraGlossyPassPixel(b.f, b.glossyRow.data(), b.glossyOut.data(), x, y, 0, 1);
    });
    double total = 0;
    const int reach = int(std::ceil(3.0f * sigma));
    for (int dy = -reach; dy <= reach; ++dy)
        for (int dx = -reach; dx <= reach; ++dx)
            total += std::exp(-double(dx * dx + dy * dy) / (2.0 * sigma * sigma));
    for (int dy = -10; dy <= 10; ++dy)
        for (int dx = -10; dx <= 10; ++dx) {
            const double want =
                std::exp(-double(dx * dx + dy * dy) / (2.0 * sigma * sigma)) / total;
            ASSERT_NEAR(b.glossyOut[3 * size_t((40 + dy) * 81 + 40 + dx)], want, 1e-6)
                << dx << "," << dy;
        }
}

TEST(Mara2017, M9NoBilateralStageCrossesAPlaneStep) {
    MaraPlane a(40, 30);
    a.each([&](int x, int y) {
        a.setPosition(long(y) * a.w + x,
                      {float(x) * 0.01f, float(y) * 0.01f, x < 20 ? 0.0f : 1.0f});
    });
    a.f.preRadius = 4, a.f.preSigma = 2;
    for (size_t k = 0; k < a.preSpiral.size(); ++k)
        a.preOffsets[k] = maraTapOffset(a.preSpiral[k], 4);
    a.radius.assign(a.radius.size(), 6.0f);
    a.rough.assign(a.rough.size(), 1.0f);
    auto run = [&](std::vector<float> input) {
        a.temporal = input, a.glossy = input;
        a.each([&](int x, int y) { maraPreBilateralPixel(a.f, x, y); });
        a.each([&](int x, int y) { maraFinalBilateralPixel(a.f, input.data(), x, y); });
        a.each([&](int x, int y) {
            maraGlossyPassPixel(a.f, input.data(), a.glossyRow.data(), x, y, 1, 0);
        });
        return std::vector<std::vector<float>>{a.history, a.matteOut, a.glossyRow};
    };
    std::vector<float> in = randomValues(a.temporal.size(), 0, 1, 6);
    const auto before = run(in);
    a.each([&](int x, int y) {
        if (x >= 20)
            for (int c = 0; c < 3; ++c) in[3 * size_t(y * a.w + x) + c] += 5.0f;
    });
    const auto after = run(in);
    for (size_t s = 0; s < before.size(); ++s) {
        int blurred = 0;
        a.each([&](int x, int y) {
            for (int c = 0; c < 3; ++c) {
                const size_t k = 3 * size_t(y * a.w + x) + c;
                if (x < 20) {
                    ASSERT_EQ(before[s][k], after[s][k]) << "stage " << s << " " << x << "," << y;
                }
                blurred += before[s][k] != in[k] - (x >= 20 ? 5.0f : 0.0f);
            }
        });
        EXPECT_GT(blurred, a.w * a.h) << "stage " << s << " filters within each side";
    }
}

TEST(Mara2017, M10VirtualPositionLandsOnThePreviousReflection) {
    const int w = 256, h = 192;
    MaraPlane a(w, h);
    // A mirror at z = 0 seen from z = 3; the reflected point P = (0.4, 0.3, 1), mirror image P'.
    const Vec3 eye{0, 0, 3}, was{-0.5f, 0.3f, 3}, image{0.4f, 0.3f, -1};
    const Vec3 x = eye + 0.75f * (image - eye); // where the ray to P' crosses the mirror
    a.setPosition(100, x);
    a.hitDistance[100] = length(Vec3{0.4f, 0.3f, 1} - x);
    a.f.eye = eye;
    a.f.previous.viewProjection = test::cameraAt(was, w, h);
    Vec2 virt, surface, expected;
    ASSERT_TRUE(maraVirtualPreviousPixel(a.f, 100, virt));
    // The previous camera saw P through the mirror point on its own ray to P'.
    const float t = 3.0f / (3.0f - image.z);
    const Vec3 xPrev = was + t * (image - was);
    ASSERT_TRUE(
        projectToPixel(a.f.previous.viewProjection, xPrev, a.f.previous.jitter, w, h, expected));
    ASSERT_TRUE(projectToPixel(a.f.previous.viewProjection, x, a.f.previous.jitter, w, h, surface));
    EXPECT_NEAR(virt.x, expected.x, 1e-3f);
    EXPECT_NEAR(virt.y, expected.y, 1e-3f);
    EXPECT_GT(std::hypot(surface.x - expected.x, surface.y - expected.y), 2.0f)
        << "the primary surface would reproject elsewhere";
}

TEST(Mara2017, M2ConstantInputStaysConstantWithAMovingCamera) {
    const int w = 40, h = 30;
    for (bool factored : {false, true}) {
        std::vector<FrameData> frames = planeFrames(w, h, 6, {0.3f, 0.5f, 0.7f}, 0.02f);
        for (FrameData& f : frames) {
            if (!factored) continue;
            f.matteIndirect = f.color;
            f.directLight = ImageF(w, h, 3);
            for (float& v : f.directLight.pixels) v = 0.1f;
            for (float& v : f.albedo.pixels) v = 0.5f;
            for (float& v : f.color.pixels) v *= 1.7f; // ignored with the factorisation
        }
        Mara2017Denoiser d;
        for (size_t k = 0; k < frames.size(); ++k) {
            const ImageView out = d.denoise(frames[k].input());
            for (long i = 0; i < long(w) * h; ++i)
                for (int c = 0; c < 3; ++c) {
                    const float want =
                        factored ? 0.1f + 0.5f * (0.3f + 0.2f * float(c)) : 0.3f + 0.2f * float(c);
                    ASSERT_NEAR(out.data[3 * i + c], want, 1e-5f)
                        << factored << " frame " << k << " " << i;
                }
        }
    }
}

TEST(Mara2017, M11CompositionOnAFlatSurface) {
    const int w = 24, h = 18;
    std::vector<FrameData> frames = planeFrames(w, h, 3, {1, 1, 1});
    const Vec3 M{0.4f, 0.3f, 0.2f}, G{0.6f, 0.6f, 0.5f}, D{0.05f, 0.1f, 0.15f},
        rho{0.7f, 0.5f, 0.3f}, F0{0.04f, 0.5f, 0.9f}, E{0.01f, 0, 0};
    for (FrameData& f : frames) {
        auto fill3 = [&](ImageF& img, Vec3 v) {
            img = ImageF(w, h, 3);
            for (long i = 0; i < long(w) * h; ++i) store3(img.data(), i, v);
        };
        fill3(f.matteIndirect, M), fill3(f.glossyIndirect, G), fill3(f.directLight, D);
        fill3(f.albedo, rho), fill3(f.specularF0, F0), fill3(f.emission, E);
        f.roughness = ImageF(w, h, 1), f.glossyHitDistance = ImageF(w, h, 1);
        for (float& v : f.roughness.pixels) v = 0.3f;
        for (float& v : f.glossyHitDistance.pixels) v = 1.0f;
    }
    Mara2017Denoiser d;
    for (FrameData& f : frames) {
        const ImageView out = d.denoise(f.input());
        for (long i = 0; i < long(w) * h; ++i) {
            const Vec3 p = load3(f.position.data(), i);
            const double cosine = 2.0 / std::sqrt(double(p.x) * p.x + double(p.y) * p.y + 4.0);
            for (int c = 0; c < 3; ++c) {
                const double F = F0[c] + (1 - F0[c]) * std::pow(1 - cosine, 5);
                const double want = D[c] + (1 - F) * (1 - F) * rho[c] * M[c] + F * G[c] + E[c];
                ASSERT_NEAR(out.data[3 * i + c], want, 1e-5) << i << " " << c;
            }
        }
    }
}

TEST(Mara2017, M12MatteRadiiFollowTheWidthAndTheGlossySigmaDoesNot) {
    const Mara2017Settings s;
    const MaraFrame a = maraFrameSettings(s, 1280), b = maraFrameSettings(s, 640);
    EXPECT_FLOAT_EQ(a.preRadius, 6.4f);
    EXPECT_FLOAT_EQ(b.preRadius, 3.2f);
    EXPECT_EQ(a.maxRadius, 64);
    EXPECT_EQ(b.maxRadius, 32);
    EXPECT_FLOAT_EQ(a.preSigma, 2 * b.preSigma);
    EXPECT_EQ(a.glossyScale, b.glossyScale);
    EXPECT_EQ(a.glossyEpsilon, b.glossyEpsilon);
}

TEST(Mara2017, SettingsAndBuffersAreChecked) {
    EXPECT_NE(errorOf([] {
                  makeFilter("mara2017", {{"confidenceFar", "0.01"}});
              }).find("confidenceNear"),
              std::string::npos);
    EXPECT_NE(errorOf([] {
                  makeFilter("mara2017", {{"hysteresis", "1.5"}});
              }).find("hysteresis"),
              std::string::npos);
    std::vector<FrameData> frames = planeFrames(16, 12, 1, {1, 1, 1});
    frames[0].matteIndirect = ImageF(8, 12, 3);
    Mara2017Denoiser d;
    EXPECT_NE(errorOf([&] { d.denoise(frames[0].input()); }).find("matteIndirect"),
              std::string::npos);
    frames[0].matteIndirect = ImageF(16, 12, 3);
    frames[0].matteIndirect.pixels[5] = NAN;
    const ImageView out = d.denoise(frames[0].input());
    EXPECT_EQ(d.lastStats().nonFiniteInputs, 1);
    for (long k = 0; k < 3L * 16 * 12; ++k) ASSERT_TRUE(std::isfinite(out.data[k]));
}

// Stage 8 end to end: a near-mirror metal floor reflecting a striped wall, the camera moving
// sideways. Reprojecting the reflection's virtual position keeps the reflected stripes where
// they are; reprojecting the floor's own point drags them with the camera, so the glossy
// history lands on the wrong stripes.
TEST(Mara2017, VirtualReprojectionKeepsAMovingReflectionSharp) {
    using namespace render;
    Scene s;
    Material mirror, light, dark;
    mirror.baseColor = {1, 1, 1}, mirror.metallic = 1, mirror.roughness = 0.0f;
    light.baseColor = {0.9f, 0.9f, 0.9f}, light.roughness = 1, light.specular = 0;
    dark.baseColor = {0.05f, 0.05f, 0.05f}, dark.roughness = 1, dark.specular = 0;
    s.materials = {mirror, light, dark};
    auto quad = [&](Vec3 a, Vec3 b, Vec3 c, Vec3 d, int m) {
        s.addTriangle(a, b, c, m);
        s.addTriangle(a, c, d, m);
    };
    quad({-4, 0, -4}, {-4, 0, 2}, {4, 0, 2}, {4, 0, -4}, 0);
    for (int k = 0; k < 8; ++k) { // stripes 0.5 m wide on the wall at z = -2
        const float x0 = -2 + 0.5f * float(k), x1 = x0 + 0.5f;
        quad({x0, 0, -2}, {x1, 0, -2}, {x1, 1.5f, -2}, {x0, 1.5f, -2}, 1 + k % 2);
    }
    Environment env; // a sun on the wall, no sky: the floor shows glossy indirect light alone
    env.sun.direction = normalize(Vec3{0.2f, 0.6f, 1.0f});
    env.sun.irradiance = {3, 3, 3};
    env.sun.angularDiameter = 0.0093f;
    RayAccel accel(s);
    LightSet lights(s, {}, env);
    const int w = 96, h = 64, n = 10;
    FrameRenderer r(s, accel, w, h, 1, 5);
    r.setFactoredPaths(8);
    std::vector<FrameData> frames(n);
    CameraPose previous;
    for (int i = 0; i < n; ++i) {
        CameraPose pose;
        pose.position = {-0.3f + 0.06f * float(i), 0.6f, 1.5f};
        pose.target = pose.position + Vec3{0, -0.35f, -1};
        pose.fovY = 0.9f;
        FrameRenderStats stats;
        ASSERT_TRUE(r.render(i, pose, previous, i > 0, lights, false, 64, frames[size_t(i)], stats,
                             nullptr));
        previous = pose;
    }
    double err[2] = {0, 0};
    for (int virt = 0; virt < 2; ++virt) {
        Mara2017Settings st;
        st.virtualReprojection = virt == 1;
        Mara2017Denoiser d(st);
        for (int i = 0; i < n; ++i) {
            const ImageView out = d.denoise(frames[size_t(i)].input());
            if (i < 4) continue;
            // The floor's pixels (metal: all glossy), against the reference.
            for (long p = 0; p < long(w) * h; ++p) {
                if (frames[size_t(i)].position.data()[3 * p + 1] > 1e-3f) continue;
                for (int c = 0; c < 3; ++c) {
                    const double e =
                        out.data[3 * p + c] - frames[size_t(i)].reference.data()[3 * p + c];
                    err[virt] += e * e;
                }
            }
        }
    }
    std::printf("mara stage 8: floor squared error, surface %.4g, virtual %.4g\n", err[0], err[1]);
    EXPECT_LT(err[1], 0.3 * err[0]);
}

// End to end on a path-traced Cornell box with a moving camera, rendered with the paper's
// factored paths (one matte and one glossy path, 16 light samples standing in for its
// rasterised direct light). With the paper's 3x3 clamp the error is at most 0.35 of the noisy
// input's; the clamp to one sample's 3x3 holds the history's mean down, and a 5x5 box
// (clampRadius 2) brings it to at most a quarter, the target.
TEST(Mara2017, PathTracedCornellErrorIsAtMostAQuarterOfNoisyWithA5x5Clamp) {
    render::SceneDescription d = render::loadSceneDescription("cornell-moving", ".");
    d.width = 160, d.height = 120, d.frames = 16, d.referenceSpp = 128;
    d.factoredDirectSpp = 16;
    const std::string dir = testing::freshDir("Mara2017", "cornell").string();
    render::SequenceRenderOptions o;
    o.output = dir, o.quiet = true;
    render::renderSequence(
        d, o, nullptr, [](int, int) {}, [](const std::string&) {});
    auto reader = SequenceReader::open(dir);
    Mara2017Settings wide;
    wide.clampRadius = 2;
    Mara2017Denoiser paper, wider(wide);
    double outPaper = 0, outWide = 0, in = 0;
    FrameData f;
    for (int i = 0; i < d.frames; ++i) {
        reader->load(i, f);
        ASSERT_FALSE(f.matteIndirect.pixels.empty());
        auto copy = [](const ImageView& v) {
            ImageF img(v.width, v.height, 3);
            std::copy(v.data, v.data + 3L * v.width * v.height, img.data());
            return img;
        };
        const ImageF a = copy(paper.denoise(f.input())), b = copy(wider.denoise(f.input()));
        if (i < 4) continue; // the first frames have little history
        outPaper += rmseToneMapped(a, f.reference);
        outWide += rmseToneMapped(b, f.reference);
        in += rmseToneMapped(f.color, f.reference);
    }
    EXPECT_LE(outPaper, 0.35 * in) << "3x3: " << outPaper / in;
    EXPECT_LE(outWide, 0.25 * in) << "5x5: " << outWide / in;
    std::printf("mara e2e: 3x3 %.3f, 5x5 %.3f of noisy\n", outPaper / in, outWide / in);
    std::filesystem::remove_all(dir);
}

} // namespace
} // namespace bmfr
