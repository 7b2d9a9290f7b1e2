// BMFR's settings table: the shared rows, then BMFR's own. The one place their ranges live.
#pragma once
#include "core/settings_table.h"
#include <bmfr/filters/bmfr_filter.h>

namespace bmfr {

const SettingsTable<BmfrSettings>& bmfrSettingsTable();

} // namespace bmfr
