// Parallelograms that paths aim at: sky portals (where the sky gets in) and bounce guides (where
// the indirect light comes from). Both pick a point uniformly over their total area, and need
// the solid-angle pdf of that choice for multiple importance sampling.
#pragma once
#include "core/vec.h"
#include <vector>

namespace bmfr::render {

/// corner + s * edgeU + t * edgeV, s, t in [0, 1].
struct Parallelogram {
    Vec3 corner, edgeU, edgeV;
};

/// Where the ray o + t d, t in (tMin, tMax), crosses the parallelogram corner + s u + r v
/// (s, r in [0, 1]): its t and, when asked, the cosine between d and the normal.
bool crossParallelogram(Vec3 o, Vec3 d, Vec3 corner, Vec3 u, Vec3 v, float tMin, float tMax,
                        float& t, float* cosine = nullptr);

/// A set of parallelograms sampled by area: a point uniform over all of them together.
class ParallelogramSet {
  public:
    ParallelogramSet() = default;
    explicit ParallelogramSet(std::vector<Parallelogram> shapes);
    bool empty() const { return shapes_.empty(); }
    float area() const { return area_; }
    const std::vector<Parallelogram>& shapes() const { return shapes_; }
    /// The point (s, t) in [0, 1]^2: s picks the parallelogram by area, then both span it.
    Vec3 point(float s, float t) const;
    /// Solid-angle pdf, seen from p, of point() lying along d (a sum where they overlap).
    float pdf(Vec3 d, Vec3 p) const;

  private:
    std::vector<Parallelogram> shapes_;
    std::vector<float> areas_; ///< of each parallelogram: point() runs on every guided bounce
    float area_ = 0;
};

} // namespace bmfr::render
