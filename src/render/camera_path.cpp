#include "render/camera_path.h"
#include <algorithm>
#include <bmfr/error.h>

namespace bmfr::render {

CameraPath::CameraPath(std::vector<CameraKey> keys) : keys_(std::move(keys)) {
    if (keys_.empty()) throw Error("camera path needs at least one keyframe");
    std::sort(keys_.begin(), keys_.end(),
              [](const CameraKey& a, const CameraKey& b) { return a.frame < b.frame; });
}

namespace {

Vec3 catmullRom(Vec3 p0, Vec3 p1, Vec3 p2, Vec3 p3, float t) {
    float t2 = t * t, t3 = t2 * t;
    return 0.5f * ((2.0f * p1) + t * (p2 - p0) + t2 * (2.0f * p0 - 5.0f * p1 + 4.0f * p2 - p3) +
                   t3 * (3.0f * p1 - p0 - 3.0f * p2 + p3));
}

} // namespace

CameraPose CameraPath::at(float frame) const {
    if (keys_.size() == 1 || frame <= keys_.front().frame) return keys_.front().pose;
    if (frame >= keys_.back().frame) return keys_.back().pose;
    size_t i = 0;
    while (keys_[i + 1].frame < frame) ++i;
    const CameraKey& k1 = keys_[i];
    const CameraKey& k2 = keys_[i + 1];
    const CameraKey& k0 = keys_[i > 0 ? i - 1 : i];
    const CameraKey& k3 = keys_[std::min(i + 2, keys_.size() - 1)];
    float t = (frame - k1.frame) / (k2.frame - k1.frame);
    CameraPose p = k1.pose;
    p.position =
        catmullRom(k0.pose.position, k1.pose.position, k2.pose.position, k3.pose.position, t);
    p.target = catmullRom(k0.pose.target, k1.pose.target, k2.pose.target, k3.pose.target, t);
    p.fovY = k1.pose.fovY + t * (k2.pose.fovY - k1.pose.fovY);
    return p;
}

Mat4 viewProjection(const CameraPose& pose, int width, int height, float zNear, float zFar) {
    return multiply(perspectiveYDown(pose.fovY, float(width) / float(height), zNear, zFar),
                    lookAt(pose.position, pose.target, pose.up));
}

} // namespace bmfr::render
