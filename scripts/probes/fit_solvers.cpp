// Probe: BMFR's block fit by the CPU backend's Householder QR against normal equations (the Gram
// matrix A^T [A z] in double, in float, and in float after centring each column, then LDL^T in
// double), on 16x16 blocks of the default 10 features + 3 colours. Prints ns per block (best of
// 15 passes over 512 blocks, the copy of the block that the QR overwrites included in each) and
// each solver's largest relative error of the fitted value against a long-double Gram-Schmidt QR.
// Not part of the build; from the repository root, after a build in build/:
//   g++ -O3 -march=native -std=c++20 scripts/probes/fit_solvers.cpp build/libbmfr.a -ltbb
//   ./a.out
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <vector>

namespace bmfr::cpu {
int solveHouseholderFast(float* columns, int featureCount, int rows, long stride, float* coeffs);
}

namespace {

constexpr int W = 256, M = 10, T = 13;
constexpr long S = (W + 7) / 8 * 8 + 16; // qrColumnStride(W)
typedef double d8 __attribute__((vector_size(64)));
typedef float f8 __attribute__((vector_size(32)));
typedef float f16 __attribute__((vector_size(64)));

/// Lanes [r, r + L) of a column as V: doubles (widened, L = 8) or floats (L = 16).
template <class V> V lanesAt(const float* p) {
    if constexpr (sizeof(V) / sizeof(V{}[0]) == 8) {
        f8 v;
        std::memcpy(&v, p, sizeof v);
        return __builtin_convertvector(v, d8);
    } else {
        V v;
        std::memcpy(&v, p, sizeof v);
        return v;
    }
}

/// G[i][j] for i < M, j >= i, j < T: tiles of 5 x 4 entries, the products and sums in V's
/// element type (d8: double, f16: float, sixteen lanes), the lanes summed in double.
template <class V> void gram(const float* a, double G[T][T]) {
    constexpr int L = sizeof(V) / sizeof(V{}[0]);
    for (int i0 = 0; i0 < M; i0 += 5)
        for (int j0 = i0 / 4 * 4; j0 < T; j0 += 4) {
            const int nj = std::min(4, T - j0);
            V acc[5][4] = {};
            for (int r = 0; r < W; r += L) {
                V ci[5], cj[4] = {};
                for (int i = 0; i < 5; ++i) ci[i] = lanesAt<V>(a + (i0 + i) * S + r);
                for (int j = 0; j < nj; ++j) cj[j] = lanesAt<V>(a + (j0 + j) * S + r);
                for (int i = 0; i < 5; ++i)
                    for (int j = 0; j < 4; ++j) acc[i][j] += ci[i] * cj[j];
            }
            for (int i = 0; i < 5; ++i)
                for (int j = 0; j < nj; ++j) {
                    double s = 0;
                    for (int l = 0; l < L; ++l) s += acc[i][j][l];
                    G[i0 + i][j0 + j] = s;
                }
        }
}
[[gnu::noinline]] void gramDouble(const float* a, double G[T][T]) {
    gram<d8>(a, G);
}
[[gnu::noinline]] void gramFloat(const float* a, double G[T][T]) {
    gram<f16>(a, G);
}

/// gramFloat of the columns less their means (into c), the means added back in double.
[[gnu::noinline]] void gramCentred(const float* a, float* c, double G[T][T]) {
    double mean[T];
    for (int j = 0; j < T; ++j) {
        f16 acc = {};
        for (int r = 0; r < W; r += 16) {
            f16 v;
            std::memcpy(&v, a + j * S + r, sizeof v);
            acc += v;
        }
        double s = 0;
        for (int l = 0; l < 16; ++l) s += acc[l];
        const float m = float(s / W);
        mean[j] = m;
        for (int r = 0; r < W; ++r) c[j * S + r] = a[j * S + r] - m;
    }
    gramFloat(c, G);
    for (int i = 0; i < M; ++i)
        for (int j = i; j < T; ++j) G[i][j] += W * mean[i] * mean[j];
}

/// LDL^T of the M x M feature block of G with right-hand sides G[i][M .. M + 2]; a pivot below
/// 1e-10 of the largest diagonal (the QR's 1e-5 on norms, squared) is dependent: coefficient 0.
[[gnu::noinline]] void ldlSolve(const double G[T][T], float* coeffs) {
    double L[M][M] = {}, D[M], y[M][3], x[M][3];
    bool dead[M] = {};
    double largest = 0;
    for (int k = 0; k < M; ++k) {
        double d = G[k][k];
        for (int j = 0; j < k; ++j) d -= L[k][j] * L[k][j] * D[j];
        largest = std::fmax(largest, G[k][k]);
        dead[k] = !(d > 1e-10 * largest) || !(d > 1e-60);
        D[k] = dead[k] ? 0 : d;
        for (int i = k + 1; i < M && !dead[k]; ++i) {
            double s = G[k][i];
            for (int j = 0; j < k; ++j) s -= L[i][j] * L[k][j] * D[j];
            L[i][k] = s / d;
        }
    }
    for (int c = 0; c < 3; ++c) {
        for (int k = 0; k < M; ++k) {
            double s = G[k][M + c];
            for (int j = 0; j < k; ++j) s -= L[k][j] * y[j][c];
            y[k][c] = s;
        }
        for (int k = M - 1; k >= 0; --k) {
            double s = dead[k] ? 0 : y[k][c] / D[k];
            for (int j = k + 1; j < M && !dead[k]; ++j) s -= L[j][k] * x[j][c];
            x[k][c] = s;
        }
    }
    for (int k = 0; k < M; ++k)
        for (int c = 0; c < 3; ++c) coeffs[k * 3 + c] = float(x[k][c]);
}

/// The independent reference: modified Gram-Schmidt QR in long double.
void referenceSolve(const float* a, double* coeffs) {
    std::vector<long double> q(size_t(T * W));
    for (int j = 0; j < T; ++j)
        for (int r = 0; r < W; ++r) q[size_t(j * W + r)] = a[j * S + r];
    long double R[T][T] = {};
    for (int k = 0; k < M; ++k) {
        long double n = 0;
        for (int r = 0; r < W; ++r) n += q[size_t(k * W + r)] * q[size_t(k * W + r)];
        n = std::sqrt(n);
        R[k][k] = n;
        for (int r = 0; r < W; ++r) q[size_t(k * W + r)] /= n;
        for (int j = k + 1; j < T; ++j) {
            long double d = 0;
            for (int r = 0; r < W; ++r) d += q[size_t(k * W + r)] * q[size_t(j * W + r)];
            R[k][j] = d;
            for (int r = 0; r < W; ++r) q[size_t(j * W + r)] -= d * q[size_t(k * W + r)];
        }
    }
    for (int c = 0; c < 3; ++c)
        for (int k = M - 1; k >= 0; --k) {
            long double s = R[k][M + c];
            for (int j = k + 1; j < M; ++j) s -= R[k][j] * coeffs[j * 3 + c];
            coeffs[k * 3 + c] = double(s / R[k][k]);
        }
}

} // namespace

