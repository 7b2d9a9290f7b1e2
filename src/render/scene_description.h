// The scene description (JSON): mesh, lights, camera path, resolution, frame count, reference
// spp, moving lights; and the built-in presets matching the BMFR paper's test sequences.
#pragma once
#include "render/animation.h"
#include "render/camera_path.h"
#include "render/lights.h"
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace bmfr::render {

/// A rectangular two-sided light whose centre may follow keyframes (a moving light).
struct QuadLightSpec {
    Vec3 centre, edgeU, edgeV, radiance;
    std::vector<std::pair<float, Vec3>> path; ///< (frame, centre) keys, linear between
    QuadLight at(float frame) const;
};

struct SceneDescription {
    std::string name;
    std::string mesh;               ///< glTF/OBJ path or "builtin:cornell"
    float roughnessOverride = -1;   ///< >= 0: every material gets this roughness (glossy preset)
    int width = 1280, height = 720; ///< pixels
    int frames = 60;
    int referenceSpp = 4096; ///< samples per pixel of the reference; 0 = no reference
    int bounces = 1;         ///< BSDF-sampled secondary rays per path; the paper uses 1
    uint32_t seed = 1;
    bool jitter = true; ///< per-frame sub-pixel offsets (Halton 2,3)
    /// The colour and reference hold only the indirect light through the primary hit's diffuse
    /// lobe (the signal WALR's paper filters), with no emission: for comparing filters on it.
    bool diffuseIndirectOnly = false;
    /// Mara et al. 2017's factored paths ("paths": "mara"): light samples of the direct light
    /// at the first hit, [1, 4096]; 0 = the paper's paths ("paths": "bmfr").
    int factoredDirectSpp = 0;
    Environment environment;
    /// "light_sampling": "one" (the paper's: one light sample per path vertex) or "split"
    /// (local lights, the sun and the sky each sampled at every vertex).
    LightSampling lightSampling = LightSampling::One;
    std::vector<QuadLightSpec> quadLights;
    std::vector<CameraKey> cameraKeys;
    std::string gltfCamera; ///< use this named camera of the mesh file (static)
    /// Objects of the mesh left out, by name (every object of that name): for example the
    /// roof some Sponza exports carry, which keeps the sun and sky out of the atrium.
    std::vector<std::string> hiddenObjects;
    /// Moving objects: keyframed rigid transforms of the mesh's named objects.
    std::vector<ObjectAnimation> animations;
    /// Frames per second at which the mesh file's own animations play (glTF translation,
    /// rotation and scale channels); 0 = not played. (0, 1000].
    float gltfAnimationFps = 0;
};

inline constexpr int kMaxSceneSide = 16384;    ///< pixels per side
inline constexpr int kMaxSceneFrames = 100000; ///< frames per sequence

/// Throws bmfr::Error when a size, frame count, spp or bounce count is out of range (after
/// command-line overrides too).
void validate(const SceneDescription& d);
/// The farthest a camera may be from its target, scene units (the renderer's float maths
/// squares distances).
inline constexpr double kMaxCameraDistance = 1e18;
/// Why a camera pose cannot be rendered ("has its position equal to its target"), or "".
std::string cameraPoseProblem(const CameraPose& pose);

/// Parses a description; relative mesh paths resolve against `baseDir`. Throws bmfr::Error.
SceneDescription parseSceneDescription(const nlohmann::json& j, const std::string& baseDir);
/// Loads a preset by name or a JSON file. `scenesDir` replaces {scenes} in preset mesh paths;
/// with `checkMesh` a preset whose mesh is not there is an error that points to --scenes.
SceneDescription loadSceneDescription(const std::string& presetOrFile, const std::string& scenesDir,
                                      bool checkMesh = true);
std::vector<std::string> presetNames();

/// A rough render time for `d` on a 2-core machine of the CI's kind (AMD EPYC, 2 threads),
/// seconds: path samples times a per-sample time measured there for the built-in box
/// (0.37 us) and for meshes such as Sponza (1.0 us per 1-spp input sample with its features,
/// 0.65 us per reference sample). Scales about inversely with cores.
double estimatedRenderSeconds(const SceneDescription& d);

} // namespace bmfr::render
