#include "eval/run_metadata.h"
#include "eval/escape_html.h"
#include "render/sequence_renderer.h"
#include <cmath>
#include <filesystem>
#include <fmt/core.h>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

namespace bmfr {

namespace fs = std::filesystem;

namespace {

nlohmann::json readJson(const fs::path& p) {
    std::ifstream in(p);
    if (!in) return nullptr;
    try {
        return nlohmann::json::parse(in);
    } catch (const std::exception&) {
        return nullptr;
    }
}

std::string text(const nlohmann::json& v) {
    return v.is_string() ? v.get<std::string>() : v.dump();
}

} // namespace

double MethodMetadata::msPerFrame() const {
    for (const auto& [stage, ms] : stageMs)
        if (stage == "total") return ms;
    return NAN;
}

std::string cpuModel() {
    std::ifstream in("/proc/cpuinfo");
    std::string line;
    while (std::getline(in, line))
        if (line.rfind("model name", 0) == 0 && line.find(':') != std::string::npos) {
            std::string v = line.substr(line.find(':') + 1);
            return v.substr(v.find_first_not_of(' '));
        }
    return "unknown";
}

RunMetadata collectRunMetadata(const std::string& commandLine, const std::string& version,
                               const std::string& reference,
                               const std::vector<std::pair<std::string, std::string>>& methods) {
    RunMetadata m;
    m.commandLine = commandLine.empty() ? "(not given: called through the library)" : commandLine;
    m.version = version;
    m.cpu = cpuModel();
    m.threads = int(std::thread::hardware_concurrency());
    m.reference = reference;
    const nlohmann::json rendered = readJson(fs::path(reference) / render::kRenderFingerprintFile);
    m.referenceSpp = rendered.is_object() && rendered.contains("reference_spp")
                         ? text(rendered["reference_spp"])
                         : "unknown (the sequence holds no record of `bmfr render`)";
    bool cuda = false;
    for (const auto& [name, path] : methods) {
        MethodMetadata mm;
        mm.name = name;
        mm.path = path.empty() ? "(the reference sequence's noisy colour)" : path;
        const nlohmann::json r =
            path.empty() ? nlohmann::json(nullptr) : readJson(fs::path(path) / "report.json");
        if (r.is_object()) {
            mm.filter = r.value("filter", "");
            mm.backend = r.value("backend", "");
            mm.reprojection = r.value("reprojection", "");
            if (r.contains("method") && r["method"].is_string()) mm.description = r["method"];
            if (r.contains("machine") && r["machine"].is_string()) mm.machine = r["machine"];
            if (r.contains("settings") && r["settings"].is_object())
                for (const auto& [k, v] : r["settings"].items())
                    mm.settings.emplace_back(k, text(v));
            if (r.contains("median_ms") && r["median_ms"].is_object())
                for (const auto& [k, v] : r["median_ms"].items())
                    if (v.is_number()) mm.stageMs.emplace_back(k, v.get<double>());
            cuda = cuda || mm.backend == "cuda";
        }
        m.methods.push_back(std::move(mm));
    }
    m.gpu = cuda ? "a method ran on the cuda backend (see its report.json)"
                 : "none used (every method ran on a CPU backend or is an input)";
    return m;
}

std::string metadataHtml(const RunMetadata& m) {
    auto row = [](const std::string& k, const std::string& v) {
        return "<tr><th>" + escapeHtml(k) + "</th><td>" + escapeHtml(v) + "</td></tr>";
    };
    std::string h = "<table class=\"meta\">";
    h += row("command", m.commandLine);
    h += row("bmfr", m.version);
    h += row("machine", fmt::format("{}; {} hardware threads; GPU: {}", m.cpu, m.threads, m.gpu));
    h += row("reference", m.reference);
    h += row("input", fmt::format("{}x{}, frames {}:{} ({} frames)", m.width, m.height,
                                  m.firstFrame, m.lastFrame, m.lastFrame - m.firstFrame));
    h += row("reference spp", m.referenceSpp);
    h += "</table><table class=\"meta\"><tr><th>method</th><th>source</th><th>filter, "
         "backend</th><th>settings</th><th>median ms per frame</th></tr>";
    for (const MethodMetadata& mm : m.methods) {
        std::string settings, stages;
        for (const auto& [k, v] : mm.settings)
            settings += (settings.empty() ? "" : ", ") + k + "=" + v;
        for (const auto& [k, v] : mm.stageMs)
            stages += (stages.empty() ? "" : ", ") + fmt::format("{} {:.2f}", k, v);
        h += "<tr><td>" + escapeHtml(mm.name) + "</td><td>" + escapeHtml(mm.path) + "</td><td>" +
             escapeHtml(mm.filter.empty()        ? "-"
                        : mm.description.empty() ? mm.filter + ", " + mm.backend
                                                 : mm.description) +
             "</td><td class=\"wrap\">" + escapeHtml(settings.empty() ? "-" : settings) +
             "</td><td class=\"wrap\">" + escapeHtml(stages.empty() ? "-" : stages) + "</td></tr>";
    }
    return h + "</table>";
}

std::string metadataJson(const RunMetadata& m) {
    nlohmann::json j;
    j["command"] = m.commandLine;
    j["version"] = m.version;
    j["machine"] = {{"cpu", m.cpu}, {"threads", m.threads}, {"gpu", m.gpu}};
    j["input"] = {{"reference", m.reference},
                  {"resolution", {m.width, m.height}},
                  {"frames", {m.firstFrame, m.lastFrame}},
                  {"reference_spp", m.referenceSpp}};
    for (const MethodMetadata& mm : m.methods) {
        nlohmann::json x{{"name", mm.name}, {"source", mm.path}};
        if (!mm.filter.empty()) {
            x["filter"] = mm.filter, x["backend"] = mm.backend;
            if (!mm.description.empty()) x["method"] = mm.description;
            if (!mm.machine.empty()) x["machine"] = mm.machine;
            for (const auto& [k, v] : mm.settings) x["settings"][k] = v;
            for (const auto& [k, v] : mm.stageMs) x["median_ms"][k] = v;
        }
        j["methods"].push_back(x);
    }
    return j.dump(2);
}

} // namespace bmfr
