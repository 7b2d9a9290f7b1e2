#include "filters/walr/walr_settings_table.h"
#include "temporal/temporal_settings_table.h"
#include <algorithm>
#include <bmfr/error.h>
#include <cmath>

namespace bmfr {

namespace {

using S = WalrSettings;

/// A text field over an enumeration with names[k] for value k.
template <class E, E S::*member, int N> TextField<S> enumField(const char* const (&names)[N]) {
    static const char* const* table = names;
    return {+[](const S& s) { return std::string(table[int(s.*member)]); },
            +[](S& s, const std::string& v) {
                std::string known;
                for (int k = 0; k < N; ++k) {
                    if (v == table[k]) {
                        s.*member = E(k);
                        return;
                    }
                    known += (k ? ", " : "") + std::string(table[k]);
                }
                throw Error("'" + v + "' is not one of " + known);
            }};
}

constexpr const char* kSignals[] = {"color", "diffuse-indirect"};
constexpr const char* kSolvers[] = {"walr", "refwlr"};
constexpr const char* kHistoryTests[] = {"depth", "world"};

// clang-format off
SettingsTable<S> ownSettings() {
    return {
        {"signal", "walr-signal", "", {},
         "what is filtered: color (the demodulated colour, as BMFR) or diffuse-indirect (the "
         "paper: FrameInput::diffuseIndirect alone, the rest of the colour added back unfiltered)",
         enumField<WalrSignal, &S::signal>(kSignals)},
        {"solver", "walr-solver", "", {},
         "walr (a-trous averages) or refwlr (the paper's direct regression over the whole "
         "window, its oracle: some 200x slower at T = 3, 10x more at T = 4)",
         enumField<WalrSolver, &S::solver>(kSolvers)},
        {"iterations", "walr-iterations", "iterations", {0, 5},
         "a-trous iterations T: taps at spacing 3^t, a window of 3^T pixels (4: 81x81, the "
         "paper's); 0 = by size: 3^T nearest 80/1080 of the shorter side, the paper's share "
         "(4 at 720p and 1080p, 3 at 240p to 480p)",
         BMFR_FIELD(S, iterations)},
        {"edgeTracing", "walr-edge-tracing", "", {},
         "a tap's weight is the smallest along its segment, not only at its end",
         BMFR_FIELD(S, edgeTracing)},
        {"edgeStep", "walr-edge-step", "x flat run", {0, 1},
         "stepped edge tracing, the paper's distance-field steps: each new stretch of a tap's "
         "segment skips this share of the flat run (weight 1) that the last iteration traced "
         "on from where it begins, the shortest over the pixel's run of eight in its row. 0 = "
         "every pixel, the exact trace: the default, since on the CPU it is as fast (its chord "
         "bounds skip flat taps exactly); 1 moved RMSE by up to +1.2% (T = 4), 0.5 by up to "
         "+0.4%",
         BMFR_FIELD(S, edgeStep)},
        {"averageReplacement", "walr-average-replacement", "", {},
         "a tap cut by an edge takes the average of a hashed pixel before the edge",
         BMFR_FIELD(S, averageReplacement)},
        {"sampleWeights", "walr-sample-weights", "", {},
         "weight averages by their sample counts W (exact window means; the paper drops W)",
         BMFR_FIELD(S, sampleWeights)},
        {"edgeNear", "walr-edge-near", "x view depth", {0, 1},
         "plane distance below which a tap has full weight, relative to the centre's depth",
         BMFR_FIELD(S, edgeNear)},
        {"edgeFar", "walr-edge-far", "x view depth", {0, 1, true},
         "plane distance from which a tap has weight 0 (linear ramp from edgeNear)",
         BMFR_FIELD(S, edgeFar)},
        {"pivotEpsilon", "walr-pivot-epsilon", "", {0, 1},
         "Cholesky pivot floor of the normal features (in [-0.5, 0.5]): a ridge on flat "
         "directions",
         BMFR_FIELD(S, pivotEpsilon)},
        {"halfAverages", "walr-half-averages", "", {},
         "the a-trous averages pass from one iteration to the next as half floats (saturated at "
         "65504), as the paper's FP16 averages: half the bytes each iteration reads and writes; "
         "the last level, which the solve reads, stays float. False: float averages",
         BMFR_FIELD(S, halfAverages)},
        {"preAlpha", "walr-pre-alpha", "", {0, 1, true},
         "preprocess minimum new-frame weight (cumulative average before it)",
         BMFR_FIELD(S, preAlpha)},
        {"depthTolerance", "walr-depth-tolerance", "x view depth", {0, 1e3},
         "depth test: keep the history when |expected - previous depth| <= this x depth",
         BMFR_FIELD(S, depthTolerance)},
        {"historyTest", "walr-history-test", "", {},
         "depth (the paper) or world (the shared position and normal limits, BMFR's test)",
         enumField<WalrHistoryTest, &S::historyTest>(kHistoryTests)},
        {"motionDilation", "walr-motion-dilation", "", {},
         "reproject with the motion of the nearest surface in the 3x3 (edges follow it)",
         BMFR_FIELD(S, motionDilation)},
        {"varianceGamma", "walr-variance-gamma", "std devs", {0, 100},
         "postprocess: clip the history to mean +- gamma standard deviations of the 3x3",
         BMFR_FIELD(S, varianceGamma)},
        {"seed", "walr-seed", "", {0, 4294967295.0}, "seed of the hashed average replacement",
         BMFR_FIELD(S, seed)},
    };
}
// clang-format on

} // namespace

const SettingsTable<WalrSettings>& walrSettingsTable() {
    static const SettingsTable<WalrSettings> table = withTemporalSettings(ownSettings());
    return table;
}

int walrIterations(const WalrSettings& s, int width, int height) {
    if (s.iterations > 0) return s.iterations;
    const double side = std::min(width, height) * 80.0 / 1080.0;
    const int t = int(std::lround(std::log(std::max(side, 1.0)) / std::log(3.0)));
    return std::clamp(t, 1, 5);
}

void validate(const WalrSettings& s) {
    checkSettings(walrSettingsTable(), s, "WALR setting");
    if (!(s.edgeFar > s.edgeNear))
        throw SettingError("WALR setting edgeFar (" + detail::formatNumber(s.edgeFar) +
                               ") must exceed edgeNear (" + detail::formatNumber(s.edgeNear) + ")",
                           "edgeFar", detail::formatNumber(s.edgeFar),
                           "must exceed edgeNear (" + detail::formatNumber(s.edgeNear) + ")");
    if (s.signal == WalrSignal::DiffuseIndirect && s.colorIsDemodulated)
        throw Error("WALR setting signal=diffuse-indirect needs the colour as radiance "
                    "(colorIsDemodulated=false): the unfiltered rest is colour - albedo x signal");
}

} // namespace bmfr
