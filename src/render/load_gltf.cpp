// glTF 2.0 loader (tinygltf): meshes with node transforms, metal/rough materials, cameras.
#include "core/mat4.h"
#include "render/scene.h"
#include <bmfr/error.h>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <optional>
#include <tiny_gltf.h>

namespace bmfr::render {

namespace {

using Mat = std::array<double, 16>; // column-major, as glTF

Mat identity() {
    return {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
}

Mat mul(const Mat& a, const Mat& b) {
    Mat r{};
    for (int c = 0; c < 4; ++c)
        for (int rr = 0; rr < 4; ++rr)
            for (int k = 0; k < 4; ++k) r[c * 4 + rr] += a[k * 4 + rr] * b[c * 4 + k];
    return r;
}

Mat nodeMatrix(const tinygltf::Node& n) {
    if (n.matrix.size() == 16) {
        Mat m;
        for (int i = 0; i < 16; ++i) m[i] = n.matrix[i];
        return m;
    }
    Mat t = identity(), r = identity(), s = identity();
    if (n.translation.size() == 3)
        t[12] = n.translation[0], t[13] = n.translation[1], t[14] = n.translation[2];
    if (n.rotation.size() == 4) {
        double x = n.rotation[0], y = n.rotation[1], z = n.rotation[2], w = n.rotation[3];
        r = {1 - 2 * (y * y + z * z),
             2 * (x * y + z * w),
             2 * (x * z - y * w),
             0,
             2 * (x * y - z * w),
             1 - 2 * (x * x + z * z),
             2 * (y * z + x * w),
             0,
             2 * (x * z + y * w),
             2 * (y * z - x * w),
             1 - 2 * (x * x + y * y),
             0,
             0,
             0,
             0,
             1};
    }
    if (n.scale.size() == 3) s[0] = n.scale[0], s[5] = n.scale[1], s[10] = n.scale[2];
    return mul(t, mul(r, s));
}

Vec3 point(const Mat& m, Vec3 p) {
    return {float(m[0] * p.x + m[4] * p.y + m[8] * p.z + m[12]),
            float(m[1] * p.x + m[5] * p.y + m[9] * p.z + m[13]),
            float(m[2] * p.x + m[6] * p.y + m[10] * p.z + m[14])};
}
Vec3 direction(const Mat& m, Vec3 d) {
    return {float(m[0] * d.x + m[4] * d.y + m[8] * d.z),
            float(m[1] * d.x + m[5] * d.y + m[9] * d.z),
            float(m[2] * d.x + m[6] * d.y + m[10] * d.z)};
}

/// Reads accessor element i as up to 4 floats (float or normalized integer components).
struct AccessorReader {
    const unsigned char* data = nullptr;
    size_t stride = 0;
    int componentType = 0, components = 0;
    bool normalized = false;
    size_t count = 0;

    AccessorReader(const tinygltf::Model& m, int index, const std::string& what) {
        if (index < 0 || size_t(index) >= m.accessors.size())
            throw Error("glTF: bad accessor for " + what);
        const tinygltf::Accessor& a = m.accessors[size_t(index)];
        if (a.sparse.isSparse)
            throw Error("unsupported glTF feature: sparse accessor (" + what + ")");
        if (a.bufferView < 0) throw Error("glTF: accessor without bufferView (" + what + ")");
        const tinygltf::BufferView& v = m.bufferViews[size_t(a.bufferView)];
        const tinygltf::Buffer& b = m.buffers[size_t(v.buffer)];
        data = b.data.data() + v.byteOffset + a.byteOffset;
        componentType = a.componentType;
        components = tinygltf::GetNumComponentsInType(uint32_t(a.type));
        const int size = tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType));
        stride = v.byteStride ? v.byteStride : size_t(size * components);
        normalized = a.normalized;
        count = a.count;
        if (v.byteOffset + a.byteOffset +
                (count ? (count - 1) * stride + size_t(size * components) : 0) >
            b.data.size())
            throw Error("glTF: accessor for " + what + " runs past its buffer");
    }
    float component(size_t i, int c) const {
        const unsigned char* p = data + i * stride;
        switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: {
            float f;
            std::memcpy(&f, p + 4 * c, 4);
            return f;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return normalized ? p[c] / 255.0f : p[c];
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            uint16_t v;
            std::memcpy(&v, p + 2 * c, 2);
            return normalized ? v / 65535.0f : v;
        }
        default:
            throw Error("unsupported glTF feature: component type " +
                        std::to_string(componentType));
        }
    }
    uint32_t index(size_t i) const {
        const unsigned char* p = data + i * stride;
        switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return p[0];
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            uint16_t v;
            std::memcpy(&v, p, 2);
            return v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
            uint32_t v;
            std::memcpy(&v, p, 4);
            return v;
        }
        default:
            throw Error("glTF: bad index component type");
        }
    }
};

