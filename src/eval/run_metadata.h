// What a report says about its run: the command, the program's version and commit, the
// machine, the input, and each method's filter settings and stage timings where its
// `bmfr denoise` output folder records them (report.json).
#pragma once
#include <string>
#include <utility>
#include <vector>

namespace bmfr {

struct MethodMetadata {
    std::string name, path;
    std::string filter, backend, reprojection; ///< empty when the folder has no report.json
    std::string description; ///< a peer method's own words on what ran ("OIDN 2.5.1, ...")
    std::string machine;     ///< where its times were measured, as its run recorded it
    std::vector<std::pair<std::string, std::string>> settings;
    std::vector<std::pair<std::string, double>> stageMs; ///< median ms per frame, per stage
    /// The median total ms per frame its run measured, or NaN when it recorded none.
    double msPerFrame() const;
};

struct RunMetadata {
    std::string commandLine;
    std::string version; ///< the program's version and commit, as `bmfr --version` prints
    std::string cpu;
    int threads = 0;
    std::string gpu; ///< the GPU used, or why none
    std::string reference;
    int width = 0, height = 0, firstFrame = 0, lastFrame = 0;
    std::string referenceSpp; ///< from the renderer's record, or "unknown" and why
    std::vector<MethodMetadata> methods;
};

/// Gathers what can be known; missing pieces say why rather than throw.
RunMetadata collectRunMetadata(const std::string& commandLine, const std::string& version,
                               const std::string& reference,
                               const std::vector<std::pair<std::string, std::string>>& methods);

/// The metadata as an HTML section (text escaped) and as JSON text.
std::string metadataHtml(const RunMetadata& m);
std::string metadataJson(const RunMetadata& m);

/// The CPU's model name (/proc/cpuinfo), or "unknown".
std::string cpuModel();

} // namespace bmfr
