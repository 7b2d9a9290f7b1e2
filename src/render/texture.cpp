#include "render/texture.h"
#include <algorithm>
#include <cmath>
#include <stb/stb_image.h>

namespace bmfr::render {

namespace {

float srgbToLinear(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

// Filled at load time, so sampling pays no initialisation guard.
struct SrgbTable {
    float v[256];
    SrgbTable() {
        for (int i = 0; i < 256; ++i) v[i] = srgbToLinear(float(i) / 255.0f);
    }
};
const SrgbTable kSrgb;

const float* srgbTable() {
    return kSrgb.v;
}

/// Wraps into [0, n) with a cheap path for the common in-range case.
inline int wrap(int i, int n) {
    if (unsigned(i) < unsigned(n)) return i;
    i %= n;
    return i < 0 ? i + n : i;
}

uint8_t linearToSrgbByte(float v) {
    v = std::clamp(v, 0.0f, 1.0f);
    float s = v <= 0.0031308f ? v * 12.92f : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
    return uint8_t(std::lround(s * 255.0f));
}

} // namespace

bool Texture::load(const std::string& path, bool srgb, std::string& error) {
    int w = 0, h = 0, n = 0;
    unsigned char* data = stbi_load(path.c_str(), &w, &h, &n, 4);
    if (!data) {
        error = stbi_failure_reason() ? stbi_failure_reason() : "unknown error";
        return false;
    }
    levels_.assign(1, Level{w, h, std::vector<uint8_t>(data, data + size_t(w) * h * 4)});
    stbi_image_free(data);
    srgb_ = srgb;
    hasAlpha_ = n == 2 || n == 4;
    buildMips();
    return true;
}

void Texture::makeFlat(Vec3 rgb, float alpha) {
    srgb_ = true;
    auto byte = [&](float v) { return linearToSrgbByte(v); };
    levels_.assign(1, Level{1, 1, {byte(rgb.x), byte(rgb.y), byte(rgb.z), uint8_t(alpha * 255)}});
}

void Texture::makeChecker(int cellsU, int cellsV, Vec3 a, Vec3 b) {
    constexpr int kTexels = 8; // per cell side
    srgb_ = true, hasAlpha_ = false;
    Level l{cellsU * kTexels, cellsV * kTexels, {}};
    l.rgba.resize(size_t(l.w) * size_t(l.h) * 4);
    for (int y = 0; y < l.h; ++y)
        for (int x = 0; x < l.w; ++x) {
            const Vec3 c = ((x / kTexels + y / kTexels) & 1) ? b : a;
            uint8_t* t = &l.rgba[(size_t(y) * size_t(l.w) + size_t(x)) * 4];
            t[0] = linearToSrgbByte(c.x), t[1] = linearToSrgbByte(c.y);
            t[2] = linearToSrgbByte(c.z), t[3] = 255;
        }
    levels_.assign(1, std::move(l));
    buildMips();
}

void Texture::buildMips() {
    const float* lut = srgbTable();
    while (levels_.back().w > 1 || levels_.back().h > 1) {
        const Level& a = levels_.back();
        Level b{std::max(1, a.w / 2), std::max(1, a.h / 2), {}};
        b.rgba.resize(size_t(b.w) * b.h * 4);
        for (int y = 0; y < b.h; ++y)
            for (int x = 0; x < b.w; ++x)
                for (int c = 0; c < 4; ++c) {
                    float s = 0;
                    for (int dy = 0; dy < 2; ++dy)
                        for (int dx = 0; dx < 2; ++dx) {
                            int sx = std::min(a.w - 1, 2 * x + dx),
                                sy = std::min(a.h - 1, 2 * y + dy);
                            uint8_t v = a.rgba[(size_t(sy) * a.w + sx) * 4 + c];
                            s += (srgb_ && c < 3) ? lut[v] : float(v) / 255.0f;
                        }
                    s *= 0.25f;
                    b.rgba[(size_t(y) * b.w + x) * 4 + c] =
                        (srgb_ && c < 3) ? linearToSrgbByte(s) : uint8_t(std::lround(s * 255.0f));
                }
        levels_.push_back(std::move(b));
    }
}

TexSample Texture::texel(const Level& l, int x, int y) const {
    x = wrap(x, l.w);
    y = wrap(y, l.h);
    const uint8_t* p = &l.rgba[(size_t(y) * l.w + x) * 4];
    const float* lut = srgbTable();
    if (srgb_) return {{lut[p[0]], lut[p[1]], lut[p[2]]}, float(p[3]) / 255.0f};
    return {{p[0] / 255.0f, p[1] / 255.0f, p[2] / 255.0f}, p[3] / 255.0f};
}

float Texture::alphaNearest(float u, float v) const {
    if (levels_.empty()) return 1.0f;
    const Level& l = levels_[0];
    float x = u * float(l.w), y = v * float(l.h);
    if (!(std::fabs(x) < 1e7f) || !(std::fabs(y) < 1e7f)) return 1.0f;
    return l.rgba[(size_t(wrap(int(std::floor(y)), l.h)) * l.w +
                   size_t(wrap(int(std::floor(x)), l.w))) *
                      4 +
                  3] /
           255.0f;
}

TexSample Texture::sample(float u, float v, float lod) const {
    if (levels_.empty()) return {{1, 1, 1}, 1};
    int li = int(std::clamp(std::floor(lod + 0.5f), 0.0f, float(levels_.size() - 1)));
    const Level& l = levels_[size_t(li)];
    float x = u * float(l.w) - 0.5f, y = v * float(l.h) - 0.5f;
    if (!(std::fabs(x) < 1e7f) || !(std::fabs(y) < 1e7f)) return texel(l, 0, 0);
    float fx = std::floor(x), fy = std::floor(y);
    int x0 = int(fx), y0 = int(fy);
    float ax = x - fx, ay = y - fy;
    TexSample s00 = texel(l, x0, y0), s10 = texel(l, x0 + 1, y0), s01 = texel(l, x0, y0 + 1),
              s11 = texel(l, x0 + 1, y0 + 1);
    auto mix = [&](float a, float b, float c, float d) {
        return (1 - ax) * (1 - ay) * a + ax * (1 - ay) * b + (1 - ax) * ay * c + ax * ay * d;
    };
    TexSample r;
    r.rgb = {mix(s00.rgb.x, s10.rgb.x, s01.rgb.x, s11.rgb.x),
             mix(s00.rgb.y, s10.rgb.y, s01.rgb.y, s11.rgb.y),
             mix(s00.rgb.z, s10.rgb.z, s01.rgb.z, s11.rgb.z)};
    r.alpha = mix(s00.alpha, s10.alpha, s01.alpha, s11.alpha);
    return r;
}

} // namespace bmfr::render
