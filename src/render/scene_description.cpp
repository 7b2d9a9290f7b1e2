#include "render/scene_description.h"
#include "io/json_fields.h"
#include <algorithm>
#include <bmfr/error.h>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <map>

namespace bmfr::render {

namespace fs = std::filesystem;
using nlohmann::json;

QuadLight QuadLightSpec::at(float frame) const {
    Vec3 c = centre;
    if (!path.empty()) {
        if (frame <= path.front().first)
            c = path.front().second;
        else if (frame >= path.back().first)
            c = path.back().second;
        else
            for (size_t i = 0; i + 1 < path.size(); ++i)
                if (frame >= path[i].first && frame <= path[i + 1].first) {
                    float t = (frame - path[i].first) / (path[i + 1].first - path[i].first);
                    c = lerp(path[i].second, path[i + 1].second, t);
                }
    }
    return {c - 0.5f * edgeU - 0.5f * edgeV, edgeU, edgeV, radiance};
}

namespace {

Vec3 vec3(const json& j, const char* what) {
    if (!j.is_array() || j.size() != 3)
        throw Error(std::string("scene description: '") + what + "' must be [x, y, z]");
    const std::string where = std::string("scene description: '") + what + "'";
    return {floatValue(j[0], where), floatValue(j[1], where), floatValue(j[2], where)};
}

/// {"centre", "u", "v"}: a sky portal or a bounce guide (`what`).
Parallelogram parallelogram(const json& q, const std::string& what) {
    requireKnownKeys(q, {"centre", "u", "v"}, "scene description " + what);
    Parallelogram r;
    r.edgeU = vec3(q.at("u"), (what + " u").c_str());
    r.edgeV = vec3(q.at("v"), (what + " v").c_str());
    r.corner = vec3(q.at("centre"), (what + " centre").c_str()) - 0.5f * (r.edgeU + r.edgeV);
    if (!(length(cross(r.edgeU, r.edgeV)) > 1e-12f))
        throw Error("scene description: a " + what + " has zero area (u x v = 0)");
    return r;
}

/// The moving objects of the cornell-objects presets.
const std::string kCornellAnimations = R"("animations": [
                {"object": "short_block", "keys": [
                    {"frame": 0,  "translation": [0.0, 0.0, 0.0]},
                    {"frame": 15, "translation": [-0.6, 0.0, 0.0]},
                    {"frame": 30, "translation": [0.0, 0.0, 0.0]},
                    {"frame": 45, "translation": [-0.6, 0.0, 0.0]},
                    {"frame": 59, "translation": [0.0, 0.0, 0.0]}]},
                {"object": "sphere", "keys": [
                    {"frame": 0,  "translation": [0.74, 0.0, 0.58]},
                    {"frame": 4,  "translation": [0.74, -0.087, 0.58]},
                    {"frame": 8,  "translation": [0.74, -0.348, 0.58]},
                    {"frame": 11, "translation": [0.74, -0.659, 0.58]},
                    {"frame": 13.9, "translation": [0.74, -1.05, 0.58]},
                    {"frame": 17, "translation": [0.74, -0.594, 0.58]},
                    {"frame": 21, "translation": [0.74, -0.43, 0.58]},
                    {"frame": 25, "translation": [0.74, -0.38, 0.58]},
                    {"frame": 29, "translation": [0.74, -0.43, 0.58]},
                    {"frame": 33, "translation": [0.74, -0.594, 0.58]},
                    {"frame": 36, "translation": [0.74, -1.05, 0.58]},
                    {"frame": 40, "translation": [0.74, -0.72, 0.58]},
                    {"frame": 45, "translation": [0.74, -0.62, 0.58]},
                    {"frame": 50, "translation": [0.74, -0.72, 0.58]},
                    {"frame": 54, "translation": [0.74, -1.05, 0.58]},
                    {"frame": 59, "translation": [0.74, -1.05, 0.58]}]},
                {"object": "tall_block", "pivot": [-0.34, 0.0, -0.28], "keys": [
                    {"frame": 0, "rotation_deg": [0, 0, 0]},
                    {"frame": 30, "rotation_deg": [0, 60, 0]},
                    {"frame": 59, "rotation_deg": [0, 0, 0]}]}])";

