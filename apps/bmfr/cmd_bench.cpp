#include "commands.h"
#include "synth/procedural_scene.h"
#include <algorithm>
#include <bmfr/denoiser.h>
#include <bmfr/error.h>
#include <fmt/core.h>
#include <nlohmann/json.hpp>
#include <sstream>

namespace bmfr::app {

namespace {

struct BenchJob {
    std::vector<std::string> sizes{"1280x720"};
    int warmup = 5, frames = 30, distinct = 8, threads = 0;
    bool json = false;
};

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

nlohmann::json benchOne(const BenchJob& job, int w, int h) {
    ProceduralSceneOptions so;
    so.width = w, so.height = h, so.frames = job.distinct;
    ProceduralScene scene(so);
    std::vector<FrameData> frames(size_t(job.distinct));
    for (int i = 0; i < job.distinct; ++i) scene.render(i, frames[size_t(i)]);
    Settings s;
    s.threads = job.threads;
    Denoiser d(s);
    std::vector<double> acc, fit, acc2, taa, total;
    for (int i = 0; i < job.warmup + job.frames; ++i) {
        // Cycle forwards then backwards so the camera motion stays continuous.
        int period = 2 * job.distinct - 2, k = period > 0 ? i % period : 0;
        if (k >= job.distinct) k = period - k;
        d.denoise(frames[size_t(k)].input());
        if (i < job.warmup) continue;
        const StageTimes& t = d.lastStats().times;
        acc.push_back(t.accumulate), fit.push_back(t.fit), acc2.push_back(t.accumulateFitted);
        taa.push_back(t.taa), total.push_back(t.total);
    }
    return {{"total_ms", median(total)},
            {"stages",
             {{"accumulate", median(acc)},
              {"fit", median(fit)},
              {"accumulate_fitted", median(acc2)},
              {"taa", median(taa)}}}};
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
    cmd->callback([job, &exitCode] {
        nlohmann::json all;
        for (const std::string& size : job->sizes) {
            int w = 0, h = 0;
            char x = 0;
            std::istringstream in(size);
            if (!(in >> w >> x >> h) || x != 'x' || w <= 0 || h <= 0)
                throw Error("--sizes: '" + size + "' is not WxH");
            nlohmann::json r = benchOne(*job, w, h);
            all[size] = r;
            if (!job->json)
                fmt::print("{:>10}: total {:8.2f} ms | accumulate {:7.2f} | fit {:7.2f} | "
                           "accumulate fitted {:7.2f} | taa {:7.2f}   (median of {} frames)\n",
                           size, r["total_ms"].get<double>(),
                           r["stages"]["accumulate"].get<double>(),
                           r["stages"]["fit"].get<double>(),
                           r["stages"]["accumulate_fitted"].get<double>(),
                           r["stages"]["taa"].get<double>(), job->frames);
        }
        if (job->json) fmt::print("{}\n", all.dump());
        exitCode = 0;
    });
}

} // namespace bmfr::app
