#include "eval/score_tables.h"
#include "io/atomic_file.h"
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fmt/core.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <sstream>

namespace bmfr {

namespace fs = std::filesystem;

namespace {

std::string fmtValue(double v) {
    return std::isfinite(v) ? fmt::format("{:.4f}", v) : "-";
}

/// The header's arrow: lower or higher is better, or "towards the reference's value".
std::string direction(const MetricInfo& m, bool html) {
    if (m.referenceIsTarget) return html ? "&rarr; ref" : "→ ref";
    if (html) return m.lowerIsBetter ? "&darr;" : "&uarr;";
    return m.lowerIsBetter ? "↓" : "↑";
}

/// Whether method i has the best mean of metric m (ties count as best). The temporal error has
/// none: its target, the reference's own value, holds the reference's residual noise too (a
/// 64-spp reference's is about twice a 1024-spp one's, docs/evaluation.md), so the value closest
/// to it is no better. On the demo at 160x120, 16 frames, 256 spp, the closest was WALR's, not
/// the best on change error; at 96x64, 8 frames, 32 spp, "accumulation only", the denoiser with
/// the highest change error.
bool isBest(const ComparisonResult& r, size_t i, const MetricInfo& m) {
    const double v = metricValue(r.means[i], m.key);
    if (!std::isfinite(v) || m.referenceIsTarget) return false;
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
    return m.referenceIsTarget ? format(r.referenceTemporalMean) : "";
}

/// A row that `bmfr demo` names, and what it is: `brief` for the terminal and table.md, `full`
/// for the report.
struct KnownRow {
    const char* name;
    const char* brief;
    const char* full;
};

// The demo's rows (apps/bmfr/cmd_demo.cpp). Eval's rows are named by the user: a name not here
// gets no gloss, as what made it is unknown.
const KnownRow kKnownRows[] = {
    {"noisy", "the input", "the sequence's noisy input colour, not denoised"},
    {"bmfr", "BMFR, the default (quality preset)",
     "BMFR as bmfr denoise runs it by default: the paper's filter with the improvements beyond "
     "it that measured better (the quality preset), among them a TAA that takes its history "
     "from the same surface and weighs the current frame more under motion"},
    {"accumulation only", "bmfr without the fit",
     "BMFR without its blockwise fit (phase II): temporal accumulation and TAA alone"},
    {"bmfr without TAA", "bmfr, TAA off", "bmfr with its final TAA turned off, all else the same"},
    {"svgf", "SVGF, the default (quality preset)",
     "SVGF (Schied et al. 2017) as bmfr denoise runs it by default, with the quality preset's "
     "TAA"},
    {"walr", "WALR, TAA on", "WALR, with its TAA"},
    {"bmfr faithful", "BMFR as in the paper (--preset faithful)",
     "BMFR as the paper describes it, bit for bit the reproduction (--preset faithful), ending "
     "with the authors' TAA"},
    {"svgf faithful", "SVGF as in the paper (--preset faithful)",
     "SVGF as its paper describes it (--preset faithful), with the authors' TAA"},
    {"mara2017", "Mara et al. 2017 on its own factored paths",
     "Mara et al. 2017 (the paper's filter), on the same frames rendered with its own factored "
     "paths (bmfr render --paths mara: other noise, the same reference)"},
    {"bmfr camera path", "BMFR, camera-only reprojection",
     "BMFR reprojecting by the camera path alone, without the objects' motion vectors (the "
     "paper's reprojection)"},
};

/// The run record of method i, or null (a sequence's noisy colour has none).
const MethodMetadata* runOf(const ComparisonResult& r, size_t i) {
    return i < r.runs.size() ? &r.runs[i] : nullptr;
}

/// Whether the run of method i is `bmfr peer oidn`'s, whatever the user named it.
bool isOidn(const ComparisonResult& r, size_t i) {
    const MethodMetadata* run = runOf(r, i);
    return run && run->filter == "oidn";
}

/// "Rows: name: what it is; ..." for the rows of known names and OIDN's; empty when there is
/// none.
std::string rowGlosses(const ComparisonResult& r, bool html) {
    std::string text;
    auto add = [&](const std::string& name, const std::string& brief, const std::string& full) {
        text +=
            (text.empty() ? "Rows: " : "; ") +
            (html ? "<i>" + escapeHtml(name) + "</i>, " + escapeHtml(full) : name + " = " + brief);
    };
    for (size_t i = 0; i < r.names.size(); ++i) {
        if (isOidn(r, i)) {
            add(r.names[i], "Intel Open Image Denoise, single-frame",
                "Intel Open Image Denoise" +
                    (r.runs[i].description.empty() ? "" : " (" + r.runs[i].description + ")") +
                    ", the denoiser Blender and most offline renderers ship: single-frame, it "
                    "denoises each frame alone and keeps no history");
            continue;
        }
        for (const KnownRow& k : kKnownRows)
            if (r.names[i] == k.name) add(r.names[i], k.brief, k.full);
    }
    return text.empty() ? text : text + ".";
}

/// Milliseconds per frame of method i as its run measured them; NaN when not recorded.
double msPerFrame(const ComparisonResult& r, size_t i) {
    const MethodMetadata* run = runOf(r, i);
    return run ? run->msPerFrame() : NAN;
}

/// Whether any method recorded its time: the table has a time column then.
bool hasTimes(const ComparisonResult& r) {
    for (size_t i = 0; i < r.names.size(); ++i)
        if (std::isfinite(msPerFrame(r, i))) return true;
    return false;
}

std::string fmtMs(double v) {
    if (!std::isfinite(v)) return "-";
    return fmt::format("{:.{}f}", v, v >= 100 ? 0 : v >= 10 ? 1 : 2);
}

/// The time cell of method i, the fastest in bold (`bold` wraps a string).
template <class Bold> std::string timeCell(const ComparisonResult& r, size_t i, Bold bold) {
    const double v = msPerFrame(r, i);
    for (size_t k = 0; k < r.names.size(); ++k)
        if (std::isfinite(v) && msPerFrame(r, k) < v) return fmtMs(v);
    return std::isfinite(v) ? bold(fmtMs(v)) : fmtMs(v);
}

/// "ms/frame: ... on MACHINE" naming where each method's time was measured.
std::string timeNote(const ComparisonResult& r, bool html) {
    std::vector<std::pair<std::string, std::vector<std::string>>> machines; // machine, methods
    for (size_t i = 0; i < r.names.size(); ++i) {
        if (!std::isfinite(msPerFrame(r, i))) continue;
        const std::string m =
            r.runs[i].machine.empty() ? "a machine its run did not record" : r.runs[i].machine;
        auto it = std::find_if(machines.begin(), machines.end(),
                               [&](const auto& e) { return e.first == m; });
        if (it == machines.end()) it = machines.insert(machines.end(), {m, {}});
        it->second.push_back(r.names[i]);
    }
    std::string where;
    for (const auto& [machine, names] : machines) {
        where += where.empty() ? "" : "; ";
        where += machine;
        if (machines.size() > 1) where += fmt::format(" ({})", fmt::join(names, ", "));
    }
    const std::string text =
        "ms/frame: the median time per frame of each method's own run (its report.json), "
        "reading and writing files excluded, on " +
        where + ".";
    return html ? escapeHtml(text) : text;
}

/// Whether a row's name says it differs from another by its TAA ("bmfr without TAA").
bool comparesTaa(const ComparisonResult& r) {
    for (const std::string& name : r.names) {
        std::string lower;
        for (char c : name) lower += char(std::tolower(static_cast<unsigned char>(c)));
        if (lower.find("taa") != std::string::npos) return true;
    }
    return false;
}

/// The notes under the table: what the rows are, what TAA trades, and how the two temporal
/// columns read, in the terms of what metrics/basic_metrics.cpp computes (temporalError,
/// temporalChangeError).
std::string tableNotes(const ComparisonResult& r, bool html) {
    std::vector<std::string> notes;
    if (const std::string rows = rowGlosses(r, html); !rows.empty()) notes.push_back(rows);
    if (hasTimes(r)) notes.push_back(timeNote(r, html));
    if (comparesTaa(r))
        notes.push_back(
            html ? "TAA (temporal anti-aliasing over the already-denoised output) blends each "
                   "frame with its reprojected history to hide the flicker and aliasing that a "
                   "per-frame blockwise fit leaves. The authors' TAA (the faithful preset) blurs "
                   "under motion, as its history is resampled every frame: against the sharp "
                   "reference its per-frame scores (RMSE, PSNR, SSIM, FLIP, relMSE) are worse "
                   "with TAA. The default TAA weighs the current frame more where resampling "
                   "blurs the history, so it costs them little. What TAA is for is temporal "
                   "stability, less flicker from frame to frame, which per-frame scores cannot "
                   "show: the two temporal columns measure it (lag adds to the change error too)."
                 : "TAA blends each frame with its reprojected history: steadier; the authors' "
                   "(faithful) TAA also blurs under motion, so its per-frame scores are worse.");
    notes.push_back(
        html ? "Temporal error (&rarr; ref): the mean over pixels of |Y &minus; "
               "Y<sub>previous</sub>|, Y the luminance of the tone-mapped frame, averaged over "
               "every frame but the first. It counts the scene's real motion as well as flicker, "
               "so the reference row's value (the real motion plus the reference's residual "
               "noise) is the target: lower than the reference's is not better, it means lag or "
               "smearing. Read it as the distance to the reference's value. No value in it is "
               "bold: with the reference's noise in the target, the closest is not the best "
               "either; the change error ranks flicker and lag."
             : "temporal error: mean |ΔY| from the previous frame (tone-mapped luminance); the "
               "scene's motion counts too, so read it against the reference row's value: lower "
               "is not better (lag, smearing); none is bold.");
    notes.push_back(html ? "Change error (&darr;): the mean over pixels of |&Delta;Y &minus; "
                           "&Delta;Y<sub>reference</sub>|, the part of each frame-to-frame "
                           "change that the reference does not make (flicker, lag, ghosting); "
                           "lower is better, though the reference's own residual noise adds to "
                           "every row."
                         : "change error: mean |ΔY - ΔY of the reference|, lower is better.");
    std::string text;
    for (const std::string& n : notes)
        text += html ? "<p class=\"notes\">" + n + "</p>" : "- " + n + "\n";
    return text;
}

} // namespace

std::string markdownTable(const ComparisonResult& r) {
    std::string md = "| method |";
    for (const MetricInfo& m : metricList())
        md += fmt::format(" {} {} |", m.label, direction(m, false));
    const bool times = hasTimes(r);
    if (times) md += " ms/frame ↓ |";
    md += "\n|---|";
    for (size_t k = 0; k < metricList().size() + (times ? 1 : 0); ++k) md += "---|";
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
        if (times)
            md += fmt::format(" {} |", timeCell(r, i, [](const std::string& t) {
                                  return fmt::format("**{}**", t);
                              }));
        md += "\n";
    }
    md += "| reference |";
    for (const MetricInfo& m : metricList())
        md += fmt::format(" {} |", referenceCell(r, m, fmtValue));
    if (times) md += " |";
    return md + "\n\n" + tableNotes(r, false);
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
    csv << ",ms_per_frame\n", pf << "\n";
    for (size_t i = 0; i < r.names.size(); ++i) {
        csv << csvText(r.names[i]);
        for (const MetricInfo& m : metricList())
            csv << "," << csvNumber(metricValue(r.means[i], m.key));
        csv << "," << csvNumber(msPerFrame(r, i)) << "\n";
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
    csv << ",\n";
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
        mj["ms_per_frame"] = num(msPerFrame(r, i));
        if (const MethodMetadata* run = runOf(r, i); run && !run->machine.empty())
            mj["machine"] = run->machine;
        j["methods"][r.names[i]] = mj;
    }
    json = j.dump(2) + "\n";
    writeFileAtomically((out / "table.json").string(), json);
}

std::string tableHtml(const ComparisonResult& r) {
    std::string html = "<table><tr><th>method</th>";
    for (const MetricInfo& m : metricList())
        html += fmt::format("<th>{} {}</th>", m.label, direction(m, true));
    const bool times = hasTimes(r);
    if (times) html += "<th>ms/frame &darr;</th>";
    html += "</tr>";
    for (size_t i = 0; i < r.names.size(); ++i) {
        html += "<tr><td>" + escapeHtml(r.names[i]) + "</td>";
        for (const MetricInfo& m : metricList()) {
            const std::string v = fmtValue(metricValue(r.means[i], m.key));
            html += isBest(r, i, m) ? "<td><b>" + v + "</b></td>" : "<td>" + v + "</td>";
        }
        if (times)
            html +=
                "<td>" +
                timeCell(r, i, [](const std::string& t) { return fmt::format("<b>{}</b>", t); }) +
                "</td>";
        html += "</tr>";
    }
    html += "<tr><td>reference</td>";
    for (const MetricInfo& m : metricList())
        html += "<td>" + referenceCell(r, m, fmtValue) + "</td>";
    if (times) html += "<td></td>";
    return html + "</tr></table>" + tableNotes(r, true);
}

} // namespace bmfr
