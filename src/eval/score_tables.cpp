#include "eval/score_tables.h"
#include "io/atomic_file.h"
#include <cmath>
#include <filesystem>
#include <fmt/core.h>
#include <nlohmann/json.hpp>
#include <sstream>

namespace bmfr {

namespace fs = std::filesystem;

namespace {

std::string fmtValue(double v) {
    return std::isfinite(v) ? fmt::format("{:.4f}", v) : "-";
}

/// Whether method i has the best mean of metric m (ties count as best).
bool isBest(const ComparisonResult& r, size_t i, const MetricInfo& m) {
    const double v = metricValue(r.means[i], m.key);
    if (!std::isfinite(v)) return false;
    for (const FrameScores& o : r.means) {
        const double w = metricValue(o, m.key);
        if (std::isfinite(w) && (m.lowerIsBetter ? w < v : w > v)) return false;
    }
    return true;
}

/// The reference row's cell of metric m: the reference's own temporal error, for scale; the
/// other cells are empty.
template <class Format>
std::string referenceCell(const ComparisonResult& r, const MetricInfo& m, Format format) {
    return std::string(m.key) == "temporal_error" ? format(r.referenceTemporalMean) : "";
}

} // namespace

std::string markdownTable(const ComparisonResult& r) {
    std::string md = "| method |";
    for (const MetricInfo& m : metricList())
        md += fmt::format(" {} {} |", m.label, m.lowerIsBetter ? "↓" : "↑");
    md += "\n|---|";
    for (size_t k = 0; k < metricList().size(); ++k) md += "---|";
    md += "\n";
    for (size_t i = 0; i < r.names.size(); ++i) {
        std::string name;
        for (char c : r.names[i]) name += c == '|' ? std::string("\\|") : std::string(1, c);
        md += "| " + name + " |";
        for (const MetricInfo& m : metricList()) {
            const double v = metricValue(r.means[i], m.key);
            const bool best = isBest(r, i, m);
            md += best ? fmt::format(" **{}** |", fmtValue(v)) : fmt::format(" {} |", fmtValue(v));
        }
        md += "\n";
    }
    md += "| reference |";
    for (const MetricInfo& m : metricList())
        md += fmt::format(" {} |", referenceCell(r, m, fmtValue));
    return md + "\n";
}

/// The tables: table.md, table.csv, per_frame.csv, table.json (keys of metricList()).
void writeTables(const ComparisonResult& r, const ComparisonOptions& o, std::string& json) {
    const fs::path out(o.output);
    writeFileAtomically((out / "table.md").string(), markdownTable(r));
    auto csvText = [](const std::string& s) {
        if (s.find_first_of(",\"\n") == std::string::npos) return s;
        std::string q = "\"";
        for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
        return q + "\"";
    };
    std::ostringstream csv, pf;
    csv << "method", pf << "method,frame";
    for (const MetricInfo& m : metricList()) csv << "," << m.key, pf << "," << m.key;
    csv << "\n", pf << "\n";
    for (size_t i = 0; i < r.names.size(); ++i) {
        csv << csvText(r.names[i]);
        for (const MetricInfo& m : metricList())
            csv << "," << csvNumber(metricValue(r.means[i], m.key));
        csv << "\n";
        for (size_t k = 0; k < r.perFrame[i].size(); ++k) {
            pf << csvText(r.names[i]) << "," << r.first + int(k);
            for (const MetricInfo& m : metricList())
                pf << "," << csvNumber(metricValue(r.perFrame[i][k], m.key));
            pf << "\n";
        }
    }
    // The reference's own temporal error, for scale; its other cells are empty.
    csv << "reference";
    for (const MetricInfo& m : metricList()) csv << "," << referenceCell(r, m, csvNumber);
    csv << "\n";
    writeFileAtomically((out / "table.csv").string(), csv.str());
    writeFileAtomically((out / "per_frame.csv").string(), pf.str());

    auto num = [](double v) {
        return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
    };
    nlohmann::json j;
    j["reference"] = o.reference;
    j["frames"] = {r.first, r.last};
    j["color_space"] = "RMSE, PSNR, SSIM, FLIP, temporal and change error: tone-mapped "
                       "clamp(x^(1/2.2), 0, 1); relMSE: linear";
    j["reference_temporal_error"] = num(r.referenceTemporalMean);
    for (size_t i = 0; i < r.names.size(); ++i) {
        nlohmann::json mj;
        for (const MetricInfo& m : metricList()) {
            mj["mean"][m.key] = num(metricValue(r.means[i], m.key));
            nlohmann::json arr = nlohmann::json::array();
            for (const FrameScores& f : r.perFrame[i]) arr.push_back(num(metricValue(f, m.key)));
            mj["per_frame"][m.key] = arr;
        }
        j["methods"][r.names[i]] = mj;
    }
    json = j.dump(2) + "\n";
    writeFileAtomically((out / "table.json").string(), json);
}

std::string tableHtml(const ComparisonResult& r) {
    std::string html = "<table><tr><th>method</th>";
    for (const MetricInfo& m : metricList())
        html += fmt::format("<th>{} {}</th>", m.label, m.lowerIsBetter ? "&darr;" : "&uarr;");
    html += "</tr>";
    for (size_t i = 0; i < r.names.size(); ++i) {
        html += "<tr><td>" + escapeHtml(r.names[i]) + "</td>";
        for (const MetricInfo& m : metricList()) {
            const std::string v = fmtValue(metricValue(r.means[i], m.key));
            html += isBest(r, i, m) ? "<td><b>" + v + "</b></td>" : "<td>" + v + "</td>";
        }
        html += "</tr>";
    }
    html += "<tr><td>reference</td>";
    for (const MetricInfo& m : metricList())
        html += "<td>" + referenceCell(r, m, fmtValue) + "</td>";
    return html + "</tr></table>";
}

} // namespace bmfr
