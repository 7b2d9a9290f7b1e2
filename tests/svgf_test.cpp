// SVGF: the a-trous filter keeps constants and edges, the variance estimate converges, and the
// whole filter denoises, also with fewer than 1 spp.
#include "backend/cpu/isa.h"
#include "backend/cpu/svgf/cpu_svgf_atrous.h"
#include "backend/cpu/svgf/cpu_svgf_variance.h"
#include "backend/cpu/svgf/cpu_svgf_weights.h"
#include "backend/reference/svgf/reference_svgf_stages.h"
#include "core/hash.h"
#include "core/image.h"
#include "filters/svgf/svgf_kernels.h"
#include "metrics/basic_metrics.h"
#include "synth/procedural_scene.h"
#include "test_scenes.h"
#include <bmfr/bmfr.hpp>
#include <bmfr/error.h>
#include <cmath>
#include <cstring>
#include <gtest/gtest.h>

namespace bmfr {
namespace {

struct Planes {
    ImageF colorVar, normal, depth, gradient;
    ImageU8 length;
    Planes(int w, int h)
        : colorVar(w, h, 4), normal(w, h, 3), depth(w, h, 1), gradient(w, h, 2), length(w, h, 1) {
        for (auto& v : length.pixels) v = 1;
    }
};

ImageF runAtrous(const Planes& p, const SvgfSettings& s, int levels) {
    ImageF a = p.colorVar, b(p.colorVar.width, p.colorVar.height, 4);
    const int w = a.width, h = a.height;
    for (int k = 0; k < levels; ++k) {
        const AtrousLevel level{
            a.data(), b.data(), p.normal.data(), p.depth.data(), p.gradient.data(), p.length.data(),
            w,        h,        1 << k};
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) svgfAtrousPixel(level, s, x, y);
        std::swap(a, b);
    }
    return a;
}

TEST(Svgf, AtrousLeavesAConstantImageUnchanged) {
    const int w = 40, h = 30;
    Planes p(w, h);
    for (long i = 0; i < long(w) * h; ++i) {
        float* c = p.colorVar.data() + 4 * i;
        c[0] = 0.3f, c[1] = 0.5f, c[2] = 0.7f, c[3] = unitFloat(wangHash(uint32_t(i)));
        Vec3 n = normalize(
            Vec3{unitFloat(wangHash(uint32_t(i) + 7)), 1, unitFloat(wangHash(uint32_t(i) + 9))});
        store3(p.normal.data(), i, n);
        p.depth.data()[i] = 3 + unitFloat(wangHash(uint32_t(i) + 11));
        p.gradient.data()[2 * i] = 0.1f, p.gradient.data()[2 * i + 1] = -0.05f;
    }
    for (int radius : {1, 2}) {
        SvgfSettings s;
        s.kernelRadius = radius;
        ImageF out = runAtrous(p, s, 5);
        for (long i = 0; i < long(w) * h; ++i) {
            ASSERT_NEAR(out.data()[4 * i], 0.3f, 1e-5f);
            ASSERT_NEAR(out.data()[4 * i + 1], 0.5f, 1e-5f);
            ASSERT_NEAR(out.data()[4 * i + 2], 0.7f, 1e-5f);
        }
    }
}

TEST(Svgf, EdgeStoppingKeepsAStepBetweenTwoPlanes) {
    const int w = 64, h = 16;
    for (bool depthStep : {false, true}) {
        Planes p(w, h);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const long i = long(y) * w + x;
                const bool left = x < w / 2;
                const float v = left ? 0.2f : 0.8f;
                float* c = p.colorVar.data() + 4 * i;
                c[0] = c[1] = c[2] = v, c[3] = 4.0f; // large variance: luminance alone would blur
                // Either the normals differ (perpendicular planes) or the depths do.
                store3(p.normal.data(), i, depthStep || left ? Vec3{0, 0, 1} : Vec3{1, 0, 0});
                p.depth.data()[i] = depthStep && !left ? 6.0f : 5.0f;
            }
        ImageF out = runAtrous(p, SvgfSettings{}, 5);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const float expected = x < w / 2 ? 0.2f : 0.8f;
                ASSERT_NEAR(out.at(x, y, 1), expected, 1e-4f)
                    << (depthStep ? "depth" : "normal") << " step, x " << x;
            }
    }
}

