// The fitting core against an independent double-precision least-squares solve (Eigen).
#include "core/hash.h"
#include "filters/bmfr/householder_fit.h"
#include <Eigen/Dense>
#include <cmath>
#include <gtest/gtest.h>
#include <vector>

namespace bmfr {
namespace {

constexpr int W = 1024;

float uniform(uint32_t a, uint32_t b, uint32_t c) {
    return unitFloat(hashKeys(a, b, c));
}

/// Column-major block: M feature columns then 3 colour columns.
struct Block {
    int M;
    std::vector<float> cols;
    Block(int m) : M(m), cols(size_t(m + 3) * W) {}
    float& at(int col, int row) { return cols[size_t(col) * W + row]; }
};

/// Adds U[-eps, eps] to every feature column but the constant one (column 0).
void regularise(Block& b, float eps, uint32_t seed) {
    for (int f = 1; f < b.M; ++f)
        for (int k = 0; k < W; ++k) b.at(f, k) += eps * (2 * uniform(seed, f, k) - 1);
}

/// Fitted values T a for each channel from our solver, and from Eigen in double.
void compare(Block b, double tolerance, const char* what) {
    Eigen::MatrixXd A(W, b.M), Z(W, 3);
    for (int k = 0; k < W; ++k) {
        for (int f = 0; f < b.M; ++f) A(k, f) = b.at(f, k);
        for (int c = 0; c < 3; ++c) Z(k, c) = b.at(b.M + c, k);
    }
    Eigen::MatrixXd ref = A * A.colPivHouseholderQr().solve(Z);
    std::vector<float> coeffs(size_t(b.M) * 3);
    std::vector<float> work = b.cols;
    solveHouseholder(work.data(), b.M, W, coeffs.data());
    double scale = Z.cwiseAbs().maxCoeff();
    for (float c : coeffs) ASSERT_TRUE(std::isfinite(c)) << what;
    double worst = 0;
    for (int k = 0; k < W; ++k)
        for (int c = 0; c < 3; ++c) {
            double ours = 0;
            for (int f = 0; f < b.M; ++f) ours += double(coeffs[f * 3 + c]) * A(k, f);
            worst = std::max(worst, std::fabs(ours - ref(k, c)));
        }
    EXPECT_LE(worst, tolerance * scale) << what << ": max |fitted - reference| = " << worst;
}

TEST(Householder, MatchesDoubleLeastSquaresOnRandomBlocks) {
    for (uint32_t trial = 0; trial < 20; ++trial) {
        Block b(10);
        for (int k = 0; k < W; ++k) {
            b.at(0, k) = 1.0f;
            for (int f = 1; f < 10; ++f) b.at(f, k) = 2 * uniform(trial, f, k) - 1;
            for (int c = 0; c < 3; ++c)
                b.at(10 + c, k) = 0.5f + b.at(1, k) * (c + 1) + 0.3f * uniform(trial + 99, c, k);
        }
        compare(b, 1e-4, "random");
    }
}

TEST(Householder, RankDeficientBlocksWithRegularisationMatchAndStayFinite) {
    // Flat wall: constant normal, position varies in one axis only; the squares duplicate it.
    Block wall(10);
    for (int k = 0; k < W; ++k) {
        float x = float(k % 32) / 31.0f;
        const float cols[10] = {1, 0, 0, 1, x, 0.5f, 0.25f, x * x, 0.25f, 0.0625f};
        for (int f = 0; f < 10; ++f) wall.at(f, k) = cols[f];
        for (int c = 0; c < 3; ++c) wall.at(10 + c, k) = 0.2f + 0.5f * x + 0.1f * uniform(7, c, k);
    }
    regularise(wall, 0.01f, 1);
    compare(wall, 2e-3, "flat wall");

    // Empty sky: every feature constant (all zero apart from the constant column).
    Block sky(10);
    for (int k = 0; k < W; ++k) {
        sky.at(0, k) = 1.0f;
        for (int c = 0; c < 3; ++c) sky.at(10 + c, k) = 0.8f + 0.2f * uniform(9, c, k);
    }
    regularise(sky, 0.01f, 2);
    compare(sky, 2e-3, "sky");
}

TEST(Householder, UnregularisedRankDeficiencyGivesFiniteMeanFit) {
    // Without noise the dependent columns are dropped: the fit is still the block mean.
    Block b(10);
    for (int k = 0; k < W; ++k) {
        b.at(0, k) = 1.0f;
        for (int f = 1; f < 10; ++f) b.at(f, k) = 0.3f;
        for (int c = 0; c < 3; ++c) b.at(10 + c, k) = float(k % 7);
    }
    std::vector<float> coeffs(30);
    std::vector<float> work = b.cols;
    int dropped = solveHouseholder(work.data(), 10, W, coeffs.data());
    EXPECT_EQ(dropped, 9);
    double mean = 0;
    for (int k = 0; k < W; ++k) mean += k % 7;
    mean /= W;
    for (float c : coeffs) ASSERT_TRUE(std::isfinite(c));
    EXPECT_NEAR(coeffs[0], mean, 1e-4);
}

} // namespace
} // namespace bmfr
