// Small 8-bit RGB raster for plots, crops and heat maps, with text (stb_easy_font) and PNG output.
#pragma once
#include "core/image.h"
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace bmfr {

struct Rgb8 {
    uint8_t r = 0, g = 0, b = 0;
};

struct Raster {
    int width = 0, height = 0;
    std::vector<Rgb8> pixels;
    Raster(int w, int h, Rgb8 fill = {255, 255, 255})
        : width(w), height(h), pixels(size_t(w) * h, fill) {}
    void set(int x, int y, Rgb8 c) {
        if (x >= 0 && y >= 0 && x < width && y < height) pixels[size_t(y) * width + x] = c;
    }
    void fillRect(int x0, int y0, int x1, int y1, Rgb8 c);
    void line(double x0, double y0, double x1, double y1, Rgb8 c, int thickness = 1);
    /// Text with its top-left at (x, y); `scale` enlarges stb_easy_font's 7-pixel glyphs.
    void text(int x, int y, const std::string& s, Rgb8 c, int scale = 2);
    /// Copies `src` into this raster at (x, y).
    void blit(const Raster& src, int x, int y);
};

/// Width in pixels of `s` drawn by Raster::text at `scale`.
int textWidth(const std::string& s, int scale = 2);

/// Tone-mapped linear image as a raster, optionally a crop enlarged by `zoom` (nearest).
Raster rasterFromLinear(const ImageF& img, int x0 = 0, int y0 = 0, int w = -1, int h = -1,
                        int zoom = 1);
/// The heat colour map's stops, evenly spaced from 0 to 1 (8-bit RGB), shared with the viewer.
const std::array<std::array<float, 3>, 5>& heatStops();
/// 1-channel map through a perceptual colour map (magma-like), value range [0, vmax].
Raster heatMap(const ImageF& map, float vmax);
/// PNG bytes, for embedding; writePng writes a file atomically.
std::vector<unsigned char> encodePng(const Raster& r);
/// PNG bytes of the red channel alone, as 8-bit grey (a third of the bytes for grey maps).
std::vector<unsigned char> encodePngGrey(const Raster& r);
void writePng(const std::string& path, const Raster& r);
std::string base64(const std::vector<unsigned char>& bytes);

/// Distinct colours for plot series.
Rgb8 seriesColour(int i);

} // namespace bmfr