TEST(Svgf, VarianceOfAStaticNoisySequenceConvergesToTheTrueVariance) {
    const int w = 48, h = 32;
    const Mat4 cam = test::cameraAt({0, 0, 0}, w, h);
    SvgfSettings s;
    s.threads = 2;
    SvgfDenoiser d(s);
    FrameData f = test::planeFrame(cam, w, h, {1, 1, 1}, [](int, int) { return -4.0f; });
    const double trueVariance = 1.0 / 12.0; // uniform noise of width 1
    for (int k = 0; k < 60; ++k) {
        for (long i = 0; i < long(w) * h; ++i) {
            float v = 1.0f + unitFloat(hashKeys(uint32_t(i), uint32_t(k), 3)) - 0.5f;
            store3(f.color.data(), i, {v, v, v});
        }
        d.denoise(f.input());
    }
    double mean = 0;
    ImageView var = d.variance();
    for (long i = 0; i < long(w) * h; ++i) mean += var.data[i];
    mean /= double(w) * h;
    // Exponential moments with weight a estimate the variance times 1 - a / (2 - a).
    const double expected = trueVariance * (1.0 - 0.2 / 1.8);
    EXPECT_NEAR(mean, expected, 0.06 * expected);
    EXPECT_NEAR(mean, trueVariance, 0.15 * trueVariance);
}

double meanRmse(Filter& f, int frames, float sampleFraction, double* noisy) {
    ProceduralSceneOptions o;
    o.width = 128, o.height = 96, o.frames = frames;
    ProceduralScene scene(o);
    FrameData fr;
    ImageF mask(o.width, o.height, 1);
    double out = 0, in = 0;
    for (int i = 0; i < frames; ++i) {
        scene.render(i, fr);
        FrameInput input = fr.input();
        if (sampleFraction < 1) {
            for (long k = 0; k < mask.pixelCount(); ++k)
                mask.data()[k] =
                    unitFloat(hashKeys(uint32_t(k), uint32_t(i), 1)) < sampleFraction ? 1.0f : 0.0f;
            input.sampleMask = view(mask);
        }
        ImageView v = f.denoise(input);
        ImageF img(v.width, v.height, 3);
        std::memcpy(img.data(), v.data, img.pixels.size() * sizeof(float));
        for (float x : img.pixels) EXPECT_TRUE(std::isfinite(x));
        if (i >= frames / 2)
            out += rmseToneMapped(img, fr.reference), in += rmseToneMapped(fr.color, fr.reference);
    }
    if (noisy) *noisy = in;
    return out;
}

TEST(Svgf, DenoisesTheProceduralSequenceAndHandlesMissingSamples) {
    for (bool progressive : {false, true}) {
        SvgfSettings s;
        if (progressive) s.kernelRadius = 1, s.reverseLevels = true, s.spatialVarianceFrames = 0;
        SvgfDenoiser full(s), half(s);
        double noisy = 0;
        double errFull = meanRmse(full, 12, 1.0f, &noisy);
        EXPECT_LT(errFull, 0.3 * noisy) << (progressive ? "progressive" : "original");
        double errHalf = meanRmse(half, 12, 0.5f, nullptr);
        EXPECT_LT(errHalf, 0.4 * noisy) << "half the samples";
    }
}

TEST(Svgf, SettingsAndFactoryErrors) {
    SvgfSettings bad;
    bad.kernelRadius = 3;
    EXPECT_THROW(SvgfDenoiser{bad}, Error);
    EXPECT_THROW(makeFilter("nlm"), Error);
    EXPECT_STREQ(makeFilter("svgf")->name(), "svgf");
    EXPECT_STREQ(makeFilter("bmfr")->name(), "bmfr");
    // Settings by key, range-checked by the filter's table; a key of another filter is an error.
    EXPECT_NO_THROW(makeFilter("svgf", {{"iterations", "3"}, {"backend", "reference"}}));
    EXPECT_THROW(makeFilter("svgf", {{"iterations", "9"}}), Error);
    EXPECT_THROW(makeFilter("svgf", {{"blockSize", "16"}}), Error);
    EXPECT_THROW(makeFilter("bmfr", {{"blockSize", "sixteen"}}), Error);
    EXPECT_THROW(makeFilter("walr", {{"backend", "cuda"}}), Error); // bmfr and svgf only
}

