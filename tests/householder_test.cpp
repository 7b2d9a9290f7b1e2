// The fitting core, reference and fast, against an independent double-precision
// least-squares solve (Eigen), and the two against each other.
#include "backend/cpu/bmfr/cpu_bmfr_buffers.h"
#include "backend/cuda/bmfr/cooperative_fit.h"
#include "core/hash.h"
#include "filters/bmfr/householder_qr.h"
#include "test_support.h"
#include <Eigen/Dense>
#include <cmath>
#include <gtest/gtest.h>
#include <vector>

namespace bmfr {
namespace {

constexpr int kRows = 1024;

/// The CUDA backend's block-cooperative QR, run on the host by a team of 256 (the GPU's).
int solveHouseholderTeam(float* columns, int M, int rows, float* coeffs) {
    const cuda::HostTeam team{256};
    cuda::TeamFitState st{};
    std::vector<float> partial(size_t(cuda::teamFitPartials(M)) * size_t(team.size()));
    cuda::teamHouseholder(team, columns, M, rows, partial.data(), st);
    for (int k = 0; k < 3 * M; ++k) coeffs[k] = st.coeffs[k];
    return st.q.deficient;
}

using Solver = int (*)(float*, int, int, float*);
struct NamedSolver {
    const char* name;
    Solver solve;
};
const NamedSolver kSolvers[] = {{"reference", &solveHouseholder},
                                // The reference again where the processor has no AVX2.
                                {"reference avx2", cpu::bestIsa() >= cpu::Isa::Avx2
                                                       ? &solveHouseholderAvx2
                                                       : &solveHouseholder},
                                {"fast", &cpu::solveHouseholderFast},
                                {"cuda team", &solveHouseholderTeam}};

using testing::uniform;

/// Column-major block: M feature columns then 3 colour columns.
struct Block {
    int M;
    std::vector<float> cols;
    Block(int m) : M(m), cols(size_t(m + 3) * kRows) {}
    float& at(int col, int row) { return cols[size_t(col) * kRows + row]; }
};

/// Adds U[-eps, eps] to every feature column but the constant one (column 0).
void regularise(Block& b, float eps, uint32_t seed) {
    for (int f = 1; f < b.M; ++f)
        for (int k = 0; k < kRows; ++k) b.at(f, k) += eps * (2 * uniform(seed, f, k) - 1);
}

void compareOne(const Block& b, double tolerance, const char* what, Solver solve) {
    Eigen::MatrixXd A(kRows, b.M), Z(kRows, 3);
    for (int k = 0; k < kRows; ++k) {
        for (int f = 0; f < b.M; ++f) A(k, f) = b.cols[size_t(f) * kRows + k];
        for (int c = 0; c < 3; ++c) Z(k, c) = b.cols[size_t(b.M + c) * kRows + k];
    }
    Eigen::MatrixXd ref = A * A.colPivHouseholderQr().solve(Z);
    std::vector<float> coeffs(size_t(b.M) * 3);
    std::vector<float> work = b.cols;
    solve(work.data(), b.M, kRows, coeffs.data());
    double scale = Z.cwiseAbs().maxCoeff();
    for (float c : coeffs) ASSERT_TRUE(std::isfinite(c)) << what;
    double worst = 0;
    for (int k = 0; k < kRows; ++k)
        for (int c = 0; c < 3; ++c) {
            double ours = 0;
            for (int f = 0; f < b.M; ++f) ours += double(coeffs[f * 3 + c]) * A(k, f);
            worst = std::max(worst, std::fabs(ours - ref(k, c)));
        }
    EXPECT_LE(worst, tolerance * scale) << what << ": max |fitted - reference| = " << worst;
}

/// Fitted values T a for each channel from both our solvers, and from Eigen in double.
void compare(Block b, double tolerance, const char* what) {
    for (const NamedSolver& solver : kSolvers) {
        SCOPED_TRACE(solver.name);
        compareOne(b, tolerance, what, solver.solve);
    }
}

TEST(Householder, MatchesDoubleLeastSquaresOnRandomBlocks) {
    for (uint32_t trial = 0; trial < 20; ++trial) {
        Block b(10);
        for (int k = 0; k < kRows; ++k) {
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
    for (int k = 0; k < kRows; ++k) {
        float x = float(k % 32) / 31.0f;
        const float cols[10] = {1, 0, 0, 1, x, 0.5f, 0.25f, x * x, 0.25f, 0.0625f};
        for (int f = 0; f < 10; ++f) wall.at(f, k) = cols[f];
        for (int c = 0; c < 3; ++c) wall.at(10 + c, k) = 0.2f + 0.5f * x + 0.1f * uniform(7, c, k);
    }
    regularise(wall, 0.01f, 1);
    compare(wall, 2e-3, "flat wall");

    // Empty sky: every feature constant (all zero apart from the constant column).
    Block sky(10);
    for (int k = 0; k < kRows; ++k) {
        sky.at(0, k) = 1.0f;
        for (int c = 0; c < 3; ++c) sky.at(10 + c, k) = 0.8f + 0.2f * uniform(9, c, k);
    }
    regularise(sky, 0.01f, 2);
    compare(sky, 2e-3, "sky");
}

TEST(Householder, UnregularisedRankDeficiencyGivesFiniteMeanFit) {
    // Without noise the dependent columns are dropped: the fit is still the block mean.
    Block b(10);
    for (int k = 0; k < kRows; ++k) {
        b.at(0, k) = 1.0f;
        for (int f = 1; f < 10; ++f) b.at(f, k) = 0.3f;
        for (int c = 0; c < 3; ++c) b.at(10 + c, k) = float(k % 7);
    }
    double mean = 0;
    for (int k = 0; k < kRows; ++k) mean += k % 7;
    mean /= kRows;
    for (const NamedSolver& solver : kSolvers) {
        SCOPED_TRACE(solver.name);
        std::vector<float> coeffs(30);
        std::vector<float> work = b.cols;
        int dropped = solver.solve(work.data(), 10, kRows, coeffs.data());
        EXPECT_EQ(dropped, 9);
        for (float c : coeffs) ASSERT_TRUE(std::isfinite(c));
        EXPECT_NEAR(coeffs[0], mean, 1e-4);
    }
}

// The fast and the CUDA team solvers' tolerance against the reference: coefficients of
// well-conditioned blocks within 1e-4 relative (only the summation order differs), the same columns
// dropped, and any row count (masked heads when rows are whole vectors, scalar heads and tails
// around the body when not).
TEST(Householder, FastSolverMatchesReferenceForAnyRowCount) {
    for (int rows : {64, 72, 81, 144, 256, 1024, 4096}) {
        for (uint32_t trial = 0; trial < 5; ++trial) {
            const int M = 10;
            std::vector<float> cols(size_t(M + 3) * rows);
            for (int k = 0; k < rows; ++k) {
                cols[size_t(k)] = 1.0f;
                for (int f = 1; f < M; ++f)
                    cols[size_t(f) * rows + k] = 2 * uniform(trial, f, k) - 1;
                // Column 5 duplicates column 1 in half the trials: a rank deficiency.
                if (trial % 2) cols[size_t(5) * rows + k] = cols[size_t(1) * rows + k];
                for (int c = 0; c < 3; ++c)
                    cols[size_t(M + c) * rows + k] = 0.5f +
                                                     0.3f * cols[size_t(2) * rows + k] * (c + 1) +
                                                     0.2f * uniform(trial + 7, c, k);
            }
            std::vector<float> a = cols, b = cols, d = cols, ca(M * 3), cb(M * 3), cs(M * 3),
                               cd(M * 3);
            const int droppedA = solveHouseholder(a.data(), M, rows, ca.data());
            const int droppedB = cpu::solveHouseholderFast(b.data(), M, rows, cb.data());
            EXPECT_EQ(droppedA, droppedB) << rows << " rows, trial " << trial;
            EXPECT_EQ(solveHouseholderTeam(d.data(), M, rows, cd.data()), droppedA)
                << "cuda team, " << rows << " rows, trial " << trial;
            // The fitter's padded column stride gives the same bits as contiguous columns.
            const long stride = cpu::qrColumnStride(rows);
            std::vector<float> padded(size_t(M + 3) * size_t(stride), -7.0f);
            for (int f = 0; f < M + 3; ++f)
                std::copy_n(cols.data() + size_t(f) * rows, rows, padded.data() + f * stride);
            EXPECT_EQ(cpu::solveHouseholderFast(padded.data(), M, rows, stride, cs.data()),
                      droppedB);
            EXPECT_EQ(cs, cb) << rows << " rows, trial " << trial;
            for (int k = 0; k < rows; ++k)
                for (int c = 0; c < 3; ++c) {
                    double fa = 0, fb = 0, fd = 0;
                    for (int f = 0; f < M; ++f) {
                        fa += double(ca[f * 3 + c]) * cols[size_t(f) * rows + k];
                        fb += double(cb[f * 3 + c]) * cols[size_t(f) * rows + k];
                        fd += double(cd[f * 3 + c]) * cols[size_t(f) * rows + k];
                    }
                    ASSERT_NEAR(fa, fb, 1e-4 * (1.0 + std::fabs(fa)))
                        << rows << " rows, trial " << trial << ", row " << k;
                    ASSERT_NEAR(fa, fd, 1e-4 * (1.0 + std::fabs(fa)))
                        << "cuda team, " << rows << " rows, trial " << trial << ", row " << k;
                }
        }
    }
}

} // namespace
} // namespace bmfr
