// After the first frame, denoising allocates nothing (all buffers are reused).
#include "test_support.h"
#include <atomic>
#include <bmfr/bmfr.h>
#include <cstdlib>
#include <gtest/gtest.h>
#include <new>

namespace {
std::atomic<long> gAllocations{0};
std::atomic<bool> gCounting{false};
} // namespace

void* operator new(std::size_t n) {
    if (gCounting) ++gAllocations;
    if (void* p = std::malloc(n ? n : 1)) return p;
    throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
    std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
    std::free(p);
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

} // namespace
} // namespace bmfr
