// SSIM and PSNR against scikit-image; FLIP against properties that must hold; temporal error.
#include "core/hash.h"
#include "metrics/basic_metrics.h"
#include "metrics/flip.h"
#include "metrics/ssim.h"
#include <bmfr/error.h>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>

namespace bmfr {
namespace {

namespace fs = std::filesystem;

/// A smooth pattern with edges, plus optional noise, in [0, 1].
ImageF pattern(int w, int h, uint32_t seed, float noise, float shift = 0) {
    ImageF img(w, h, 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                float v = 0.5f + 0.3f * std::sin(0.21f * (x + shift) + c) * std::cos(0.13f * y) +
                          ((x / 9 + y / 7) % 2) * 0.15f;
                v += noise *
                     (unitFloat(hashKeys(seed, uint32_t(x), uint32_t(y), uint32_t(c))) - 0.5f);
                img.at(x, y, c) = std::clamp(v, 0.0f, 1.0f);
            }
    return img;
}

std::pair<double, double> skimage(const ImageF& a, const ImageF& b) {
    fs::path dir = fs::temp_directory_path() / ("bmfr_metrics_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    std::ofstream(dir / "a.raw", std::ios::binary)
        .write(reinterpret_cast<const char*>(a.data()), std::streamsize(a.pixels.size() * 4));
    std::ofstream(dir / "b.raw", std::ios::binary)
        .write(reinterpret_cast<const char*>(b.data()), std::streamsize(b.pixels.size() * 4));
    // Debian's python3-skimage lives with /usr/bin/python3, which another python3 on PATH may hide.
    const std::string python = fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
    std::string cmd = python + " " +
                      (fs::path(BMFR_SOURCE_DIR) / "tests" / "skimage_reference.py").string() +
                      " " + (dir / "a.raw").string() + " " + (dir / "b.raw").string() + " " +
                      std::to_string(a.width) + " " + std::to_string(a.height) + " 3";
    FILE* p = popen(cmd.c_str(), "r");
    double s = NAN, q = NAN;
    if (p) {
        if (std::fscanf(p, "%lf %lf", &s, &q) != 2) s = q = NAN;
        pclose(p);
    }
    fs::remove_all(dir);
    return {s, q};
}

TEST(Metrics, SsimAndPsnrMatchScikitImage) {
    struct Case {
        int w, h;
        float noiseA, noiseB, shift;
    };
    for (Case c : {Case{64, 48, 0.0f, 0.2f, 0}, Case{37, 29, 0.1f, 0.3f, 1.5f},
                   Case{120, 80, 0.05f, 0.05f, 4}, Case{16, 16, 0.4f, 0.0f, 0}}) {
        ImageF a = pattern(c.w, c.h, 1, c.noiseA), b = pattern(c.w, c.h, 2, c.noiseB, c.shift);
        auto [refSsim, refPsnr] = skimage(a, b);
        ASSERT_TRUE(std::isfinite(refSsim))
            << "python3 with scikit-image is needed (python3-skimage)";
        EXPECT_NEAR(ssim(a, b), refSsim, 1e-3) << c.w << "x" << c.h;
        EXPECT_NEAR(psnr(b, a), refPsnr, 1e-3) << c.w << "x" << c.h;
    }
    ImageF a = pattern(50, 40, 3, 0.1f);
    EXPECT_NEAR(ssim(a, a), 1.0, 1e-12);
}

TEST(Metrics, FlipProperties) {
    ImageF ref = pattern(96, 64, 5, 0.0f);
    EXPECT_EQ(flip(ref, ref), 0.0);
    double previous = 0;
    for (float noise : {0.02f, 0.1f, 0.3f}) {
        ImageF test = ref;
        ImageF n = pattern(96, 64, 9, noise);
        ImageF base = pattern(96, 64, 9, 0.0f);
        for (size_t i = 0; i < test.pixels.size(); ++i)
            test.pixels[i] = std::clamp(test.pixels[i] + n.pixels[i] - base.pixels[i], 0.0f, 1.0f);
        double f = flip(ref, test);
        EXPECT_GT(f, previous) << "noise " << noise;
        EXPECT_LE(f, 1.0);
        previous = f;
    }
    // A change of hue at constant luminance is detected.
    ImageF hue = ref;
    for (long i = 0; i < hue.pixelCount(); ++i) {
        float r = hue.pixels[3 * i], g = hue.pixels[3 * i + 1];
        hue.pixels[3 * i] = g, hue.pixels[3 * i + 1] = r;
    }
    EXPECT_GT(flip(ref, hue), 0.02);
    ImageF map = flipMap(ref, hue);
    for (float v : map.pixels) ASSERT_TRUE(v >= 0 && v <= 1);
    // Black against white is (nearly) the largest difference.
    ImageF black(32, 32, 3), white(32, 32, 3);
    for (float& v : white.pixels) v = 1;
    EXPECT_GT(flip(white, black), 0.9);
}

TEST(Metrics, TemporalErrorIsMeanAbsoluteLuminanceChange) {
    ImageF a(8, 8, 3), b(8, 8, 3);
    for (float& v : a.pixels) v = 0.25f;
    for (float& v : b.pixels) v = 0.5f;
    const double expected = std::pow(0.5, 1 / 2.2) - std::pow(0.25, 1 / 2.2);
    EXPECT_NEAR(temporalError(b, a), expected, 1e-6);
    EXPECT_EQ(temporalError(a, a), 0.0);
}

TEST(Metrics, TemporalChangeErrorCountsOnlyTheChangeTheReferenceDoesNotMake) {
    // Two pixels. Pixel 0: the reference goes 0.25 -> 0.5, the result follows it exactly.
    // Pixel 1: the reference stays at 0.25, the result flickers 0.25 -> 1.
    ImageF prev(2, 1, 3), cur(2, 1, 3), prevRef(2, 1, 3), ref(2, 1, 3);
    auto set = [](ImageF& img, int x, float v) {
        for (int c = 0; c < 3; ++c) img.pixels[3 * x + c] = v;
    };
    set(prevRef, 0, 0.25f), set(ref, 0, 0.5f), set(prev, 0, 0.25f), set(cur, 0, 0.5f);
    set(prevRef, 1, 0.25f), set(ref, 1, 0.25f), set(prev, 1, 0.25f), set(cur, 1, 1.0f);
    const double flicker = 1.0 - std::pow(0.25, 1 / 2.2);
    EXPECT_NEAR(temporalChangeError(cur, prev, ref, prevRef), flicker / 2, 1e-6);
    // The plain temporal error also counts pixel 0's true change.
    const double motion = std::pow(0.5, 1 / 2.2) - std::pow(0.25, 1 / 2.2);
    EXPECT_NEAR(temporalError(cur, prev), (flicker + motion) / 2, 1e-6);
    // A result that stands still while the reference moves lags by the reference's change.
    EXPECT_NEAR(temporalChangeError(prev, prev, ref, prevRef), motion / 2, 1e-6);
    EXPECT_THROW(temporalChangeError(cur, prev, ImageF(3, 1, 3), prevRef), Error);
}

} // namespace
} // namespace bmfr
