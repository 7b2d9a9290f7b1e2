// FLIP against two independent references (NVIDIA's own code is the third:
// Metrics.FlipAgreesWithNvidiasImplementation, tests/python/flip_against_nvidia.py): (1) constant
// images, whose FLIP is the colour term alone, from published CIELAB values of the sRGB primaries;
// (2) a direct, non-separable transcription of NVIDIA's published algorithm (full 2-D kernels,
// clamp-to-edge borders), pixel by pixel on textured images.
#include "core/hash.h"
#include "metrics/flip.h"
#include <algorithm>
#include <array>
#include <cmath>
#include <gtest/gtest.h>
#include <vector>

namespace bmfr {
namespace {

using V3 = std::array<double, 3>;
constexpr double kPi = 3.14159265358979323846;

/// cmax and the error redistribution from published CIELAB (D65) values of sRGB green and blue.
double redistribute(double powered) {
    const double gL = 87.7347, ga = -86.1827, gb = 83.1793;  // sRGB (0, 1, 0)
    const double bL = 32.2970, ba = 79.1875, bb = -107.8602; // sRGB (0, 0, 1)
    const double hyab = std::fabs(gL - bL) + std::hypot(0.01 * gL * ga - 0.01 * bL * ba,
                                                        0.01 * gL * gb - 0.01 * bL * bb);
    const double cmax = std::pow(hyab, 0.7), pc = 0.4 * cmax;
    return powered < pc ? 0.95 / pc * powered : 0.95 + (powered - pc) / (cmax - pc) * 0.05;
}

ImageF constant(int w, int h, float v) {
    ImageF img(w, h, 3);
    std::fill(img.pixels.begin(), img.pixels.end(), v);
    return img;
}

TEST(FlipReference, ConstantImagesScoreTheirColourDifferenceAlone) {
    // White against black: L* 100 against 0, no chroma.
    EXPECT_NEAR(flip(constant(40, 30, 1), constant(40, 30, 0)), redistribute(std::pow(100, 0.7)),
                2e-4);
    // Mid grey (sRGB 0.5 is L* 53.389) against white: the lower, linear branch.
    EXPECT_NEAR(flip(constant(40, 30, 1), constant(40, 30, 0.5f)),
                redistribute(std::pow(100 - 53.389, 0.7)), 2e-4);
}

// --- NVIDIA's algorithm, transcribed directly (double precision, 2-D kernels) ---------------

V3 toXyz(V3 c) {
    const double m[3][3] = {{10135552.0 / 24577794, 8788810.0 / 24577794, 4435075.0 / 24577794},
                            {2613072.0 / 12288897, 8788810.0 / 12288897, 887015.0 / 12288897},
                            {1425312.0 / 73733382, 8788810.0 / 73733382, 70074185.0 / 73733382}};
    V3 o{};
    for (int i = 0; i < 3; ++i) o[i] = m[i][0] * c[0] + m[i][1] * c[1] + m[i][2] * c[2];
    return o;
}
V3 white() {
    return toXyz({1, 1, 1});
}
V3 toYcxcz(V3 xyz) {
    const V3 w = white();
    const double x = xyz[0] / w[0], y = xyz[1] / w[1], z = xyz[2] / w[2];
    return {116 * y - 16, 500 * (x - y), 200 * (y - z)};
}
V3 ycxczToLinear(V3 v) {
    const V3 w = white();
    const double y = (v[0] + 16) / 116, x = v[1] / 500 + y, z = y - v[2] / 200;
    const V3 xyz{x * w[0], y * w[1], z * w[2]};
    // The inverse of toXyz, solved here by Cramer's rule rather than taken from a table.
    const V3 c0 = toXyz({1, 0, 0}), c1 = toXyz({0, 1, 0}), c2 = toXyz({0, 0, 1});
    auto det = [](V3 a, V3 b, V3 c) {
        return a[0] * (b[1] * c[2] - b[2] * c[1]) - b[0] * (a[1] * c[2] - a[2] * c[1]) +
               c[0] * (a[1] * b[2] - a[2] * b[1]);
    };
    const double d = det(c0, c1, c2);
    return {det(xyz, c1, c2) / d, det(c0, xyz, c2) / d, det(c0, c1, xyz) / d};
}
V3 huntLab(V3 linear) {
    const V3 w = white(), xyz = toXyz(linear);
    auto f = [](double t) {
        const double d = 6.0 / 29;
        return t > d * d * d ? std::cbrt(t) : t / (3 * d * d) + 4.0 / 29;
    };
    const double fx = f(xyz[0] / w[0]), fy = f(xyz[1] / w[1]), fz = f(xyz[2] / w[2]);
    const double L = 116 * fy - 16;
    return {L, 0.01 * L * 500 * (fx - fy), 0.01 * L * 200 * (fy - fz)};
}
double hyab(V3 a, V3 b) {
    return std::fabs(a[0] - b[0]) + std::hypot(a[1] - b[1], a[2] - b[2]);
}

std::vector<double> flipMapDirect(const ImageF& ref, const ImageF& test, double ppd) {
    const int w = ref.width, h = ref.height;
    auto at = [&](int x, int y) {
        return std::pair{std::clamp(x, 0, w - 1), std::clamp(y, 0, h - 1)};
    };
    // Opponent images.
    std::vector<V3> opp[2];
    for (int k = 0; k < 2; ++k) {
        const ImageF& img = k ? test : ref;
        for (int i = 0; i < w * h; ++i) {
            V3 lin;
            for (int c = 0; c < 3; ++c) {
                const double s = img.pixels[3 * size_t(i) + size_t(c)];
                lin[c] = s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4);
            }
            opp[k].push_back(toYcxcz(toXyz(lin)));
        }
    }
    // Contrast sensitivity: one 2-D kernel per channel, a1 sqrt(pi/b1) e^(-pi^2 r^2 / b1) + ...
    const double a1[3] = {1, 1, 34.1}, b1[3] = {0.0047, 0.0053, 0.04}, a2[3] = {0, 0, 13.5},
                 b2[3] = {1e-5, 1e-5, 0.025};
    const int r = int(std::ceil(3 * std::sqrt(0.04 / (2 * kPi * kPi)) * ppd));
    std::vector<double> csf[3];
    for (int c = 0; c < 3; ++c) {
        double sum = 0;
        for (int y = -r; y <= r; ++y)
            for (int x = -r; x <= r; ++x) {
                const double z = (x * x + y * y) / (ppd * ppd);
                const double g = a1[c] * std::sqrt(kPi / b1[c]) * std::exp(-kPi * kPi * z / b1[c]) +
                                 a2[c] * std::sqrt(kPi / b2[c]) * std::exp(-kPi * kPi * z / b2[c]);
                csf[c].push_back(g), sum += g;
            }
        for (double& g : csf[c]) g /= sum;
    }
    // Feature kernels: first and second derivatives of a Gaussian along x (and transposed).
    const double sd = 0.5 * 0.082 * ppd;
    const int fr = int(std::ceil(3 * sd));
    std::vector<double> edge, point;
    for (int y = -fr; y <= fr; ++y)
        for (int x = -fr; x <= fr; ++x) {
            const double g = std::exp(-(x * x + y * y) / (2 * sd * sd));
            edge.push_back(-x * g), point.push_back((x * x / (sd * sd) - 1) * g);
        }
    for (auto* kern : {&edge, &point}) {
        double pos = 0, neg = 0;
        for (double v : *kern) (v > 0 ? pos : neg) += std::fabs(v);
        for (double& v : *kern) v = v > 0 ? v / pos : v / neg;
    }
    const double cmax = std::pow(hyab(huntLab({0, 1, 0}), huntLab({0, 0, 1})), 0.7);
    std::vector<double> out(size_t(w) * h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            V3 lab[2];
            double feat[2][4] = {};
            for (int k = 0; k < 2; ++k) {
                V3 f{};
                for (int j = -r; j <= r; ++j)
                    for (int i = -r; i <= r; ++i) {
                        auto [xx, yy] = at(x + i, y + j);
                        const size_t t = size_t(j + r) * size_t(2 * r + 1) + size_t(i + r);
                        for (int c = 0; c < 3; ++c)
                            f[c] += csf[c][t] * opp[k][size_t(yy) * w + xx][c];
                    }
                V3 lin = ycxczToLinear(f);
                for (double& c : lin) c = std::clamp(c, 0.0, 1.0);
                lab[k] = huntLab(lin);
                for (int j = -fr; j <= fr; ++j)
                    for (int i = -fr; i <= fr; ++i) {
                        auto [xx, yy] = at(x + i, y + j);
                        const double lum = (opp[k][size_t(yy) * w + xx][0] + 16) / 116;
                        const size_t tx = size_t(j + fr) * size_t(2 * fr + 1) + size_t(i + fr);
                        const size_t ty = size_t(i + fr) * size_t(2 * fr + 1) + size_t(j + fr);
                        feat[k][0] += edge[tx] * lum, feat[k][1] += edge[ty] * lum;
                        feat[k][2] += point[tx] * lum, feat[k][3] += point[ty] * lum;
                    }
            }
            double dc = std::pow(hyab(lab[0], lab[1]), 0.7);
            dc = dc < 0.4 * cmax ? 0.95 / (0.4 * cmax) * dc
                                 : 0.95 + (dc - 0.4 * cmax) / (0.6 * cmax) * 0.05;
            const double de =
                std::fabs(std::hypot(feat[0][0], feat[0][1]) - std::hypot(feat[1][0], feat[1][1]));
            const double dp =
                std::fabs(std::hypot(feat[0][2], feat[0][3]) - std::hypot(feat[1][2], feat[1][3]));
            const double df = std::pow(std::max(de, dp) / std::sqrt(2.0), 0.5);
            out[size_t(y) * w + x] = std::pow(dc, 1 - df);
        }
    return out;
}

ImageF textured(int w, int h, uint32_t seed) {
    ImageF img(w, h, 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                const float edge = (x > w / 2) == (y > h / 3) ? 0.7f : 0.2f;
                img.at(x, y, c) = std::clamp(
                    edge +
                        0.25f * (unitFloat(hashKeys(seed, uint32_t(x), uint32_t(y), uint32_t(c))) -
                                 0.5f),
                    0.0f, 1.0f);
            }
    return img;
}

TEST(FlipReference, MatchesADirectTranscriptionOfNvidiasAlgorithm) {
    const ImageF ref = textured(37, 29, 1), test = textured(37, 29, 2);
    for (double ppd : {kFlipDefaultPpd, 20.0}) {
        const std::vector<double> expected = flipMapDirect(ref, test, ppd);
        const ImageF map = flipMap(ref, test, ppd);
        double worst = 0, mean = 0, expectedMean = 0;
        for (size_t i = 0; i < expected.size(); ++i) {
            worst = std::max(worst, std::fabs(map.pixels[i] - expected[i]));
            mean += map.pixels[i], expectedMean += expected[i];
        }
        EXPECT_LT(worst, 1e-5) << "ppd " << ppd;
        EXPECT_NEAR(mean / double(expected.size()), expectedMean / double(expected.size()), 1e-6);
    }
}

TEST(FlipReference, DefaultViewingConditionsAreNvidias) {
    EXPECT_NEAR(kFlipDefaultPpd, 67.0206, 1e-4);
}

} // namespace
} // namespace bmfr