/// Every Sponza preset: the file's roof left out (it keeps all sun and sky out of the atrium),
/// and the sun, the sky and the local lights sampled apart at each vertex.
const std::string kOpenAtrium = R"("hide_objects": ["Roof"], "light_sampling": "split",)";
/// The atrium's opening, where the hidden roof was: most sky samples aim at it, so the
/// walls and floor below find the sky through it instead of mostly hitting the galleries.
const std::string kAtriumPortal =
    R"("portals": [{"centre": [-1.45, 22.3, -0.9], "u": [26.2, 0, 0], "v": [0, 0, 6.8]}])";
/// The part of the atrium's floor that the sun lights (from the visibility buffer of a top-down
/// render): bounces aim most of their samples at it where it is in view.
const std::string kSunlitFloor =
    R"("bounce_guides": [{"centre": [2.0, 3.99, -1.34], "u": [21.6, 0, 0], "v": [0, 0, 5.0]}],)";
/// The sunlit Sponza presets' sky and sun: steep, along the atrium's long axis, from the end
/// the cameras look towards, so the floor before them is lit and the far end is in shadow.
const std::string kSunAndSky = kSunlitFloor + R"(
            "sun": {"direction": [-0.3, 1.0, 0.05], "angular_diameter_deg": 0.53, "irradiance": [30.0, 28.0, 25.0]},
            "sky": {"radiance": [3.0, 3.5, 4.5], )" +
                               kAtriumPortal + "},";