// The CPU backend's variance estimate against the reference's, on every path the processor has:
// long histories bit for bit, short ones (the 7x7 bilateral) within rounding, at the sides too
// (a width that is no multiple of eight) and with a non-default normal exponent.
TEST(Svgf, CpuVarianceEstimateMatchesTheReference) {
    const int w = 45, h = 23;
    const long n = long(w) * h;
    std::vector<float> integrated(size_t(3 * n)), moments(size_t(2 * n)), normal(size_t(3 * n));
    std::vector<float> depth(static_cast<size_t>(n)), gradient(size_t(2 * n));
    std::vector<uint8_t> length(static_cast<size_t>(n));
    auto rnd = [](long i, uint32_t k) { return unitFloat(hashKeys(uint32_t(i), k, 91u)); };
    for (long i = 0; i < n; ++i) {
        for (int c = 0; c < 3; ++c) integrated[size_t(3 * i + c)] = 2.0f * rnd(i, uint32_t(c));
        const float l = rnd(i, 3);
        moments[size_t(2 * i)] = l, moments[size_t(2 * i + 1)] = l * l + 0.1f * rnd(i, 4);
        const Vec3 nv = normalize(Vec3{0.2f * rnd(i, 5), 0.2f * rnd(i, 6), 1.0f});
        normal[size_t(3 * i)] = nv.x, normal[size_t(3 * i + 1)] = nv.y;
        normal[size_t(3 * i + 2)] = nv.z;
        depth[size_t(i)] = 5.0f + float(i % w) * 0.01f + (i % 7 == 0 ? 1.0f : 0.0f);
        gradient[size_t(2 * i)] = 0.01f, gradient[size_t(2 * i + 1)] = 0.002f;
        length[size_t(i)] = uint8_t(hashKeys(uint32_t(i), 8u) % 7); // 0 (no sample) to 6
    }
    SvgfFrame f;
    f.width = w, f.height = h;
    f.integrated = integrated.data(), f.moments = moments.data();
    f.normal = normal.data(), f.depth = depth.data(), f.depthGradient = gradient.data();
    f.length = length.data();
    // The CPU backend makes the gradient from the depth (svgfFirstLevelRows); so does the
    // reference's accumulation.
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) svgfDepthGradientPixel(f, x, y);
    for (float phiNormal : {128.0f, 32.0f})
        for (cpu::Isa isa : cpu::supportedIsas()) {
            cpu::setActiveIsa(isa);
            SvgfSettings s;
            s.phiNormal = phiNormal;
            ASSERT_TRUE(cpu::cpuNormalPowerSupports(s));
            std::vector<float> refOut(size_t(4 * n)), refVar(static_cast<size_t>(n)),
                var(refVar.size());
            reference::svgfVariancePixels(f, s, 0, h, refOut.data(), refVar.data());
            cpu::CpuAtrous atrous;
            const cpu::SvgfFirstLevel level = atrous.firstLevel(w, h, s);
            cpu::svgfFirstLevelRows(f, level, 0, h);
            cpu::svgfVarianceRows(f, s, level, 0, h, var.data());
            int estimated = 0;
            for (long i = 0; i < n; ++i) {
                const long p = i / w * atrous.pitch() + i % w;
                const bool estimate = length[size_t(i)] > 0 && length[size_t(i)] < 4;
                estimated += estimate;
                for (int c = 0; c < 3; ++c)
                    ASSERT_EQ(atrous.level(0, c)[p], refOut[size_t(4 * i + c)]) << i;
                if (estimate) {
                    EXPECT_NEAR(var[size_t(i)], refVar[size_t(i)], 1e-5f * (1 + refVar[size_t(i)]))
                        << i << " " << cpu::isaName(isa);
                } else {
                    ASSERT_EQ(var[size_t(i)], refVar[size_t(i)]) << i << " " << cpu::isaName(isa);
                }
                ASSERT_EQ(atrous.level(0, 3)[p], var[size_t(i)]) << i;
            }
            EXPECT_GT(estimated, int(n / 3));
        }
    cpu::setActiveIsa(cpu::bestIsa());
}

} // namespace
} // namespace bmfr
