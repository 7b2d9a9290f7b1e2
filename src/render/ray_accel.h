// Thin wrapper around Embree 3: closest-hit and occlusion queries with alpha-masked geometry.
// Everything Embree-specific stays in ray_accel.cpp.
#pragma once
#include "render/scene.h"
#include <memory>

namespace bmfr::render {

struct RayHit {
    float t = 0;
    int triangle = -1;  ///< index into Scene triangles, -1 = miss
    float u = 0, v = 0; ///< barycentrics of vertices 1 and 2
};

class RayAccel {
  public:
    /// Builds the BVH. Triangles of alpha-masked materials get an alpha test per hit.
    explicit RayAccel(const Scene& scene);
    ~RayAccel();
    RayAccel(const RayAccel&) = delete;
    RayAccel& operator=(const RayAccel&) = delete;

    RayHit intersect(Vec3 origin, Vec3 direction, float tMax) const;
    bool occluded(Vec3 origin, Vec3 direction, float tMax) const;

    struct Impl; ///< Embree state (public only so the alpha filter callback can name it)

  private:
    std::unique_ptr<Impl> impl_;
};

} // namespace bmfr::render
