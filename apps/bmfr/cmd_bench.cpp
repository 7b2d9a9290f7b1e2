#include "backend/cpu/isa.h"
#include "backend/cuda/cuda_device.h"
#include "bench_inputs.h"
#include "commands.h"
#include "core/vec.h"
#include "progress.h"
#include "stage_log.h"
#include "stream_floor.h"
#include "synth/procedural_scene.h"
#include "usage.h"
#include <algorithm>
#include <bmfr/bmfr.hpp>
#include <fmt/core.h>
#include <fmt/format.h>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string_view>

namespace bmfr::app {

namespace {

/// A CUDA frame's time on the device: every stage but the host uploads and downloads (an
/// engine that hands over device buffers has neither).
double onDeviceMs(const StageTimes& t) {
    double ms = 0;
    for (int k = 0; k < t.count; ++k)
        if (std::string_view(t.name[k]) != "upload" && std::string_view(t.name[k]) != "download")
            ms += t.ms[k];
    return ms;
}

nlohmann::json benchOne(const BenchJob& job, int w, int h, const std::function<void()>& frameDone) {
    // With motion, each frame twice (half as many): its vectors point to the frame before it
    // when the cycle goes forwards and to the one after it when it comes back.
    const int distinct = job.motion ? std::max(2, distinctFrames(w, h) / 2) : distinctFrames(w, h);
    ProceduralSceneOptions so;
    so.width = w, so.height = h, so.frames = distinct;
    so.objectSpeed = job.motion ? 1.0f : 0.0f, so.motionVectors = job.motion;
    ProceduralScene scene(so);
    std::vector<FrameData> frames(static_cast<size_t>(distinct)), backwards;
    for (int i = 0; i < distinct; ++i) scene.render(i, frames[size_t(i)]);
    if (job.motion) {
        backwards.resize(static_cast<size_t>(distinct));
        for (int i = 0; i < distinct; ++i) scene.render(i, backwards[size_t(i)], i + 1);
    }
    const bool mara = job.filter == "mara2017", maraBaseline = job.referenceFilter() == "mara2017";
    if (mara || maraBaseline)
        for (auto* set : {&frames, &backwards})
            for (FrameData& f : *set) addFactorisation(f);
    const std::string threads = std::to_string(job.threads);
    SettingValues values = {{"threads", threads}, {"backend", job.backend}};
    auto addSets = [](SettingValues& v, const std::string& filter,
                      const std::vector<std::string>& sets, const char* flag) {
        for (const std::string& kv : sets) v.push_back(parseSetting(filter, kv, flag));
    };
    for (const auto& kv : presetSettings(job.filter, job.preset)) values.push_back(kv);
    addSets(values, job.filter, job.sets, "--set");
    std::unique_ptr<Filter> d = makeFromCommandLine(job.filter, values);
    // The baseline backend runs on the same frames, interleaved frame by frame with the
    // measured one, so both see the same machine load.
    std::unique_ptr<Filter> ref;
    const std::string baseline = job.motion ? job.backend : job.baselineBackend;
    if (job.baseline) {
        SettingValues baseValues = {{"threads", threads}, {"backend", baseline}};
        for (const auto& kv : presetSettings(job.referenceFilter(), job.baselinePreset))
            baseValues.push_back(kv);
        addSets(baseValues, job.referenceFilter(), job.baselineSets, "--baseline-set");
        ref = makeFromCommandLine(job.referenceFilter(), baseValues);
    }
    // The memory baselines, measured in this run on buffers freed before the passes start: the
    // BMFR fast passes' own traffic, and (any filter) the inputs and a float history once.
    const bool floors = job.filter == "bmfr" && job.backend == "cpu";
    const auto* bmfrFilter = dynamic_cast<const BmfrDenoiser*>(d.get());
    const bool half = bmfrFilter && bmfrFilter->settings().halfHistory;
    const double floor = floors ? streamFloorMs(w, h, job.threads, 5, fastPassTraffic(half)) : 0.0;
    const bool gpu = job.backend == "cuda";
    const double single = job.backend == "cpu"
                              ? streamFloorMs(w, h, job.threads, 5, singlePassTraffic())
                          : gpu ? cuda::copyFloorMs(trafficBytes(w, h, singlePassTraffic()))
                                : 0.0;
    const double singleHalf = job.backend == "cpu" && half
                                  ? streamFloorMs(w, h, job.threads, 5, singlePassTraffic(true))
                                  : 0.0;
    // Device copies of every frame's buffers, made before timing starts.
    DeviceFrames onDevice;
    std::vector<FrameInput> deviceFrames, deviceBackwards;
    if (job.deviceBuffers) {
        for (const FrameData& f : frames) deviceFrames.push_back(onDevice.add(f.input()));
        for (const FrameData& f : backwards) deviceBackwards.push_back(onDevice.add(f.input()));
    }
    StageLog log, refLog;
    std::vector<double> deviceMs; // GPU frame time without the host transfers
    for (int i = 0; i < job.warmup + job.frames; ++i) {
        bool back = false;
        const int k = cycledFrame(i, distinct, back);
        const FrameData& frame = (back && job.motion ? backwards : frames)[size_t(k)];
        const FrameInput in = frame.input();
        if (job.deviceBuffers)
            d->denoise((back && job.motion ? deviceBackwards : deviceFrames)[size_t(k)]);
        else
            d->denoise(mara ? in : withoutFactorisation(in));
        if (i >= job.warmup) {
            log.add(d->lastStats().times);
            if (gpu) deviceMs.push_back(onDeviceMs(d->lastStats().times));
        }
        if (ref) {
            const FrameInput base = job.motion ? frame.input(false) : in;
            ref->denoise(maraBaseline ? base : withoutFactorisation(base));
            if (i >= job.warmup) refLog.add(ref->lastStats().times);
        }
        frameDone();
    }
    nlohmann::json r = {
        {"total_ms", log.totalMedian()}, {"stages", log.medians()}, {"line", log.line()}};
    if (floors) r["stream_floor_ms"] = floor;
    if (single > 0) r["single_pass_floor_ms"] = single;
    if (singleHalf > 0) r["single_pass_floor_half_ms"] = singleHalf;
    if (bmfrFilter) r["history"] = half ? "half" : "float";
    r["backend"] = job.backend;
    if (job.deviceBuffers) r["input"] = "device buffers";
    if (job.backend == "cpu") r["cpu_path"] = cpu::isaName(cpu::activeIsa());
    if (gpu) {
        r["device"] = cuda::deviceName();
        std::nth_element(deviceMs.begin(), deviceMs.begin() + long(deviceMs.size() / 2),
                         deviceMs.end());
        r["device_ms"] = deviceMs.empty() ? 0.0 : deviceMs[deviceMs.size() / 2];
    }
    if (ref) {
        r["baseline_backend"] = job.motion ? job.backend + ", camera path" : baseline;
        r["baseline_filter"] = job.referenceFilter();
        r["baseline_total_ms"] = refLog.totalMedian();
        r["baseline_stages"] = refLog.medians();
        r["speedup"] = refLog.totalMedian() / log.totalMedian();
        r["baseline_line"] = refLog.line();
    }
    return r;
}

} // namespace

void addBenchCommand(CLI::App& app, int& exitCode) {
    auto job = std::make_shared<BenchJob>();
    CLI::App* cmd =
        app.add_subcommand("bench", "median ms per frame and per stage on synthetic input");
    cmd->add_option("--sizes", job->sizes, "resolutions WxH")
        ->delimiter(',')
        ->default_str("1280x720,1920x1080,3840x2160");
    cmd->add_option("--warmup", job->warmup, "untimed frames first")->default_val(5);
    cmd->add_option("--frames", job->frames, "timed frames")->default_val(30);
    cmd->add_option("--threads", job->threads, "worker threads, 0 = all cores")->default_val(0);
    cmd->add_flag("--json", job->json, "print one JSON object");
    cmd->add_flag("-q,--quiet", job->quiet, "no progress (the results are still printed)");
    CLI::Option* noBaseline =
        cmd->add_flag("!--no-baseline", job->baseline,
                      "skip the baseline backend run interleaved with the measured one");
    CLI::Option* baselineBackend = cmd->add_option("--baseline-backend", job->baselineBackend,
                                                   "the backend the speed-up is measured against")
                                       ->check(oneOf(backendNames()))
                                       ->default_val("reference");
    cmd->add_option("--backend", job->backend, "the backend measured: reference, cpu or cuda")
        ->check(oneOf(backendNames()))
        ->default_val("cpu");
    CLI::Option* one = cmd->add_option("--filter", job->filter, "the filter measured")
                           ->check(oneOf(filterNames()))
                           ->default_val("bmfr");
    std::vector<std::string> choices = filterNames();
    choices.push_back("all");
    CLI::Option* several =
        cmd->add_option("--filters", job->filters,
                        "several filters on --backend, interleaved frame by frame, as one table "
                        "beside BMFR and the single-pass floor: a comma list, or all")
            ->delimiter(',')
            ->check(oneOf(choices))
            ->excludes(one);
    CLI::Option* baselineFilter =
        cmd->add_option("--baseline-filter", job->baselineFilter,
                        "another filter as the baseline, on --baseline-backend (walr beside bmfr: "
                        "--filter walr --baseline-filter bmfr --baseline-backend cpu)")
            ->check(oneOf(filterNames()));
    cmd->add_option("--preset", job->preset,
                    "the measured filter's preset: quality (the default) or faithful (bmfr "
                    "settings --preset)")
        ->check(oneOf(presetNames()))
        ->default_val("quality");
    CLI::Option* baselinePreset =
        cmd->add_option("--baseline-preset", job->baselinePreset,
                        "the baseline's preset (the quality preset against the faithful one: "
                        "--baseline-preset faithful --baseline-backend cpu)")
            ->check(oneOf(presetNames()))
            ->default_val("quality");
    CLI::Option* baselineSet =
        cmd->add_option("--baseline-set", job->baselineSets,
                        "key=value: a setting of the baseline, repeatable (half against float "
                        "history: --set halfHistory=true --baseline-backend cpu --baseline-set "
                        "halfHistory=false)");
    // --filters has no baseline: its options would be dropped without a word.
    for (CLI::Option* o :
         {noBaseline, baselineBackend, baselineFilter, baselinePreset, baselineSet})
        several->excludes(o);
    cmd->add_option("--set", job->sets,
                    "key=value: a setting of the measured filter (bmfr settings NAME), "
                    "repeatable; with --filters, of every filter that has the key (a flag "
                    "name, walr-iterations=3, reaches only its own)");
    cmd->add_flag("--device-buffers", job->deviceBuffers,
                  "with --backend cuda: the input in device memory (copied there once, as an "
                  "engine's G-buffer) and the output left there: no upload or download");
    cmd->add_flag("--motion", job->motion,
                  "moving objects with motion vectors and previous positions; the baseline is "
                  "the same backend reprojecting by the camera alone (the cost of the motion "
                  "path)");
    cmd->callback([job, &exitCode] {
        nlohmann::json all;
        Progress progress("bench", int(job->sizes.size()) * (job->warmup + job->frames),
                          job->quiet);
        int done = 0;
        if (std::find(job->filters.begin(), job->filters.end(), "all") != job->filters.end())
            job->filters = filterNames();
        const bool table = !job->filters.empty();
        if (table && job->motion)
            throw UsageError("--filters times the filters on plain frames: drop --motion, or "
                             "time one --filter");
        if (job->deviceBuffers && job->backend != "cuda")
            throw UsageError("--device-buffers needs --backend cuda");
        if (table) // an unknown --set key before any size runs (a bad value: at the first)
            parseSharedSettings(job->filters.front(), job->filters, job->sets, "--set");
        for (const std::string& size : job->sizes) {
            int w = 0, h = 0;
            char x = 0;
            std::istringstream in(size);
            if (!(in >> w >> x >> h) || x != 'x' || w <= 0 || h <= 0)
                throw UsageError("--sizes: '" + size + "' is not WxH");
            if (table) {
                nlohmann::json r = benchFilters(*job, w, h, [&] { progress.step(++done); });
                progress.pause();
                if (!job->json) printFilterTable(*job, size, r);
                for (auto& [name, f] : r["filters"].items()) f.erase("line");
                all[size] = r;
                continue;
            }
            nlohmann::json r = benchOne(*job, w, h, [&] { progress.step(++done); });
            if (!job->json) {
                progress.pause();
                std::string how;
                if (r.contains("cpu_path")) how = r["cpu_path"].get<std::string>() + " path";
                if (r.contains("device")) how = r["device"].get<std::string>();
                if (r.contains("input")) how += ", " + r["input"].get<std::string>();
                if (job->preset != "quality")
                    how += (how.empty() ? "" : ", ") + job->preset + " preset";
                if (r.contains("history"))
                    how += (how.empty() ? "" : ", ") + r["history"].get<std::string>() + " history";
                fmt::print("{:>10} {} on {}{}: {} ms   (median of {} frames)\n", size, job->filter,
                           job->backend, how.empty() ? "" : " (" + how + ")",
                           r["line"].get<std::string>(), job->frames);
                if (r.contains("baseline_line") && job->motion)
                    fmt::print("{:>10} camera path: {} ms   -> motion vectors cost {:+.1f}%\n", "",
                               r["baseline_line"].get<std::string>(),
                               100.0 * (1.0 / r["speedup"].get<double>() - 1.0));
                else if (r.contains("baseline_line") &&
                         (!job->baselineFilter.empty() || !job->baselineSets.empty() ||
                          job->preset != job->baselinePreset))
                    fmt::print("{:>10} {} on {}{}: {} ms   -> {} takes {:.2f}x its time\n", "",
                               job->referenceFilter(), job->baselineBackend,
                               job->baselineSets.empty() && job->preset == job->baselinePreset
                                   ? ""
                                   : fmt::format(" ({} preset{}{})", job->baselinePreset,
                                                 job->baselineSets.empty() ? "" : ", ",
                                                 fmt::join(job->baselineSets, ", ")),
                               r["baseline_line"].get<std::string>(), job->filter,
                               1.0 / r["speedup"].get<double>());
                else if (r.contains("baseline_line"))
                    fmt::print("{:>10} {} backend: {} ms   -> {} is {:.1f}x faster\n", "",
                               job->baselineBackend, r["baseline_line"].get<std::string>(),
                               job->backend, r["speedup"].get<double>());
                // On a GPU the floor is held to the device's own time (no host transfers).
                const bool gpu = r.contains("device_ms");
                if (gpu)
                    fmt::print("{:>10} on the device (without upload and download): {:.3f} ms\n",
                               "", r["device_ms"].get<double>());
                auto floorLine = [&r, gpu](const char* key, const char* what) {
                    if (!r.contains(key)) return;
                    const double ms = r[key].get<double>();
                    const double measured = r[gpu ? "device_ms" : "total_ms"].get<double>();
                    fmt::print("{:>10} {}: {:.3f} ms -> measured is {:.1f}x that\n", "", what, ms,
                               measured / ms);
                };
                floorLine("stream_floor_ms", "memory floor (streaming the same bytes)");
                floorLine("single_pass_floor_ms",
                          gpu ? "memory floor (inputs and float history once, at this GPU's "
                                "device-to-device copy rate)"
                              : "single-pass floor (inputs and float history once)");
                floorLine("single_pass_floor_half_ms",
                          "single-pass floor (inputs and half history once)");
                std::fflush(stdout);
            }
            r.erase("line");
            r.erase("baseline_line");
            all[size] = r;
        }
        progress.finish();
        if (job->json) fmt::print("{}\n", all.dump());
        exitCode = 0;
    });
}

} // namespace bmfr::app
