// Adaptive history (BmfrSettings::adaptiveHistory, filters/bmfr/history_change.h): the tile
// change against a double-precision computation, its noise allowance, the weights it gives,
// and a light that dims under a still camera, where the history must follow it without
// flickering more where nothing changed.
#include "core/color.h"
#include "filters/bmfr/history_change.h"
#include "synth/procedural_scene.h"
#include "test_support.h"
#include <bmfr/bmfr.hpp>
#include <cmath>
#include <gtest/gtest.h>
#include <random>

namespace bmfr {
namespace {

/// One 32x32 tile of (sample, history) luminance pairs, interleaved; history -1: none.
struct Tile {
    std::vector<float> v = std::vector<float>(2 * kChangeTile * kChangeTile, 0.0f);
    float change(float threshold = 2.0f, float gain = 1.0f) const {
        return tileHistoryChange(v.data(), v.data() + 1, 2, kChangeTile, kChangeTile, 0, 0,
                                 threshold, gain);
    }
};

/// tileHistoryChange's definition, in double precision.
double expectedChange(const Tile& t, double threshold, double gain) {
    double n = 0, sum = 0, squares = 0, history = 0;
    for (size_t k = 0; k < t.v.size(); k += 2) {
        if (t.v[k + 1] < 0) continue;
        n += 1, sum += t.v[k], squares += double(t.v[k]) * t.v[k], history += t.v[k + 1];
    }
    if (n < kChangeMinPixels) return 0;
    const double mean = sum / n, past = history / n;
    const double se = std::sqrt(std::max(squares / n - mean * mean, 0.0) / n);
    const double excess = std::fabs(mean - past) - threshold * se;
    return excess > 0 ? std::min(gain * excess / std::max(mean, past), 1.0) : 0.0;
}

/// Unit-mean exponential noise, as 1-spp Monte Carlo.
Tile noisyTile(std::mt19937& rng, float truth, float history, int withoutHistory = 0) {
    std::exponential_distribution<float> noise(1.0f);
    Tile t;
    for (size_t k = 0; k < t.v.size(); k += 2) {
        t.v[k] = truth * noise(rng);
        t.v[k + 1] = int(k / 2) < withoutHistory ? -1.0f : history;
    }
    return t;
}

TEST(AdaptiveHistory, TileChangeMatchesADoublePrecisionComputation) {
    std::mt19937 rng(7);
    for (int trial = 0; trial < 50; ++trial) {
        std::uniform_real_distribution<float> level(0.01f, 4.0f);
        const Tile t = noisyTile(rng, level(rng), level(rng), trial * 19);
        for (float threshold : {0.0f, 2.0f, 5.0f})
            for (float gain : {1.0f, 4.0f})
                EXPECT_NEAR(t.change(threshold, gain), expectedChange(t, threshold, gain), 5e-4)
                    << "trial " << trial << ", threshold " << threshold << ", gain " << gain;
    }
}

const BmfrSettings kDefaults;

TEST(AdaptiveHistory, NoiseAloneRarelyCountsAsAChange) {
    // The history holds the true mean; the samples scatter as 1-spp light does. At 2 standard
    // errors about one tile in twenty may show a change, and then a small one (measured: 95 of
    // 2000).
    std::mt19937 rng(11);
    int changed = 0;
    double total = 0;
    const int tiles = 2000;
    for (int k = 0; k < tiles; ++k) {
        const float c = noisyTile(rng, 0.5f, 0.5f)
                            .change(kDefaults.historyChangeThreshold, kDefaults.historyChangeGain);
        changed += c > 0.0f;
        total += c;
    }
    EXPECT_LT(changed, tiles / 10);
    EXPECT_LT(total / tiles, 0.005); // measured: 0.0021 at the default gain of 4
}

TEST(AdaptiveHistory, AFireflyIsNotAChange) {
    Tile t;
    for (size_t k = 0; k < t.v.size(); k += 2) t.v[k] = t.v[k + 1] = 1.0f;
    t.v[200] = 1e4f; // one sample ten thousand times its neighbours
    EXPECT_EQ(t.change(), 0.0f);
}

TEST(AdaptiveHistory, ALightDimmedToAQuarterIsAboutThreeQuartersOfAChange) {
    std::mt19937 rng(3);
    const Tile t = noisyTile(rng, 0.25f, 1.0f);
    // (1 - 0.25 - 2 SE) / 1, with SE = 0.25 / 32 for unit exponential noise.
    EXPECT_NEAR(t.change(), 0.75 - 2 * 0.25 / 32, 0.02);
    EXPECT_EQ(t.change(2.0f, 4.0f), 1.0f) << "amplified, capped at a whole change";
    EXPECT_EQ(
        noisyTile(rng, 0.25f, 1.0f, kChangeTile * kChangeTile - kChangeMinPixels + 1).change(),
        0.0f)
        << "too few pixels with history";
}

TEST(AdaptiveHistory, WeightsAndLengths) {
    EXPECT_EQ(adaptedBlendWeight(0.1f, 0.0f), 0.1f);
    EXPECT_FLOAT_EQ(adaptedBlendWeight(0.1f, 0.5f), 0.55f);
    EXPECT_FLOAT_EQ(adaptedBlendWeight(0.1f, 1.0f), 1.0f);
    EXPECT_EQ(shortenedHistory(200.0f, 0.0f, 0.1f), 200.0f) << "the paper's length at no change";
    // 1 / (0.1 + 0.5 * 0.9) = 1.818 frames, the new one included.
    EXPECT_NEAR(shortenedHistory(200.0f, 0.5f, 0.1f), 1.0f / 0.55f - 1.0f, 1e-6f);
    EXPECT_EQ(shortenedHistory(0.3f, 0.5f, 0.1f), 0.3f) << "never longer";
    EXPECT_EQ(shortenedHistory(9.0f, 1.0f, 0.1f), 0.0f) << "a whole change drops the history";
    // Tiles of a 70x33 image: 3 x 2; pixel (69, 32) is in the last one. Each tile's record is
    // (in effect, measured).
    const float tiles[12] = {0, -1, 1, -1, 2, -1, 3, -1, 4, -1, 5, -1};
    EXPECT_EQ(changeTilesX(70), 3);
    EXPECT_EQ(changeTilesY(33), 2);
    EXPECT_EQ(changeTileFloats(70, 33), 12);
    EXPECT_EQ(pixelHistoryChange(tiles, 70, 69, 32), 5.0f);
    EXPECT_EQ(pixelHistoryChange(tiles, 70, 31, 31), 0.0f);
}

TEST(AdaptiveHistory, AWeakChangeCountsFromItsSecondFrame) {
    float tiles[4] = {}; // two tiles, nothing measured before
    storeTileChange(tiles, 1, 0.3f);
    EXPECT_EQ(tiles[2], 0.0f) << "a weak change in one frame is not yet in effect";
    EXPECT_EQ(tiles[3], 0.3f);
    storeTileChange(tiles, 1, 0.2f);
    EXPECT_EQ(tiles[2], 0.2f) << "the tile changed in the frame before too";
    storeTileChange(tiles, 1, 0.0f);
    storeTileChange(tiles, 1, 0.6f);
    EXPECT_EQ(tiles[2], 0.6f) << "a strong change counts at once";
    storeTileChange(tiles, 1, 0.0f);
    EXPECT_EQ(tiles[2], 0.0f);
    EXPECT_EQ(tiles[0], 0.0f);
    EXPECT_EQ(tiles[1], 0.0f) << "the other tile is untouched";
    // Noise alone: of 2000 tiles measured twice, a weak change in both frames is rare.
    std::mt19937 rng(11);
    int measured = 0, confirmed = 0;
    for (int k = 0; k < 2000; ++k) {
        float tile[2] = {};
        bool any = false;
        for (int frame = 0; frame < 2; ++frame) {
            storeTileChange(
                tile, 0,
                noisyTile(rng, 0.5f, 0.5f)
                    .change(kDefaults.historyChangeThreshold, kDefaults.historyChangeGain));
            any = any || tile[1] > 0.0f;
        }
        measured += any;
        confirmed += tile[0] > 0.0f;
    }
    EXPECT_GT(measured, 100); // measured: 189 tiles with a change in a frame, 3 in both
    EXPECT_LT(confirmed, measured / 8) << measured;
}

/// Tone-mapped RMSE of the output against the truth, over frames [first, last), with the light
/// dimmed to a quarter from frame kDimStep on, under a still camera.
constexpr int kDimW = 160, kDimH = 96, kDimFrames = 20, kDimStep = 12;
struct Errors {
    double steady = 0; ///< frames 4 to kDimStep - 1
    double after = 0;  ///< the 4 frames from kDimStep
};
Errors dimmingLightErrors(bool adaptive) {
    ProceduralSceneOptions o;
    o.width = kDimW, o.height = kDimH, o.frames = kDimFrames, o.cameraSpeed = 0.0f,
    o.jitter = false;
    const ProceduralScene scene(o);
    auto f = makeFilter("bmfr", {{"adaptiveHistory", adaptive ? "true" : "false"}});
    double steady = 0, after = 0;
    for (int i = 0; i < kDimStep + 4; ++i) {
        FrameData d;
        scene.render(i, d);
        if (i >= kDimStep)
            for (ImageF* img : {&d.color, &d.reference})
                for (float& v : img->pixels) v *= 0.25f;
        const ImageView out = f->denoise(d.input());
        if (i < 4) continue;
        double sum = 0;
        for (long p = 0; p < 3L * kDimW * kDimH; ++p) {
            const double e =
                double(gammaEncode(out.data[p])) - double(gammaEncode(d.reference.data()[p]));
            sum += e * e;
        }
        (i < kDimStep ? steady : after) += sum / (3.0 * kDimW * kDimH);
    }
    return {std::sqrt(steady / (kDimStep - 4)), std::sqrt(after / 4)};
}

TEST(AdaptiveHistory, FollowsADimmingLightAndLeavesASteadyOneAlone) {
    const Errors paper = dimmingLightErrors(false), adaptive = dimmingLightErrors(true);
    // Measured: steady 0.0347 both; in the 4 frames after the step 0.208 (paper) against 0.101.
    EXPECT_LT(adaptive.after, 0.6 * paper.after)
        << "paper " << paper.after << ", adaptive " << adaptive.after;
    EXPECT_LT(adaptive.steady, 1.02 * paper.steady)
        << "paper " << paper.steady << ", adaptive " << adaptive.steady;
}

} // namespace
} // namespace bmfr
