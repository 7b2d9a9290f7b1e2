// After the first frame, denoising allocates nothing (all buffers are reused).
#include "synth/procedural_scene.h"
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

TEST(Allocation, SteadyStateFramesAllocateNothing) {
    ProceduralSceneOptions o;
    o.width = 200, o.height = 120, o.frames = 6;
    ProceduralScene scene(o);
    std::vector<FrameData> frames(6);
    std::vector<FrameInput> inputs;
    for (int i = 0; i < 6; ++i) scene.render(i, frames[i]), inputs.push_back(frames[i].input());
    Denoiser d;
    d.setDebugOutputs(true);
    for (int i = 0; i < 3; ++i) d.denoise(inputs[i]);
    gCounting = true;
    for (int i = 3; i < 6; ++i) d.denoise(inputs[i]);
    gCounting = false;
    EXPECT_EQ(gAllocations.load(), 0);
}

} // namespace
} // namespace bmfr
