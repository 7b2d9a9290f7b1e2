// The filters by name. A new filter adds one line to kFilters.
#include "filters/bmfr/bmfr_settings_table.h"
#include "filters/mara2017/mara_settings_table.h"
#include "filters/svgf/svgf_settings_table.h"
#include "filters/walr/walr_settings_table.h"
#include "library/filter_entry.h"
#include <bmfr/error.h>

namespace bmfr {

namespace {

const std::vector<FilterEntry>& filters() {
    static const std::vector<FilterEntry> kFilters = {
        tableFilterEntry<BmfrDenoiser>("bmfr", "BMFR (Koskela et al. 2019)", bmfrSettingsTable),
        tableFilterEntry<SvgfDenoiser>("svgf", "SVGF (Schied et al. 2017)", svgfSettingsTable),
        tableFilterEntry<WalrDenoiser>("walr", "WALR (Meunier and Harada 2022)", walrSettingsTable),
        tableFilterEntry<Mara2017Denoiser>("mara2017", "Mara et al. 2017", mara2017SettingsTable),
    };
    return kFilters;
}

const FilterEntry& find(const std::string& name) {
    std::string known;
    for (const FilterEntry& f : filters()) {
        if (name == f.name) return f;
        known += (known.empty() ? "" : ", ") + std::string(f.name);
    }
    throw Error("unknown filter '" + name + "' (expected " + known + ")");
}

} // namespace

std::unique_ptr<Filter> makeFilter(const std::string& name, const SettingValues& values) {
    return find(name).make(values, nullptr);
}

std::unique_ptr<Filter> Device::makeFilter(const std::string& name,
                                           const SettingValues& values) const {
    for (const auto& kv : values)
        if (kv.first == "backend" || kv.first == "threads")
            throw Error("'" + kv.first +
                        "' is the device's: make a Device with the backend and "
                        "threads you want, then its filters");
    return find(name).make(values, this);
}

std::vector<std::string> filterNames() {
    std::vector<std::string> names;
    for (const FilterEntry& f : filters()) names.push_back(f.name);
    return names;
}

std::vector<SettingDoc> filterSettings(const std::string& name) {
    return find(name).settings();
}

std::vector<InputUse> filterInputs(const std::string& name, const SettingValues& values) {
    return find(name).inputs(values);
}

std::vector<std::string> presetNames() {
    return {"quality", "faithful"};
}

SettingValues presetSettings(const std::string& name, const std::string& preset) {
    const std::vector<SettingDoc> docs = filterSettings(name);
    if (preset == "quality") return {};
    if (preset != "faithful")
        throw Error("unknown preset '" + preset + "' (expected quality or faithful)");
    SettingValues v;
    for (const SettingDoc& d : docs)
        if (!d.faithful.empty()) v.emplace_back(d.key, d.faithful);
    return v;
}

} // namespace bmfr
