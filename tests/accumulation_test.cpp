// Temporal weights on a static sequence: exact cumulative average first, then EMA.
#include "filters/bmfr/bmfr_settings_table.h"
#include "test_scenes.h"
#include <bmfr/bmfr.hpp>
#include <cmath>
#include <gtest/gtest.h>
#include <string>

namespace bmfr {
namespace {

TEST(Accumulation, CumulativeAverageThenExponentialInBothPhases) {
    // Float history to 1e-5; half history to the error its roundings can build up: each store
    // adds at most half an ulp (2^-11 relative) and each blend shrinks the old error by 1 - w,
    // so at w >= 0.1 the error stays below 5 ulps.
    for (bool half : {false, true}) {
        const double tol = half ? 5.0 * std::ldexp(1.0, -10) : 1e-5;
        const int w = 40, h = 36;
        const Mat4 cam = test::cameraAt({0, 1, 3}, w, h);
        Settings s; // the paper's weights: the faithful preset
        applySettings(bmfrSettingsTable(), s, presetSettings("bmfr", "faithful"), "bmfr");
        s.taa = false;
        s.threads = 2;
        s.halfHistory = half;
        Denoiser d(s);
        d.setDebugOutputs(true);
        double first = 0, second = 0; // expected phase I and phase III accumulations
        for (int k = 0; k < 14; ++k) {
            const double value = 1.0 + 0.37 * k + 0.2 * (k % 3); // a different colour each frame
            FrameData f = test::planeFrame(cam, w, h, {float(value), float(value), float(value)},
                                           [](int, int) { return -4.0f; });
            ImageView out = d.denoise(f.input());
            DebugBuffers dbg = d.debug();
            // Phase I: weight max(1/(n+1), 0.2) with n = k previous samples.
            first = k == 0 ? value : first + std::max(1.0 / (k + 1), 0.2) * (value - first);
            // Phase III: weight max(1/n, 0.1) with n = k + 1 (the history length after phase I).
            second = k == 0 ? first : second + std::max(1.0 / (k + 1), 0.1) * (first - second);
            const std::string what =
                std::string(half ? "half" : "float") + " history, frame " + std::to_string(k);
            for (int i = 0; i < w * h; i += 37) {
                ASSERT_NEAR(dbg.accumulatedNoisy.data[3 * i], first, tol * first) << what;
                ASSERT_EQ(dbg.historyLength.data[i], float(std::min(k + 1, 255)));
                // A constant block is fitted exactly by the constant feature.
                ASSERT_NEAR(dbg.fitted.data[3 * i + 1], first, (tol + 1e-4) * first) << what;
                ASSERT_NEAR(out.data[3 * i + 2], second, (2 * tol + 1e-4) * second) << what;
            }
        }
    }
}

TEST(Accumulation, ResetRestartsFromTheCurrentFrame) {
    const int w = 32, h = 32;
    const Mat4 cam = test::cameraAt({0, 0, 0}, w, h);
    Denoiser d;
    d.setDebugOutputs(true);
    FrameData a = test::planeFrame(cam, w, h, {1, 1, 1}, [](int, int) { return -3.0f; });
    FrameData b = test::planeFrame(cam, w, h, {5, 5, 5}, [](int, int) { return -3.0f; });
    d.denoise(a.input());
    d.denoise(a.input());
    FrameInput in = b.input();
    in.reset = true;
    ImageView out = d.denoise(in);
    EXPECT_NEAR(d.debug().accumulatedNoisy.data[100], 5.0f, 1e-6);
    EXPECT_EQ(d.debug().historyLength.data[100], 1.0f);
    EXPECT_NEAR(out.data[100], 5.0f, 1e-4);
}

} // namespace
} // namespace bmfr