const std::map<std::string, std::string>& presets() {
    static const std::map<std::string, std::string> p = {
        {"cornell-moving", R"({
            "mesh": "builtin:cornell", "width": 640, "height": 480, "frames": 60, "reference_spp": 4096,
            "camera": {"keyframes": [
                {"frame": 0,  "position": [-0.45, 1.0, 0.95], "target": [0.1, 0.8, -1.0],  "fov_deg": 70},
                {"frame": 30, "position": [0.0, 1.2, 0.9],    "target": [0.0, 0.85, -1.0], "fov_deg": 70},
                {"frame": 59, "position": [0.45, 1.0, 0.95],  "target": [-0.1, 0.8, -1.0], "fov_deg": 70}]}})"},
        // Two small rooms for measuring quality (docs/rendering.md, "Presets"): the built-in
        // box at the paper's one bounce, seen through its open front by a panning camera, the
        // lamp out of view and in view.
        // Rendered in the original layout (no emission buffer) the second is the case of a
        // visible light that a filter must find by itself.
        {"room-dark", R"({
            "mesh": "builtin:cornell", "width": 256, "height": 192, "frames": 24, "reference_spp": 64,
            "camera": {"keyframes": [
                {"frame": 0,  "position": [-0.3, 0.9, 2.6], "target": [0.1, 0.5, 0.0],  "fov_deg": 42},
                {"frame": 23, "position": [0.3, 0.9, 2.6],  "target": [-0.1, 0.5, 0.0], "fov_deg": 42}]}})"},
        {"room-light", R"({
            "mesh": "builtin:cornell", "width": 256, "height": 192, "frames": 24, "reference_spp": 64,
            "camera": {"keyframes": [
                {"frame": 0,  "position": [-0.3, 1.0, 3.0], "target": [0.1, 1.1, 0.0],  "fov_deg": 45},
                {"frame": 23, "position": [0.3, 1.0, 3.0],  "target": [-0.1, 1.1, 0.0], "fov_deg": 45}]}})"},
        // Objects that move across a static camera's view and occlude each other, at the
        // speeds of a game at 30 frames a second: the short block slides to and fro in front
        // of the tall one (1.2 m/s), which turns (2 degrees a frame); a sphere falls in front
        // of the short block under gravity (up to 4.5 m/s) and bounces.
        {"cornell-objects", R"({
            "mesh": "builtin:cornell-objects", "width": 640, "height": 480, "frames": 60, "reference_spp": 4096,
            "camera": {"keyframes": [{"frame": 0, "position": [0.0, 1.0, 3.4], "target": [0.0, 1.0, 0.0], "fov_deg": 40}]},
            )" + kCornellAnimations +
                                "}"},
        // The same objects seen from a camera that moves as well.
        {"cornell-objects-moving", R"({
            "mesh": "builtin:cornell-objects", "width": 640, "height": 480, "frames": 60, "reference_spp": 4096,
            "camera": {"keyframes": [
                {"frame": 0,  "position": [-0.45, 1.0, 3.0],  "target": [0.1, 0.9, 0.0],  "fov_deg": 45},
                {"frame": 30, "position": [0.0, 1.2, 3.2],    "target": [0.0, 0.95, 0.0], "fov_deg": 45},
                {"frame": 59, "position": [0.45, 1.0, 3.0],   "target": [-0.1, 0.9, 0.0], "fov_deg": 45}]},
            )" + kCornellAnimations + "}"},
        // The Sponza presets trace two bounces where the paper traces one: in the arcades, out
        // of the sun and the sky, most light has bounced twice (at one bounce 31.8% of
        // sponza-static's 1-spp pixels are black, at two 28.4%; a path costs 1.6x).
        {"sponza-moving", R"({
            "mesh": "{scenes}/sponza/Sponza.gltf", "width": 1280, "height": 720, "frames": 60,
            "reference_spp": 4096, "bounces": 2,
            )" + kOpenAtrium + kSunAndSky +
                              R"(
            "camera": {"keyframes": [
                {"frame": 0,  "position": [12.5, 4.6, 0.4],  "target": [0.0, 5.5, -0.6], "fov_deg": 50},
                {"frame": 30, "position": [9.0, 5.0, -2.0],  "target": [-4.0, 6.0, 0.0], "fov_deg": 50},
                {"frame": 59, "position": [3.0, 5.2, -2.0],  "target": [-10.0, 6.5, 1.0], "fov_deg": 50}]}})"},
        {"sponza-static", R"({
            "mesh": "{scenes}/sponza/Sponza.gltf", "width": 1280, "height": 720, "frames": 60,
            "reference_spp": 4096, "bounces": 2,
            )" + kOpenAtrium + kSunAndSky +
                              R"(
            "camera": {"keyframes": [
                {"frame": 0, "position": [12.0, 4.8, -3.0], "target": [0.0, 6.0, 1.5], "fov_deg": 50}]}})"},
        {"sponza-light", R"({
            "mesh": "{scenes}/sponza/Sponza.gltf", "width": 1280, "height": 720, "frames": 60,
            "reference_spp": 4096, "bounces": 2,
            )" + kOpenAtrium +
                             R"(
            "sky": {"radiance": [0.04, 0.05, 0.07], )" +
                             kAtriumPortal + R"(},
            "lights": [{"type": "quad", "centre": [8.0, 9.0, 0.0], "u": [0.6, 0, 0], "v": [0, 0, 0.6],
                        "radiance": [120, 105, 85],
                        "path": [{"frame": 0, "centre": [10.0, 9.0, -1.0]}, {"frame": 59, "centre": [-8.0, 9.0, 1.0]}]}],
            "camera": {"keyframes": [
                {"frame": 0, "position": [14.0, 5.0, 0.0], "target": [0.0, 6.5, 0.0], "fov_deg": 55}]}})"},
        // Multi-bounce, unclamped: a steep sun along the atrium's long axis casts the columns'
        // hard shadows on the floor; four bounces carry its light into the colonnades.
        {"sponza-atrium", R"({
            "mesh": "{scenes}/sponza/Sponza.gltf", "width": 1280, "height": 720, "frames": 60,
            "reference_spp": 4096, "bounces": 4,
            )" + kOpenAtrium + kSunAndSky +
                              R"(
            "camera": {"keyframes": [
                {"frame": 0,  "position": [9.0, 5.5, -2.0], "target": [-10.0, 10.0, 1.5], "fov_deg": 60},
                {"frame": 59, "position": [3.0, 5.5, -2.0], "target": [-16.0, 10.0, 1.0], "fov_deg": 60}]}})"},
        {"sponza-glossy", R"({
            "mesh": "{scenes}/sponza/Sponza.gltf", "width": 1280, "height": 720, "frames": 60,
            "reference_spp": 4096, "bounces": 2, "roughness_override": 0.1,
            )" + kOpenAtrium + kSunAndSky +
                              R"(
            "camera": {"keyframes": [
                {"frame": 0,  "position": [12.5, 4.6, 0.4],  "target": [0.0, 5.5, -0.6], "fov_deg": 50},
                {"frame": 59, "position": [3.0, 5.2, -2.0],  "target": [-10.0, 6.5, 1.0], "fov_deg": 50}]}})"},
    };
    return p;
}

} // namespace

