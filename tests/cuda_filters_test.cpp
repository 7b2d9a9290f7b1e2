// Several cuda filters in one process, as bench with a cuda baseline, two Python filters or an
// engine with two views: filters of different block sizes denoising alternately give each one's
// solo bits, and the library leaves the caller's device current. Reported skipped, with the
// reason, where there is no GPU; the device checks that need none run everywhere.
#include "backend/cuda/cuda_device.h"
#include "needs_gpu.h"
#include "path_traced_box.h"
#include "synth/procedural_scene.h"
#include <bmfr/bmfr.hpp>
#include <gtest/gtest.h>
#include <memory>
#include <vector>

namespace bmfr {
namespace {

using CudaFilters = test::NeedsGpu;

std::vector<FrameData> movingObjects(int w, int h, int n) {
    ProceduralSceneOptions o;
    o.width = w, o.height = h, o.frames = n, o.objectSpeed = 1.0f;
    ProceduralScene scene(o);
    std::vector<FrameData> out(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) scene.render(i, out[size_t(i)]);
    return out;
}

std::vector<float> rgbOf(const ImageView& v) {
    return std::vector<float>(v.data, v.data + size_t(v.width) * v.height * 3);
}

SettingValues onCuda(SettingValues values) {
    values.emplace_back("backend", "cuda");
    return values;
}

// The fit kernel's shared-memory limit is the process's, not a filter's: a filter with 16x16
// blocks (about 29 KB) made after one with 32x32 blocks and ten features (about 79 KB) must
// not shrink it under the other's next launch.
TEST_F(CudaFilters, BlockSizesThatDifferDenoiseAlternately) {
    const std::vector<FrameData> seq = movingObjects(96, 64, 4);
    const SettingValues wide = onCuda(presetSettings("bmfr", "faithful"));
    const SettingValues narrow = onCuda({{"blockSize", "16"}});
    std::vector<std::vector<float>> soloWide, soloNarrow;
    {
        auto a = makeFilter("bmfr", wide);
        auto b = makeFilter("bmfr", narrow);
        for (const FrameData& f : seq) soloWide.push_back(rgbOf(a->denoise(f.input())));
        for (const FrameData& f : seq) soloNarrow.push_back(rgbOf(b->denoise(f.input())));
    }
    auto a = makeFilter("bmfr", wide);
    (void)a->denoise(seq[0].input()); // allocates with the larger plan first
    auto b = makeFilter("bmfr", narrow);
    for (size_t i = 0; i < seq.size(); ++i) {
        if (i > 0) {
            EXPECT_EQ(rgbOf(a->denoise(seq[i].input())), soloWide[i]) << "frame " << i;
        }
        EXPECT_EQ(rgbOf(b->denoise(seq[i].input())), soloNarrow[i]) << "frame " << i;
    }
}

// Every call leaves the caller's device current. With one GPU the filter's device is the
// caller's, so only a machine with two tells a switch that is not undone.
TEST_F(CudaFilters, TheCallersDeviceStaysCurrent) {
    const int last = cuda::deviceCount() - 1;
    const std::vector<FrameData> seq = movingObjects(40, 24, 3);
    for (const char* name : {"bmfr", "svgf", "walr", "mara2017"}) {
        SCOPED_TRACE(name);
        const cuda::DeviceScope caller(last);
        Device device(Backend::Cuda, 0, 0);
        auto filter = device.makeFilter(name);
        EXPECT_EQ(cuda::currentDevice(), last);
        for (const FrameData& f : seq) {
            (void)filter->denoise(f.input());
            EXPECT_EQ(cuda::currentDevice(), last);
        }
        filter.reset();
        EXPECT_EQ(cuda::currentDevice(), last);
    }
    EXPECT_THROW(Device(Backend::Cuda, 0, last + 1), Error);
}

} // namespace

// Without a GPU too. The CUDA passes time the reference backend's stages with events, plus the
// upload and the download: every filter's stages, Mara's with the glossy passes, leave room for
// those two in StageTimes, where CUDA's events would otherwise run out.
TEST(CudaStageTimes, EveryFiltersStagesLeaveRoomForTheTransfers) {
    const std::vector<FrameData> frames = test::pathTracedBox(24, 16, 2, 5, 0.03f, 0, 4);
    ASSERT_NE(frames[0].glossyIndirect.data(), nullptr);
    for (const std::string& name : filterNames()) {
        SCOPED_TRACE(name);
        auto f = makeFilter(name, {{"backend", "reference"}});
        for (const FrameData& frame : frames) (void)f->denoise(frame.input());
        EXPECT_LE(f->lastStats().times.count + 2, StageTimes::kMaxStages);
    }
}

// Without a GPU too: the device's GPU is chosen only for the cuda backend, and never below 0.
TEST(CudaDeviceChoice, OnlyTheCudaBackendTakesAGpu) {
    try {
        Device(Backend::Cpu, 1, 1);
        FAIL() << "a cpu device took cudaDevice 1";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("cudaDevice 1"), std::string::npos) << e.what();
    }
    EXPECT_EQ(Device(Backend::Cpu, 1).cudaDevice(), 0);
    try {
        Device(Backend::Cuda, 1, -1);
        FAIL() << "cudaDevice -1 was taken";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("no CUDA device"), std::string::npos) << e.what();
    }
}

} // namespace bmfr
