// Renders one frame of a sequence: the 1-spp input with every feature and split, and the
// reference (the same estimator averaged over many samples, same camera and sub-pixel offset).
#pragma once
#include "io/sequence.h"
#include "render/camera_path.h"
#include "render/integrator.h"
#include <atomic>
#include <cstdint>

namespace bmfr::render {

struct FrameRenderStats {
    uint64_t rays = 0;
    double inputSeconds = 0, referenceSeconds = 0;
};

/// Where each object's points and normals were one frame earlier (SceneAnimator::toPrevious),
/// indexed by Scene::triangleObject.
struct ObjectMotion {
    std::vector<Mat4> points, normals;
};

/// Sub-pixel offset of frame `index`: Halton (2, 3) minus 0.5, pixels.
void frameJitter(int index, bool enabled, float jitter[2]);

class FrameRenderer {
  public:
    FrameRenderer(const Scene& scene, const RayAccel& accel, int width, int height, int bounces,
                  uint32_t seed);

    /// Fills `out` (colour, albedo, normal, position, emission, motion, extras material_id and
    /// roughness, the sun's visibility when the scene has a sun, AOVs depth, direct, indirect, diffuse, glossy; reference when referenceSpp >
    /// 0). With `objects` (a scene whose objects move), also the previous position and normal of
    /// each visible point, and motion vectors that follow the objects. Returns false when
    /// `cancel` became true (out is then incomplete and must be dropped).
    bool render(int index, const CameraPose& pose, const CameraPose& previousPose, bool hasPrevious,
                const LightSet& lights, bool jitter, int referenceSpp, FrameData& out,
                FrameRenderStats& stats, const std::atomic<bool>* cancel,
                const ObjectMotion* objects = nullptr) const;

    /// Traces this frame's posed copy of the scene (moving objects); the clip planes stay
    /// those of the scene given at construction, so every frame's matrices agree.
    void setGeometry(const Scene& scene, const RayAccel& accel) {
        scene_ = &scene;
        accel_ = &accel;
    }

    /// Colour and reference hold only the diffuse indirect light (SceneDescription).
    void setDiffuseIndirectOnly(bool on) { diffuseIndirectOnly_ = on; }

    /// With directSpp > 0, Mara et al. 2017's paths: the colour is their factored estimate
    /// (direct light from directSpp light samples, one matte and one glossy path), the frame
    /// also holds M, G, the direct light, F0, roughness and the glossy hit distance, and the
    /// reference averages the same estimator (one light sample each). 0 = the paper's paths.
    void setFactoredPaths(int directSpp) { factoredDirectSpp_ = directSpp; }

    /// The world-to-clip matrix render() uses for `pose`.
    Mat4 viewProjectionOf(const CameraPose& pose) const;

    /// Names of FrameData::extras and FrameData::aovs in the order render() fills them.
    static std::vector<std::string> extraNames();
    static std::vector<std::string> aovNames();

  private:
    const Scene* scene_;
    const RayAccel* accel_;
    int width_, height_, bounces_;
    uint32_t seed_;
    bool diffuseIndirectOnly_ = false;
    int factoredDirectSpp_ = 0;
    float zNear_, zFar_, skyDistance_;
};

} // namespace bmfr::render