std::vector<std::string> presetNames() {
    std::vector<std::string> names;
    for (const auto& [k, v] : presets()) names.push_back(k);
    return names;
}

double estimatedRenderSeconds(const SceneDescription& d) {
    const bool builtin = d.mesh.rfind("builtin:", 0) == 0;
    // Per sample at one bounce, on 2 cores: the built-in box, and Sponza's open atrium. An
    // input sample's rate holds writing the frame's buffers.
    const double input = builtin ? 2.7e-6 : 3.1e-6, reference = builtin ? 0.37e-6 : 0.86e-6;
    // A path's cost grows by 0.6 of a one-bounce path per bounce (measured on both scenes at 1
    // to 4 bounces): the camera ray and the first light samples are paid once.
    const double bounces = 0.4 + 0.6 * std::max(1, d.bounces);
    // Factored paths: two paths per sample, and the light samples of the input's direct light.
    const double paths = d.factoredDirectSpp > 0 ? 2.0 : 1.0;
    const double lightSamples = d.factoredDirectSpp > 0 ? 0.1 * d.factoredDirectSpp : 0.0;
    return double(d.width) * d.height * d.frames * bounces *
           (input * (paths + lightSamples) + reference * paths * double(d.referenceSpp));
}

SceneDescription parseSceneDescription(const json& j, const std::string& baseDir) {
    SceneDescription d;
    const std::string where = "scene description";
    try {
        requireKnownKeys(j,
                         {"mesh",
                          "width",
                          "height",
                          "frames",
                          "reference_spp",
                          "bounces",
                          "seed",
                          "jitter",
                          "roughness_override",
                          "sky",
                          "sun",
                          "lights",
                          "camera",
                          "diffuse_indirect_only",
                          "animations",
                          "gltf_animation",
                          "paths",
                          "direct_spp",
                          "hide_objects",
                          "light_sampling",
                          "bounce_guides"},
                         where);
        d.mesh = j.at("mesh").get<std::string>();
        if (d.mesh.rfind("builtin:", 0) != 0 && fs::path(d.mesh).is_relative())
            d.mesh = (fs::path(baseDir) / d.mesh).lexically_normal().string();
        d.roughnessOverride = float(numberField(j, "roughness_override", -1, 1, -1, where));
        d.width = int(integerField(j, "width", 1, kMaxSceneSide, d.width, where));
        d.height = int(integerField(j, "height", 1, kMaxSceneSide, d.height, where));
        d.frames = int(integerField(j, "frames", 1, kMaxSceneFrames, d.frames, where));
        d.referenceSpp = int(integerField(j, "reference_spp", 0, 1 << 20, d.referenceSpp, where));
        d.bounces = int(integerField(j, "bounces", 0, 64, d.bounces, where));
        d.seed = uint32_t(integerField(j, "seed", 0, 4294967295LL, d.seed, where));
        d.jitter = j.value("jitter", d.jitter);
        d.diffuseIndirectOnly = j.value("diffuse_indirect_only", d.diffuseIndirectOnly);
        const json hidden = j.value("hide_objects", json::array());
        for (const json& o : hidden) {
            if (!hidden.is_array() || !o.is_string())
                throw Error(where + ": \"hide_objects\" must be a list of object names");
            d.hiddenObjects.push_back(o.get<std::string>());
        }
        const std::string paths = j.value("paths", std::string("bmfr"));
        if (paths != "bmfr" && paths != "mara")
            throw Error(where + ": \"paths\" is '" + paths + "', expected bmfr or mara");
        const int directSpp = int(integerField(j, "direct_spp", 1, 4096, 16, where));
        if (j.contains("direct_spp") && paths != "mara")
            throw Error(where + ": \"direct_spp\" needs \"paths\": \"mara\"");
        d.factoredDirectSpp = paths == "mara" ? directSpp : 0;
        const std::string sampling = j.value("light_sampling", std::string("one"));
        if (sampling != "one" && sampling != "split")
            throw Error(where + ": \"light_sampling\" is '" + sampling +
                        "', expected one or split");
        d.lightSampling = sampling == "split" ? LightSampling::Split : LightSampling::One;
        if (d.lightSampling == LightSampling::Split && paths == "mara")
            throw Error(where + ": \"light_sampling\": \"split\" is for the paper's paths; "
                                "\"paths\": \"mara\" takes \"direct_spp\" light samples instead");
        if (j.contains("sky")) {
            requireKnownKeys(j["sky"], {"radiance", "portals"}, "scene description 'sky'");
            d.environment.sky = vec3(j["sky"].at("radiance"), "sky.radiance");
            for (const json& q : j["sky"].value("portals", json::array()))
                d.environment.portals.push_back(parallelogram(q, "sky portal"));
        }
        for (const json& q : j.value("bounce_guides", json::array()))
            d.environment.bounceGuides.push_back(parallelogram(q, "bounce guide"));
        if (j.contains("sun")) {
            const json& s = j["sun"];
            requireKnownKeys(s, {"direction", "angular_diameter_deg", "irradiance"},
                             "scene description 'sun'");
            const Vec3 direction = vec3(s.at("direction"), "sun.direction");
            if (!(length(direction) > 1e-6f))
                throw Error("scene description: sun.direction must not be zero");
            d.environment.sun.direction = normalize(direction);
            d.environment.sun.angularDiameter =
                float(numberField(s, "angular_diameter_deg", 1e-6, 90, 0.53,
                                  "scene description "
                                  "'sun'")) *
                3.14159265f / 180.0f;
            d.environment.sun.irradiance = vec3(s.at("irradiance"), "sun.irradiance");
        }
        for (const json& l : j.value("lights", json::array())) {
            requireKnownKeys(l, {"type", "centre", "u", "v", "radiance", "path"},
                             "scene description light");
            if (l.value("type", "") != "quad")
                throw Error("scene description: light type must be \"quad\"");
            QuadLightSpec q;
            q.centre = vec3(l.at("centre"), "light centre");
            q.edgeU = vec3(l.at("u"), "light u");
            q.edgeV = vec3(l.at("v"), "light v");
            q.radiance = vec3(l.at("radiance"), "light radiance");
            if (!(length(cross(q.edgeU, q.edgeV)) > 1e-12f))
                throw Error("scene description: a quad light has zero area (u x v = 0)");
            if (std::fabs(dot(q.edgeU, q.edgeV)) > 1e-4f * length(q.edgeU) * length(q.edgeV))
                throw Error("scene description: quad light edges u and v must be perpendicular");
            for (const json& k : l.value("path", json::array())) {
                requireKnownKeys(k, {"frame", "centre"}, "scene description light path");
                q.path.emplace_back(float(numberField(k, "frame", -1e9, 1e9, 0, "light path")),
                                    vec3(k.at("centre"), "light path centre"));
            }
            std::sort(q.path.begin(), q.path.end(),
                      [](auto& a, auto& b) { return a.first < b.first; });
            d.quadLights.push_back(q);
        }
        for (const json& a : j.value("animations", json::array())) {
            requireKnownKeys(a, {"object", "pivot", "keys"}, "scene description animation");
            ObjectAnimation anim;
            anim.object = a.at("object").get<std::string>();
            const std::string what = "scene description animation of '" + anim.object + "'";
            if (a.contains("pivot")) anim.pivot = vec3(a["pivot"], "animation pivot");
            for (const json& k : a.at("keys")) {
                requireKnownKeys(k, {"frame", "translation", "rotation_deg", "scale"}, what);
                RigidKey key;
                key.frame = float(numberField(k, "frame", -1e9, 1e9, 0, what));
                if (k.contains("translation"))
                    key.translation = vec3(k["translation"], "animation translation");
                if (k.contains("rotation_deg"))
                    key.rotation = quatFromEulerDegrees(vec3(k["rotation_deg"], "rotation_deg"));
                if (k.contains("scale"))
                    key.scale = k["scale"].is_number()
                                    ? Vec3{1, 1, 1} * floatValue(k["scale"], "animation scale")
                                    : vec3(k["scale"], "animation scale");
                for (float c : {key.scale.x, key.scale.y, key.scale.z})
                    if (!(c > 0.0f && c <= 1000.0f))
                        throw Error(what + ": scale must be in (0, 1000]");
                for (float c : {key.translation.x, key.translation.y, key.translation.z})
                    if (!std::isfinite(c)) throw Error(what + ": translation is not finite");
                anim.keys.push_back(key);
            }
            if (anim.keys.empty()) throw Error(what + ": \"keys\" is empty");
            std::sort(anim.keys.begin(), anim.keys.end(),
                      [](const RigidKey& x, const RigidKey& y) { return x.frame < y.frame; });
            for (size_t i = 1; i < anim.keys.size(); ++i)
                if (anim.keys[i].frame == anim.keys[i - 1].frame)
                    throw Error(what + ": two keys at frame " + std::to_string(anim.keys[i].frame));
            d.animations.push_back(anim);
        }
        if (j.contains("gltf_animation")) {
            requireKnownKeys(j["gltf_animation"], {"fps"}, "scene description 'gltf_animation'");
            d.gltfAnimationFps =
                float(numberField(j["gltf_animation"], "fps", 1e-3, 1000, 30, "gltf_animation"));
        }
        const json& cam = j.at("camera");
        requireKnownKeys(cam, {"keyframes", "gltf_camera"}, "scene description 'camera'");
        if (cam.contains("gltf_camera")) {
            d.gltfCamera = cam["gltf_camera"].get<std::string>();
        } else {
            for (const json& k : cam.at("keyframes")) {
                requireKnownKeys(k, {"frame", "position", "target", "up", "fov_deg"},
                                 "scene description camera keyframe");
                CameraKey key;
                key.frame = float(numberField(k, "frame", -1e9, 1e9, 0, "camera keyframe"));
                key.pose.position = vec3(k.at("position"), "camera position");
                key.pose.target = vec3(k.at("target"), "camera target");
                if (k.contains("up")) key.pose.up = vec3(k["up"], "camera up");
                key.pose.fovY = float(numberField(k, "fov_deg", 0.01, 179, 45, "camera keyframe")) *
                                3.14159265f / 180.0f;
                const std::string problem = cameraPoseProblem(key.pose);
                if (!problem.empty())
                    throw Error("scene description: the camera keyframe at frame " +
                                std::to_string(key.frame) + " " + problem);
                d.cameraKeys.push_back(key);
            }
            if (d.cameraKeys.empty()) throw Error("scene description: camera.keyframes is empty");
        }
    } catch (const json::exception& e) {
        throw Error("scene description: " + jsonProblem(e));
    }
    validate(d);
    return d;
}

