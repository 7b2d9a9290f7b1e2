// TAA against hand-computed values: the authors' history from all four bilinear taps, and the
// same-surface history (TemporalSettings::taaSameSurface) from the accepted taps only, in the
// reference's per-pixel code and the CPU backend's eight-wide rows.
#include "backend/cpu/cpu_taa.h"
#include "temporal/taa.h"
#include <cmath>
#include <gtest/gtest.h>
#include <vector>

namespace bmfr {
namespace {

// A 4x3 grey image with a vertical edge: columns 0-1 at 0.2, columns 2-3 at 0.8. The history
// holds 0.3 in column 1 and 0.7 in column 2. Pixel (1, 1) was at (1.5, 1): half way between
// them, so the bilinear taps are (1, 1) and (2, 1) at weight 0.5 each.
struct EdgeFrame {
    static constexpr int w = 4, h = 3;
    std::vector<float> current, history, previousPixel;
    EdgeFrame() {
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const float c = x < 2 ? 0.2f : 0.8f, o = x < 2 ? 0.3f : 0.7f;
                current.insert(current.end(), {c, c, c});
                history.insert(history.end(), {o, o, o});
                previousPixel.insert(previousPixel.end(), {float(x) + 0.5f, float(y)});
            }
    }
};

// Pixel (1, 1) by hand, alpha 0.2. The clamp box spans [0.2, 0.8]: no clamping.
//   all four taps:          0.8 (0.5 * 0.3 + 0.5 * 0.7) + 0.2 * 0.2 = 0.44
//   only tap (1, 1) (bit 0): 0.8 * 0.3 + 0.2 * 0.2 = 0.28
//   no tap accepted:        the current colour, 0.2
constexpr float kAllTaps = 0.44f, kSameSurface = 0.28f, kNoTap = 0.2f;

float referenceTaa(const EdgeFrame& f, const uint8_t* accept, TaaSpace space, TaaBlend blend) {
    TaaInputs a{
        f.current.data(), nullptr, f.history.data(), f.previousPixel.data(), f.w, f.h, blend,
        accept,           space};
    std::vector<float> ycocg;
    for (size_t i = 0; i < f.current.size(); i += 3) {
        const Vec3 v = rgbToYCoCg(taaSpace(a, {f.current[i], f.current[i + 1], f.current[i + 2]}));
        ycocg.insert(ycocg.end(), {v.x, v.y, v.z});
    }
    a.ycocg = ycocg.data();
    return taaPixel(a, 1, 1).y;
}

float cpuTaaOf(const EdgeFrame& f, const cpu::TaaCurrent& current, const uint8_t* accept,
               TaaSpace space, TaaBlend blend) {
    ThreadPool pool(1);
    std::vector<float> scratch(cpu::taaScratchFloats(f.w, 1)), out(f.current.size());
    cpu::temporalAntiAliasing(pool, current, f.history.data(), f.previousPixel.data(),
                              scratch.data(), out.data(), f.w, f.h, blend, true, accept, space);
    return out[3 * (f.w + 1) + 1];
}

float cpuTaa(const EdgeFrame& f, const uint8_t* accept, TaaSpace space, TaaBlend blend) {
    cpu::TaaCurrent current;
    current.rgb = f.current.data();
    return cpuTaaOf(f, current, accept, space, blend);
}

// The current frame as SVGF's last level: demodulated planes (twice the colour, rows 8 floats
// apart) that the TAA multiplies by the albedo, 0.5, as it reads them: the same frame, exactly.
float cpuTaaFromPlanes(const EdgeFrame& f, const uint8_t* accept, TaaSpace space, TaaBlend blend) {
    constexpr long kPitch = 8;
    std::vector<float> planes(3 * kPitch * f.h), albedo(f.current.size(), 0.5f);
    cpu::TaaCurrent current;
    for (int k = 0; k < 3; ++k) {
        current.planes[k] = planes.data() + k * kPitch * f.h;
        for (int i = 0; i < f.w * f.h; ++i)
            planes[size_t(k * kPitch * f.h + i / f.w * kPitch + i % f.w)] =
                2 * f.current[3 * i + k];
    }
    InputPlanes in;
    in.albedo = albedo.data();
    current.pitch = kPitch;
    current.in = &in;
    current.albedoEpsilon = 1e-3f;
    return cpuTaaOf(f, current, accept, space, blend);
}

TEST(Taa, HistoryFromAllTapsOrOnlyTheSameSurfaceMatchesHandValues) {
    const EdgeFrame f;
    std::vector<uint8_t> all(size_t(f.w * f.h), 15), first(all.size(), 1), none(all.size(), 0);
    for (auto taa : {referenceTaa, cpuTaa, cpuTaaFromPlanes}) {
        EXPECT_NEAR(taa(f, nullptr, TaaSpace::Linear, {0.2f}), kAllTaps, 1e-6f);
        EXPECT_NEAR(taa(f, all.data(), TaaSpace::Linear, {0.2f}), kAllTaps, 1e-6f);
        EXPECT_NEAR(taa(f, first.data(), TaaSpace::Linear, {0.2f}), kSameSurface, 1e-6f);
        EXPECT_NEAR(taa(f, none.data(), TaaSpace::Linear, {0.2f}), kNoTap, 1e-6f);
    }
}

TEST(Taa, OnToneMappedValuesBlendsDisplayValuesAndClipsAtOne) {
    // The authors' TAA: pixel (1, 1) blended as display values e(v) = v^(1/2.2), then decoded.
    const auto e = [](double v) { return std::pow(v, 1 / 2.2); };
    const double allTaps = std::pow(0.8 * 0.5 * (e(0.3) + e(0.7)) + 0.2 * e(0.2), 2.2);
    const double sameSurface = std::pow(0.8 * e(0.3) + 0.2 * e(0.2), 2.2);
    EdgeFrame f;
    std::vector<uint8_t> first(size_t(f.w * f.h), 1), none(first.size(), 0);
    for (auto taa : {referenceTaa, cpuTaa}) {
        EXPECT_NEAR(taa(f, nullptr, TaaSpace::Display, {0.2f}), allTaps, 1e-5);
        EXPECT_NEAR(taa(f, first.data(), TaaSpace::Display, {0.2f}), sameSurface, 1e-5);
        EXPECT_NEAR(taa(f, none.data(), TaaSpace::Display, {0.2f}), kNoTap, 1e-5);
        EXPECT_GT(std::fabs(taa(f, nullptr, TaaSpace::Display, {0.2f}) - kAllTaps), 1e-3)
            << "not the linear blend";
    }
    // Above 1 the display value, and so the output, is 1.
    for (int c = 0; c < 3; ++c) f.current[3 * (f.w + 1) + c] = 3.0f;
    for (auto taa : {referenceTaa, cpuTaa}) {
        EXPECT_NEAR(taa(f, none.data(), TaaSpace::Display, {0.2f}), 1.0f, 1e-6f);
        EXPECT_NEAR(taa(f, none.data(), TaaSpace::Linear, {0.2f}), 3.0f, 1e-6f);
    }
}

TEST(Taa, OnRangeCompressedValuesBlendsThemAndExpandsTheResultWithoutClipping) {
    // Pixel (1, 1) with every value v as v / (1 + v) (grey), then expanded: x / (1 - x).
    const auto e = [](double v) { return v / (1 + v); };
    const auto d = [](double x) { return x / (1 - x); };
    const double allTaps = d(0.8 * 0.5 * (e(0.3) + e(0.7)) + 0.2 * e(0.2));
    EdgeFrame f;
    for (auto taa : {referenceTaa, cpuTaa}) {
        EXPECT_NEAR(taa(f, nullptr, TaaSpace::Compressed, {0.2f}), allTaps, 1e-5);
        EXPECT_GT(std::fabs(taa(f, nullptr, TaaSpace::Compressed, {0.2f}) - kAllTaps), 1e-3);
    }
    // A light's radiance comes back whole: nothing is clipped.
    std::vector<uint8_t> none(size_t(f.w * f.h), 0);
    for (int c = 0; c < 3; ++c) f.current[3 * (f.w + 1) + c] = 300.0f;
    for (auto taa : {referenceTaa, cpuTaa})
        EXPECT_NEAR(taa(f, none.data(), TaaSpace::Compressed, {0.2f}), 300.0f, 0.05f);
    for (float v : {0.0f, 0.01f, 1.0f, 17.0f, 1000.0f})
        EXPECT_NEAR(expandRange(compressRange({v, v / 2, 0})).x, v, 1e-6f + 1e-4f * v);
}

TEST(Taa, TheMotionWeightFollowsTheHistorysBilinearBlur) {
    // Pixel (1, 1) was at (1.5, 1): the blur b = 0.25 px^2, so the current frame weighs
    // max(alpha, b / (b + limit)): 5/6 with limit 0.05, 0.5 with 0.25, and alpha 0.6 above that.
    const EdgeFrame f;
    const auto blend = [](double a) { return (1 - a) * 0.5 * (0.3 + 0.7) + a * 0.2; };
    EXPECT_NEAR(bilinearBlur(bilinearFootprint({1.5f, 1.0f}).weight), 0.25f, 1e-7f);
    EXPECT_EQ(bilinearBlur(bilinearFootprint({2.0f, 3.0f}).weight), 0.0f);
    for (auto taa : {referenceTaa, cpuTaa}) {
        EXPECT_NEAR(taa(f, nullptr, TaaSpace::Linear, {0.2f, 0.05f}), blend(0.25 / 0.3), 1e-6);
        EXPECT_NEAR(taa(f, nullptr, TaaSpace::Linear, {0.2f, 0.25f}), blend(0.5), 1e-6);
        EXPECT_NEAR(taa(f, nullptr, TaaSpace::Linear, {0.6f, 0.25f}), blend(0.6), 1e-6);
    }
}

} // namespace
} // namespace bmfr
