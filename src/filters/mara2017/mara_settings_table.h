// Mara 2017's settings table: the shared rows, then its own. The one place their ranges live.
#pragma once
#include "core/settings_table.h"
#include <bmfr/filters/mara2017_filter.h>

namespace bmfr {

const SettingsTable<Mara2017Settings>& mara2017SettingsTable();

} // namespace bmfr
