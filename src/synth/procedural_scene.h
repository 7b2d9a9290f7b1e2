// A procedurally generated moving-camera sequence with an exact noise-free truth: an analytic
// room (planes, a sphere, a box) lit by two point lights with hard shadows. The noisy colour is
// truth times unit-mean exponential noise, like 1-spp Monte Carlo. It is the default input of
// the demo, the benchmark and the end-to-end tests until the path tracer exists.
#pragma once
#include "io/sequence.h"
#include <cstdint>

namespace bmfr {

struct ProceduralSceneOptions {
    int width = 640;          ///< pixels, [1, 16384]
    int height = 360;         ///< pixels, [1, 16384]
    int frames = 30;          ///< sequence length; [1, 100000]
    uint32_t seed = 1;        ///< noise seed
    bool jitter = true;       ///< per-frame sub-pixel offsets (Halton 2,3), else pixel centres
    float cameraSpeed = 1.0f; ///< scales the camera path per frame; 0 = static camera
    /// Scales the objects' motion per frame: the sphere slides 0.05 m and the box turns 0.04 rad
    /// about its vertical axis per frame at 1. 0 = static objects; [-100, 100].
    float objectSpeed = 0.0f;
    /// Also write the exact motion vectors and previous positions and normals (FrameInput).
    bool motionVectors = false;
};

class ProceduralScene {
  public:
    explicit ProceduralScene(const ProceduralSceneOptions& options);
    /// Renders frame `index`: noisy colour, albedo, normal, position, extras (material id), the
    /// key light's visibility, reference (the exact truth), matrix and jitter; with motionVectors,
    /// motion and previous positions and normals too.
    void render(int index, FrameData& out) const { render(index, out, index - 1); }
    /// The same, with the motion vectors and previous positions pointing to frame `previous`
    /// (a sequence played backwards: index + 1).
    void render(int index, FrameData& out, int previous) const;
    SequenceInfo info() const;
    const ProceduralSceneOptions& options() const { return opt_; }

  private:
    ProceduralSceneOptions opt_;
};

} // namespace bmfr
