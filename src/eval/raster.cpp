#include "eval/raster.h"
#include "core/color.h"
#include "io/atomic_file.h"
#include <algorithm>
#include <bmfr/error.h>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <stb/stb_easy_font.h>
#include <stb/stb_image_write.h>

namespace bmfr {

void Raster::fillRect(int x0, int y0, int x1, int y1, Rgb8 c) {
    for (int y = std::max(0, y0); y < std::min(height, y1); ++y)
        for (int x = std::max(0, x0); x < std::min(width, x1); ++x)
            pixels[size_t(y) * width + x] = c;
}

void Raster::line(double x0, double y0, double x1, double y1, Rgb8 c, int thickness) {
    const int steps = int(std::max(std::fabs(x1 - x0), std::fabs(y1 - y0))) + 1;
    for (int i = 0; i <= steps; ++i) {
        double t = double(i) / steps;
        int x = int(std::lround(x0 + t * (x1 - x0))), y = int(std::lround(y0 + t * (y1 - y0)));
        fillRect(x - thickness / 2, y - thickness / 2, x - thickness / 2 + thickness,
                 y - thickness / 2 + thickness, c);
    }
}

void Raster::text(int x, int y, const std::string& s, Rgb8 c, int scale) {
    static char buffer[99999];
    const int quads =
        stb_easy_font_print(0, 0, const_cast<char*>(s.c_str()), nullptr, buffer, sizeof buffer);
    for (int q = 0; q < quads; ++q) {
        const float* v = reinterpret_cast<const float*>(buffer + q * 64);
        // Each vertex: x, y, z, colour (4 bytes) = 16 bytes; a quad is axis-aligned.
        int qx0 = int(v[0]), qy0 = int(v[1]), qx1 = int(v[8]), qy1 = int(v[9]);
        fillRect(x + qx0 * scale, y + qy0 * scale, x + qx1 * scale, y + qy1 * scale, c);
    }
}

int textWidth(const std::string& s, int scale) {
    return stb_easy_font_width(const_cast<char*>(s.c_str())) * scale;
}

void Raster::blit(const Raster& src, int x, int y) {
    for (int j = 0; j < src.height; ++j)
        for (int i = 0; i < src.width; ++i)
            set(x + i, y + j, src.pixels[size_t(j) * src.width + i]);
}

Raster rasterFromLinear(const ImageF& img, int x0, int y0, int w, int h, int zoom) {
    if (w < 0) w = img.width;
    if (h < 0) h = img.height;
    Raster r(w * zoom, h * zoom);
    for (int y = 0; y < r.height; ++y)
        for (int x = 0; x < r.width; ++x) {
            int sx = std::clamp(x0 + x / zoom, 0, img.width - 1),
                sy = std::clamp(y0 + y / zoom, 0, img.height - 1);
            const float* p = &img.pixels[(size_t(sy) * img.width + sx) * size_t(img.channels)];
            auto byte = [](float v) { return uint8_t(gammaEncode(v) * 255.0f + 0.5f); };
            r.pixels[size_t(y) * r.width + x] = img.channels >= 3
                                                    ? Rgb8{byte(p[0]), byte(p[1]), byte(p[2])}
                                                    : Rgb8{byte(p[0]), byte(p[0]), byte(p[0])};
        }
    return r;
}

const std::array<std::array<float, 3>, 5>& heatStops() {
    // Magma-like ramp: black, purple, red-orange, light yellow.
    static const std::array<std::array<float, 3>, 5> stops = {
        {{0, 0, 4}, {81, 18, 124}, {183, 55, 121}, {252, 137, 97}, {252, 253, 191}}};
    return stops;
}

Raster heatMap(const ImageF& map, float vmax) {
    const auto& stops = heatStops();
    Raster r(map.width, map.height);
    for (size_t i = 0; i < r.pixels.size(); ++i) {
        float t =
            std::clamp(map.pixels[i * size_t(map.channels)] / std::max(vmax, 1e-12f), 0.0f, 1.0f) *
            4.0f;
        int k = std::min(3, int(t));
        float f = t - float(k);
        auto mix = [&](int c) {
            return uint8_t(stops[size_t(k)][size_t(c)] +
                           f * (stops[size_t(k + 1)][size_t(c)] - stops[size_t(k)][size_t(c)]) +
                           0.5f);
        };
        r.pixels[i] = {mix(0), mix(1), mix(2)};
    }
    return r;
}

namespace {
void appendBytes(void* ctx, void* data, int size) {
    auto* v = static_cast<std::vector<unsigned char>*>(ctx);
    v->insert(v->end(), static_cast<unsigned char*>(data),
              static_cast<unsigned char*>(data) + size);
}
} // namespace

std::vector<unsigned char> encodePng(const Raster& r) {
    std::vector<unsigned char> out;
    if (!stbi_write_png_to_func(appendBytes, &out, r.width, r.height, 3, r.pixels.data(),
                                r.width * 3))
        throw Error("cannot encode PNG");
    return out;
}

std::vector<unsigned char> encodePngGrey(const Raster& r) {
    std::vector<unsigned char> grey(r.pixels.size()), out;
    for (size_t i = 0; i < grey.size(); ++i) grey[i] = r.pixels[i].r;
    if (!stbi_write_png_to_func(appendBytes, &out, r.width, r.height, 1, grey.data(), r.width))
        throw Error("cannot encode PNG");
    return out;
}

void writePng(const std::string& path, const Raster& r) {
    const std::vector<unsigned char> bytes = encodePng(r);
    writeFileAtomically(path, bytes.data(), bytes.size());
}

std::string base64(const std::vector<unsigned char>& in) {
    static const char* t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    size_t i = 0;
    for (; i + 2 < in.size(); i += 3) {
        unsigned v = unsigned(in[i]) << 16 | unsigned(in[i + 1]) << 8 | in[i + 2];
        out += {t[v >> 18], t[(v >> 12) & 63], t[(v >> 6) & 63], t[v & 63]};
    }
    if (i + 1 == in.size()) {
        unsigned v = unsigned(in[i]) << 16;
        out += {t[v >> 18], t[(v >> 12) & 63], '=', '='};
    } else if (i + 2 == in.size()) {
        unsigned v = unsigned(in[i]) << 16 | unsigned(in[i + 1]) << 8;
        out += {t[v >> 18], t[(v >> 12) & 63], t[(v >> 6) & 63], '='};
    }
    return out;
}

Rgb8 seriesColour(int i) {
    static const Rgb8 c[8] = {{31, 119, 180},  {255, 127, 14}, {44, 160, 44},   {214, 39, 40},
                              {148, 103, 189}, {140, 86, 75},  {227, 119, 194}, {127, 127, 127}};
    return c[i % 8];
}

} // namespace bmfr
