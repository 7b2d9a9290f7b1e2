// SVGF's settings table: the shared rows, then SVGF's own. The one place their ranges live.
#pragma once
#include "core/settings_table.h"
#include <bmfr/filters/svgf_filter.h>

namespace bmfr {

const SettingsTable<SvgfSettings>& svgfSettingsTable();

} // namespace bmfr
