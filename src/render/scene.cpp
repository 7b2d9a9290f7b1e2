#include "render/scene.h"
#include <bmfr/error.h>
#include <cmath>
#include <filesystem>

namespace bmfr::render {

void Scene::beginObject(const std::string& name) {
    objectNames.push_back(name);
    objectNode.push_back(-1);
}

void Scene::addTriangle(Vec3 a, Vec3 b, Vec3 c, int material) {
    if (objectNames.empty()) beginObject("scene");
    triangleObject.push_back(int(objectNames.size() - 1));
    Vec3 n = cross(b - a, c - a);
    float len = length(n);
    n = len > 0 ? n / len : Vec3{0, 1, 0};
    positions.insert(positions.end(), {a, b, c});
    normals.insert(normals.end(), {n, n, n});
    uvs.insert(uvs.end(), {Vec2f{0, 0}, Vec2f{1, 0}, Vec2f{0, 1}});
    triangleMaterial.push_back(material);
}

void Scene::removeObjects(const std::vector<std::string>& names) {
    std::vector<char> drop(objectNames.size(), 0);
    for (const std::string& name : names) {
        bool found = false;
        for (size_t o = 0; o < objectNames.size(); ++o)
            if (objectNames[o] == name) drop[o] = 1, found = true;
        if (!found) {
            std::string list;
            for (const std::string& n : objectNames) list += (list.empty() ? "" : ", ") + n;
            throw Error("scene description: hide_objects names '" + name +
                        "', but the scene has no such object (objects: " + list + ")");
        }
    }
    size_t kept = 0;
    for (size_t t = 0; t < triangleCount(); ++t) {
        if (drop[size_t(triangleObject[t])]) continue;
        for (size_t k = 0; k < 3; ++k) {
            positions[3 * kept + k] = positions[3 * t + k];
            normals[3 * kept + k] = normals[3 * t + k];
            uvs[3 * kept + k] = uvs[3 * t + k];
        }
        triangleMaterial[kept] = triangleMaterial[t];
        triangleObject[kept] = triangleObject[t];
        ++kept;
    }
    positions.resize(3 * kept), normals.resize(3 * kept), uvs.resize(3 * kept);
    triangleMaterial.resize(kept), triangleObject.resize(kept);
}

void Scene::bounds(Vec3& lo, Vec3& hi) const {
    lo = {INFINITY, INFINITY, INFINITY};
    hi = -1.0f * lo;
    for (Vec3 p : positions) lo = vmin(lo, p), hi = vmax(hi, p);
}

namespace {

void addQuad(Scene& s, Vec3 a, Vec3 b, Vec3 c, Vec3 d, int m) {
    s.addTriangle(a, b, c, m);
    s.addTriangle(a, c, d, m);
}

/// Axis-aligned box of half-size `h` rotated by `angle` around y, standing on y = 0.
void addBlock(Scene& s, Vec3 centre, Vec3 h, float angle, int m) {
    float c = std::cos(angle), sn = std::sin(angle);
    auto at = [&](float x, float y, float z) {
        return Vec3{centre.x + c * x * h.x + sn * z * h.z, y * h.y * 2,
                    centre.z - sn * x * h.x + c * z * h.z};
    };
    Vec3 p[8];
    for (int i = 0; i < 8; ++i)
        p[i] = at(i & 1 ? 1.f : -1.f, i & 2 ? 1.f : 0.f, i & 4 ? 1.f : -1.f);
    addQuad(s, p[2], p[6], p[7], p[3], m); // top
    addQuad(s, p[0], p[1], p[5], p[4], m); // bottom
    addQuad(s, p[0], p[2], p[3], p[1], m); // -z
    addQuad(s, p[4], p[5], p[7], p[6], m); // +z
    addQuad(s, p[0], p[4], p[6], p[2], m); // -x
    addQuad(s, p[1], p[3], p[7], p[5], m); // +x
}

} // namespace

Scene builtinCornellBox() {
    Scene s;
    auto mat = [&](const char* name, Vec3 albedo, Vec3 emission = {}) {
        Material m;
        m.name = name;
        m.baseColor = albedo;
        m.roughness = 1.0f;
        m.specular = 0.0f;
        m.emission = emission;
        s.materials.push_back(m);
        return int(s.materials.size() - 1);
    };
    int white = mat("white", {0.725f, 0.71f, 0.68f}), red = mat("red", {0.63f, 0.065f, 0.05f}),
        green = mat("green", {0.14f, 0.45f, 0.091f}),
        light = mat("light", {0.78f, 0.78f, 0.78f}, {17, 12, 4});
    s.beginObject("room");
    addQuad(s, {-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}, white);   // floor
    addQuad(s, {-1, 2, -1}, {1, 2, -1}, {1, 2, 1}, {-1, 2, 1}, white);   // ceiling
    addQuad(s, {-1, 0, -1}, {1, 0, -1}, {1, 2, -1}, {-1, 2, -1}, white); // back
    addQuad(s, {-1, 0, -1}, {-1, 2, -1}, {-1, 2, 1}, {-1, 0, 1}, red);   // left
    addQuad(s, {1, 0, -1}, {1, 0, 1}, {1, 2, 1}, {1, 2, -1}, green);     // right
    s.beginObject("light");
    addQuad(s, {-0.24f, 1.98f, -0.22f}, {0.23f, 1.98f, -0.22f}, {0.23f, 1.98f, 0.16f},
            {-0.24f, 1.98f, 0.16f}, light);
    s.beginObject("short_block");
    addBlock(s, {0.33f, 0, 0.37f}, {0.3f, 0.3f, 0.3f}, -0.29f, white);
    s.beginObject("tall_block");
    addBlock(s, {-0.34f, 0, -0.28f}, {0.3f, 0.6f, 0.3f}, 0.31f, white);
    NamedCamera cam;
    cam.name = "front";
    cam.position = {0, 1, 3.4f}, cam.forward = {0, 0, -1}, cam.up = {0, 1, 0}, cam.fovY = 0.69f;
    s.cameras.push_back(cam);
    return s;
}

Scene builtinCornellObjects() {
    Scene s = builtinCornellBox();
    Material m;
    m.name = "sphere";
    m.baseColor = {1, 1, 1};
    m.roughness = 1.0f;
    m.specular = 0.0f;
    // Checkered, so that history taken from the wrong place shows.
    Texture checker;
    checker.makeChecker(12, 6, {0.75f, 0.75f, 0.72f}, {0.12f, 0.25f, 0.65f});
    s.textures.push_back(std::move(checker));
    m.baseColorTexture = int(s.textures.size() - 1);
    s.materials.push_back(m);
    const int material = int(s.materials.size() - 1);
    s.beginObject("sphere");
    // A UV sphere with smooth normals: 24 rings of 48 segments.
    const Vec3 c{0.0f, 1.3f, 0.2f};
    const float r = 0.25f, pi = 3.14159265f;
    const int rings = 24, segments = 48;
    auto at = [&](int i, int j) {
        const float theta = pi * float(i) / float(rings), phi = 2 * pi * float(j) / float(segments);
        return Vec3{std::sin(theta) * std::cos(phi), std::cos(theta),
                    std::sin(theta) * std::sin(phi)};
    };
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            const Vec3 d[4] = {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)};
            const Vec2f uv[4] = {{float(j) / float(segments), float(i) / float(rings)},
                                 {float(j) / float(segments), float(i + 1) / float(rings)},
                                 {float(j + 1) / float(segments), float(i + 1) / float(rings)},
                                 {float(j + 1) / float(segments), float(i) / float(rings)}};
            for (int t = 0; t < 2; ++t) {
                const int k[3] = {0, t == 0 ? 2 : 3, t == 0 ? 1 : 2};
                if ((i == 0 && t == 1) || (i == rings - 1 && t == 0)) continue; // at a pole
                s.addTriangle(c + r * d[k[0]], c + r * d[k[1]], c + r * d[k[2]], material);
                for (int v = 0; v < 3; ++v) {
                    s.normals[s.normals.size() - 3 + size_t(v)] = d[k[v]];
                    s.uvs[s.uvs.size() - 3 + size_t(v)] = uv[k[v]];
                }
            }
        }
    return s;
}

Scene loadScene(const std::string& path) {
    if (path == "builtin:cornell") return builtinCornellBox();
    if (path == "builtin:cornell-objects") return builtinCornellObjects();
    if (!std::filesystem::exists(path)) throw Error("scene file not found: " + path);
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = char(std::tolower((unsigned char)c));
    if (ext == ".gltf" || ext == ".glb") return loadGltf(path);
    if (ext == ".obj") return loadObj(path);
    throw Error("unsupported scene format '" + ext + "' (" + path + "): use .gltf, .glb or .obj");
}

} // namespace bmfr::render
