// OBJ + MTL loader (tinyobjloader).
#include "render/scene.h"
#include <bmfr/error.h>
#include <cmath>
#include <filesystem>
#include <map>
#include <tiny_obj_loader.h>

namespace bmfr::render {

Scene loadObj(const std::string& path) {
    tinyobj::ObjReaderConfig cfg;
    cfg.triangulate = true;
    cfg.mtl_search_path = std::filesystem::path(path).parent_path().string();
    tinyobj::ObjReader reader;
    if (!reader.ParseFromFile(path, cfg))
        throw Error("cannot load OBJ " + path + ": " + reader.Error());
    Scene s;
    if (!reader.Warning().empty()) s.warnings.push_back("OBJ " + path + ": " + reader.Warning());
    const auto& attrib = reader.GetAttrib();
    std::map<std::string, int> textures;
    for (const tinyobj::material_t& om : reader.GetMaterials()) {
        Material m;
        m.name = om.name;
        m.baseColor = {float(om.diffuse[0]), float(om.diffuse[1]), float(om.diffuse[2])};
        m.emission = {float(om.emission[0]), float(om.emission[1]), float(om.emission[2])};
        const bool specular = om.specular[0] + om.specular[1] + om.specular[2] > 0;
        // Blinn-Phong exponent to GGX: alpha = sqrt(2 / (Ns + 2)), roughness = sqrt(alpha).
        m.roughness = specular ? std::sqrt(std::sqrt(2.0f / (float(om.shininess) + 2.0f))) : 1.0f;
        m.specular = specular ? 0.04f : 0.0f;
        if (!om.diffuse_texname.empty()) {
            std::string file =
                (std::filesystem::path(cfg.mtl_search_path) / om.diffuse_texname).string();
            if (auto it = textures.find(file); it != textures.end()) {
                m.baseColorTexture = it->second;
            } else {
                Texture t;
                std::string error;
                if (t.load(file, true, error)) {
                    s.textures.push_back(std::move(t));
                    m.baseColorTexture = textures[file] = int(s.textures.size() - 1);
                    m.baseColor = {1, 1, 1};
                } else {
                    s.warnings.push_back("missing texture " + file + " (" + error +
                                         "): flat colour used");
                    textures[file] = -1;
                }
            }
        }
        s.materials.push_back(m);
    }
    Material fallback;
    fallback.name = "default";
    s.materials.push_back(fallback);
    for (const tinyobj::shape_t& shape : reader.GetShapes()) {
        s.beginObject(shape.name.empty() ? "scene" : shape.name);
        const auto& idx = shape.mesh.indices;
        for (size_t f = 0; f + 2 < idx.size(); f += 3) {
            int mid = shape.mesh.material_ids[f / 3];
            int material = mid >= 0 ? mid : int(s.materials.size() - 1);
            Vec3 v[3];
            for (int j = 0; j < 3; ++j) {
                const int vi = idx[f + size_t(j)].vertex_index;
                v[j] = {attrib.vertices[3 * size_t(vi)], attrib.vertices[3 * size_t(vi) + 1],
                        attrib.vertices[3 * size_t(vi) + 2]};
            }
            s.addTriangle(v[0], v[1], v[2], material);
            const size_t base = s.positions.size() - 3;
            for (int j = 0; j < 3; ++j) {
                const auto& ix = idx[f + size_t(j)];
                if (ix.normal_index >= 0) {
                    Vec3 n{attrib.normals[3 * size_t(ix.normal_index)],
                           attrib.normals[3 * size_t(ix.normal_index) + 1],
                           attrib.normals[3 * size_t(ix.normal_index) + 2]};
                    if (length(n) > 0) s.normals[base + size_t(j)] = normalize(n);
                }
                s.uvs[base + size_t(j)] =
                    ix.texcoord_index >= 0
                        ? Vec2f{attrib.texcoords[2 * size_t(ix.texcoord_index)],
                                1.0f - attrib.texcoords[2 * size_t(ix.texcoord_index) + 1]}
                        : Vec2f{};
            }
        }
    }
    if (s.triangleCount() == 0) throw Error("OBJ " + path + " has no triangles");
    return s;
}

} // namespace bmfr::render
