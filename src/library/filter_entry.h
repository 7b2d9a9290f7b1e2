// What a filter registers: its name, how to make it from text settings, and its settings table.
#pragma once
#include "temporal/temporal_settings_table.h"
#include <bmfr/filter.h>
#include <functional>

namespace bmfr {

struct FilterEntry {
    const char* name;  ///< as in --filter and makeFilter
    const char* title; ///< for reports and help
    std::function<std::unique_ptr<Filter>(const SettingValues&)> make;
    std::function<std::vector<SettingDoc>()> settings;
};

/// The entry of a filter class D whose settings S are described by `table`.
template <class D, class S>
FilterEntry tableFilterEntry(const char* name, const char* title,
                             const SettingsTable<S>& (*table)()) {
    return {name, title,
            [name, table](const SettingValues& values) -> std::unique_ptr<Filter> {
                S s;
                applySettings(table(), s, values, name);
                return std::make_unique<D>(s);
            },
            [table] { return documentSettings(table(), temporalSettingCount()); }};
}

} // namespace bmfr