void validate(const SceneDescription& d) {
    if (d.width < 1 || d.height < 1 || d.width > kMaxSceneSide || d.height > kMaxSceneSide)
        throw Error("scene description: resolution " + std::to_string(d.width) + "x" +
                    std::to_string(d.height) + " outside [1, " + std::to_string(kMaxSceneSide) +
                    "]");
    if (d.frames < 1 || d.frames > kMaxSceneFrames)
        throw Error("scene description: frames " + std::to_string(d.frames) + " outside [1, " +
                    std::to_string(kMaxSceneFrames) + "]");
    if (d.referenceSpp < 0) throw Error("scene description: reference_spp must be >= 0");
    if (d.bounces < 0 || d.bounces > 64)
        throw Error("scene description: bounces must be in [0, 64]");
}

std::string cameraPoseProblem(const CameraPose& p) {
    // In double: a float's squared length overflows from about 1.8e19 units.
    const double dx = double(p.target.x) - p.position.x, dy = double(p.target.y) - p.position.y,
                 dz = double(p.target.z) - p.position.z;
    const double distance = std::sqrt(dx * dx + dy * dy + dz * dz);
    if (!std::isfinite(distance)) return "has a position or target that is not finite";
    if (!(distance > 1e-6)) return "has its position equal to its target";
    if (distance > kMaxCameraDistance)
        return fmt::format("is {:g} units from its target, more than the {:g} that float maths "
                           "can take",
                           distance, kMaxCameraDistance);
    const Vec3 forward = p.target - p.position;
    if (!(length(cross(normalize(forward), normalize(p.up))) > 1e-4f))
        return "looks along its up vector (give a different \"up\")";
    if (!(p.fovY > 0.0f && p.fovY < 3.13f)) return "has a field of view outside (0, 179) degrees";
    return {};
}

