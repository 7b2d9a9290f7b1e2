#include "filters/svgf/svgf_settings_table.h"
#include "temporal/temporal_settings_table.h"

namespace bmfr {

namespace {

using S = SvgfSettings;

// clang-format off
SettingsTable<S> ownSettings() {
    return {
        {"colorAlpha", "svgf-color-alpha", "", {0, 1, true},
         "colour accumulation minimum new-frame weight (cumulative average before it)",
         BMFR_FIELD(S, colorAlpha)},
        {"momentsAlpha", "svgf-moments-alpha", "", {0, 1, true},
         "luminance moments minimum new-frame weight", BMFR_FIELD(S, momentsAlpha)},
        {"iterations", "svgf-iterations", "levels", {1, 8},
         "a-trous levels (steps 1, 2, 4, ... pixels)", BMFR_FIELD(S, iterations)},
        {"kernelRadius", "svgf-kernel-radius", "taps", {1, 2},
         "2 = 5x5 B3 spline (Schied), 1 = 3x3 (progressive variant)", BMFR_FIELD(S, kernelRadius)},
        {"reverseLevels", "svgf-reverse-levels", "", {},
         "coarse-to-fine level order (progressive variant); the step-1 level still feeds the "
         "colour history",
         BMFR_FIELD(S, reverseLevels)},
        {"phiDepth", "svgf-phi-depth", "", {0, 1e6, true},
         "depth edge stopping sigma_z: exp(-|z0-z1| / (sigma_z |grad z . offset| + eps))",
         BMFR_FIELD(S, phiDepth)},
        {"phiNormal", "svgf-phi-normal", "", {1, 1024},
         "normal edge-stopping exponent sigma_n: weight max(0, n0.n1)^sigma_n",
         BMFR_FIELD(S, phiNormal)},
        {"phiLuminance", "svgf-phi-luminance", "", {0, 1e6, true},
         "luminance edge stopping sigma_l: exp(-|l0-l1| / (sigma_l sqrt(var) + eps))",
         BMFR_FIELD(S, phiLuminance)},
        {"spatialVarianceFrames", "svgf-spatial-variance-frames", "frames", {0, 255},
         "7x7 spatial variance estimate below this history length; 0 = off (progressive)",
         BMFR_FIELD(S, spatialVarianceFrames)},
    };
}
// clang-format on

} // namespace

const SettingsTable<SvgfSettings>& svgfSettingsTable() {
    static const SettingsTable<SvgfSettings> table = withTemporalSettings(ownSettings());
    return table;
}

void validate(const SvgfSettings& s) {
    checkSettings(svgfSettingsTable(), s, "SVGF setting");
}

} // namespace bmfr
