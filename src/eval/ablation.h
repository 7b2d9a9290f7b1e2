// The paper's ablations on one sequence: each BMFR stage switched off in turn, and the greedy
// feature-set study of its Figs. 5 and 6 (add, each round, the feature group that lowers RMSE
// the most).
#pragma once
#include <bmfr/settings.h>
#include <functional>
#include <string>
#include <vector>

namespace bmfr {

struct AblationRow {
    std::string name, features;
    double rmse = 0, ssim = 0; ///< means over frames, tone-mapped
};

struct AblationResult {
    std::vector<AblationRow> stages;
    /// Greedy study: row k is the best set after k additions (row 0: the constant only).
    std::vector<AblationRow> greedy;
    /// Every configuration tried in the study, in order.
    std::vector<AblationRow> greedyTrials;
};

/// `base` holds the settings to vary (limits etc. resolved for the sequence). Writes
/// ablation.md, ablation.csv, ablation.json and plot_greedy_{rmse,ssim}.png into `output`.
AblationResult runAblation(const std::string& input, const std::string& output,
                           const std::string& frames, const Settings& base,
                           const std::function<void(const std::string&)>& onConfiguration);

} // namespace bmfr
