#include "commands.h"
#include "core/hash.h"
#include "core/image.h"
#include "core/stopwatch.h"
#include "eval/comparison.h"
#include "eval/frame_scores.h"
#include "io/atomic_file.h"
#include "io/exr.h"
#include "io/png.h"
#include "io/range_parsers.h"
#include "io/sequence.h"
#include "metrics/basic_metrics.h"
#include "progress.h"
#include "stage_log.h"
#include <algorithm>
#include <bmfr/bmfr.h>
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

} // namespace

int runDenoise(const DenoiseJob& job) {
    std::error_code ec;
    if (fs::exists(job.output, ec) && fs::equivalent(job.input, job.output, ec))
        throw Error("-o " + job.output + " is the input folder " + job.input +
                    "; refusing to write the results among the inputs (give another folder)");
    auto reader = SequenceReader::open(job.input);
    reader->setLayerOverrides(parseLayerMap(job.channels));
    const SequenceInfo& info = reader->info();
    const SettingValues values = job.options.resolve(
        job.filter, {info.positionLimitSquared, info.normalLimitSquared, info.colorIsDemodulated});
    std::unique_ptr<Filter> filter = makeFilter(job.filter, values);
    auto* bmfrFilter = dynamic_cast<BmfrDenoiser*>(filter.get());
    if (bmfrFilter)
        for (const Feature& f : bmfrFilter->settings().features)
            if (f.source == FeatureSource::Extra && f.extraIndex >= int(info.extraNames.size()))
                throw Error(fmt::format("feature extra{} requested, {} has {} extra buffers",
                                        f.extraIndex, job.input, info.extraNames.size()));
    const std::string features =
        bmfrFilter ? formatFeatures(bmfrFilter->settings().features) : std::string();
    const int threads = std::stoi(settingValue(values, "threads", "0"));
    auto [first, last] = parseFrameRange(job.frames, info.frameCount);
    fs::create_directories(job.output);
    if (job.debug) fs::create_directories(fs::path(job.output) / "debug");

    filter->setDebugOutputs(job.debug);
    if (!job.quiet)
        fmt::print("bmfr denoise ({}, {} backend): {} ({} layout, {}x{}, frames {}:{}){}\n",
                   job.filter, settingValue(values, "backend", "cpu"), job.input, info.layout,
                   info.width, info.height, first, last,
                   bmfrFilter ? ", features " + features : std::string());

    Progress progress("denoise", last - first, job.quiet);
    if (!(job.sampleFraction > 0.0f && job.sampleFraction <= 1.0f))
        throw Error(fmt::format("--sample-fraction {} is outside (0, 1]", job.sampleFraction));
    ImageF sampleMask(info.width, info.height, 1);
    StageLog stages;
    std::vector<double> tRead, tWrite;
    int64_t nonFinite = 0;
    std::vector<int> badFrames;
    std::vector<FrameScores> scores, noisyScores;
    FrameData frame;
    ImageF previousOut, previousRef, previousNoisy;
    std::vector<double> referenceTemporal;
    int motionFrames = 0; // frames that came with motion vectors or previous positions

    for (int i = first; i < last; ++i) {
        Stopwatch clock;
        reader->load(i, frame);
        tRead.push_back(clock.lap());
        FrameInput in = frame.input(job.motion);
        if (i == first && job.filter == "mara2017" && !in.matteIndirect.data)
            fmt::print(stderr,
                       "bmfr: warning: {} has no matte_indirect (render it with --paths mara): "
                       "mara2017 filters the whole demodulated colour as matte light, with no "
                       "glossy term and no separate direct light, a deviation from the paper\n",
                       job.input);
        motionFrames += frame.motion.width || frame.previousPosition.width ? 1 : 0;
        if (job.sampleFraction < 1.0f) {
            // Fewer than 1 spp, simulated: a fixed pseudo-random subset of pixels per frame.
            for (long k = 0; k < sampleMask.pixelCount(); ++k)
                sampleMask.data()[k] =
                    unitFloat(hashKeys(uint32_t(k), uint32_t(i), 0x5eedu)) < job.sampleFraction
                        ? 1.0f
                        : 0.0f;
            in.sampleMask = view(sampleMask);
        }
        ImageF out = copyOf(filter->denoise(in));
        const FrameStats& st = filter->lastStats();
        stages.add(st.times);
        if (st.nonFiniteInputs) nonFinite += st.nonFiniteInputs, badFrames.push_back(i);

        clock.lap();
        const std::string stem = fmt::format("{:04d}", i);
        writeExr((fs::path(job.output) / ("denoised_" + stem + ".exr")).string(), out);
        if (job.png)
            writePngToneMapped((fs::path(job.output) / ("denoised_" + stem + ".png")).string(),
                               out);
        if (job.debug) {
            DebugBuffers d = filter->debug();
            const fs::path dd = fs::path(job.output) / "debug";
            writeExr((dd / ("accumulated_" + stem + ".exr")).string(), copyOf(d.accumulatedNoisy));
            writeExr((dd / ("fitted_" + stem + ".exr")).string(), copyOf(d.fitted));
            writeExr((dd / ("history_length_" + stem + ".exr")).string(), copyOf(d.historyLength));
            writeExr((dd / ("discard_mask_" + stem + ".exr")).string(), copyOf(d.discardMask));
            writePngToneMapped((dd / ("history_length_" + stem + ".png")).string(),
                               copyOf(d.historyLength), 1.0f / 16.0f);
            writePngToneMapped((dd / ("discard_mask_" + stem + ".png")).string(),
                               copyOf(d.discardMask), 1.0f / 15.0f);
        }
        tWrite.push_back(clock.lap());

        if (info.hasReference) {
            ImageF noisy = frame.color;
            if (info.colorIsDemodulated)
                for (size_t k = 0; k < noisy.pixels.size(); ++k)
                    noisy.pixels[k] *= frame.albedo.pixels[k];
            const PreviousScoredFrame before{previousOut, previousRef};
            scores.push_back(
                scoreFrame(out, frame.reference, i > first ? &before : nullptr, job.flip));
            FrameScores n;
            n.rmse = rmseToneMapped(noisy, frame.reference);
            if (i > first) n.temporal = temporalError(noisy, previousNoisy);
            noisyScores.push_back(n);
            referenceTemporal.push_back(i > first ? temporalError(frame.reference, previousRef)
                                                  : NAN);
            previousRef = frame.reference;
            previousNoisy = std::move(noisy);
        }
        previousOut = std::move(out);
        progress.step(i - first + 1);
    }
    progress.finish();

    if (nonFinite)
        fmt::print(stderr,
                   "bmfr: warning: replaced {} NaN/Inf input values with 0 in {} frame(s) "
                   "(first: frame {})\n",
                   nonFinite, badFrames.size(), badFrames.front());

    nlohmann::json report;
    std::string summary;
    report["input"] = job.input;
    report["frames"] = last - first;
    report["resolution"] = {info.width, info.height};
    if (bmfrFilter) report["features"] = features;
    report["filter"] = job.filter;
    report["backend"] = settingValue(values, "backend", "cpu");
    report["reprojection"] = motionFrames == 0 ? "camera (the input has no motion vectors)"
                             : job.motion      ? "motion vectors"
                                               : "camera (motion vectors ignored: --no-motion)";
    for (const auto& [key, value] : values) report["settings"][key] = value;
    report["median_ms"] = stages.medians();
    report["median_ms"]["total"] = stages.totalMedian();
    if (info.hasReference) {
        std::ostringstream csv;
        // The metric columns and keys of `bmfr eval`'s per_frame.csv, then the input's own.
        csv << "frame";
        for (const MetricInfo& m : metricList()) csv << "," << m.key;
        csv << ",noisy_rmse,noisy_temporal_error,reference_temporal_error\n";
        for (size_t k = 0; k < scores.size(); ++k) {
            csv << first + int(k);
            for (const MetricInfo& m : metricList())
                csv << "," << csvNumber(metricValue(scores[k], m.key));
            csv << "," << csvNumber(noisyScores[k].rmse) << ","
                << csvNumber(noisyScores[k].temporal) << "," << csvNumber(referenceTemporal[k])
                << "\n";
        }
        writeFileAtomically((fs::path(job.output) / "scores.csv").string(), csv.str());
        const FrameScores m = meanScores(scores), nm = meanScores(noisyScores);
        double refTemporal = 0;
        int n = 0;
        for (double v : referenceTemporal)
            if (std::isfinite(v)) refTemporal += v, ++n;
        refTemporal = n ? refTemporal / n : NAN;
        auto num = [](double v) {
            return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
        };
        for (const MetricInfo& k : metricList())
            report["scores"][k.key] = num(metricValue(m, k.key));
        report["scores"]["noisy_rmse"] = num(nm.rmse);
        report["scores"]["noisy_temporal_error"] = num(nm.temporal);
        report["scores"]["reference_temporal_error"] = num(refTemporal);
        report["scores"]["color_space"] = "tone-mapped: clamp(x^(1/2.2), 0, 1); relmse linear";
        summary = fmt::format(
            "\nScores vs reference (mean over frames; tone-mapped x^(1/2.2), relMSE linear):\n"
            "  {:<10} {:>8} {:>8} {:>7} {:>7} {:>8} {:>13} {:>11}\n"
            "  {:<10} {:>8.4f} {:>8} {:>7} {:>7} {:>8} {:>13.4f} {:>11}\n"
            "  {:<10} {:>8.4f} {:>8.2f} {:>7.4f} {:>7} {:>8.4f} {:>13.4f} {:>11.4f}\n"
            "  {:<10} {:>8} {:>8} {:>7} {:>7} {:>8} {:>13.4f} {:>11}\n",
            "", "RMSE", "PSNR dB", "SSIM", "FLIP", "relMSE", "temporal err", "change err", "noisy",
            nm.rmse, "", "", "", "", nm.temporal, "", job.filter, m.rmse, m.psnr, m.ssim,
            std::isfinite(m.flip) ? fmt::format("{:.4f}", m.flip) : "-", m.relmse, m.temporal,
            m.temporalChange, "reference", "", "", "", "", "", refTemporal, "");
    }
    writeFileAtomically((fs::path(job.output) / "report.json").string(), report.dump(2) + "\n");

    if (!job.quiet) {
        fmt::print("\n{} frames, {}x{}, {} threads. Median ms per frame:\n", last - first,
                   info.width, info.height,
                   threads ? threads : int(std::thread::hardware_concurrency()));
        fmt::print("  {}   (read {:.1f}, write {:.1f})\n", stages.line(), median(tRead),
                   median(tWrite));
        fmt::print("  reprojection: {}\n", report["reprojection"].get<std::string>());
        fmt::print("{}", summary);
        fmt::print("\nwrote {}/denoised_NNNN.exr{}, report.json{}\n", job.output,
                   job.png ? " and .png" : "", info.hasReference ? ", scores.csv" : "");
    }
    return 0;
}