// Images are decoded by our Texture class (so a missing file is a warning, not a failure).
bool skipImage(tinygltf::Image*, const int, std::string*, std::string*, int, int,
               const unsigned char*, int, void*) {
    return true;
}

struct Loader {
    const tinygltf::Model& model;
    std::string dir;
    Scene scene;
    std::map<std::pair<int, bool>, int> textureCache;

    int texture(int gltfTexture, bool srgb) {
        if (gltfTexture < 0 || size_t(gltfTexture) >= model.textures.size()) return -1;
        int source = model.textures[size_t(gltfTexture)].source;
        if (source < 0) return -1;
        auto key = std::make_pair(source, srgb);
        if (auto it = textureCache.find(key); it != textureCache.end()) return it->second;
        const tinygltf::Image& img = model.images[size_t(source)];
        Texture t;
        std::string error, file = (std::filesystem::path(dir) / img.uri).string();
        int result = -1;
        if (img.uri.empty()) {
            scene.warnings.push_back("texture '" + img.name +
                                     "' is embedded (not supported): flat colour used");
        } else if (!t.load(file, srgb, error)) {
            scene.warnings.push_back("missing texture " + file + " (" + error +
                                     "): flat colour used");
        } else {
            scene.textures.push_back(std::move(t));
            result = int(scene.textures.size() - 1);
        }
        textureCache[key] = result;
        return result;
    }

    void materials() {
        for (const tinygltf::Material& gm : model.materials) {
            Material m;
            m.name = gm.name;
            const auto& pbr = gm.pbrMetallicRoughness;
            if (pbr.baseColorFactor.size() >= 3)
                m.baseColor = {float(pbr.baseColorFactor[0]), float(pbr.baseColorFactor[1]),
                               float(pbr.baseColorFactor[2])};
            m.baseColorTexture = texture(pbr.baseColorTexture.index, true);
            m.roughness = float(pbr.roughnessFactor);
            m.metallic = float(pbr.metallicFactor);
            m.normalTexture = texture(gm.normalTexture.index, false);
            m.normalScale = float(gm.normalTexture.scale);
            m.alphaMask = gm.alphaMode == "MASK";
            m.alphaCutoff = float(gm.alphaCutoff);
            if (gm.alphaMode == "BLEND")
                scene.warnings.push_back("material '" + gm.name +
                                         "': alphaMode BLEND rendered as MASK");
            m.alphaMask = m.alphaMask || gm.alphaMode == "BLEND";
            if (gm.emissiveFactor.size() == 3)
                m.emission = {float(gm.emissiveFactor[0]), float(gm.emissiveFactor[1]),
                              float(gm.emissiveFactor[2])};
            scene.materials.push_back(m);
        }
        Material fallback;
        fallback.name = "default";
        scene.materials.push_back(fallback);
    }

