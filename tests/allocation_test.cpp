// After the first frame, denoising allocates nothing (all buffers are reused).
#include "test_support.h"
#include <atomic>
#include <bmfr/bmfr.h>
#include <cstdlib>
#include <gtest/gtest.h>
#include <malloc.h>
#include <new>

namespace {
std::atomic<long> gAllocations{0};
std::atomic<bool> gCounting{false};
std::atomic<long> gLiveBytes{0}; ///< bytes new gave minus bytes delete took back, while counting
} // namespace

void* operator new(std::size_t n) {
    if (gCounting) ++gAllocations;
    if (void* p = std::malloc(n ? n : 1)) {
        if (gCounting) gLiveBytes += long(malloc_usable_size(p));
        return p;
    }
    throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
    if (gCounting && p) gLiveBytes -= long(malloc_usable_size(p));
    std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
    operator delete(p);
}

namespace bmfr {
namespace {

constexpr int kWidth = 200, kHeight = 120;

/// The procedural scene's first n frames, as inputs (their images live as long as the process).
std::vector<FrameInput> frameInputs(int n) {
    static std::vector<std::vector<FrameData>> kept;
    kept.push_back(testing::proceduralFrames(kWidth, kHeight, n));
    std::vector<FrameInput> inputs;
    for (const FrameData& f : kept.back()) inputs.push_back(f.input());
    return inputs;
}

TEST(Allocation, SteadyStateFramesAllocateNothing) {
    const std::vector<FrameInput> inputs = frameInputs(6);
    Denoiser d;
    d.setDebugOutputs(true);
    for (int i = 0; i < 3; ++i) d.denoise(inputs[i]);
    gCounting = true;
    for (int i = 3; i < 6; ++i) d.denoise(inputs[i]);
    gCounting = false;
    EXPECT_EQ(gAllocations.load(), 0);
}

/// A filter made from a Device that reserved the frame size allocates nothing on its first frame
/// either (the frames' own buffers are packed RGB, read in place).
class AllocationOnAReservedDevice : public ::testing::TestWithParam<std::string> {};

TEST_P(AllocationOnAReservedDevice, FirstFrameAllocatesNothing) {
    const std::vector<FrameInput> inputs = frameInputs(2);
    for (Backend b : {Backend::Reference, Backend::Cpu}) {
        Device device(b, 2);
        device.reserve(kWidth, kHeight);
        std::unique_ptr<Filter> f = device.makeFilter(GetParam());
        gAllocations = 0;
        gCounting = true;
        f->denoise(inputs[0]);
        f->denoise(inputs[1]);
        gCounting = false;
        EXPECT_EQ(gAllocations.load(), 0) << backendName(b);
    }
}

INSTANTIATE_TEST_SUITE_P(EveryFilter, AllocationOnAReservedDevice,
                         ::testing::ValuesIn(filterNames()), [](const auto& p) { return p.param; });

/// Through the C API as an engine calls it: committed with a reservation, then every frame sets
/// its images again (half, octahedral, padded and UV-motion ones among them, long names too)
/// and executes. After the first setting of each image nothing allocates, the first execute
/// included.
TEST(AllocationThroughTheCApi, ConvertedInputsOnAReservedFilterAllocateNothing) {
    std::vector<FrameData> frames = testing::proceduralFrames(kWidth, kHeight, 3);
    const size_t n = size_t(kWidth) * kHeight;
    std::vector<uint16_t> color(n * 4, 0x3c00), albedo(n * 4, 0x3800);
    std::vector<float> normal(n * 2, 0.0f), out(n * 4), previous(n * 4), motion(n * 2, 0.5f);
    BMFRDevice device = bmfrNewDevice(BMFR_DEVICE_TYPE_CPU);
    bmfrCommitDevice(device);
    for (const std::string& name : filterNames()) {
        BMFRFilter filter = bmfrNewFilter(device, name.c_str());
        bmfrSetFilterInt(filter, "maxWidth", kWidth);
        bmfrSetFilterInt(filter, "maxHeight", kHeight);
        bmfrCommitFilter(filter);
        const auto setImages = [&](const FrameData& f) {
            bmfrSetFilterImage(filter, "color", color.data(), BMFR_FORMAT_HALF4, kWidth, kHeight, 0,
                               0, 0);
            bmfrSetFilterImage(filter, "albedo", albedo.data(), BMFR_FORMAT_HALF4, kWidth, kHeight,
                               0, 0, 0);
            bmfrSetFilterImage(filter, "normal", normal.data(), BMFR_FORMAT_FLOAT2, kWidth, kHeight,
                               0, 0, 0);
            bmfrSetFilterImage(filter, "position", (void*)f.position.data(), BMFR_FORMAT_FLOAT3,
                               kWidth, kHeight, 0, 0, 0);
            bmfrSetFilterImage(filter, "previousPosition", previous.data(), BMFR_FORMAT_FLOAT4,
                               kWidth, kHeight, 0, 0, 0);
            bmfrSetFilterImage(filter, "motion", motion.data(), BMFR_FORMAT_FLOAT2, kWidth, kHeight,
                               0, 0, 0);
            bmfrSetFilterImage(filter, "output", out.data(), BMFR_FORMAT_FLOAT4, kWidth, kHeight, 0,
                               0, 0);
        };
        setImages(frames[0]); // the first setting of each image sizes its buffer
        gAllocations = 0;
        gCounting = true;
        for (size_t i = 0; i < frames.size(); ++i) {
            const FrameData& f = frames[i];
            setImages(f);
            bmfrSetFilterMatrix(filter, "viewProjection", &f.viewProjection.m[0][0]);
            bmfrSetFilterFloat(filter, "motionScaleX", float(kWidth));
            bmfrSetFilterBool(filter, "motionIncludesJitter", false);
            bmfrSetFilterInt(filter, "accumulationMode", BMFR_ACCUMULATION_MODE_CONTINUE);
            bmfrSetFilterInt(filter, "frameIndex", int(i));
            bmfrExecuteFilter(filter);
        }
        gCounting = false;
        const char* message = nullptr;
        EXPECT_EQ(bmfrGetDeviceError(device, &message), BMFR_ERROR_NONE) << message;
        EXPECT_EQ(gAllocations.load(), 0) << name;
        bmfrReleaseFilter(filter);
    }
    bmfrReleaseDevice(device);
}

/// bmfrGetFilterMemoryBytes (glibc's heap statistics around a probe) against the bytes this
/// program's operator new handed out for the same filter, counted one allocation at a time.
TEST(AllocationThroughTheCApi, MemoryQueryMatchesTheBytesNewHandsOut) {
#if defined(__SANITIZE_ADDRESS__)
    GTEST_SKIP() << "AddressSanitizer's allocator keeps no glibc heap statistics";
#endif
    BMFRDevice device = bmfrNewDevice(BMFR_DEVICE_TYPE_CPU);
    bmfrSetDeviceInt(device, "threads", 2);
    bmfrCommitDevice(device);
    for (const std::string& name : filterNames()) {
        for (const char* preset : {"faithful", "quality"}) {
            BMFRFilter filter = bmfrNewFilter(device, name.c_str());
            bmfrSetFilterString(filter, "preset", preset);
            bmfrCommitFilter(filter);
            const size_t queried = bmfrGetFilterMemoryBytes(filter, 640, 360);
            Device cpp(Backend::Cpu, 2);
            cpp.reserve(640, 360);
            gLiveBytes = 0;
            gCounting = true;
            std::unique_ptr<Filter> made = cpp.makeFilter(name, presetSettings(name, preset));
            gCounting = false;
            const double counted = double(gLiveBytes.load());
            EXPECT_GT(counted, 640.0 * 360 * 12) << name << " " << preset;
            EXPECT_NEAR(double(queried), counted, 0.01 * counted + 65536) << name << " " << preset;
            bmfrReleaseFilter(filter);
        }
    }
    const char* message = nullptr;
    EXPECT_EQ(bmfrGetDeviceError(device, &message), BMFR_ERROR_NONE) << message;
    bmfrReleaseDevice(device);
}

} // namespace
} // namespace bmfr
