#include "temporal/temporal_settings_table.h"

namespace bmfr {

void validate(const TemporalSettings& s) {
    static const SettingsTable<TemporalSettings> table = temporalSettingsTable<TemporalSettings>();
    checkSettings(table, s, "setting");
}

} // namespace bmfr
