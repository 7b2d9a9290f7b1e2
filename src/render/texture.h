// Mipmapped 8-bit RGBA textures with bilinear filtering (base colour in sRGB, normal maps linear).
#pragma once
#include "core/vec.h"
#include <cstdint>
#include <string>
#include <vector>

namespace bmfr::render {

struct TexSample {
    Vec3 rgb;
    float alpha = 1;
};

class Texture {
  public:
    /// Loads a PNG/JPEG/TGA file; returns false (with the reason in `error`) when it cannot.
    bool load(const std::string& path, bool srgb, std::string& error);
    /// Flat 1x1 texture.
    void makeFlat(Vec3 rgb, float alpha = 1);
    /// A checkerboard of cellsU x cellsV cells over [0, 1]^2, colours a and b (linear RGB).
    void makeChecker(int cellsU, int cellsV, Vec3 a, Vec3 b);
    /// Bilinear sample at `lod` (0 = full resolution), wrapping (glTF's default sampler).
    TexSample sample(float u, float v, float lod) const;
    /// Alpha of the nearest full-resolution texel: the cheap lookup an alpha test needs.
    float alphaNearest(float u, float v) const;
    int width() const { return levels_.empty() ? 0 : levels_[0].w; }
    int height() const { return levels_.empty() ? 0 : levels_[0].h; }
    bool hasAlpha() const { return hasAlpha_; }

  private:
    struct Level {
        int w = 0, h = 0;
        std::vector<uint8_t> rgba;
    };
    std::vector<Level> levels_;
    bool srgb_ = false, hasAlpha_ = false;
    void buildMips();
    TexSample texel(const Level& l, int x, int y) const;
};

} // namespace bmfr::render
