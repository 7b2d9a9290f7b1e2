// The quality rule for a CPU path that does not keep the reference backend's bits (SVGF's
// a-trous levels, each tap's weight one power of two of its terms' logarithms; on each
// instruction-set path the machine has): against the reference backend, the tone-mapped RMSE to
// the ground truth moves by at most 0.5% (relative) and the temporal error by at most 1%, on a
// path-traced sequence (moving camera, the lamp in view) and on the procedural truth with
// moving objects. A deliberate approximation of a paper's algorithm (Mara's taps sharing a
// rotation along runs of eight pixels; WALR's half averages, as the paper's FP16, with the pivot
// floor they need; WALR's stepped trace) moves either by at most 2% against the exact setting.
#include "backend/cpu/isa.h"
#include "core/image.h"
#include "metrics/basic_metrics.h"
#include "path_traced_box.h"
#include "synth/procedural_scene.h"
#include <bmfr/bmfr.hpp>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <gtest/gtest.h>
#include <ostream>

namespace bmfr {
namespace {

/// The procedural truth, 128x96, camera and objects moving, with motion vectors.
std::vector<FrameData> movingObjects() {
    ProceduralSceneOptions o;
    o.width = 128, o.height = 96, o.frames = 16, o.cameraSpeed = 1.0f, o.jitter = true;
    o.objectSpeed = 2.0f, o.motionVectors = true;
    ProceduralScene scene(o);
    std::vector<FrameData> frames(16);
    for (int i = 0; i < 16; ++i) scene.render(i, frames[size_t(i)]);
    return frames;
}

struct BackendScores {
    double rmse = 0, temporal = 0;
};

/// Mean tone-mapped RMSE against the references and mean temporal error over frames [1, n).
BackendScores scoreOn(const std::string& filter, const SettingValues& values,
                      const std::vector<FrameData>& frames) {
    auto d = makeFilter(filter, values);
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
    const BackendScores ref = scoreOn(filter, {{"backend", "reference"}}, frames);
    for (int k = 0; k <= int(cpu::bestIsa()); ++k) {
        const char* path = cpu::isaName(cpu::Isa(k));
        cpu::setActiveIsa(cpu::Isa(k));
        const BackendScores got = scoreOn(filter, {{"backend", "cpu"}}, frames);
        cpu::setActiveIsa(cpu::bestIsa());
        std::printf("%s, %s: RMSE %.5f (reference) -> %.5f (cpu %s, %+.4f%%), temporal %.5f -> "
                    "%.5f (%+.4f%%)\n",
                    filter.c_str(), what, ref.rmse, got.rmse, path,
                    100 * (got.rmse - ref.rmse) / ref.rmse, ref.temporal, got.temporal,
                    100 * (got.temporal - ref.temporal) / ref.temporal);
        EXPECT_LE(std::fabs(got.rmse - ref.rmse) / ref.rmse, 0.005)
            << filter << ", " << what << ", " << path;
        EXPECT_LE(std::fabs(got.temporal - ref.temporal) / ref.temporal, 0.01)
            << filter << ", " << what << ", " << path;
    }
}

class QualityRule : public ::testing::TestWithParam<const char*> {};

TEST_P(QualityRule, PathTracedBoxWithTheLampInViewKeepsItsQuality) {
    expectBackendQualityRule(GetParam(), test::pathTracedBox(96, 72, 12, 5, 0.03f, 64),
                             "path-traced box, moving camera");
}

TEST_P(QualityRule, ProceduralTruthWithMovingObjectsKeepsItsQuality) {
    expectBackendQualityRule(GetParam(), movingObjects(), "procedural, moving objects");
}

INSTANTIATE_TEST_SUITE_P(CpuPathsThatRound, QualityRule, ::testing::Values("svgf"));

/// A default (or a setting) that approximates the paper, against the setting that does not, on
/// the CPU.
struct Approximation {
    const char* filter;
    SettingValues exact;       ///< the setting (or settings) that undo the approximation
    SettingValues common;      ///< settings of both runs
    SettingValues approximate; ///< the approximation's own setting, where it is not a default
};

/// gtest's name for a case in its listing and its failures, not the struct's bytes.
void PrintTo(const Approximation& a, std::ostream* os) {
    *os << a.filter << " against " << a.exact[0].first << "=" << a.exact[0].second;
}

void expectApproximationRule(const Approximation& a, const std::vector<FrameData>& frames,
                             const char* what) {
    SettingValues exact = a.exact, approximate = a.approximate;
    exact.insert(exact.end(), a.common.begin(), a.common.end());
    approximate.insert(approximate.end(), a.common.begin(), a.common.end());
    exact.push_back({"backend", "cpu"});
    approximate.push_back({"backend", "cpu"});
    const BackendScores paper = scoreOn(a.filter, exact, frames),
                        ours = scoreOn(a.filter, approximate, frames);
    const std::string ourName =
        a.approximate.empty() ? "default" : a.approximate[0].first + "=" + a.approximate[0].second;
    std::printf("%s, %s: RMSE %.5f (%s=%s) -> %.5f (%s, %+.3f%%), temporal %.5f -> %.5f "
                "(%+.3f%%)\n",
                a.filter, what, paper.rmse, a.exact[0].first.c_str(), a.exact[0].second.c_str(),
                ours.rmse, ourName.c_str(), 100 * (ours.rmse - paper.rmse) / paper.rmse,
                paper.temporal, ours.temporal,
                100 * (ours.temporal - paper.temporal) / paper.temporal);
    EXPECT_LE(ours.rmse, paper.rmse * 1.02) << a.filter << ", " << what;
    EXPECT_LE(ours.temporal, paper.temporal * 1.02) << a.filter << ", " << what;
}

class ApproximationRule : public ::testing::TestWithParam<Approximation> {};

TEST_P(ApproximationRule, PathTracedBoxWithTheLampInViewKeepsItsQuality) {
    expectApproximationRule(GetParam(), test::pathTracedBox(96, 72, 12, 5, 0.03f, 64),
                            "path-traced box, moving camera");
}

TEST_P(ApproximationRule, ProceduralTruthWithMovingObjectsKeepsItsQuality) {
    expectApproximationRule(GetParam(), movingObjects(), "procedural, moving objects");
}

// WALR at three iterations, so that two levels pass through half averages; its stepped trace
// (a setting: on the CPU it is no faster than the exact trace) at four, so that two iterations
// step by the runs of the last.
INSTANTIATE_TEST_SUITE_P(
    Defaults, ApproximationRule,
    ::testing::Values(
        Approximation{"mara2017", {{"rotationWidth", "1"}}, {}, {}},
        Approximation{"walr", {{"halfAverages", "false"}}, {{"iterations", "3"}}, {}},
        Approximation{"walr", {{"edgeStep", "0"}}, {{"iterations", "4"}}, {{"edgeStep", "1"}}}));

} // namespace
} // namespace bmfr