    void mesh(const tinygltf::Mesh& mesh, const Mat& m) {
        // Normals transform with the inverse transpose; for the similarity transforms in
        // practice the cofactor matrix (the same up to scale) is enough.
        Mat n = m;
        auto cof = [&](int r, int c) {
            int r0 = (r + 1) % 3, r1 = (r + 2) % 3, c0 = (c + 1) % 3, c1 = (c + 2) % 3;
            return m[c0 * 4 + r0] * m[c1 * 4 + r1] - m[c1 * 4 + r0] * m[c0 * 4 + r1];
        };
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) n[c * 4 + r] = cof(r, c);
        for (const tinygltf::Primitive& p : mesh.primitives) {
            if (p.mode != TINYGLTF_MODE_TRIANGLES && p.mode != -1) {
                scene.warnings.push_back("mesh '" + mesh.name + "': primitive mode " +
                                         std::to_string(p.mode) + " is not triangles, skipped");
                continue;
            }
            auto pos = p.attributes.find("POSITION");
            if (pos == p.attributes.end())
                throw Error("glTF: mesh '" + mesh.name + "' has no POSITION");
            AccessorReader P(model, pos->second, "POSITION");
            std::optional<AccessorReader> N, T;
            if (auto it = p.attributes.find("NORMAL"); it != p.attributes.end())
                N.emplace(model, it->second, "NORMAL");
            if (auto it = p.attributes.find("TEXCOORD_0"); it != p.attributes.end())
                T.emplace(model, it->second, "TEXCOORD_0");
            std::optional<AccessorReader> I;
            if (p.indices >= 0) I.emplace(model, p.indices, "indices");
            const size_t count = I ? I->count : P.count;
            const int material = p.material >= 0 ? p.material : int(scene.materials.size() - 1);
            for (size_t k = 0; k + 2 < count; k += 3) {
                Vec3 v[3], nn[3];
                Vec2f uv[3];
                for (int j = 0; j < 3; ++j) {
                    size_t idx = I ? I->index(k + size_t(j)) : k + size_t(j);
                    if (idx >= P.count)
                        throw Error("glTF: index out of range in mesh '" + mesh.name + "'");
                    v[j] =
                        point(m, {P.component(idx, 0), P.component(idx, 1), P.component(idx, 2)});
                    if (N)
                        nn[j] = normalize(direction(
                            n, {N->component(idx, 0), N->component(idx, 1), N->component(idx, 2)}));
                    if (T) uv[j] = {T->component(idx, 0), T->component(idx, 1)};
                }
                scene.addTriangle(v[0], v[1], v[2], material);
                const size_t base = scene.positions.size() - 3;
                for (int j = 0; j < 3; ++j) {
                    if (N && std::isfinite(nn[j].x)) scene.normals[base + size_t(j)] = nn[j];
                    scene.uvs[base + size_t(j)] = T ? uv[j] : Vec2f{};
                }
            }
        }
    }

    /// The hierarchy (parents, rest transforms) and every animation's channels, so that a
    /// scene description can play them.
    void hierarchy() {
        scene.nodes.resize(model.nodes.size());
        for (size_t i = 0; i < model.nodes.size(); ++i) {
            const tinygltf::Node& nd = model.nodes[i];
            SceneNode& n = scene.nodes[i];
            for (int child : nd.children)
                if (child >= 0 && size_t(child) < scene.nodes.size())
                    scene.nodes[size_t(child)].parent = int(i);
            n.hasMatrix = nd.matrix.size() == 16;
            for (size_t k = 0; k < 16 && n.hasMatrix; ++k) n.matrix[k] = float(nd.matrix[k]);
            if (nd.translation.size() == 3)
                n.translation = {float(nd.translation[0]), float(nd.translation[1]),
                                 float(nd.translation[2])};
            if (nd.rotation.size() == 4)
                n.rotation = {float(nd.rotation[0]), float(nd.rotation[1]), float(nd.rotation[2]),
                              float(nd.rotation[3])};
            if (nd.scale.size() == 3)
                n.scale = {float(nd.scale[0]), float(nd.scale[1]), float(nd.scale[2])};
        }
        for (const tinygltf::Animation& a : model.animations)
            for (const tinygltf::AnimationChannel& c : a.channels) {
                const std::string what = "animation '" + a.name + "'";
                if (c.sampler < 0 || size_t(c.sampler) >= a.samplers.size() || c.target_node < 0 ||
                    size_t(c.target_node) >= model.nodes.size())
                    throw Error("glTF: " + what + " has a channel without a sampler or node");
                NodeChannel ch;
                ch.node = c.target_node;
                if (c.target_path == "translation")
                    ch.path = NodeChannel::Path::Translation;
                else if (c.target_path == "rotation")
                    ch.path = NodeChannel::Path::Rotation;
                else if (c.target_path == "scale")
                    ch.path = NodeChannel::Path::Scale;
                else {
                    scene.warnings.push_back(what + ": " + c.target_path +
                                             " channels are not played");
                    continue;
                }
                if (scene.nodes[size_t(ch.node)].hasMatrix) {
                    scene.warnings.push_back(what + ": a channel targets a node placed by a "
                                                    "matrix (not allowed by glTF), ignored");
                    continue;
                }
                const tinygltf::AnimationSampler& sm = a.samplers[size_t(c.sampler)];
                ch.step = sm.interpolation == "STEP";
                const bool cubic = sm.interpolation == "CUBICSPLINE";
                if (cubic)
                    scene.warnings.push_back(what + ": CUBICSPLINE played as LINEAR through "
                                                    "its keys");
                AccessorReader in(model, sm.input, what + " times");
                AccessorReader out(model, sm.output, what + " values");
                const int width = ch.path == NodeChannel::Path::Rotation ? 4 : 3;
                const size_t perKey = cubic ? 3 : 1; // in-tangent, value, out-tangent
                if (out.components != width || out.count != in.count * perKey || in.count == 0)
                    throw Error("glTF: " + what + " has " + std::to_string(out.count) +
                                " values of " + std::to_string(out.components) + " for " +
                                std::to_string(in.count) + " times");
                for (size_t k = 0; k < in.count; ++k) {
                    ch.times.push_back(in.component(k, 0));
                    if (k && !(ch.times[k] > ch.times[k - 1]))
                        throw Error("glTF: " + what + ": key times must increase");
                    for (int v = 0; v < width; ++v)
                        ch.values.push_back(out.component(k * perKey + (cubic ? 1 : 0), v));
                }
                scene.nodeChannels.push_back(std::move(ch));
            }
    }

    void node(int index, const Mat& parent) {
        const tinygltf::Node& nd = model.nodes[size_t(index)];
        Mat m = mul(parent, nodeMatrix(nd));
        if (nd.mesh >= 0) {
            scene.beginObject(nd.name.empty() ? "node" + std::to_string(index) : nd.name);
            scene.objectNode.back() = index;
            mesh(model.meshes[size_t(nd.mesh)], m);
        }
        if (nd.skin >= 0)
            scene.warnings.push_back("node '" + nd.name + "': skinning ignored (static pose)");
        if (nd.camera >= 0) {
            const tinygltf::Camera& c = model.cameras[size_t(nd.camera)];
            if (c.type == "perspective") {
                NamedCamera cam;
                cam.name = c.name.empty() ? nd.name : c.name;
                cam.position = point(m, {0, 0, 0});
                cam.forward = normalize(direction(m, {0, 0, -1}));
                cam.up = normalize(direction(m, {0, 1, 0}));
                cam.fovY = float(c.perspective.yfov);
                scene.cameras.push_back(cam);
            }
        }
        for (int child : nd.children) node(child, m);
    }
};

} // namespace

