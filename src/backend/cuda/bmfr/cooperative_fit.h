// The BMFR fitting kernel (paper section 4.2) as one thread team per block, the GPU's shape of
// it: the team gathers the block into a column-major matrix in shared memory, every column
// reduction is a fixed tree over the team's partial sums, and one thread does each Householder
// step's scalar work through HouseholderSteps (the CPU solvers' own). The weighted sum
// re-evaluates the noise-free features per pixel rather than keeping a second copy of them.
// BMFR_HD and templated on the team (backend/cuda/team.h): the GPU runs it in
// cuda_fit_kernel.cu, and the host tests run the same code against the reference fitBlock.
#pragma once
#include "backend/cuda/team.h"
#include "filters/bmfr/fitting_kernel.h"

namespace bmfr::cuda {

/// The scalar state of one block's fit, in the team's shared memory.
struct TeamFitState {
    HouseholderSteps q;
    float lo[kMaxFeatures], hi[kMaxFeatures]; ///< each feature column's range in the block
    float factor[kMaxFeatures + 3];           ///< 2 v.a_j / v.v of the current step
    float coeffs[kMaxFeatures * 3];
    int histogram[kMaskBuckets]; ///< excludeEmitters: the block's luminance histogram
    float maskThreshold;         ///< and the luminance above which a pixel is a candidate
};

/// Partial sums per thread: min and max of every feature, or one dot product per column.
BMFR_HD int teamFitPartials(int featureCount) {
    return 2 * featureCount > featureCount + 3 ? 2 * featureCount : featureCount + 3;
}

/// Where one block's fit keeps its data.
struct TeamFitMemory {
    TeamFitState* state;
    float* partial; ///< teamFitPartials(M) x team size
    float* matrix;  ///< (M + 3) x W, column-major: noised scaled features, then colour
    uint8_t* mask;  ///< W: the emitter mask (emitter_exclusion.h)
    uint8_t* next;  ///< W: a stage's new bits, merged into `mask` after a barrier
};

/// Combines partial[c * T + t] over the T threads into partial[c * T] for columns
/// [0, count), in a fixed tree (T a power of two), by op(c, x, y).
template <class Team, class Op>
BMFR_HD void teamReduce(const Team& team, float* partial, int count, Op op) {
    const int T = team.size();
    // On the device the levels below 32 run in the first warp through shuffles (T >= 32): the
    // same pairs in the same order, so the same sums, with five barriers fewer.
    const int lastPhase = Team::kWarps ? 32 : 1;
    for (int s = T / 2; s >= lastPhase; s /= 2)
        team.parallel([&](int t) {
            if (t < s)
                for (int c = 0; c < count; ++c)
                    partial[c * T + t] = op(c, partial[c * T + t], partial[c * T + t + s]);
        });
#if defined(__CUDA_ARCH__)
    if constexpr (Team::kWarps)
        team.parallel([&](int t) {
            if (t >= 32) return;
            for (int c = 0; c < count; ++c) {
                float v = partial[c * T + t];
                for (int s = 16; s > 0; s /= 2) {
                    const float other = __shfl_down_sync(0xffffffffu, v, unsigned(s));
                    if (t < s) v = op(c, v, other);
                }
                if (t == 0) partial[c * T] = v;
            }
        });
#endif
}

/// One image pixel's feature sources: its normal and position, read once for all features.
struct TeamPixel {
    long idx;
    float n[3], p[3];
    template <class H> BMFR_HD TeamPixel(const BlockFitOf<H>& a, long i) : idx(i) {
        for (int c = 0; c < 3; ++c) n[c] = a.normal[3 * i + c], p[c] = a.position[3 * i + c];
    }
};

/// Feature f of a pixel, unscaled (gatherBlock and buildFeatureColumns, per pixel).
template <class H> BMFR_HD float teamFeature(const BlockFitOf<H>& a, int f, const TeamPixel& px) {
    const Feature& feat = a.features[f];
    if (feat.source == FeatureSource::Extra) {
        const float v = a.in.extras[feat.extraIndex][px.idx];
        return raiseFeature(std::isfinite(v) ? v : 0.0f, feat.exponent);
    }
    return featureValue(feat, px.n, px.p, nullptr);
}

/// solveHouseholder's contract for a team: QR of the (M + 3) x W column-major matrix `A`
/// (overwritten), coefficients into st.coeffs, dependent columns counted in st.q.deficient.
/// `P` holds (M + 3) x team-size partial sums; st.q must be fresh.
template <class Team>
BMFR_HD void teamHouseholder(const Team& team, float* A, int M, int W, float* P, TeamFitState& st) {
    const int C = M + 3, T = team.size();
    // Step k reflects column k onto e_k.
    for (int k = 0; k < M; ++k) {
        const int J = C - k; // columns k .. C-1; partial j holds sum_{i>k} x_i a_(k+j),i
        team.parallel([&](int t) {
            const float* x = A + long(k) * W;
            for (int j = 0; j < J; ++j) {
                const float* col = A + long(k + j) * W;
                float s = 0.0f;
                for (int i = t; i < W; i += T)
                    if (i > k) s += x[i] * col[i];
                P[j * T + t] = s;
            }
        });
        teamReduce(team, P, J, [](int, float x, float y) { return x + y; });
        team.single([&] {
            const float vtv = st.q.reflect(A, k, C, W, P[0]);
            if (st.q.dead[k]) return;
            const float vk = A[long(k) * W + k];
            for (int j = k + 1; j < C; ++j) {
                float* col = A + long(j) * W;
                const float f = 2.0f * (vk * col[k] + P[(j - k) * T]) / vtv;
                st.factor[j] = f;
                col[k] -= f * vk;
                st.q.R[k][j] = col[k];
            }
        });
        team.parallel([&](int t) {
            if (st.q.dead[k]) return;
            const float* v = A + long(k) * W;
            for (int i = t; i < W; i += T)
                if (i > k)
                    for (int j = k + 1; j < C; ++j) A[long(j) * W + i] -= st.factor[j] * v[i];
        });
    }
    team.single([&] { st.q.solve(M, st.coeffs); });
}

/// mask[k] |= bits(k) for every block pixel, where bits(k) reads the neighbours' mask: the new
/// bits go to `next` first, so no thread writes a byte that another reads in the same phase.
/// (The bits read and written differ, so the result is the sequential one either way; this
/// keeps the phase free of data races.)
template <class Team, class Bits>
BMFR_HD void teamMaskStage(const Team& team, uint8_t* mask, uint8_t* next, int W, Bits bits) {
    const int T = team.size();
    team.parallel([&](int t) {
        for (int k = t; k < W; k += T) next[k] = bits(k);
    });
    team.parallel([&](int t) {
        for (int k = t; k < W; k += T) mask[k] |= next[k];
    });
}

/// clampFireflies for a team: the threshold on one thread, the stages pixel-parallel.
template <class Team, class H>
BMFR_HD void teamClampFireflies(const Team& team, const BlockFitOf<H>& a, int bx, int by, float* A,
                                int M, const TeamFitMemory& mem) {
    const int B = a.grid.blockSize, W = B * B, T = team.size();
    TeamFitState& st = *mem.state;
    uint8_t *mask = mem.mask, *next = mem.next;
    float* z[3] = {A + long(M) * W, A + long(M + 1) * W, A + long(M + 2) * W};
    auto lum = [&](int k) { return luminance({z[0][k], z[1][k], z[2][k]}); };
    team.single([&] { st.maskThreshold = blockThreshold(W, kFireflyRatio, lum, st.histogram); });
    team.parallel([&](int t) {
        for (int k = t; k < W; k += T) mask[k] = fireflyCandidate(lum(k), st.maskThreshold);
    });
    teamMaskStage(team, mask, next, W, [&](int k) { return fireflyDense(mask, B, k); });
    // Reads the neighbours' bits and scales only its own pixel's colour.
    team.parallel([&](int t) {
        for (int k = t; k < W; k += T) {
            float f = fireflyScale(mask, B, k, lum(k), st.maskThreshold);
            if (f != 1.0f) f = fireflyFade(f, blockFadeLength(a, bx, by, k));
            if (f != 1.0f)
                for (int c = 0; c < 3; ++c) z[c][k] *= f;
        }
    });
}

/// excludeEmitterRows for a team: the mask's stages pixel-parallel (the histogram on one thread),
/// then the excluded rows of the M + 3 columns of `A` zeroed.
template <class Team, class H>
BMFR_HD void teamEmitterMask(const Team& team, const BlockFitOf<H>& a, int bx, int by, float* A,
                             const TeamFitMemory& mem) {
    const BlockGrid& g = a.grid;
    const int B = g.blockSize, W = B * B, M = a.featureCount, T = team.size();
    TeamFitState& st = *mem.state;
    uint8_t *mask = mem.mask, *next = mem.next;
    const InputModes& modes = a.emitters.modes;
    auto accumulated = [&](int k) {
        return luminance({A[long(M) * W + k], A[long(M + 1) * W + k], A[long(M + 2) * W + k]});
    };
    auto pixel = [&](int k) {
        bool owned;
        return blockPixel(g, bx, by, k, owned);
    };
    team.single([&] {
        st.maskThreshold = emitterThreshold(W, a.emitters.ratio, accumulated, st.histogram);
    });
    team.parallel([&](int t) {
        for (int k = t; k < W; k += T)
            mask[k] = maskCandidate(accumulated(k), a.in, modes, pixel(k), st.maskThreshold);
    });
    team.parallel([&](int t) {
        for (int k = t; k < W; k += T)
            mask[k] |= maskSeed(mask[k], a.in, modes, pixel(k), st.maskThreshold, accumulated(k),
                                wasEmitter(a.emitters, pixel(k), g.width, g.height));
    });
    teamMaskStage(team, mask, next, W, [&](int k) { return maskExcluded(mask, B, k); });
    teamMaskStage(team, mask, next, W, [&](int k) { return maskGrown(mask, B, k); });
    team.parallel([&](int t) {
        for (int k = t; k < W; k += T) {
            mask[k] = maskWithGrowth(mask[k]);
            if (mask[k] & kMaskExcluded)
                for (int f = 0; f < M + 3; ++f) A[long(f) * W + k] = 0.0f;
        }
    });
}

/// Fits block (bx, by) with `team`: fitBlock's result, with the QR's sums in tree order.
template <class Team, class H>
BMFR_HD void fitBlockTeam(const Team& team, const BlockFitOf<H>& a, int bx, int by,
                          const TeamFitMemory& mem) {
    const BlockGrid& g = a.grid;
    const int W = g.blockSize * g.blockSize, M = a.featureCount, T = team.size();
    float* A = mem.matrix;
    float* P = mem.partial;
    TeamFitState& st = *mem.state;

    team.parallel([&](int t) {
        for (int k = t; k < W; k += T) {
            bool owned;
            const TeamPixel px(a, blockPixel(g, bx, by, k, owned));
            for (int f = 0; f < M; ++f) A[long(f) * W + k] = teamFeature(a, f, px);
            for (int c = 0; c < 3; ++c) A[long(M + c) * W + k] = a.color[3 * px.idx + c];
        }
    });

    // Each feature's range over the block, for the authors' block scaling.
    team.parallel([&](int t) {
        for (int f = 0; f < M; ++f) {
            float lo = INFINITY, hi = -INFINITY;
            for (int k = t; k < W; k += T) {
                const float v = A[long(f) * W + k];
                lo = v < lo ? v : lo;
                hi = hi < v ? v : hi;
            }
            P[f * T + t] = lo;
            P[(M + f) * T + t] = hi;
        }
    });
    teamReduce(team, P, 2 * M,
               [M](int c, float x, float y) { return c < M ? (y < x ? y : x) : (x < y ? y : x); });
    team.single([&] {
        st.q = HouseholderSteps{};
        for (int f = 0; f < M; ++f) st.lo[f] = P[f * T], st.hi[f] = P[(M + f) * T];
    });
    team.parallel([&](int t) {
        for (int f = 0; f < M; ++f) {
            const bool scaled = a.features[f].scaled;
            for (int k = t; k < W; k += T) {
                float& v = A[long(f) * W + k];
                const float clean = scaled ? scaleFeature(v, st.lo[f], st.hi[f]) : v;
                v = clean + a.noise[long(f) * W + k];
            }
        }
    });

    if (a.clampFireflies) teamClampFireflies(team, a, bx, by, A, M, mem);
    if (a.emitters.on) teamEmitterMask(team, a, bx, by, A, mem);
    teamHouseholder(team, A, M, W, P, st);

    // Weighted sum of the noise-free features, written to the pixels the block owns.
    team.parallel([&](int t) {
        for (int k = t; k < W; k += T) {
            bool owned;
            const long idx = blockPixel(g, bx, by, k, owned);
            if (!owned) continue;
            const TeamPixel px(a, idx);
            float sum[3] = {0.0f, 0.0f, 0.0f};
            for (int f = 0; f < M; ++f) {
                float v = teamFeature(a, f, px);
                if (a.features[f].scaled) v = scaleFeature(v, st.lo[f], st.hi[f]);
                for (int c = 0; c < 3; ++c) sum[c] += st.coeffs[f * 3 + c] * v;
            }
            for (int c = 0; c < 3; ++c) a.fitted[3 * idx + c] = sum[c] > 0.0f ? sum[c] : 0.0f;
            if (!a.emitters.on) continue;
            const bool emitter = maskEmitter(mem.mask[k]);
            if (emitter) store3(a.fitted, idx, emitterSample(a.in, idx, a.emitters.modes));
            // The second grid restores its emitters too but keeps no bits (null) of its own.
            if (a.emitters.bits) a.emitters.bits[idx] = emitter;
        }
    });
}

} // namespace bmfr::cuda
