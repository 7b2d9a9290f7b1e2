// What a filter registers: its name, how to make it from text settings, and its settings table.
#pragma once
#include <bmfr/filter.h>
#include <functional>

namespace bmfr {

struct FilterEntry {
    const char* name;  ///< as in --filter and makeFilter
    const char* title; ///< for reports and help
    std::function<std::unique_ptr<Filter>(const SettingValues&)> make;
    std::function<std::vector<SettingDoc>()> settings;
};

/// Each filter folder defines its entry (src/filters/<name>/<name>_denoiser.cpp).
FilterEntry bmfrFilterEntry();
FilterEntry svgfFilterEntry();

} // namespace bmfr