SceneDescription loadSceneDescription(const std::string& presetOrFile, const std::string& scenesDir,
                                      bool checkMesh) {
    if (auto it = presets().find(presetOrFile); it != presets().end()) {
        std::string text = it->second;
        for (size_t at; (at = text.find("{scenes}")) != std::string::npos;)
            text.replace(at, 8, scenesDir);
        SceneDescription d = parseSceneDescription(json::parse(text), ".");
        d.name = presetOrFile;
        if (checkMesh && d.mesh.rfind("builtin:", 0) != 0 && !fs::exists(d.mesh))
            throw Error("preset '" + presetOrFile + "' needs " + d.mesh +
                        ", which is not there: give the folder holding sponza/ with --scenes DIR" +
                        (fs::path(scenesDir).is_relative()
                             ? " (the relative '" + scenesDir + "' is read from " +
                                   fs::current_path().string() + ")"
                             : std::string()));
        return d;
    }
    if (!fs::exists(presetOrFile)) {
        std::string list;
        for (const std::string& n : presetNames()) list += " " + n;
        throw Error("'" + presetOrFile +
                    "' is neither a scene description file nor a preset (presets:" + list + ")");
    }
    std::ifstream in(presetOrFile);
    json j;
    try {
        j = json::parse(in);
    } catch (const json::exception& e) {
        throw Error(presetOrFile + ": " + jsonProblem(e));
    }
    SceneDescription d = parseSceneDescription(j, fs::path(presetOrFile).parent_path().string());
    d.name = fs::path(presetOrFile).stem().string();
    return d;
}

} // namespace bmfr::render
