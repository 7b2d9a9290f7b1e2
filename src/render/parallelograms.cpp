#include "render/parallelograms.h"
#include <algorithm>
#include <cmath>

namespace bmfr::render {

bool crossParallelogram(Vec3 o, Vec3 d, Vec3 corner, Vec3 u, Vec3 v, float tMin, float tMax,
                        float& t, float* cosine) {
    const Vec3 n = cross(u, v);
    const float denom = dot(n, d);
    if (std::fabs(denom) < 1e-12f) return false;
    const float tt = dot(n, corner - o) / denom;
    if (!(tt > tMin && tt < tMax)) return false;
    const Vec3 x = o + tt * d - corner;
    const float s = dot(x, u) / dot(u, u), r = dot(x, v) / dot(v, v);
    if (s < 0 || s > 1 || r < 0 || r > 1) return false;
    t = tt;
    if (cosine) *cosine = std::fabs(denom) / length(n);
    return true;
}

ParallelogramSet::ParallelogramSet(std::vector<Parallelogram> shapes) : shapes_(std::move(shapes)) {
    for (const Parallelogram& q : shapes_) {
        areas_.push_back(length(cross(q.edgeU, q.edgeV)));
        area_ += areas_.back();
    }
}

Vec3 ParallelogramSet::point(float s, float t) const {
    // s picks the parallelogram by area and is stretched back to [0, 1) within it.
    float below = 0;
    for (size_t i = 0; i < shapes_.size(); ++i) {
        const Parallelogram& q = shapes_[i];
        const float share = areas_[i] / area_;
        if (s < below + share || i + 1 == shapes_.size()) {
            const float u = std::clamp((s - below) / share, 0.0f, 1.0f);
            return q.corner + u * q.edgeU + t * q.edgeV;
        }
        below += share;
    }
    return {};
}

float ParallelogramSet::pdf(Vec3 d, Vec3 p) const {
    // A point uniform over the total area A: dist^2 / (A cos) per parallelogram the ray crosses.
    float pdf = 0, t = 0, cosL = 0;
    for (const Parallelogram& q : shapes_)
        if (crossParallelogram(p, d, q.corner, q.edgeU, q.edgeV, 0.0f, HUGE_VALF, t, &cosL))
            pdf += t * t / (area_ * cosL);
    return pdf;
}

} // namespace bmfr::render
