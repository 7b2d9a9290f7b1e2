// What a filter registers: its name, how to make it from text settings, and its settings table.
#pragma once
#include "filters/filter_inputs.h"
#include "temporal/temporal_settings_table.h"
#include <bmfr/device.h>
#include <bmfr/filter.h>
#include <functional>

namespace bmfr {

struct FilterEntry {
    const char* name;  ///< as in --filter and makeFilter
    const char* title; ///< for reports and help
    /// The filter on `device`, or on its own when null.
    std::function<std::unique_ptr<Filter>(const SettingValues&, const Device*)> make;
    std::function<std::vector<SettingDoc>()> settings;
    std::function<std::vector<InputUse>(const SettingValues&)> inputs;
};

/// The entry of a filter class D whose settings S are described by `table`.
template <class D, class S>
FilterEntry tableFilterEntry(const char* name, const char* title,
                             const SettingsTable<S>& (*table)()) {
    return {name, title,
            [name, table](const SettingValues& values,
                          const Device* device) -> std::unique_ptr<Filter> {
                S s;
                if (device) s.backend = device->backend();
                applySettings(table(), s, values, name);
                if (!device) return std::make_unique<D>(s);
                return std::make_unique<D>(s, *device);
            },
            [table] { return documentSettings(table(), temporalSettingCount()); },
            [name, table](const SettingValues& values) {
                S s;
                applySettings(table(), s, values, name);
                return inputsRead(s);
            }};
}

} // namespace bmfr
