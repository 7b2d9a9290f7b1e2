// The CPU backend's SVGF a-trous levels: eight pixels of a row at a time (sixteen on the
// AVX-512 path) over planes of the colour, variance, luminance and guides (which the variance
// estimate writes: cpu_svgf_variance.h), each row padded by an apron whose mask is zero, so
// that a tap past the row's ends needs no bounds test.
// Same taps, order and feedback as the reference (filters/svgf/svgf_kernels.h); rounded
// differently, within the conformance tolerance: each tap's weight one power of two of its
// terms' logarithms (the default normal exponent's by a series, at least 2^-126 where the
// reference's is 0), fused multiply-adds, phiDepth folded into the gradient, the luminance and
// depth terms multiplied by reciprocals (the depth term's shared by a tap and its mirror), and
// the sums by the reciprocal of the weights' sum.
#pragma once
#include "backend/cpu/svgf/cpu_svgf_variance.h"
#include "core/parallel.h"
#include "filters/svgf/svgf_passes.h"
#include <vector>

namespace bmfr::cpu {

class CpuAtrous {
  public:
    /// Sizes the planes for a w x h frame with these settings (firstLevel does it when they
    /// change).
    void reserve(int w, int h, const SvgfSettings& s);
    /// Sizes the planes for a w x h frame and returns the first level's, for the variance
    /// estimate to fill (svgfVarianceRows).
    SvgfFirstLevel firstLevel(int w, int h, const SvgfSettings& s);
    /// The levels from the first, once filled. Writes the step-1 level's RGB to `colorHistory`
    /// (3 floats per pixel), as the reference's runAtrousLevels; returns the set (0 or 1) that
    /// holds the last level.
    int run(ThreadPool& pool, const SvgfSettings& s, float* colorHistory);
    /// Channel k (R, G, B, variance, luminance) of set `set`'s level, at (0, 0) of its image;
    /// rows are pitch() floats apart.
    const float* level(int set, int k) const {
        return planes_.data() + long(Colour + 5 * set + k) * planeFloats_ + apron_;
    }
    long pitch() const { return pitch_; }
    /// Set `set`'s level as RGB + variance, 4 floats per pixel (the debug buffers' copy; the
    /// last level's variance is not made, and its channel holds an earlier level's).
    void copyLevel(int set, float* rgbv) const;

  private:
    /// Colour + 5 s + k: ping-pong set s's R, G, B, variance and luminance (k = 0 .. 4).
    enum Plane { Nx, Ny, Nz, Depth, GradX, GradY, Mask, Colour, Count = Colour + 10 };
    int width_ = 0, height_ = 0, apron_ = 0;
    long pitch_ = 0, planeFloats_ = 0;
    std::vector<float> planes_;

    float* plane(int k) { return planes_.data() + long(k) * planeFloats_ + apron_; }
    float* levelPlane(int set, int k) { return plane(Colour + 5 * set + k); }
    SvgfFirstLevel firstPlanes(); ///< the first level's planes and the guides, as sized
};

} // namespace bmfr::cpu
