#include "metrics/flip.h"
#include "metrics/separable_filter.h"
#include <algorithm>
#include <array>
#include <bmfr/error.h>
#include <cmath>
#include <vector>

namespace bmfr {

namespace {

using Plane = std::vector<double>;
constexpr double kPi = 3.14159265358979323846;
// D65 white: the row sums of rgbToXyz.
constexpr double kWhite[3] = {23359437.0 / 24577794, 1.0, 80288307.0 / 73733382};

double srgbToLinear(double c) {
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// NVIDIA's FLIP takes sRGB to XYZ with the exact fractions of this matrix (image-engineering.de),
// and its D65 white is the matrix's row sums; the rounded Lindbloom matrix moves FLIP by ~1e-4.
std::array<double, 3> rgbToXyz(double r, double g, double b) {
    return {10135552.0 / 24577794 * r + 8788810.0 / 24577794 * g + 4435075.0 / 24577794 * b,
            2613072.0 / 12288897 * r + 8788810.0 / 12288897 * g + 887015.0 / 12288897 * b,
            1425312.0 / 73733382 * r + 8788810.0 / 73733382 * g + 70074185.0 / 73733382 * b};
}
std::array<double, 3> xyzToRgb(double x, double y, double z) {
    return {3.241003232976358 * x - 1.537398969488785 * y - 0.498615881996363 * z,
            -0.969224252202516 * x + 1.875929983695176 * y + 0.041554226340085 * z,
            0.055639419851975 * x - 0.204011206123910 * y + 1.057148977187533 * z};
}
std::array<double, 3> xyzToYcxcz(const std::array<double, 3>& v) {
    double x = v[0] / kWhite[0], y = v[1] / kWhite[1], z = v[2] / kWhite[2];
    return {116 * y - 16, 500 * (x - y), 200 * (y - z)};
}
std::array<double, 3> ycxczToXyz(const std::array<double, 3>& v) {
    double y = (v[0] + 16) / 116, x = v[1] / 500 + y, z = y - v[2] / 200;
    return {x * kWhite[0], y * kWhite[1], z * kWhite[2]};
}
/// CIELAB with the Hunt adjustment (a, b scaled by 0.01 L).
std::array<double, 3> xyzToHuntLab(const std::array<double, 3>& v) {
    auto f = [](double t) {
        const double d = 6.0 / 29.0;
        return t > d * d * d ? std::cbrt(t) : t / (3 * d * d) + 4.0 / 29.0;
    };
    double fx = f(v[0] / kWhite[0]), fy = f(v[1] / kWhite[1]), fz = f(v[2] / kWhite[2]);
    double L = 116 * fy - 16;
    return {L, 0.01 * L * 500 * (fx - fy), 0.01 * L * 200 * (fy - fz)};
}
double hyab(const std::array<double, 3>& a, const std::array<double, 3>& b) {
    return std::fabs(a[0] - b[0]) + std::hypot(a[1] - b[1], a[2] - b[2]);
}

Plane separable(const Plane& in, int w, int h, const std::vector<double>& kx,
                const std::vector<double>& ky) {
    // Clamp-to-edge borders, as NVIDIA's implementation (its Python port once mirrored).
    return separableFilter(in, w, h, kx, ky, FilterBorder::Clamp);
}

/// The contrast sensitivity filter of one opponent channel: a normalised sum of two Gaussians.
Plane csfFilter(const Plane& in, int w, int h, double ppd, double a1, double b1, double a2,
                double b2) {
    const double maxB = 0.04; // largest scale parameter over the three channels
    const int r = int(std::ceil(3 * std::sqrt(maxB / (2 * kPi * kPi)) * ppd));
    auto gauss = [&](double b) {
        std::vector<double> k(size_t(2 * r + 1));
        for (int i = -r; i <= r; ++i)
            k[size_t(i + r)] = std::exp(-kPi * kPi * (i / ppd) * (i / ppd) / b);
        return k;
    };
    auto sum = [](const std::vector<double>& k) {
        double s = 0;
        for (double v : k) s += v;
        return s;
    };
    std::vector<double> g1 = gauss(b1), g2 = gauss(b2);
    const double w1 = a1 * std::sqrt(kPi / b1), w2 = a2 * std::sqrt(kPi / b2);
    const double total = w1 * sum(g1) * sum(g1) + w2 * sum(g2) * sum(g2);
    Plane out = separable(in, w, h, g1, g1);
    for (double& v : out) v *= w1 / total;
    if (a2 != 0) {
        Plane second = separable(in, w, h, g2, g2);
        for (size_t i = 0; i < out.size(); ++i) out[i] += w2 / total * second[i];
    }
    return out;
}

/// Edge (first derivative) or point (second derivative) magnitude of a luminance plane.
Plane features(const Plane& lum, int w, int h, double ppd, bool edge) {
    const double sd = 0.5 * 0.082 * ppd;
    const int r = int(std::ceil(3 * sd));
    std::vector<double> d(size_t(2 * r + 1)), g(d.size());
    double pos = 0, neg = 0, gs = 0;
    for (int i = -r; i <= r; ++i) {
        double gi = std::exp(-double(i * i) / (2 * sd * sd));
        double v = edge ? -i * gi : (double(i * i) / (sd * sd) - 1) * gi;
        d[size_t(i + r)] = v, g[size_t(i + r)] = gi;
        (v > 0 ? pos : neg) += std::fabs(v);
        gs += gi;
    }
    // Positive and negative weights are normalised apart (each sums to 1 in magnitude).
    for (double& v : d) v = v > 0 ? v / pos : v / neg;
    for (double& v : g) v /= gs;
    Plane fx = separable(lum, w, h, d, g), fy = separable(lum, w, h, g, d);
    for (size_t i = 0; i < fx.size(); ++i) fx[i] = std::hypot(fx[i], fy[i]);
    return fx;
}

} // namespace

ImageF flipMap(const ImageF& ref, const ImageF& test, double ppd) {
    if (ref.width != test.width || ref.height != test.height || ref.channels != 3 ||
        test.channels != 3 || ref.width == 0)
        throw Error("FLIP: needs two RGB images of one size");
    const int w = ref.width, h = ref.height;
    const size_t n = size_t(w) * h;
    const double qc = 0.7, pc = 0.4, pt = 0.95, qf = 0.5;

    std::array<Plane, 3> ycc[2];
    Plane lum[2];
    for (int k = 0; k < 2; ++k) {
        const ImageF& img = k == 0 ? ref : test;
        for (auto& p : ycc[k]) p.resize(n);
        lum[k].resize(n);
        for (size_t i = 0; i < n; ++i) {
            auto v =
                xyzToYcxcz(rgbToXyz(srgbToLinear(std::clamp(img.pixels[3 * i], 0.0f, 1.0f)),
                                    srgbToLinear(std::clamp(img.pixels[3 * i + 1], 0.0f, 1.0f)),
                                    srgbToLinear(std::clamp(img.pixels[3 * i + 2], 0.0f, 1.0f))));
            for (int c = 0; c < 3; ++c) ycc[k][size_t(c)][i] = v[size_t(c)];
            lum[k][i] = (v[0] + 16) / 116;
        }
        ycc[k][0] = csfFilter(ycc[k][0], w, h, ppd, 1, 0.0047, 0, 1e-5);
        ycc[k][1] = csfFilter(ycc[k][1], w, h, ppd, 1, 0.0053, 0, 1e-5);
        ycc[k][2] = csfFilter(ycc[k][2], w, h, ppd, 34.1, 0.04, 13.5, 0.025);
    }
    auto huntLab = [](std::array<double, 3> ycxcz) {
        const auto xyz = ycxczToXyz(ycxcz);
        auto rgb = xyzToRgb(xyz[0], xyz[1], xyz[2]);
        for (double& c : rgb) c = std::clamp(c, 0.0, 1.0);
        return xyzToHuntLab(rgbToXyz(rgb[0], rgb[1], rgb[2]));
    };
    const double cmax =
        std::pow(hyab(xyzToHuntLab(rgbToXyz(0, 1, 0)), xyzToHuntLab(rgbToXyz(0, 0, 1))), qc);
    Plane edges[2], points[2];
    for (int k = 0; k < 2; ++k) {
        edges[k] = features(lum[k], w, h, ppd, true);
        points[k] = features(lum[k], w, h, ppd, false);
    }

    ImageF map(w, h, 1);
    for (size_t i = 0; i < n; ++i) {
        auto a = huntLab({ycc[0][0][i], ycc[0][1][i], ycc[0][2][i]});
        auto b = huntLab({ycc[1][0][i], ycc[1][1][i], ycc[1][2][i]});
        double dc = std::pow(hyab(a, b), qc);
        dc = dc < pc * cmax ? pt / (pc * cmax) * dc
                            : pt + (dc - pc * cmax) / (cmax - pc * cmax) * (1 - pt);
        double df = std::pow(
            std::max(std::fabs(edges[0][i] - edges[1][i]), std::fabs(points[0][i] - points[1][i])) /
                std::sqrt(2.0),
            qf);
        map.pixels[i] = float(std::pow(dc, 1 - df));
    }
    return map;
}

double flipMean(const ImageF& map) {
    double s = 0;
    for (float v : map.pixels) s += v;
    return s / double(map.pixels.size());
}

double flip(const ImageF& ref, const ImageF& test, double ppd) {
    return flipMean(flipMap(ref, test, ppd));
}

} // namespace bmfr
