// WALR's settings table: the shared rows, then WALR's own. The one place their ranges live.
#pragma once
#include "core/settings_table.h"
#include <bmfr/filters/walr_filter.h>

namespace bmfr {

const SettingsTable<WalrSettings>& walrSettingsTable();

} // namespace bmfr
