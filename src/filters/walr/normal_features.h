// WALR's regression features (paper section 5.2): the view-space normal in two octahedral
// coordinates (Cigolle et al. 2014), remapped to [0, 1]. Camera-facing normals fill the inner
// diamond, so the features are continuous over everything the camera sees.
#pragma once
#include "core/octahedral.h"
#include "core/view_basis.h"
#include <cmath>

namespace bmfr {

/// The two features of a surface with world normal n at world position p: n flipped towards
/// the camera when it faces away (normal mapping), in view space, octahedral, halved: in
/// [-0.5, 0.5], 0 for a normal facing the camera. The regression has an intercept, so a shift
/// of the features changes nothing but rounding; centred, the averages of their products stay
/// small, and so do half averages' rounding errors in the features' variances.
BMFR_HD Vec2 walrNormalFeatures(Vec3 n, Vec3 p, const ViewBasis& view) {
    if (dot(n, view.eye - p) < 0) n = -1.0f * n;
    const Vec2 o = octahedralEncode({dot(n, view.right), dot(n, view.down), dot(n, view.toward)});
    return {0.5f * o.x, 0.5f * o.y};
}

} // namespace bmfr
