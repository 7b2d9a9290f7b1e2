#include "commands.h"
#include "stage_log.h"
#include "synth/procedural_scene.h"
#include <algorithm>
#include <bmfr/denoiser.h>
#include <bmfr/error.h>
#include <bmfr/svgf.h>
#include <fmt/core.h>
#include <nlohmann/json.hpp>
#include <sstream>

namespace bmfr::app {

namespace {

struct BenchJob {
    std::vector<std::string> sizes{"1280x720"};
    int warmup = 5, frames = 30, distinct = 8, threads = 0;
    bool json = false;
    std::string filter = "bmfr";
};

nlohmann::json benchOne(const BenchJob& job, int w, int h) {
    ProceduralSceneOptions so;
    so.width = w, so.height = h, so.frames = job.distinct;
    ProceduralScene scene(so);
    std::vector<FrameData> frames(size_t(job.distinct));
    for (int i = 0; i < job.distinct; ++i) scene.render(i, frames[size_t(i)]);
    Settings s;
    s.threads = job.threads;
    SvgfSettings sv;
    sv.threads = job.threads;
    std::unique_ptr<Filter> d = makeFilter(job.filter, s, sv);
    StageLog log;
    for (int i = 0; i < job.warmup + job.frames; ++i) {
        // Cycle forwards then backwards so the camera motion stays continuous.
        int period = 2 * job.distinct - 2, k = period > 0 ? i % period : 0;
        if (k >= job.distinct) k = period - k;
        d->denoise(frames[size_t(k)].input());
        if (i >= job.warmup) log.add(d->lastStats().times);
    }
    return {{"total_ms", log.totalMedian()}, {"stages", log.medians()}, {"line", log.line()}};
}

} // namespace

void addBenchCommand(CLI::App& app, int& exitCode) {
    auto job = std::make_shared<BenchJob>();
    CLI::App* cmd =
        app.add_subcommand("bench", "median ms per frame and per stage on synthetic input");
    cmd->add_option("--sizes", job->sizes, "resolutions WxH")
        ->delimiter(',')
        ->default_str("1280x720");
    cmd->add_option("--warmup", job->warmup, "untimed frames first")->default_val(5);
    cmd->add_option("--frames", job->frames, "timed frames")->default_val(30);
    cmd->add_option("--threads", job->threads, "worker threads, 0 = all cores")->default_val(0);
    cmd->add_flag("--json", job->json, "print one JSON object");
    cmd->add_option("--filter", job->filter, "bmfr or svgf")->default_val("bmfr");
    cmd->callback([job, &exitCode] {
        nlohmann::json all;
        for (const std::string& size : job->sizes) {
            int w = 0, h = 0;
            char x = 0;
            std::istringstream in(size);
            if (!(in >> w >> x >> h) || x != 'x' || w <= 0 || h <= 0)
                throw Error("--sizes: '" + size + "' is not WxH");
            nlohmann::json r = benchOne(*job, w, h);
            if (!job->json)
                fmt::print("{:>10} {}: {} ms   (median of {} frames)\n", size, job->filter,
                           r["line"].get<std::string>(), job->frames);
            r.erase("line");
            all[size] = r;
        }
        if (job->json) fmt::print("{}\n", all.dump());
        exitCode = 0;
    });
}

} // namespace bmfr::app
