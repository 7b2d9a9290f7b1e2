// The renderer's scene: world-space triangles, materials, textures, lights, cameras.
#pragma once
#include "core/vec.h"
#include "render/texture.h"
#include <string>
#include <vector>

namespace bmfr::render {

/// Lambertian + GGX (metal/rough, as glTF). Every setting in the units of glTF 2.0.
struct Material {
    std::string name;
    Vec3 baseColor{0.8f, 0.8f, 0.8f}; ///< linear RGB multiplier, [0, 1]
    int baseColorTexture = -1;        ///< index into Scene::textures, -1 = none
    float roughness = 0.5f;           ///< perceptual roughness, [0, 1]; GGX alpha = roughness^2
    float metallic = 0.0f;            ///< [0, 1]
    float specular = 0.04f;           ///< dielectric normal-incidence reflectance F0, [0, 1];
                                      ///< 0 = purely Lambertian (glTF implies 0.04)
    int normalTexture = -1;
    float normalScale = 1.0f;
    bool alphaMask = false; ///< glTF alphaMode MASK
    float alphaCutoff = 0.5f;
    Vec3 emission{0, 0, 0}; ///< emitted radiance, W/(sr m^2) per channel, both sides
};

struct Vec2f {
    float x = 0, y = 0;
};

/// A unit quaternion (x, y, z, w): a rotation.
struct Quat {
    float x = 0, y = 0, z = 0, w = 1;
};

/// A node of the file's transform hierarchy (glTF), kept for the file's own animations.
struct SceneNode {
    int parent = -1;
    Vec3 translation{0, 0, 0};
    Quat rotation;
    Vec3 scale{1, 1, 1};
    bool hasMatrix = false; ///< placed by a matrix (which glTF does not let animations touch)
    float matrix[16] = {};  ///< column-major, as glTF, when hasMatrix
};

/// One animation channel of the file: a node's translation, rotation or scale over time.
struct NodeChannel {
    enum class Path { Translation, Rotation, Scale } path = Path::Translation;
    int node = 0;
    bool step = false;         ///< STEP interpolation, else LINEAR
    std::vector<float> times;  ///< seconds, increasing
    std::vector<float> values; ///< 3 (or 4 for rotations) per time
};

/// A camera keyframe as read from a file (glTF cameras).
struct NamedCamera {
    std::string name;
    Vec3 position, forward, up;
    float fovY = 1.0f; ///< radians
};

/// Unindexed triangles in world space: vertex k of triangle t is at [3t + k].
struct Scene {
    std::vector<Vec3> positions, normals;
    std::vector<Vec2f> uvs;
    std::vector<int> triangleMaterial;
    /// Parts that can move on their own: glTF mesh nodes, OBJ objects or groups, the built-in
    /// scenes' named parts. Several objects may share a name (an animation moves them all).
    std::vector<std::string> objectNames;
    std::vector<int> triangleObject; ///< per triangle: index into objectNames
    /// The file's node hierarchy and animation channels (glTF); objectNode[o] is object o's
    /// node, -1 for objects of other sources.
    std::vector<SceneNode> nodes;
    std::vector<NodeChannel> nodeChannels;
    std::vector<int> objectNode;
    std::vector<Material> materials;
    std::vector<Texture> textures;
    std::vector<NamedCamera> cameras;
    std::vector<std::string> warnings;
    size_t triangleCount() const { return triangleMaterial.size(); }
    /// Adds a triangle to the current object (the first call starts one named "scene").
    void addTriangle(Vec3 a, Vec3 b, Vec3 c, int material);
    /// Starts an object: the triangles added from now on belong to it.
    void beginObject(const std::string& name);
    /// Drops every triangle of the objects with these names. Throws bmfr::Error naming the
    /// scene's objects when a name matches none.
    void removeObjects(const std::vector<std::string>& names);
    /// Axis-aligned bounds of all vertices.
    void bounds(Vec3& lo, Vec3& hi) const;
};

/// The built-in Cornell box (needs no files): 2 m box, two blocks, a ceiling light. Objects:
/// room, light, short_block, tall_block.
Scene builtinCornellBox();
/// The built-in box with a sphere (objects as builtinCornellBox, plus "sphere": radius 0.25 m,
/// centre (0, 1.3, 0.2)), for scenes that move things.
Scene builtinCornellObjects();
/// Loads glTF 2.0 (.gltf/.glb). Throws bmfr::Error for unsupported required features.
Scene loadGltf(const std::string& path);
/// Loads OBJ + MTL (Kd, Ke, map_Kd, d/map_d ignored, Ns -> roughness).
Scene loadObj(const std::string& path);
/// Chooses the loader by extension ("builtin:cornell" for the built-in box).
Scene loadScene(const std::string& path);

} // namespace bmfr::render
