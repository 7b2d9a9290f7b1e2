// The whole pipeline on the procedural moving-camera sequence with known truth; determinism;
// NaN/Inf sanitisation; rejection of bad input.
#include "core/image.h"
#include "metrics/basic_metrics.h"
#include "synth/procedural_scene.h"
#include <bmfr/bmfr.hpp>
#include <bmfr/error.h>
#include <cmath>
#include <cstring>
#include <gtest/gtest.h>

namespace bmfr {
namespace {

ImageF copyOf(const ImageView& v) {
    ImageF img(v.width, v.height, v.channels);
    std::memcpy(img.data(), v.data, img.pixels.size() * sizeof(float));
    return img;
}

struct SequenceRun {
    std::vector<ImageF> outputs, noisy, truth;
};

SequenceRun denoiseSequence(const Settings& s, int frames, int w = 256, int h = 144,
                            bool moving = true) {
    ProceduralSceneOptions o;
    o.width = w, o.height = h, o.frames = frames;
    o.cameraSpeed = moving ? 1.0f : 0.0f;
    o.jitter = moving;
    ProceduralScene scene(o);
    Denoiser d(s);
    SequenceRun r;
    FrameData f;
    for (int i = 0; i < frames; ++i) {
        scene.render(i, f);
        r.outputs.push_back(copyOf(d.denoise(f.input())));
        r.noisy.push_back(f.color);
        r.truth.push_back(f.reference);
    }
    return r;
}

TEST(EndToEnd, MovingCameraRmseAtMostAQuarterOfNoisy) {
    SequenceRun r = denoiseSequence(Settings{}, 30);
    double out = 0, in = 0;
    for (size_t i = 0; i < r.outputs.size(); ++i) {
        out += rmseToneMapped(r.outputs[i], r.truth[i]);
        in += rmseToneMapped(r.noisy[i], r.truth[i]);
    }
    EXPECT_LE(out, 0.25 * in) << "mean RMSE denoised " << out / 30 << " noisy " << in / 30;
    EXPECT_LE(rmseToneMapped(r.outputs.back(), r.truth.back()),
              0.25 * rmseToneMapped(r.noisy.back(), r.truth.back()));
    // Flicker: close to the truth's own frame-to-frame change, far below the noisy input's.
    double teOut = 0, teRef = 0, teNoisy = 0;
    for (size_t i = 1; i < r.outputs.size(); ++i) {
        teOut += temporalError(r.outputs[i], r.outputs[i - 1]);
        teRef += temporalError(r.truth[i], r.truth[i - 1]);
        teNoisy += temporalError(r.noisy[i], r.noisy[i - 1]);
    }
    EXPECT_LT(teOut, 1.3 * teRef);
    EXPECT_LT(teOut, 0.2 * teNoisy);
}

TEST(EndToEnd, StaticCameraTemporalErrorFallsAsHistoryAccumulates) {
    SequenceRun r = denoiseSequence(Settings{}, 30, 256, 144, false);
    ASSERT_EQ(temporalError(r.truth[5], r.truth[4]), 0.0); // the truth is static
    double early = 0, late = 0;
    for (int i = 1; i <= 4; ++i) early += temporalError(r.outputs[i], r.outputs[i - 1]) / 4;
    for (int i = 20; i < 30; ++i) late += temporalError(r.outputs[i], r.outputs[i - 1]) / 10;
    EXPECT_LT(late, 0.5 * early) << "temporal error early " << early << " late " << late;
    EXPECT_LT(rmseToneMapped(r.outputs[29], r.truth[29]), rmseToneMapped(r.outputs[2], r.truth[2]));
}

TEST(EndToEnd, FittingHelpsOverAccumulationAlone) {
    Settings noFit;
    noFit.stages.fitting = false;
    SequenceRun a = denoiseSequence(noFit, 16), b = denoiseSequence(Settings{}, 16);
    double errA = 0, errB = 0;
    for (size_t i = 0; i < a.outputs.size(); ++i) {
        errA += rmseToneMapped(a.outputs[i], a.truth[i]);
        errB += rmseToneMapped(b.outputs[i], b.truth[i]);
    }
    EXPECT_LT(errB, 0.85 * errA);
}

TEST(EndToEnd, SameInputSameBitsForAnyThreadCount) {
    Settings one, two;
    one.threads = 1;
    two.threads = 2;
    SequenceRun a = denoiseSequence(one, 5, 100, 70), b = denoiseSequence(two, 5, 100, 70),
                c = denoiseSequence(two, 5, 100, 70);
    for (size_t i = 0; i < a.outputs.size(); ++i) {
        EXPECT_EQ(a.outputs[i].pixels, b.outputs[i].pixels) << "frame " << i;
        EXPECT_EQ(b.outputs[i].pixels, c.outputs[i].pixels) << "frame " << i;
    }
}

TEST(EndToEnd, OddSizesWork) {
    for (auto [w, h] : {std::pair{1, 1}, {33, 17}, {7, 64}}) {
        SequenceRun r = denoiseSequence(Settings{}, 3, w, h);
        for (float v : r.outputs.back().pixels) ASSERT_TRUE(std::isfinite(v)) << w << "x" << h;
    }
}

FrameData renderFrame(int w, int h) {
    ProceduralSceneOptions o;
    o.width = w, o.height = h, o.frames = 1;
    FrameData f;
    ProceduralScene(o).render(0, f);
    return f;
}

TEST(EndToEnd, NonFiniteInputsAreReplacedAndCounted) {
    FrameData f = renderFrame(64, 48);
    f.color.at(3, 4, 0) = NAN;
    f.position.at(10, 10, 2) = INFINITY;
    f.normal.at(20, 5, 1) = -INFINITY;
    f.albedo.at(0, 0, 1) = NAN;
    Denoiser d;
    ImageView out = d.denoise(f.input());
    EXPECT_EQ(d.lastStats().nonFiniteInputs, 4);
    for (long i = 0; i < 64L * 48 * 3; ++i) ASSERT_TRUE(std::isfinite(out.data[i])) << i;
}

TEST(EndToEnd, BadInputIsRejectedWithAReason) {
    FrameData f = renderFrame(32, 32);
    Denoiser d;
    auto expectError = [&](FrameInput in, const char* needle) {
        try {
            d.denoise(in);
            ADD_FAILURE() << "no error for " << needle;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
        }
    };
    FrameInput in = f.input();
    in.albedo.width = 31;
    expectError(in, "albedo");
    in = f.input();
    in.normal.data = nullptr;
    expectError(in, "missing");
    in = f.input();
    in.color.width = in.color.height = 0;
    expectError(in, "zero size");
    in = f.input();
    in.position.channels = 2;
    expectError(in, "channels");
    in = f.input();
    in.albedo.rowStride = 3 * 32 - 1;
    expectError(in, "row stride");
    in = f.input();
    in.viewProjection.m[1][2] = NAN;
    expectError(in, "matrix");
    in = f.input();
    in.viewProjection = Mat4{};
    for (auto& row : in.viewProjection.m) row[0] = row[1] = row[2] = row[3] = 0;
    expectError(in, "matrix");
    Settings withExtra;
    withExtra.features = parseFeatures("1,n.x,extra3");
    Denoiser needsExtra(withExtra);
    EXPECT_THROW(needsExtra.denoise(f.input()), Error);
    Settings bad;
    bad.blockSize = 5;
    EXPECT_THROW(Denoiser{bad}, Error);
    EXPECT_THROW(parseFeatures("1,q.x"), Error);
}

TEST(EndToEnd, OutputIsWrittenIntoACallersRgbaView) {
    FrameData f = renderFrame(20, 10);
    for (const std::string& name : filterNames()) {
        auto filter = makeFilter(name);
        const long stride = 20 * 4 + 3;
        std::vector<float> rgba(size_t(stride) * 10, -1.0f);
        const MutableImageView out{rgba.data(), 20, 10, 4, stride};
        const ImageView packed = filter->denoise(f.input(), out);
        for (int y = 0; y < 10; ++y)
            for (int x = 0; x < 20; ++x) {
                for (int c = 0; c < 3; ++c)
                    ASSERT_EQ(rgba[size_t(y * stride + 4 * x + c)],
                              packed.data[(y * 20 + x) * 3 + c])
                        << name;
                ASSERT_EQ(rgba[size_t(y * stride + 4 * x + 3)], -1.0f) << name << ": alpha kept";
            }
        EXPECT_THROW(filter->denoise(f.input(), MutableImageView{rgba.data(), 19, 10, 4, stride}),
                     Error);
    }
}

TEST(EndToEnd, ExtraFeatureBuffersAreUsed) {
    Settings s;
    s.features = parseFeatures("1,n.x,n.y,n.z,p.x,p.y,p.z,p.x^2,p.y^2,p.z^2,extra0");
    EXPECT_EQ(formatFeatures(s.features), "1,n.x,n.y,n.z,p.x,p.y,p.z,p.x^2,p.y^2,p.z^2,extra0");
    SequenceRun r = denoiseSequence(s, 8, 96, 64);
    EXPECT_LT(rmseToneMapped(r.outputs.back(), r.truth.back()),
              0.5 * rmseToneMapped(r.noisy.back(), r.truth.back()));
}

} // namespace
} // namespace bmfr
