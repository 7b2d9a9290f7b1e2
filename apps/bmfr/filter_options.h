// A command line's filter settings, made from the filters' settings tables: one flag per table
// row, `--set key=value` for any row, and `--disable` for switches.
#pragma once
#include <CLI/CLI.hpp>
#include <bmfr/filter.h>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace bmfr::app {

/// What a sequence says about its own settings (SequenceInfo), the fallback for unset ones.
struct SequenceDefaults {
    std::optional<float> positionLimitSquared, normalLimitSquared;
    bool colorIsDemodulated = false;
};

struct FilterOptions {
    /// Adds the flags of every filter in `filters` (a shared flag once), --set and --disable.
    void addTo(CLI::App& cmd, const std::vector<std::string>& filters);
    /// The values for filter `name`, in order: the sequence's, the preset's, the flags, --set,
    /// --disable.
    /// Throws bmfr::Error for a flag or key that `name` does not have.
    SettingValues resolve(const std::string& name, const SequenceDefaults& sequence) const;

    std::string preset = "faithful";          ///< presetSettings(), applied before the flags
    std::map<std::string, std::string> flags; ///< flag -> text, as given
    std::vector<std::string> sets;            ///< "key=value"
    std::vector<std::string> disabled;        ///< switch flags to turn off
};

/// The value of `key` in `values` (the last one given), or `fallback`.
std::string settingValue(const SettingValues& values, const std::string& key,
                         const std::string& fallback);

} // namespace bmfr::app