int main() {
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> u(-1, 1);
    const int blocks = 512;
    // The default features (1, n, p, p^2) scaled to [0, 1] with BMFR's +-0.005 regularisation
    // noise, on four kinds of block: a flat wall, a tilted plane, a curved one, random normals;
    // colours a smooth function of them with 80% noise.
    std::vector<float> data(size_t(blocks * T * S)), clean(size_t(blocks * M * W));
    for (int b = 0; b < blocks; ++b) {
        float* a = data.data() + b * T * S;
        float* cl = clean.data() + b * M * W;
        const int kind = b % 4;
        const float nx = u(rng), ny = u(rng), nz = u(rng);
        for (int r = 0; r < W; ++r) {
            const float x = float(r % 16) / 15.0f, y = float(r / 16) / 15.0f;
            const float bend = kind == 2 ? 0.3f * x * x : 0.0f;
            float f[M];
            f[0] = 1;
            f[1] = kind == 3 ? 0.5f + 0.5f * u(rng) : 0.5f + 0.1f * nx + bend;
            f[2] = kind == 3 ? 0.5f + 0.5f * u(rng) : 0.5f + 0.1f * ny;
            f[3] = kind == 3 ? 0.5f + 0.5f * u(rng) : 0.5f + 0.1f * nz;
            f[4] = x, f[5] = y, f[6] = kind == 0 ? 0.0f : 0.5f * x + 0.3f * y + bend;
            for (int k = 0; k < 3; ++k) f[7 + k] = f[4 + k] * f[4 + k];
            const float light = 0.2f + 0.5f * x + 0.1f * y * y + 0.3f * f[1];
            for (int k = 0; k < M; ++k) {
                cl[k * W + r] = f[k];
                a[k * S + r] = f[k] + (k ? 0.005f * u(rng) : 0.0f);
            }
            for (int c = 0; c < 3; ++c)
                a[(M + c) * S + r] = light * (1 + 0.2f * float(c)) * (1 + 0.8f * u(rng));
        }
    }
    const char* names[4] = {"Householder QR (the CPU backend's)", "Gram in double + LDL^T",
                            "Gram in float + LDL^T", "centred Gram in float + LDL^T"};
    std::vector<float> work(size_t(T * S)), centred(size_t(T * S));
    std::vector<float> coeffs[4];
    for (auto& c : coeffs) c.resize(size_t(blocks * 30));
    double best[4] = {1e30, 1e30, 1e30, 1e30};
    for (int pass = 0; pass < 15; ++pass)
        for (int s = 0; s < 4; ++s) {
            const auto t0 = std::chrono::steady_clock::now();
            for (int b = 0; b < blocks; ++b) {
                std::memcpy(work.data(), data.data() + b * T * S, sizeof(float) * size_t(T * S));
                float* out = coeffs[s].data() + b * 30;
                double G[T][T];
                if (s == 0) bmfr::cpu::solveHouseholderFast(work.data(), M, W, S, out);
                if (s == 1) gramDouble(work.data(), G);
                if (s == 2) gramFloat(work.data(), G);
                if (s == 3) gramCentred(work.data(), centred.data(), G);
                if (s > 0) ldlSolve(G, out);
            }
            const auto t1 = std::chrono::steady_clock::now();
            best[s] = std::min(best[s],
                               std::chrono::duration<double, std::nano>(t1 - t0).count() / blocks);
        }
    double error[4][4] = {};
    std::vector<double> ref(30);
    for (int b = 0; b < blocks; ++b) {
        referenceSolve(data.data() + b * T * S, ref.data());
        const float* cl = clean.data() + b * M * W;
        for (int r = 0; r < W; ++r)
            for (int c = 0; c < 3; ++c) {
                double want = 0, got[4] = {};
                for (int k = 0; k < M; ++k) {
                    want += ref[size_t(k * 3 + c)] * cl[k * W + r];
                    for (int s = 0; s < 4; ++s)
                        got[s] += double(coeffs[s][size_t(b * 30 + k * 3 + c)]) * cl[k * W + r];
                }
                for (int s = 0; s < 4; ++s)
                    error[s][b % 4] = std::fmax(error[s][b % 4], std::fabs(got[s] - want) /
                                                                     (std::fabs(want) + 1e-3));
            }
    }
    std::printf("solver                              ns/block  largest relative error "
                "(flat, tilted, curved, random)\n");
    for (int s = 0; s < 4; ++s)
        std::printf("%-36s %8.0f  %.1e %.1e %.1e %.1e\n", names[s], best[s], error[s][0],
                    error[s][1], error[s][2], error[s][3]);
}
