#include "backend/cuda/cuda_device.h"
#include "commands.h"
#include "core/hash.h"
#include "core/image.h"
#include "core/stopwatch.h"
#include "denoise_scores.h"
#include "eval/comparison.h"
#include "eval/frame_scores.h"
#include "eval/run_metadata.h"
#include "filters/filter_inputs.h"
#include "help_format.h"
#include "io/atomic_file.h"
#include "io/exr.h"
#include "io/output_folder.h"
#include "io/png.h"
#include "io/range_parsers.h"
#include "io/sequence.h"
#include "metrics/basic_metrics.h"
#include "progress.h"
#include "stage_log.h"
#include "usage.h"
#include <algorithm>
#include <bmfr/bmfr.hpp>
#include <filesystem>
#include <fmt/core.h>
#include <fmt/format.h>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

namespace bmfr::app {

namespace fs = std::filesystem;

namespace {

ImageF copyOf(const ImageView& v) {
    ImageF img(v.width, v.height, v.channels);
    std::copy(v.data, v.data + img.pixels.size(), img.data());
    return img;
}

/// The frames a run writes into its folder: NAME_NNNN.exr and .png.
constexpr const char* kFrameOutput = "denoised";

/// The debug buffers a run writes into its debug/ folder: NAME_NNNN.exr, and for the two counts
/// a PNG preview scaled by `pngScale`.
struct DebugOutput {
    const char* name;
    ImageView DebugBuffers::*buffer;
    float pngScale; ///< 0: no PNG
};
constexpr DebugOutput kDebugOutputs[] = {
    {"accumulated", &DebugBuffers::accumulatedNoisy, 0.0f},
    {"fitted", &DebugBuffers::fitted, 0.0f},
    {"history_length", &DebugBuffers::historyLength, 1.0f / 16.0f},
    {"discard_mask", &DebugBuffers::discardMask, 1.0f / 15.0f},
};

/// The debug buffers of one frame into dir.
void writeDebug(const fs::path& dir, const std::string& stem, const DebugBuffers& d) {
    for (const DebugOutput& o : kDebugOutputs) {
        const std::string base = (dir / (std::string(o.name) + "_" + stem)).string();
        writeExr(base + ".exr", copyOf(d.*o.buffer));
        if (o.pngScale > 0) writePngToneMapped(base + ".png", copyOf(d.*o.buffer), o.pngScale);
    }
}

/// Fewer than 1 spp, simulated: a fixed pseudo-random `fraction` of the pixels of frame i.
void fillSampleMask(ImageF& mask, int i, float fraction) {
    for (long k = 0; k < mask.pixelCount(); ++k)
        mask.data()[k] =
            unitFloat(hashKeys(uint32_t(k), uint32_t(i), 0x5eedu)) < fraction ? 1.0f : 0.0f;
}

/// The feature columns the filter fits ("" for a filter without a `features` setting); throws
/// when one reads an extra buffer the sequence at `input` lacks.
std::string checkedFeatures(const std::string& filter, const SettingValues& values,
                            const std::string& input, const SequenceInfo& info) {
    std::string text;
    for (const SettingDoc& d : filterSettings(filter))
        if (d.key == "features") text = settingValue(values, "features", d.defaultValue);
    if (text.empty()) return text;
    const std::vector<Feature> features = parseFeatures(text);
    for (const Feature& f : features)
        if (f.source == FeatureSource::Extra && f.extraIndex >= int(info.extraNames.size()))
            throw Error(fmt::format("feature extra{} requested, {} has {} extra buffers",
                                    f.extraIndex, input, info.extraNames.size()));
    return formatFeatures(features);
}

/// True for "PREFIX_NNNN.exr" or ".png" (four or more digits) with a prefix in `prefixes`.
bool isFrameFile(const std::string& name, const std::vector<std::string>& prefixes) {
    for (const std::string& p : prefixes) {
        if (name.rfind(p + "_", 0) != 0) continue;
        const size_t digits = p.size() + 1, dot = name.find('.', digits);
        if (dot == std::string::npos || dot - digits < 4) continue;
        if (name.find_first_not_of("0123456789", digits) != dot) continue;
        if (name.substr(dot) == ".exr" || name.substr(dot) == ".png") return true;
    }
    return false;
}

/// A report.json that a denoise run wrote (not a user's file of that name).
bool isDenoiseReport(const fs::path& p) {
    try {
        const nlohmann::json j = nlohmann::json::parse(std::ifstream(p));
        return j.is_object() && j.contains("filter") && j.contains("median_ms");
    } catch (const std::exception&) {
        return false;
    }
}

/// The files an earlier denoise run wrote into `dir` (frames, report, scores) and into its
/// debug/ folder, never inside `input`.
std::vector<fs::path> earlierOutputs(const fs::path& dir, const fs::path& input) {
    std::vector<fs::path> found;
    std::error_code ec;
    std::vector<std::string> debugNames;
    for (const DebugOutput& o : kDebugOutputs) debugNames.push_back(o.name);
    for (const auto& e : fs::directory_iterator(dir, ec))
        if (e.is_regular_file(ec) && isFrameFile(e.path().filename().string(), {kFrameOutput}))
            found.push_back(e.path());
    const bool frames = !found.empty();
    if (isDenoiseReport(dir / "report.json")) found.push_back(dir / "report.json");
    if ((frames || !found.empty()) && fs::is_regular_file(dir / "scores.csv", ec))
        found.push_back(dir / "scores.csv");
    if (!fs::equivalent(dir / "debug", input, ec))
        for (const auto& e : fs::directory_iterator(dir / "debug", ec))
            if (e.is_regular_file(ec) && isFrameFile(e.path().filename().string(), debugNames))
                found.push_back(e.path());
    std::sort(found.begin(), found.end());
    return found;
}

/// Refuses `out` when it holds an earlier run's outputs (a shorter run would leave stale frames
/// beside new scores), or with `overwrite` removes them first; returns how many it removed.
/// Runs under the folder's lock.
size_t claimOutputs(const fs::path& out, const fs::path& input, bool overwrite, bool quiet) {
    const std::vector<fs::path> earlier = earlierOutputs(out, input);
    // A file of a name this run writes that no earlier run wrote is the user's: never replaced.
    std::error_code ec;
    for (const char* name : {"report.json", "scores.csv"})
        if (fs::exists(out / name, ec) &&
            std::find(earlier.begin(), earlier.end(), out / name) == earlier.end())
            throw Error(fmt::format("{} is not the output of an earlier bmfr denoise run, and this "
                                    "run would replace it; give another folder",
                                    (out / name).string()));
    if (earlier.empty()) return 0;
    if (!overwrite)
        throw Error(fmt::format("{} holds the outputs of an earlier run ({} files: {}{}); "
                                "refusing to mix them with this run's. Use another folder, or "
                                "--overwrite to replace them",
                                out.string(), earlier.size(), earlier.front().filename().string(),
                                earlier.size() > 1 ? ", ..." : ""));
    for (const fs::path& p : earlier)
        if (!fs::remove(p, ec) && ec)
            throw Error("cannot remove " + p.string() +
                        " (an earlier run's output): " + ec.message());
    if (!quiet)
        fmt::print("removed {} files of an earlier run from {} (--overwrite)\n", earlier.size(),
                   out.string());
    return earlier.size();
}

/// What denoises a run: one of the library's filters, or a peer method.
struct Method {
    std::unique_ptr<Filter> filter;
    SettingValues values;         ///< for report.json, by setting key
    std::string features;         ///< the feature columns fitted, or ""
    std::string backend;          ///< the backend's name
    std::string title;            ///< the summary's first words
    std::string description;      ///< a peer's own words on what ran ("" for a filter)
    std::string reprojection;     ///< how it uses history when that is fixed ("" for a filter)
    std::vector<InputUse> inputs; ///< optional buffers it reads
    int threads = 0;              ///< the CPU threads it runs on (0: every core)
};

Method makeMethod(const DenoiseJob& job, const SequenceInfo& info) {
    Method m;
    if (job.oidn) {
        oidn::PeerSettings s = *job.oidn;
        s.colorIsDemodulated = info.colorIsDemodulated;
        oidn::Peer peer = oidn::makePeer(s);
        m.filter = std::move(peer.filter);
        m.description = peer.description;
        m.threads = peer.threads;
        m.values = {{"quality", s.quality},
                    {"prefilter", s.prefilter},
                    {"threads", std::to_string(s.threads)}};
        m.backend = "cpu";
        m.title = "bmfr peer oidn";
        m.reprojection = "none (single-frame)";
        return m;
    }
    const SequenceDefaults own{info.positionLimitSquared, info.normalLimitSquared,
                               info.colorIsDemodulated};
    m.values = job.options.resolve(job.filter, own);
    m.filter = job.options.makeFilter(job.filter, m.values, own);
    m.features = checkedFeatures(job.filter, m.values, job.input, info);
    m.backend = settingValue(m.values, "backend", "cpu");
    m.title = fmt::format("bmfr denoise ({}, {} backend)", job.filter, m.backend);
    m.inputs = filterInputs(job.filter, m.values);
    m.threads = std::stoi(settingValue(m.values, "threads", "0"));
    return m;
}

} // namespace

int runDenoise(const DenoiseJob& job) {
    std::error_code ec;
    if (job.output.empty()) throw UsageError("-o: the output folder is an empty name");
    if (fs::exists(job.output, ec) && fs::equivalent(job.input, job.output, ec))
        throw UsageError("-o " + job.output + " is the input folder " + job.input +
                         "; refusing to write the results among the inputs (give another folder)");
    if (!(job.sampleFraction > 0.0f && job.sampleFraction <= 1.0f))
        throw UsageError(fmt::format("--sample-fraction {} is outside (0, 1]", job.sampleFraction));
    // A range that does not parse is the command line's error; one the input lacks is the input's.
    usageChecked([&] { checkFrameRangeSyntax(job.frames); });
    auto reader = SequenceReader::open(job.input);
    reader->setLayerOverrides(usageChecked([&] { return parseLayerMap(job.channels); }));
    const SequenceInfo& info = reader->info();
    const Method method = makeMethod(job, info);
    Filter* filter = method.filter.get();
    auto [first, last] = parseFrameRange(job.frames, info.frameCount);
    reader->checkFrames(first, last); // a bad frame fails the run before its first output
    const OutputFolder folder(job.output, invocation());
    const fs::path out(job.output), debugDir = out / "debug";
    const size_t removed = claimOutputs(out, job.input, job.overwrite, job.quiet);
    if (job.debug && !fs::create_directories(debugDir, ec) && !fs::is_directory(debugDir, ec))
        throw Error("cannot make the debug folder " + debugDir.string() +
                    (ec ? ": " + ec.message() : ": a file of that name is in the way"));
    filter->setDebugOutputs(job.debug);
    if (!job.quiet)
        fmt::print("{}: {} ({} layout, {}x{}, frames {}:{}){}\n", method.title, job.input,
                   info.layout, info.width, info.height, first, last,
                   method.features.empty() ? std::string() : ", features " + method.features);
    for (const std::string& note : reader->notes()) fmt::print(stderr, "bmfr: note: {}\n", note);

    int lastWritten = first - 1; // the last frame whose denoised EXR is on disk
    Progress progress("denoise", last - first, job.quiet);
    ImageF sampleMask(info.width, info.height, 1);
    StageLog stages;
    std::vector<double> tRead, tWrite;
    int64_t nonFinite = 0;
    std::vector<int> badFrames;
    DenoiseScores scores(first, info.colorIsDemodulated, job.flip);
    FrameData frame;
    int motionFrames = 0; // frames that came with motion vectors or previous positions
    auto denoiseFrame = [&](int i) {
        Stopwatch clock;
        reader->load(i, frame);
        tRead.push_back(clock.lap());
        FrameInput in = frame.input(job.motion);
        if (i == first)
            if (const std::string w = missingInputWarning(method.inputs, in); !w.empty())
                fmt::print(stderr, "bmfr: warning: {}: {}\n", job.input, w);
        motionFrames += frame.motion.width || frame.previousPosition.width ? 1 : 0;
        if (job.sampleFraction < 1.0f) {
            fillSampleMask(sampleMask, i, job.sampleFraction);
            in.sampleMask = view(sampleMask);
        }
        const ImageF result = copyOf(filter->denoise(in));
        const FrameStats& st = filter->lastStats();
        stages.add(st.times);
        if (st.nonFiniteInputs) {
            nonFinite += st.nonFiniteInputs;
            badFrames.push_back(i);
        }

        clock.lap();
        const std::string stem = fmt::format("{:04d}", i);
        const std::string frameBase = (out / (std::string(kFrameOutput) + "_" + stem)).string();
        writeExr(frameBase + ".exr", result);
        lastWritten = i;
        if (job.png) writePngToneMapped(frameBase + ".png", result);
        if (job.debug) writeDebug(debugDir, stem, filter->debug());
        tWrite.push_back(clock.lap());
        if (info.hasReference) scores.add(i, result, frame);
        progress.step(i - first + 1);
    };
    for (int i = first; i < last; ++i) {
        try {
            denoiseFrame(i);
        } catch (const std::exception& e) {
            // A file that breaks only when its pixels are read (truncated after its header).
            if (lastWritten < first && job.debug) fs::remove(debugDir, ec); // only if empty
            throw Error(fmt::format(
                "{}\n{}", e.what(),
                lastWritten < first
                    ? fmt::format("no frame was written{}{}",
                                  folder.madeHere() ? fmt::format(" ({} is removed)", job.output)
                                                    : "",
                                  removed ? fmt::format("; the {} files of the earlier run were "
                                                        "removed before (--overwrite)",
                                                        removed)
                                          : "")
                    : fmt::format("frames {} to {} were written to {} (denoised_{:04d}.exr to "
                                  "denoised_{:04d}.exr), report.json was not",
                                  first, lastWritten, job.output, first, lastWritten)));
        }
    }
    progress.finish();

    if (nonFinite)
        fmt::print(stderr,
                   "bmfr: warning: replaced {} NaN/Inf input values with 0 in {} frame(s) "
                   "(first: frame {})\n",
                   nonFinite, badFrames.size(), badFrames.front());

    nlohmann::json report;
    report["input"] = job.input;
    report["frames"] = last - first;
    report["resolution"] = {info.width, info.height};
    if (!method.features.empty()) report["features"] = method.features;
    report["filter"] = job.filter;
    report["backend"] = method.backend;
    if (!method.description.empty()) report["method"] = method.description;
    report["reprojection"] = !method.reprojection.empty() ? method.reprojection
                             : motionFrames == 0 ? "camera (the input has no motion vectors)"
                             : job.motion        ? "motion vectors"
                                                 : "camera (motion vectors ignored: --no-motion)";
    for (const auto& [key, value] : method.values) report["settings"][key] = value;
    report["median_ms"] = stages.medians();
    report["median_ms"]["total"] = stages.totalMedian();
    const int threadsUsed =
        method.threads ? method.threads : int(std::thread::hardware_concurrency());
    report["machine"] = method.backend == "cuda"
                            ? fmt::format("GPU {} (host CPU {})", cuda::deviceName(), cpuModel())
                            : fmt::format("{}, {} threads", cpuModel(), threadsUsed);
    if (info.hasReference) {
        scores.writeCsv((out / "scores.csv").string());
        scores.addTo(report);
    }
    writeFileAtomically((out / "report.json").string(), report.dump(2) + "\n");

    if (!job.quiet) {
        fmt::print("\n{} frames, {}x{}, {} threads. Median ms per frame:\n", last - first,
                   info.width, info.height, threadsUsed);
        fmt::print("  {}   (read {:.1f}, write {:.1f})\n", stages.line(), median(tRead),
                   median(tWrite));
        fmt::print("  reprojection: {}\n", report["reprojection"].get<std::string>());
        if (!method.description.empty()) fmt::print("  {}\n", method.description);
        if (info.hasReference) fmt::print("{}", scores.summary(job.filter));
        fmt::print("\nwrote {}/denoised_NNNN.exr{}, report.json{}\n", job.output,
                   job.png ? " and .png" : "", info.hasReference ? ", scores.csv" : "");
    }
    return 0;
}

void addDenoiseCommand(CLI::App& app, int& exitCode) {
    auto job = std::make_shared<DenoiseJob>();
    CLI::App* cmd = app.add_subcommand(
        "denoise", "denoise a sequence into OUTPUT: denoised_NNNN.exr (linear) and .png "
                   "(tone-mapped), report.json, and scores.csv when the input has references");
    cmd->add_option("input", job->input, "input directory")->required();
    cmd->add_option("-o,--output", job->output, "output directory")->required();
    cmd->add_option("--frames", job->frames, "frame range A:B (A..B-1), A: or :B");
    cmd->add_flag("-q,--quiet", job->quiet, "no progress or summary");
    cmd->add_flag("--overwrite", job->overwrite,
                  "replace the outputs of an earlier run in OUTPUT instead of refusing them");
    cmd->add_flag("--debug", job->debug,
                  "also write accumulated colour, fitted frame, history length, discard mask");
    cmd->add_flag("!--no-png", job->png, "skip the tone-mapped PNGs");
    cmd->add_flag("!--no-flip", job->flip, "skip FLIP when scoring (the slowest metric)");
    cmd->add_flag("!--no-motion", job->motion,
                  "ignore the sequence's motion vectors and previous positions: reproject by "
                  "the cameras alone, as the BMFR paper does (for comparisons)");
    cmd->add_option("--filter", job->filter,
                    "the filter: " + fmt::format("{}", fmt::join(filterNames(), ", ")))
        ->check(oneOf(filterNames()))
        ->default_val("bmfr");
    cmd->add_option("--sample-fraction", job->sampleFraction,
                    "simulate fewer than 1 spp: keep this fraction of pixels per frame (0, 1]")
        ->default_val(1.0);
    cmd->add_option("--channel", job->channels,
                    "BUFFER=LAYER: read a buffer (" +
                        fmt::format("{}", fmt::join(layeredBufferNames(), ", ")) +
                        ") from this layer of multilayer EXRs, as albedo=ViewLayer.DiffCol; "
                        "repeatable");
    job->options.addTo(*cmd, filterNames());
    setHelpIntro(cmd, R"(examples:
  bmfr denoise bmfr-demo/input -o denoised
  bmfr denoise frames/ -o out --filter svgf --preset quality --frames 0:60

input: a folder of linear EXR frames with noise-free features and the camera: sequence.json
  naming each frame's files (`bmfr render` writes it, and tools/blender/render_sequence.py for
  Blender Cycles, with multilayer EXRs), or the original BMFR dataset (color0.exr ... and
  camera_matrices.h).
  required per frame: color (1-spp radiance, RGB), albedo (RGB), normal (world space, XYZ),
                      position (world space, XYZ), view_projection (4x4 camera matrix)
  optional: motion (pixels; else reprojection by the cameras), reference (then every frame
            is scored), emission, visibility, jitter, reset (a camera cut)
  the layouts: docs/input-layouts.md; `bmfr settings FILTER` lists every setting)");
    cmd->callback([job, &exitCode] { exitCode = runDenoise(*job); });
}

} // namespace bmfr::app
