// The quality rule of half-precision history (BmfrSettings::halfHistory): against the float32
// history, the tone-mapped RMSE to the reference moves by at most 0.5% (relative) and the
// temporal error by at most 1%, on the procedural truth and on path-traced sequences, with and
// without an emission buffer (the original dataset layout has none, so its emitters pass
// through the fit as huge demodulated values that the half planes saturate).
#include "backend/reference/bmfr/reference_bmfr_passes.h"
#include "core/half.h"
#include "core/image.h"
#include "filters/bmfr/bmfr_hooks.h"
#include "filters/filter_core.h"
#include "metrics/basic_metrics.h"
#include "path_traced_box.h"
#include "synth/procedural_scene.h"
#include <bmfr/bmfr.hpp>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <gtest/gtest.h>

namespace bmfr {
namespace {

struct HalfHistoryScores {
    double rmse = 0, temporal = 0;
    std::vector<float> last; ///< the last output frame
};

/// Mean tone-mapped RMSE against the references over frames [first, n) and mean temporal error
/// of the output over the same frames.
HalfHistoryScores score(bool half, const std::vector<FrameData>& frames, int first,
             const std::function<FrameInput(const FrameData&)>& input) {
    BmfrSettings s;
    s.halfHistory = half;
    BmfrDenoiser d(s);
    ImageF previous;
    HalfHistoryScores sc;
    const int n = int(frames.size());
    for (int i = 0; i < n; ++i) {
        const ImageView v = d.denoise(input(frames[size_t(i)]));
        ImageF out(v.width, v.height, 3);
        std::memcpy(out.data(), v.data, out.pixels.size() * sizeof(float));
        if (i >= first) {
            sc.rmse += rmseToneMapped(out, frames[size_t(i)].reference) / (n - first);
            sc.temporal += temporalError(out, previous) / (n - first);
        }
        previous = std::move(out);
    }
    sc.last.assign(previous.pixels.begin(), previous.pixels.end());
    return sc;
}

void expectQualityRule(const std::vector<FrameData>& frames, int first, const char* what,
                       const std::function<FrameInput(const FrameData&)>& input) {
    const HalfHistoryScores f = score(false, frames, first, input), h = score(true, frames, first, input);
    const double dr = std::fabs(h.rmse - f.rmse) / f.rmse;
    const double dt = std::fabs(h.temporal - f.temporal) / f.temporal;
    std::printf("%s: RMSE %.5f -> %.5f (%+.3f%%), temporal %.5f -> %.5f (%+.3f%%)\n", what, f.rmse,
                h.rmse, 100 * (h.rmse - f.rmse) / f.rmse, f.temporal, h.temporal,
                100 * (h.temporal - f.temporal) / f.temporal);
    // The setting must take effect: half storage rounds, so some output bits differ.
    EXPECT_NE(h.last, f.last) << what << ": half and float history gave the same output";
    EXPECT_LE(dr, 0.005) << what << ": RMSE " << f.rmse << " (float) -> " << h.rmse << " (half)";
    EXPECT_LE(dt, 0.01) << what << ": temporal error " << f.temporal << " (float) -> " << h.temporal
                        << " (half)";
}

TEST(HalfHistory, RoundToHalfSaturatesAndRoundsToNearestEven) {
    EXPECT_EQ(roundToHalf(1e9f), kHalfMax);
    EXPECT_EQ(roundToHalf(-1e9f), -kHalfMax);
    EXPECT_EQ(roundToHalf(1.0f + 1.0f / 2048), 1.0f);               // tie: to the even 1.0
    EXPECT_EQ(roundToHalf(1.0f + 3.0f / 2048), 1.0f + 2.0f / 1024); // tie: to the even 1 + 2^-9
    EXPECT_EQ(roundToHalf(255.0f), 255.0f);                         // history lengths are exact
    EXPECT_EQ(roundToHalf(std::ldexp(1.0f, -24)), std::ldexp(1.0f, -24)); // smallest subnormal
}

TEST(HalfHistory, ProceduralTruthKeepsItsQuality) {
    ProceduralSceneOptions o;
    o.width = 256, o.height = 144, o.frames = 30, o.cameraSpeed = 1.0f, o.jitter = true;
    ProceduralScene scene(o);
    std::vector<FrameData> frames(30);
    for (int i = 0; i < 30; ++i) scene.render(i, frames[size_t(i)]);
    expectQualityRule(frames, 1, "procedural, moving camera",
                      [](const FrameData& f) { return f.input(); });
}

TEST(HalfHistory, PathTracedBoxKeepsItsQualityWithAndWithoutAnEmissionBuffer) {
    // The ceiling light is in view: without the emission buffer it is in the colour.
    const std::vector<FrameData> frames = test::pathTracedBox(96, 72, 16, 5, 0.03f, 64);
    expectQualityRule(frames, 1, "path-traced box, emission buffer",
                      [](const FrameData& f) { return f.input(); });
    expectQualityRule(frames, 1, "path-traced box, no emission buffer", [](const FrameData& f) {
        FrameInput in = f.input();
        in.emission = {};
        return in;
    });
}

std::vector<float> floatsOf(const ImageView& v) {
    return std::vector<float>(v.data, v.data + size_t(v.width) * v.height * v.channels);
}

// The CUDA backend keeps the rounded planes as Half; the reference, as floats holding the same
// values. One set of kernels reads and writes both, so both give the same bits: the output and
// phase I's and the fit's debug views, every frame, with the emitter exclusion (no emission
// buffer), the visibility taps and the second grid of the defaults, and without the fit.
TEST(HalfHistory, HalfPlanesGiveTheFloatPlanesBits) {
    const std::vector<FrameData> frames = test::pathTracedBox(64, 48, 8, 5, 0.03f, 64);
    for (int variant = 0; variant < 3; ++variant) {
        SCOPED_TRACE(variant);
        BmfrSettings s;
        s.backend = Backend::Reference, s.threads = 2;
        s.stages.fitting = variant != 2;
        BmfrDenoiser floats(s);
        FilterCore<BmfrSettings, BmfrHooks> halves(
            "bmfr", s, reference::makeBmfrPassesStoringHalves(), std::make_shared<ThreadPool>(2));
        floats.setDebugOutputs(true);
        halves.setDebugOutputs(true);
        for (size_t i = 0; i < frames.size(); ++i) {
            FrameInput in = frames[i].input();
            if (variant == 1) in.emission = {};
            EXPECT_EQ(floatsOf(halves.denoise(in)), floatsOf(floats.denoise(in))) << "frame " << i;
            EXPECT_EQ(floatsOf(halves.debug().accumulatedNoisy),
                      floatsOf(floats.debug().accumulatedNoisy))
                << i;
            EXPECT_EQ(floatsOf(halves.debug().fitted), floatsOf(floats.debug().fitted)) << i;
        }
    }
    BmfrSettings full;
    full.backend = Backend::Reference, full.halfHistory = false;
    FilterCore<BmfrSettings, BmfrHooks> wrong(
        "bmfr", full, reference::makeBmfrPassesStoringHalves(), std::make_shared<ThreadPool>(1));
    EXPECT_THROW(wrong.denoise(frames[0].input()), Error);
}

} // namespace
} // namespace bmfr
