// The CUDA backend's block-cooperative fit (backend/cuda/bmfr/cooperative_fit.h), run on the
// host by HostTeam, against the reference fitBlock: the same algorithm with the QR's sums in
// tree order, so within the conformance suite's tolerance. Runs on every machine; the GPU
// runs this very code.
#include "backend/cuda/bmfr/cooperative_fit.h"
#include "backend/reference/bmfr/reference_householder.h"
#include "core/hash.h"
#include "filters/bmfr/regularisation_noise.h"
#include "test_support.h"
#include <algorithm>
#include <bmfr/features.h>
#include <cmath>
#include <gtest/gtest.h>
#include <string>
#include <vector>

namespace bmfr {
namespace {

using testing::uniform;

/// A w x h frame of smooth features (a tilted floor meeting a wall), an extra buffer, and a
/// noisy colour that the features can mostly explain.
struct Frame {
    int w, h;
    std::vector<float> normal, position, color, extra, albedo;
    Frame(int width, int height, uint32_t seed) : w(width), h(height) {
        const size_t n = size_t(w) * size_t(h);
        normal.resize(3 * n), position.resize(3 * n), color.resize(3 * n), extra.resize(n);
        albedo.assign(3 * n, 1.0f);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const size_t i = size_t(y) * w + x;
                const bool wall = x > w / 2 + y / 3;
                const float px = float(x) * 0.05f, py = float(y) * 0.04f;
                const float p[3] = {px, wall ? 1.0f + py : 0.0f, wall ? 2.0f : py};
                const float nn[3] = {0.0f, wall ? 0.0f : 1.0f, wall ? -1.0f : 0.0f};
                for (int c = 0; c < 3; ++c) {
                    position[3 * i + c] = p[c] + 3.0f;
                    normal[3 * i + c] = nn[c];
                    color[3 * i + c] = 0.4f + 0.2f * px * (c + 1) + (wall ? 0.3f : 0.0f) +
                                       0.5f * (uniform(seed, uint32_t(i), uint32_t(c)) - 0.5f);
                }
                extra[i] = std::sin(px * 3.0f) + (i % 97 == 0 ? NAN : 0.0f);
            }
    }
    /// Paints a lamp: a flat, bright w x h patch at (x0, y0), the same in every channel.
    Frame& lamp(int x0, int y0, int lw, int lh) {
        for (int y = y0; y < y0 + lh; ++y)
            for (int x = x0; x < x0 + lw; ++x)
                for (int c = 0; c < 3; ++c) color[3 * (size_t(y) * w + x) + c] = 30.0f;
        return *this;
    }
};

/// Both fitters' scratch for M features, blocks of W pixels and a team of `threads`.
struct Scratch {
    std::vector<float> clean, work, sum, sources, partial, matrix;
    std::vector<int> index, histogram;
    std::vector<uint8_t> mask, teamMask, teamNext;
    Scratch(int M, int W, int threads)
        : clean(size_t(M) * size_t(W)), work(size_t(M + 3) * size_t(W)), sum(3 * size_t(W)),
          sources(size_t(6 + 16) * size_t(W)),
          partial(size_t(cuda::teamFitPartials(M)) * size_t(threads)), matrix(work.size()),
          index(size_t(W)), histogram(size_t(kMaskBuckets)), mask(size_t(W)), teamMask(size_t(W)),
          teamNext(size_t(W)) {}
    BlockFitScratch reference() {
        return {clean.data(), work.data(), sum.data(),      sources.data(),
                index.data(), mask.data(), histogram.data()};
    }
    cuda::TeamFitMemory team(cuda::TeamFitState& st) {
        return {&st, partial.data(), matrix.data(), teamMask.data(), teamNext.data()};
    }
};

/// Fits every block of frame `f` with the reference and with a host team of `threads`; returns
/// the worst excess over the conformance tolerance (<= 0 passes).
/// With `history`, every accumulated colour is 10% below the current sample (unsteady), and a
/// previous frame's emitters are given (every other column, through previous pixels a quarter
/// pixel off): only the pixels that were emitters can seed.
double worstExcess(const Frame& f, int blockSize, const std::vector<Feature>& features,
                   float noiseAmplitude, int threads, long frameIndex, bool excludeEmitters = false,
                   bool history = false) {
    const int M = int(features.size()), W = blockSize * blockSize;
    std::vector<float> noise(size_t(M) * W);
    for (int m = 0; m < M; ++m)
        for (int k = 0; k < W; ++k)
            noise[size_t(m) * W + k] =
                regularisationNoise(5, uint32_t(frameIndex), m, k, noiseAmplitude,
                                    features[size_t(m)].source == FeatureSource::One);
    BlockFit a;
    a.grid = makeBlockGrid(f.w, f.h, blockSize, frameIndex);
    a.features = features.data(), a.featureCount = M, a.noise = noise.data();
    a.normal = f.normal.data(), a.position = f.position.data(), a.color = f.color.data();
    std::vector<float> accumulated = f.color, previousPixel(f.extra.size() * 2);
    std::vector<uint8_t> previousEmitter(f.extra.size()), lengths(f.extra.size());
    // Every history length from none to past the firefly clamp's fade.
    for (size_t i = 0; i < lengths.size(); ++i) lengths[i] = uint8_t(1 + i % 7);
    a.length = lengths.data();
    if (history) {
        for (size_t i = 0; i < f.extra.size(); ++i) {
            for (int c = 0; c < 3; ++c) accumulated[3 * i + c] *= 0.9f;
            const int x = int(i % size_t(f.w)), y = int(i / size_t(f.w));
            previousPixel[2 * i] = float(x) + 0.25f, previousPixel[2 * i + 1] = float(y) + 0.5f;
            previousEmitter[i] = x % 2;
        }
        a.color = accumulated.data();
    }
    a.in.extras[0] = f.extra.data(), a.in.extraCount = 1;
    a.in.width = f.w, a.in.height = f.h;
    a.in.color = f.color.data(), a.in.albedo = f.albedo.data();
    a.in.normal = f.normal.data(), a.in.position = f.position.data();
    std::vector<uint8_t> referenceBits(f.extra.size(), 7), teamBits(f.extra.size(), 9);
    std::vector<float> reference(f.color.size(), -1.0f), team(f.color.size(), -1.0f);
    Scratch scratch(M, W, threads);
    const BlockFitScratch sc = scratch.reference();
    const cuda::HostTeam host{threads};
    cuda::TeamFitState st{};
    const cuda::TeamFitMemory mem = scratch.team(st);
    for (int by = 0; by < a.grid.blocksY; ++by)
        for (int bx = 0; bx < a.grid.blocksX; ++bx) {
            a.fitted = reference.data();
            a.emitters = {excludeEmitters, 16.0f, InputModes{}, referenceBits.data()};
            if (history) {
                a.emitters.previous = previousEmitter.data();
                a.emitters.previousX = previousPixel.data();
                a.emitters.previousY = previousPixel.data() + 1, a.emitters.previousStep = 2;
            }
            a.clampFireflies = excludeEmitters;
            fitBlock(a, bx, by, sc, reference::householderSolver());
            a.fitted = team.data();
            a.emitters.bits = teamBits.data();
            cuda::fitBlockTeam(host, a, bx, by, mem);
        }
    if (excludeEmitters) {
        EXPECT_EQ(referenceBits, teamBits);
        EXPECT_GT(std::count(teamBits.begin(), teamBits.end(), 1), 0) << "no emitter found";
    }
    double worst = -1.0;
    for (size_t i = 0; i < team.size(); ++i) {
        EXPECT_GE(team[i], 0.0f) << "pixel " << i / 3 << " not written or negative";
        const double excess =
            std::fabs(double(team[i]) - reference[i]) - (1e-4 + 1e-3 * std::fabs(reference[i]));
        worst = std::max(worst, excess);
    }
    return worst;
}

TEST(TeamFit, MatchesTheReferenceFitterOnEveryBlock) {
    const std::vector<Feature> features = defaultFeatures();
    const Frame f(101, 67, 3);
    for (int threads : {256, 64, 32})
        for (long frame : {0L, 5L})
            EXPECT_LE(worstExcess(f, 32, features, 0.01f, threads, frame), 0.0)
                << threads << " threads, frame " << frame;
}

TEST(TeamFit, OtherBlockSizesFeaturesAndRankDeficiency) {
    const Frame f(70, 45, 4);
    const std::vector<Feature> features = defaultFeatures();
    const std::vector<Feature> withExtra =
        parseFeatures("1,n.x,n.y,n.z,p.x,p.y^3,p.z^0.5,p.x^2,extra0^2,extra0");
    for (int block : {8, 20, 64}) {
        SCOPED_TRACE("block size " + std::to_string(block));
        EXPECT_LE(worstExcess(f, block, features, 0.01f, 256, 1), 0.0);
        EXPECT_LE(worstExcess(f, block, withExtra, 0.01f, 128, 2), 0.0);
        // Without regularisation the flat floor's dependent columns are dropped by both. The
        // blocks are rank-deficient, so the fit follows the summation order: against the
        // reference QR summed eight wide (AVX2) the team is within the tolerance, against the
        // same QR summed one by one (the baseline path, or any path under ASan) it is up to
        // 0.0015 beyond it; Householder.* holds both to Eigen's double-precision solve.
        EXPECT_LE(worstExcess(f, block, features, 0.0f, 256, 3), 0.002);
    }
    // A lamp across a block edge, left out of the fit, and fireflies clamped, on every thread
    // count.
    Frame lit(101, 67, 7);
    lit.lamp(20, 25, 24, 6);
    // Fireflies for the clamp that runs with it: one alone, one smeared over 2x2.
    lit.lamp(70, 10, 1, 1).lamp(80, 50, 2, 2);
    for (int threads : {256, 32}) {
        EXPECT_LE(worstExcess(lit, 32, features, 0.01f, threads, 4, true), 0.0) << threads;
        EXPECT_LE(worstExcess(lit, 16, features, 0.01f, threads, 5, true, true), 0.0)
            << threads << ", with history";
    }
    // An image smaller than a block: everything mirrored in.
    EXPECT_LE(worstExcess(Frame(5, 3, 6), 32, features, 0.01f, 256, 0), 0.0);
}

} // namespace
} // namespace bmfr
