// A command line's filter settings, made from the filters' settings tables: one flag per table
// row, `--set key=value` for any row, and `--disable` for switches.
#pragma once
#include <CLI/CLI.hpp>
#include <bmfr/error.h>
#include <bmfr/filter.h>
#include <map>
#include <memory>
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
    /// Throws UsageError for a flag, key or switch that `name` does not have.
    SettingValues resolve(const std::string& name, const SequenceDefaults& sequence) const;
    /// makeFilter(name, values), with a setting error in a value from this command line thrown
    /// as a UsageError in the flag's words (`--block-size 33 must be even`).
    std::unique_ptr<Filter> makeFilter(const std::string& name, const SettingValues& values,
                                       const SequenceDefaults& sequence = {}) const;
    /// Throws `e` again: as a UsageError unless its value is the sequence's own.
    [[noreturn]] void rethrow(const std::string& name, const SettingError& e,
                              const SequenceDefaults& sequence = {}) const;

    std::string preset = "quality";           ///< presetSettings(), applied before the flags
    std::map<std::string, std::string> flags; ///< flag -> text, as given
    std::vector<std::string> sets;            ///< "key=value"
    std::vector<std::string> disabled;        ///< switch flags to turn off
};

/// "key=value" (or "flag=value") given to `flag` as filter `filter`'s (key, value); throws
/// UsageError naming the nearest key for one the filter does not have.
std::pair<std::string, std::string> parseSetting(const std::string& filter, const std::string& text,
                                                 const std::string& flag);

/// parseSetting for texts given to several filters at once (`bench --filters`): `filter`'s
/// pairs, from the texts whose key (or flag) it has, so a key two filters share reaches both and
/// a flag (`walr-iterations`) one. Throws UsageError for a text whose key none of `filters`
/// has, so that no text is silently dropped.
SettingValues parseSharedSettings(const std::string& filter,
                                  const std::vector<std::string>& filters,
                                  const std::vector<std::string>& texts, const std::string& flag);

/// The value of `key` in `values` (the last one given), or `fallback`.
std::string settingValue(const SettingValues& values, const std::string& key,
                         const std::string& fallback);

} // namespace bmfr::app