void addDenoiseCommand(CLI::App& app, int& exitCode) {
    auto job = std::make_shared<DenoiseJob>();
    CLI::App* cmd = app.add_subcommand("denoise", "denoise a sequence (original BMFR dataset "
                                                  "layout or bmfr's sequence.json layout)");
    cmd->add_option("input", job->input, "input directory")->required();
    cmd->add_option("-o,--output", job->output, "output directory")->required();
    cmd->add_option("--frames", job->frames, "frame range A:B (A..B-1), A: or :B");
    cmd->add_flag("-q,--quiet", job->quiet, "no progress or summary");
    cmd->add_flag("--debug", job->debug,
                  "also write accumulated colour, fitted frame, history length, discard mask");
    cmd->add_flag("!--no-png", job->png, "skip the tone-mapped PNGs");
    cmd->add_flag("!--no-flip", job->flip, "skip FLIP when scoring (the slowest metric)");
    cmd->add_flag("!--no-motion", job->motion,
                  "ignore the sequence's motion vectors and previous positions: reproject by "
                  "the cameras alone, as the BMFR paper does (for comparisons)");
    cmd->add_option("--filter", job->filter,
                    "the filter: " + fmt::format("{}", fmt::join(filterNames(), ", ")))
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
    cmd->callback([job, &exitCode] { exitCode = runDenoise(*job); });
}

} // namespace bmfr::app
