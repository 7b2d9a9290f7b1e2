// Random numbers (Wang hash, seeded by pixel, frame and sample) and sample warps.
#pragma once
#include "core/hash.h"
#include "core/vec.h"
#include <cmath>

namespace bmfr::render {

constexpr float kPi = 3.14159265358979f;

/// Stateless-seeded stream: each call hashes a running counter with the seed.
class Rng {
  public:
    Rng(uint32_t pixel, uint32_t frame, uint32_t sample, uint32_t seed)
        : state_(hashKeys(pixel, frame, sample, seed)) {}
    float next() {
        state_ = wangHash(state_ + 0x9e3779b9u);
        return unitFloat(state_);
    }

  private:
    uint32_t state_;
};

/// Orthonormal basis around n (Duff et al. 2017).
inline void basis(Vec3 n, Vec3& t, Vec3& b) {
    float s = n.z >= 0 ? 1.0f : -1.0f;
    float a = -1.0f / (s + n.z), c = n.x * n.y * a;
    t = {1 + s * n.x * n.x * a, s * c, -s * n.x};
    b = {c, s + n.y * n.y * a, -n.y};
}

inline Vec3 toWorld(Vec3 local, Vec3 n) {
    Vec3 t, b;
    basis(n, t, b);
    return local.x * t + local.y * b + local.z * n;
}

/// Cosine-weighted hemisphere around +z; pdf = cos / pi.
inline Vec3 cosineHemisphere(float u1, float u2) {
    float r = std::sqrt(u1), phi = 2 * kPi * u2;
    return {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::fmax(0.0f, 1 - u1))};
}

/// Uniform direction in the cone of half-angle acos(cosMax) around +z; pdf = 1 / solid angle.
inline Vec3 uniformCone(float u1, float u2, float cosMax) {
    float c = 1 - u1 * (1 - cosMax), s = std::sqrt(std::fmax(0.0f, 1 - c * c)), phi = 2 * kPi * u2;
    return {s * std::cos(phi), s * std::sin(phi), c};
}

/// Uniform barycentrics on a triangle.
inline void uniformTriangle(float u1, float u2, float& b1, float& b2) {
    float su = std::sqrt(u1);
    b1 = 1 - su;
    b2 = u2 * su;
}

inline float powerHeuristic(float a, float b) {
    return a * a / (a * a + b * b);
}

} // namespace bmfr::render
