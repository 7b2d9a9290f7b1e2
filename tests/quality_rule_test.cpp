// The quality rule for a CPU path that does not keep the reference backend's bits (SVGF's
// eight-wide a-trous levels with exp8): against the reference backend, the tone-mapped RMSE to
// the ground truth moves by at most 0.5% (relative) and the temporal error by at most 1%, on a
// path-traced sequence (moving camera, the lamp in view) and on the procedural truth with
// moving objects.
#include "core/image.h"
#include "metrics/basic_metrics.h"
#include "path_traced_box.h"
#include "synth/procedural_scene.h"
#include <bmfr/bmfr.hpp>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <gtest/gtest.h>

namespace bmfr {
namespace {

struct BackendScores {
    double rmse = 0, temporal = 0;
};

/// Mean tone-mapped RMSE against the references and mean temporal error over frames [1, n).
BackendScores scoreOn(const std::string& filter, const std::string& backend,
                      const std::vector<FrameData>& frames) {
    auto d = makeFilter(filter, {{"backend", backend}});
    ImageF previous;
    BackendScores s;
    const int n = int(frames.size());
    for (int i = 0; i < n; ++i) {
        const ImageView v = d->denoise(frames[size_t(i)].input());
        ImageF out(v.width, v.height, 3);
        std::memcpy(out.data(), v.data, out.pixels.size() * sizeof(float));
        if (i >= 1) {
            s.rmse += rmseToneMapped(out, frames[size_t(i)].reference) / (n - 1);
            s.temporal += temporalError(out, previous) / (n - 1);
        }
        previous = std::move(out);
    }
    return s;
}

void expectBackendQualityRule(const std::string& filter, const std::vector<FrameData>& frames,
                              const char* what) {
    const BackendScores ref = scoreOn(filter, "reference", frames),
                        cpu = scoreOn(filter, "cpu", frames);
    std::printf("%s, %s: RMSE %.5f (reference) -> %.5f (cpu, %+.3f%%), temporal %.5f -> %.5f "
                "(%+.3f%%)\n",
                filter.c_str(), what, ref.rmse, cpu.rmse, 100 * (cpu.rmse - ref.rmse) / ref.rmse,
                ref.temporal, cpu.temporal, 100 * (cpu.temporal - ref.temporal) / ref.temporal);
    EXPECT_LE(std::fabs(cpu.rmse - ref.rmse) / ref.rmse, 0.005) << filter << ", " << what;
    EXPECT_LE(std::fabs(cpu.temporal - ref.temporal) / ref.temporal, 0.01)
        << filter << ", " << what;
}

class QualityRule : public ::testing::TestWithParam<const char*> {};

TEST_P(QualityRule, PathTracedBoxWithTheLampInViewKeepsItsQuality) {
    expectBackendQualityRule(GetParam(), test::pathTracedBox(96, 72, 12, 5, 0.03f, 64),
                             "path-traced box, moving camera");
}

TEST_P(QualityRule, ProceduralTruthWithMovingObjectsKeepsItsQuality) {
    ProceduralSceneOptions o;
    o.width = 128, o.height = 96, o.frames = 16, o.cameraSpeed = 1.0f, o.jitter = true;
    o.objectSpeed = 2.0f, o.motionVectors = true;
    ProceduralScene scene(o);
    std::vector<FrameData> frames(16);
    for (int i = 0; i < 16; ++i) scene.render(i, frames[size_t(i)]);
    expectBackendQualityRule(GetParam(), frames, "procedural, moving objects");
}

INSTANTIATE_TEST_SUITE_P(CpuPathsThatRound, QualityRule, ::testing::Values("svgf"));

} // namespace
} // namespace bmfr
