// The conformance suite: every backend against the reference backend, for every filter, on the
// same frames. Outputs must agree within the stated tolerance; discard masks, history lengths
// and the non-finite and discarded counts must be identical. A new backend joins with one line
// in kBackends, a new filter with one entry in kFilters. The CPU backend is held to it on each of
// its instruction-set paths; a path this processor lacks is reported skipped. The CUDA backend
// (bmfr and svgf) is reported skipped, with the reason, where there is no GPU.
#include "../path_traced_box.h"
#include "backend/cpu/isa.h"
#include "backend/cuda/cuda_device.h"
#include "core/image.h"
#include "synth/procedural_scene.h"
#include <bmfr/bmfr.hpp>
#include <cmath>
#include <cstring>
#include <functional>
#include <gtest/gtest.h>
#include <stdexcept>

namespace bmfr {
namespace {

/// The backends held to the reference backend, as "backend" or "backend_path".
const std::vector<std::string> kBackends = {"cpu_baseline", "cpu_avx2", "cpu_avx512", "cuda"};

/// Each filter with the configurations beyond the common ones (defaults and every switch).
struct FilterCase {
    const char* name;
    std::vector<std::pair<std::string, SettingValues>> configurations;
};
const FilterCase kFilters[] = {
    {"bmfr",
     {{"block size 8", {{"blockSize", "8"}}},
      {"block size 20", {{"blockSize", "20"}}},
      {"block size 64", {{"blockSize", "64"}}},
      // The paper's 32-pixel blocks: with 16 the -O0 sanitizer build's rank-deficient solves
      // differed by 1.4e-4, beyond the tolerance.
      {"no regularisation: rank-deficient blocks", {{"noiseAmplitude", "0"}, {"blockSize", "32"}}},
      {"an extra feature", {{"features", "1,n.x,n.y,n.z,p.x,p.y,p.z,p.x^2,p.y^2,p.z^2,extra0"}}},
      {"the visibility after an extra",
       {{"visibilityFeature", "true"},
        {"features", "1,n.x,n.y,n.z,p.x,p.y,p.z,p.x^2,p.y^2,p.z^2,extra0"}}},
      {"block size 14, exponents 3, 0.5 and 2 on an extra",
       {{"blockSize", "14"}, {"features", "1,n.x,n.y,n.z,p.x,p.y^3,p.z^0.5,p.x^2,extra0^2"}}}}},
    {"svgf",
     {{"progressive variant",
       {{"kernelRadius", "1"}, {"reverseLevels", "true"}, {"spatialVarianceFrames", "0"}}},
      {"one level", {{"iterations", "1"}}}}},
    {"walr",
     {{"REFWLR over a 9x9 window", {{"solver", "refwlr"}, {"iterations", "2"}}},
      {"three iterations", {{"iterations", "3"}}},
      {"three iterations, float averages", {{"iterations", "3"}, {"halfAverages", "false"}}},
      {"four iterations, the stepped trace", {{"iterations", "4"}, {"edgeStep", "1"}}},
      {"the world-space history test", {{"historyTest", "world"}}}}},
    {"mara2017",
     {{"the paper's first frames (no cumulative start)", {{"cumulativeStart", "false"}}},
      {"c / h in stage 5, fewer taps",
       {{"normaliseConfidence", "true"}, {"preTaps", "8"}, {"finalTaps", "12"}}},
      {"each pixel its own spiral rotation", {{"rotationWidth", "1"}}},
      {"runs of three sharing a rotation", {{"rotationWidth", "3"}}},
      {"runs of eight sharing a rotation", {{"rotationWidth", "8"}}},
      {"TAA on", {{"taa", "true"}}},
      {"TAA on, from the same surface", {{"taa", "true"}, {"taaSameSurface", "true"}}}}},
};

// The stated tolerance: |backend - reference| <= kAbs + kRel * |reference| per channel, and the
// mean difference below kMean. Backends run the same algorithm; they may differ by summation
// order in the QR, fused multiply-adds outside the decision code, and one reciprocal per scaled
// column.
constexpr double kAbs = 1e-4, kRel = 1e-3, kMean = 1e-5;

struct Difference {
    double worstExcess = 0; ///< max of |d| - (kAbs + kRel |ref|); <= 0 passes
    double mean = 0, maxAbs = 0;
};

Difference compareViews(const ImageView& a, const ImageView& ref) {
    Difference d;
    const long n = long(ref.width) * ref.height * 3;
    for (long i = 0; i < n; ++i) {
        const double r = ref.data[i], e = std::fabs(double(a.data[i]) - r);
        d.worstExcess = std::max(d.worstExcess, e - (kAbs + kRel * std::fabs(r)));
        d.maxAbs = std::max(d.maxAbs, e);
        d.mean += e;
    }
    d.mean /= double(n);
    return d;
}

using FrameSource = std::function<FrameInput(int)>;

SettingValues with(SettingValues v, const std::string& key, const std::string& value) {
    v.push_back({key, value});
    return v;
}

/// Runs `frames` frames through `backend` and the reference backend and compares them.
/// `tested` may hand the backend under test a different layout of the same pixels.
void expectConformance(const std::string& filter, const std::string& backend,
                       const SettingValues& values, int frames, const FrameSource& frame,
                       const std::string& what, const FrameSource& tested = nullptr) {
    auto a = makeFilter(filter, with(values, "backend", backend));
    auto ref = makeFilter(filter, with(values, "backend", "reference"));
    a->setDebugOutputs(true);
    ref->setDebugOutputs(true);
    const std::string label = filter + " on " + backend + ", " + what;
    for (int i = 0; i < frames; ++i) {
        const FrameInput in = frame(i);
        const ImageView out = a->denoise(tested ? tested(i) : in), expected = ref->denoise(in);
        ASSERT_EQ(a->lastStats().nonFiniteInputs, ref->lastStats().nonFiniteInputs) << label;
        ASSERT_EQ(a->lastStats().discardedPixels, ref->lastStats().discardedPixels) << label;
        const Difference d = compareViews(out, expected);
        EXPECT_LE(d.worstExcess, 0.0) << label << ", frame " << i << ": max |diff| " << d.maxAbs;
        EXPECT_LE(d.mean, kMean) << label << ", frame " << i;
        const DebugBuffers da = a->debug(), db = ref->debug();
        ASSERT_TRUE(da.discardMask.data && db.discardMask.data) << label;
        for (long p = 0; p < long(in.color.width) * in.color.height; ++p) {
            ASSERT_EQ(da.discardMask.data[p], db.discardMask.data[p]) << label << ", pixel " << p;
            ASSERT_EQ(da.historyLength.data[p], db.historyLength.data[p]) << label;
        }
    }
}

struct ProceduralFrames {
    std::vector<FrameData> frames;
    /// With `moving`, the sphere slides and the box turns, and the frames carry motion vectors
    /// and previous positions and normals (poisoned too, with `poison`).
    ProceduralFrames(int w, int h, int n, bool poison, bool moving = false) {
        ProceduralSceneOptions o;
        o.width = w, o.height = h, o.frames = n;
        o.objectSpeed = moving ? 2.0f : 0.0f, o.motionVectors = moving;
        ProceduralScene scene(o);
        frames.resize(size_t(n));
        for (int i = 0; i < n; ++i) {
            FrameData& f = frames[size_t(i)];
            scene.render(i, f);
            if (poison && i % 3 == 1) {
                f.color.pixels[5] = NAN;
                f.normal.pixels[3 * 17 + 1] = INFINITY;
                f.position.pixels.back() = -INFINITY;
                f.visibility.pixels[29] = NAN;
                if (moving) {
                    f.motion.pixels[2 * 40] = NAN;
                    f.motion.pixels[2 * 41 + 1] = -INFINITY;
                    f.motion.pixels[2 * 42] = 5e9f; // finite, far outside every image
                    f.previousPosition.pixels[3 * 50 + 2] = NAN;
                    f.previousNormal.pixels[3 * 60] = INFINITY;
                }
            }
        }
    }
    FrameSource source() const {
        return [this](int i) { return frames[size_t(i)].input(); };
    }
};

/// The same pixels as RGBA with padded rows, the layout engines hand over.
struct PaddedRgba {
    std::vector<ImageF> images; // color, albedo, normal, position per frame
    std::vector<FrameInput> inputs;
    explicit PaddedRgba(const ProceduralFrames& p) {
        for (const FrameData& f : p.frames) {
            FrameInput in = f.input();
            for (ImageView* v : {&in.color, &in.albedo, &in.normal, &in.position}) {
                const long stride = long(v->width) * 4 + 5;
                ImageF img(int(stride), v->height, 1);
                for (int y = 0; y < v->height; ++y)
                    for (int x = 0; x < v->width; ++x) {
                        for (int c = 0; c < 3; ++c)
                            img.data()[y * stride + 4 * x + c] =
                                v->data[(y * v->width + x) * 3 + c];
                        img.data()[y * stride + 4 * x + 3] = 7.0f; // alpha: must be ignored
                    }
                images.push_back(std::move(img));
                *v = ImageView{images.back().data(), v->width, v->height, 4, stride};
            }
            inputs.push_back(in);
        }
        // The vector of images moved while it grew: point the views at their final homes.
        for (size_t k = 0; k < inputs.size(); ++k) {
            ImageView* views[] = {&inputs[k].color, &inputs[k].albedo, &inputs[k].normal,
                                  &inputs[k].position};
            for (int v = 0; v < 4; ++v) views[v]->data = images[4 * k + size_t(v)].data();
        }
    }
    FrameSource source() const {
        return [this](int i) { return inputs[size_t(i)]; };
    }
};

/// Parameters: (backend, filter name).
struct Conformance : ::testing::TestWithParam<std::tuple<std::string, std::string>> {
    std::string backend() const {
        const std::string b = std::get<0>(GetParam());
        return b.substr(0, b.find('_'));
    }
    void SetUp() override {
        const std::string b = std::get<0>(GetParam());
        if (b == "cuda") {
            try {
                cuda::requireDevice();
            } catch (const Error& e) {
                GTEST_SKIP() << e.what();
            }
            return;
        }
        if (b.find('_') == std::string::npos) return;
        const cpu::Isa isa = cpu::parseIsa(b.substr(b.find('_') + 1));
        if (int(isa) > int(cpu::bestIsa()))
            GTEST_SKIP() << "this processor lacks the " << cpu::isaName(isa)
                         << " path (best: " << cpu::isaName(cpu::bestIsa()) << ")";
        cpu::setActiveIsa(isa);
    }
    void TearDown() override { cpu::setActiveIsa(cpu::bestIsa()); }
    const FilterCase& filter() const {
        for (const FilterCase& f : kFilters)
            if (f.name == std::get<1>(GetParam())) return f;
        throw std::logic_error("no such filter case");
    }
};

TEST_P(Conformance, ProceduralFramesOfOddSizeWithNonFiniteInput) {
    const ProceduralFrames p(203, 117, 12, true);
    expectConformance(filter().name, backend(), {}, 12, p.source(), "203x117 with NaN/Inf");
}

TEST_P(Conformance, MovingObjectsThroughMotionVectors) {
    const ProceduralFrames p(131, 77, 10, true, true);
    expectConformance(filter().name, backend(), {}, 10, p.source(),
                      "131x77, moving objects, motion vectors with NaN/Inf");
    // World-space motion alone: previous positions projected by the previous camera.
    const FrameSource worldOnly = [&p](int i) {
        FrameInput in = p.frames[size_t(i)].input();
        in.motion = {};
        return in;
    };
    expectConformance(filter().name, backend(), {}, 10, worldOnly,
                      "131x77, previous positions without motion vectors");
}

TEST_P(Conformance, ImagesSmallerThanABlock) {
    for (auto [w, h] : {std::pair{9, 70}, {70, 9}, {5, 3}, {1, 1}}) {
        const ProceduralFrames p(w, h, 6, false);
        expectConformance(filter().name, backend(), {}, 6, p.source(),
                          std::to_string(w) + "x" + std::to_string(h));
    }
}

TEST_P(Conformance, EverySwitchAndConfiguration) {
    const ProceduralFrames p(96, 72, 6, false);
    // Every switch of the filter's settings table, flipped from its default.
    for (const SettingDoc& d : filterSettings(filter().name)) {
        if (d.range != "true, false") continue;
        const std::string flipped = d.defaultValue == "true" ? "false" : "true";
        expectConformance(filter().name, backend(), {{d.key, flipped}}, 6, p.source(),
                          d.key + " = " + flipped);
    }
    for (const auto& [what, values] : filter().configurations)
        expectConformance(filter().name, backend(), values, 6, p.source(), what);
    // The defaults hold the switches together, as users run them (the second grid's emitter
    // restore once wrote through the emitter bits it does not keep); the faithful preset none.
    expectConformance(filter().name, backend(), presetSettings(filter().name, "faithful"), 6,
                      p.source(), "the faithful preset");
}

TEST_P(Conformance, RgbaInputWithRowPaddingGivesThePackedResult) {
    const ProceduralFrames p(61, 37, 5, false);
    const PaddedRgba padded(p);
    expectConformance(filter().name, backend(), {}, 5, p.source(), "RGBA with padded rows",
                      padded.source());
}

TEST_P(Conformance, PathTracedFrames) {
    const int n = 8;
    // Our own paths, then Mara et al.'s factored ones (matte, glossy and direct apart).
    for (int directSpp : {0, 4}) {
        const std::vector<FrameData> frames =
            test::pathTracedBox(77, 61, n, 11, 0.05f, 0, directSpp);
        expectConformance(
            filter().name, backend(), {}, n, [&](int i) { return frames[size_t(i)].input(); },
            directSpp ? "path-traced Cornell box, 77x61, factored paths"
                      : "path-traced Cornell box, 77x61");
    }
}

TEST_P(Conformance, ALightThatDims) {
    if (filter().name != std::string("bmfr")) GTEST_SKIP() << "a setting of bmfr's";
    // The left two thirds of the frame dim to a quarter from frame 3 on: adaptiveHistory's tile
    // changes, shortened weights and lengths must be the reference's.
    ProceduralFrames p(96, 72, 7, false);
    for (size_t i = 3; i < p.frames.size(); ++i)
        for (int y = 0; y < 72; ++y)
            for (int x = 0; x < 64; ++x)
                for (int c = 0; c < 3; ++c)
                    p.frames[i].color.pixels[3 * (size_t(y) * 96 + x) + c] *= 0.25f;
    expectConformance(filter().name, backend(),
                      with(presetSettings(filter().name, "faithful"), "adaptiveHistory", "true"), 7,
                      p.source(), "a light that dims, the faithful preset");
    expectConformance(filter().name, backend(), {}, 7, p.source(),
                      "a light that dims, the defaults");
}

TEST_P(Conformance, ALampInViewWithoutAnEmissionBuffer) {
    if (filter().name != std::string("bmfr")) GTEST_SKIP() << "a setting of bmfr's";
    // A bright, flat rectangle painted over the moving scene: the emitter exclusion finds it,
    // and every backend must find the same pixels and drop the same history taps.
    ProceduralFrames p(96, 72, 6, false);
    for (FrameData& f : p.frames) {
        f.emission = {};
        for (int y = 20; y < 29; ++y)
            for (int x = 30; x < 52; ++x)
                for (int c = 0; c < 3; ++c) {
                    const size_t i = 3 * (size_t(y) * 96 + x) + c;
                    f.color.pixels[i] = 25.0f * f.albedo.pixels[i];
                }
    }
    // The reference finds the lamp: the ceiling above it is no longer lit by the fit.
    // On the paper's filter (the faithful preset) with the exclusion alone.
    const SettingValues paper = with(presetSettings("bmfr", "faithful"), "backend", "reference");
    auto on = makeFilter("bmfr", with(paper, "excludeEmitters", "true"));
    auto off = makeFilter("bmfr", paper);
    double lit = 0.0;
    for (int i = 0; i < 6; ++i) {
        const ImageView a = on->denoise(p.frames[size_t(i)].input());
        const ImageView b = off->denoise(p.frames[size_t(i)].input());
        for (int x = 30; x < 52; ++x) lit += b.data[3 * (14 * 96 + x)] - a.data[3 * (14 * 96 + x)];
    }
    EXPECT_GT(lit, 50.0) << "the exclusion changed nothing above the lamp";
    for (const char* ratio : {"16", "4"})
        expectConformance(filter().name, backend(),
                          {{"excludeEmitters", "true"}, {"emitterRatio", ratio}}, 6, p.source(),
                          std::string("a lamp, emitter ratio ") + ratio);
}

std::vector<std::string> filterCases() {
    std::vector<std::string> v;
    for (const FilterCase& f : kFilters) v.push_back(f.name);
    return v;
}

INSTANTIATE_TEST_SUITE_P(AllBackendsAndFilters, Conformance,
                         ::testing::Combine(::testing::ValuesIn(kBackends),
                                            ::testing::ValuesIn(filterCases())),
                         [](const ::testing::TestParamInfo<Conformance::ParamType>& p) {
                             return std::get<0>(p.param) + "_" + std::get<1>(p.param);
                         });

TEST(Conformance, EveryRegisteredFilterIsInTheSuite) {
    for (const std::string& name : filterNames()) {
        bool found = false;
        for (const FilterCase& f : kFilters) found = found || name == f.name;
        EXPECT_TRUE(found) << name << " is registered but not in kFilters";
    }
}

} // namespace
} // namespace bmfr
