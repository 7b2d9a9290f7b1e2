// Feature buffers that BMFR regresses the noisy colour onto, one column of the block matrix each.
#pragma once
#include <bmfr/api.h>
#include <string>
#include <vector>

namespace bmfr {

/// Where a feature column takes its values from.
enum class FeatureSource {
    One,     ///< the constant buffer 1 (must come first; never scaled or noised)
    NormalX, ///< shading normal, world space, unit length
    NormalY,
    NormalZ,
    PositionX, ///< world-space position of the first hit, scene units
    PositionY,
    PositionZ,
    Extra, ///< FrameInput::extras[extraIndex] (e.g. material id, roughness)
};

/// One column of T: source^exponent, optionally min/max-scaled per block.
struct Feature {
    FeatureSource source = FeatureSource::One;
    int extraIndex = 0;    ///< index into FrameInput::extras when source == Extra; [0, 15]
    float exponent = 1.0f; ///< power applied to the raw value; (0, 8], default 1 (2 = "p.x^2")
    /// Per-block scaling (v-min)/(max-min) if max-min > 1, else v-min, as the authors' code.
    /// Default: on for positions and extras, off for normals (already in [-1, 1]).
    bool scaled = true;
};

/// The paper's feature set, eq. (8): [1, n.xyz, p.xyz, p.xyz^2].
BMFR_API std::vector<Feature> defaultFeatures();

/// Parses a comma-separated list such as "1,n.x,n.y,n.z,p.x,p.y,p.z,p.x^2,extra0".
/// Tokens: 1, n.x|n.y|n.z, p.x|p.y|p.z, extraK; each may end in ^E. Throws bmfr::Error.
BMFR_API std::vector<Feature> parseFeatures(const std::string& list);

/// Inverse of parseFeatures.
BMFR_API std::string formatFeatures(const std::vector<Feature>& features);

/// Largest number of feature columns (constant included) a block fit supports.
inline constexpr int kMaxFeatures = 24;

} // namespace bmfr
