// Moving objects: keyframed rigid transforms of named scene objects, the scene posed at a
// frame, and the map from a point of a frame back to where it was one frame earlier.
#pragma once
#include "core/mat4.h"
#include "render/scene.h"
#include <string>
#include <vector>

namespace bmfr::render {

/// A rotation from Euler angles in degrees, applied about x, then y, then z.
Quat quatFromEulerDegrees(Vec3 degrees);
/// Shortest-arc spherical interpolation; t in [0, 1].
Quat slerp(Quat a, Quat b, float t);

/// One key of an object's motion, relative to the object as the scene file places it.
struct RigidKey {
    float frame = 0;
    Vec3 translation{0, 0, 0}; ///< scene units
    Quat rotation;             ///< about the animation's pivot
    Vec3 scale{1, 1, 1};       ///< about the pivot; each in (0, 1000]
};

/// The motion of every scene object with one name: T(translation) T(pivot) R S T(-pivot), keys
/// interpolated linearly (rotations by slerp, so keys must be less than 180 degrees apart) and
/// held before the first and after the last.
struct ObjectAnimation {
    std::string object;
    Vec3 pivot{0, 0, 0};        ///< scene units, in the scene file's placement
    std::vector<RigidKey> keys; ///< sorted by frame, at least one
    Mat4 at(float frame) const;
};

/// The scene posed at any frame, and each object's map from one frame to the one before.
class SceneAnimator {
  public:
    /// Resolves every animation's object name against scene.objectNames. With `fileFps` > 0,
    /// also plays the file's own node animations (glTF), frame f at f / fileFps seconds, before
    /// the keyed transforms. Throws bmfr::Error for a name the scene lacks (listing the names
    /// it has), or for fileFps > 0 with a file that has no animations.
    SceneAnimator(const Scene& rest, std::vector<ObjectAnimation> animations, float fileFps = 0);
    bool animated() const { return animated_; }
    /// Writes the rest scene's triangles moved to `frame` into `posed` (a copy of the rest
    /// scene): positions, and normals through the inverse transpose.
    void pose(float frame, Scene& posed) const;
    /// Per object, the matrices taking a point at `frame` to where it was at `frame - 1` and
    /// its normal likewise (the inverse transpose; identity for objects that do not move).
    void toPrevious(float frame, std::vector<Mat4>& points, std::vector<Mat4>& normals) const;

  private:
    const Scene& rest_;
    std::vector<ObjectAnimation> animations_;
    float fileFps_ = 0;
    bool animated_ = false;
    std::vector<int> animationOf_;  ///< per object: index into animations_, -1 = none
    std::vector<char> moves_;       ///< per object: keyed or moved by the file's animations
    std::vector<Mat4> restInverse_; ///< per object moved by the file: its node's rest world^-1
    std::vector<Mat4> objectMatrices(float frame) const;
    /// World matrices of every file node at `seconds` (< 0: the rest pose, no channels).
    std::vector<Mat4> nodeWorlds(float seconds) const;
};

} // namespace bmfr::render
