// Camera poses per frame: keyframes of position, target and field of view, interpolated with
// Catmull-Rom splines (smooth velocity through the keys).
#pragma once
#include "core/mat4.h"
#include <vector>

namespace bmfr::render {

struct CameraPose {
    Vec3 position{0, 0, 5}, target{0, 0, 0}, up{0, 1, 0};
    float fovY = 1.0f; ///< vertical field of view, radians
};

struct CameraKey {
    float frame = 0;
    CameraPose pose;
};

class CameraPath {
  public:
    CameraPath() = default;
    explicit CameraPath(std::vector<CameraKey> keys); ///< sorted by frame; at least one
    CameraPose at(float frame) const;

  private:
    std::vector<CameraKey> keys_;
};

/// World-to-clip matrix for the pose (library convention: NDC y down), near/far in scene units.
Mat4 viewProjection(const CameraPose& pose, int width, int height, float zNear, float zFar);

} // namespace bmfr::render
