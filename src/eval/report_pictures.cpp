#include "eval/report_pictures.h"
#include <algorithm>
#include <cmath>
#include <fmt/core.h>

namespace bmfr {

Raster labelledRow(const std::vector<const ImageF*>& images, const std::vector<std::string>& labels,
                   std::array<int, 4> crop, int zoom) {
    const int labelH = 30, gap = 8;
    const int w = crop[2] > 0 ? crop[2] : images.at(0)->width;
    const int h = crop[2] > 0 ? crop[3] : images.at(0)->height;
    const int cw = w * zoom, ch = h * zoom;
    Raster row(int(images.size()) * (cw + gap) - gap, ch + labelH);
    for (size_t i = 0; i < images.size(); ++i) {
        const int x = int(i) * (cw + gap);
        row.blit(crop[2] > 0 ? rasterFromLinear(*images[i], crop[0], crop[1], w, h, zoom)
                             : rasterFromLinear(*images[i]),
                 x, labelH);
        std::string label = labels[i];
        while (label.size() > 3 && textWidth(label, 2) > cw) label.pop_back();
        if (label != labels[i]) label.back() = '~'; // the full name is in the caption and table
        row.text(x + 2, 6, label, {0, 0, 0}, 2);
    }
    return row;
}

Raster heatMapWithBar(const ImageF& map, float vmax, const std::string& caption) {
    const Raster heat = heatMap(map, vmax);
    const int barH = 12, w = std::max(heat.width, 220);
    Raster out(w, heat.height + barH + 44);
    out.blit(heat, 0, 0);
    const int y = heat.height + 6, barW = w - 20;
    ImageF ramp(barW, 1, 1);
    for (int x = 0; x < barW; ++x) ramp.pixels[size_t(x)] = vmax * float(x) / float(barW - 1);
    const Raster bar = heatMap(ramp, vmax);
    for (int j = 0; j < barH; ++j) out.blit(bar, 10, y + j);
    const Rgb8 ink{30, 30, 30};
    const std::string mid = fmt::format("{:g}", vmax / 2), hi = fmt::format("{:g}+", vmax);
    out.text(10, y + barH + 4, "0", ink, 1);
    out.text(10 + barW / 2 - textWidth(mid, 1) / 2, y + barH + 4, mid, ink, 1);
    out.text(10 + barW - textWidth(hi, 1), y + barH + 4, hi, ink, 1);
    out.text(10, y + barH + 18, caption, ink, 1);
    return out;
}

float heatScale(const std::vector<const ImageF*>& maps, double percentile) {
    std::vector<float> all;
    for (const ImageF* m : maps) all.insert(all.end(), m->pixels.begin(), m->pixels.end());
    if (all.empty()) return 1.0f;
    const size_t k = std::min(all.size() - 1, size_t(percentile * double(all.size())));
    std::nth_element(all.begin(), all.begin() + long(k), all.end());
    const double v = std::max(1e-2, double(all[k]));
    const double p = std::pow(10.0, std::floor(std::log10(v)));
    const double m = v / p;
    return float(std::min(1.0, (m <= 1 ? 1 : m <= 2 ? 2 : m <= 5 ? 5 : 10) * p));
}

Raster downscale(const Raster& r, int f) {
    if (f <= 1) return r;
    Raster out(std::max(1, r.width / f), std::max(1, r.height / f));
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x) {
            int s[3] = {0, 0, 0}, n = 0;
            for (int j = y * f; j < std::min(r.height, (y + 1) * f); ++j)
                for (int i = x * f; i < std::min(r.width, (x + 1) * f); ++i, ++n) {
                    const Rgb8 c = r.pixels[size_t(j) * r.width + i];
                    s[0] += c.r, s[1] += c.g, s[2] += c.b;
                }
            out.pixels[size_t(y) * out.width + x] = {uint8_t((s[0] + n / 2) / n),
                                                     uint8_t((s[1] + n / 2) / n),
                                                     uint8_t((s[2] + n / 2) / n)};
        }
    return out;
}

Raster greyRaster(const ImageF& map) {
    Raster r(map.width, map.height);
    for (size_t i = 0; i < r.pixels.size(); ++i) {
        const auto v =
            uint8_t(std::clamp(map.pixels[i * size_t(map.channels)], 0.0f, 1.0f) * 255.0f + 0.5f);
        r.pixels[i] = {v, v, v};
    }
    return r;
}

} // namespace bmfr
