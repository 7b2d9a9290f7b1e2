// A short path-traced sequence of the built-in Cornell box for tests: the camera slides
// sideways with the ceiling light in view.
#pragma once
#include "render/frame_renderer.h"
#include "render/lights.h"
#include "render/ray_accel.h"
#include "render/scene.h"
#include <gtest/gtest.h>
#include <vector>

namespace bmfr::test {

/// n frames of w x h at 1 spp, the camera moving `step` a frame; with referenceSpp > 0 each
/// frame has a reference, with directSpp > 0 Mara et al.'s factored paths; jitter: the frames'
/// sub-pixel offsets (else every frame samples the pixel centres).
inline std::vector<FrameData> pathTracedBox(int w, int h, int n, uint32_t seed, float step,
                                            int referenceSpp = 0, int directSpp = 0,
                                            bool jitter = true) {
    using namespace render;
    Scene box = builtinCornellBox();
    RayAccel accel(box);
    LightSet lights(box, {}, {});
    FrameRenderer r(box, accel, w, h, 1, seed);
    if (directSpp) r.setFactoredPaths(directSpp);
    std::vector<FrameData> frames{size_t(n)};
    CameraPose previous;
    for (int i = 0; i < n; ++i) {
        CameraPose pose;
        pose.position = {step * float(i), 1.0f, 3.4f}, pose.target = {0, 1, 0};
        pose.fovY = 0.69f;
        FrameRenderStats stats;
        EXPECT_TRUE(r.render(i, pose, previous, i > 0, lights, jitter, referenceSpp,
                             frames[size_t(i)], stats, nullptr));
        previous = pose;
    }
    return frames;
}

} // namespace bmfr::test