Scene loadGltf(const std::string& path) {
    tinygltf::Model model;
    tinygltf::TinyGLTF gltf;
    gltf.SetImageLoader(skipImage, nullptr);
    std::string err, warn;
    const bool binary = std::filesystem::path(path).extension() == ".glb";
    bool ok = binary ? gltf.LoadBinaryFromFile(&model, &err, &warn, path)
                     : gltf.LoadASCIIFromFile(&model, &err, &warn, path);
    if (!ok) throw Error("cannot load glTF " + path + ": " + err);
    for (const std::string& ext : model.extensionsRequired)
        throw Error("unsupported glTF feature in " + path + ": required extension " + ext);
    Loader loader{model, std::filesystem::path(path).parent_path().string(), {}, {}};
    loader.materials();
    loader.hierarchy();
    const int sceneIndex = model.defaultScene >= 0 ? model.defaultScene : 0;
    if (model.scenes.empty()) throw Error("glTF " + path + " has no scene");
    for (int n : model.scenes[size_t(sceneIndex)].nodes) loader.node(n, identity());
    if (loader.scene.triangleCount() == 0) throw Error("glTF " + path + " has no triangles");
    for (const std::string& ext : model.extensionsUsed)
        loader.scene.warnings.push_back("glTF extension " + ext + " is ignored");
    return std::move(loader.scene);
}

} // namespace bmfr::render
