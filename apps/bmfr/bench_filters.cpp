// `bmfr bench --filters`: several filters on one backend, timed on the same frames and
// interleaved frame by frame (each sees the same machine load), beside BMFR and the single-pass
// floor measured in the same run.
#include "backend/cpu/isa.h"
#include "backend/cuda/cuda_device.h"
#include "bench_inputs.h"
#include "filter_options.h"
#include "stage_log.h"
#include "stream_floor.h"
#include "synth/procedural_scene.h"
#include <fmt/core.h>

namespace bmfr::app {

nlohmann::json benchFilters(const BenchJob& job, int w, int h,
                            const std::function<void()>& frameDone) {
    const int distinct = distinctFrames(w, h);
    ProceduralSceneOptions so;
    so.width = w, so.height = h, so.frames = distinct;
    ProceduralScene scene(so);
    std::vector<FrameData> frames(static_cast<size_t>(distinct));
    for (int i = 0; i < distinct; ++i) {
        scene.render(i, frames[size_t(i)]);
        addFactorisation(frames[size_t(i)]); // read by Mara only
    }
    struct Timed {
        std::string name;
        std::unique_ptr<Filter> filter;
        StageLog log;
    };
    std::vector<Timed> timed;
    for (const std::string& name : job.filters) {
        SettingValues values = {{"threads", std::to_string(job.threads)}, {"backend", job.backend}};
        for (const auto& kv : presetSettings(name, job.preset)) values.push_back(kv);
        for (const auto& kv : parseSharedSettings(name, job.filters, job.sets, "--set"))
            values.push_back(kv);
        timed.push_back({name, makeFromCommandLine(name, values), {}});
    }
    const bool cpu = job.backend == "cpu";
    const double floor = cpu ? streamFloorMs(w, h, job.threads, 5, singlePassTraffic())
                         : job.backend == "cuda"
                             ? cuda::copyFloorMs(trafficBytes(w, h, singlePassTraffic()))
                             : 0.0;
    // With --device-buffers, each frame in device memory (copied there before timing), with
    // the factorisation (Mara's) and without (the others').
    DeviceFrames onDevice;
    std::vector<FrameInput> factored, plain;
    if (job.deviceBuffers)
        for (const FrameData& f : frames) {
            factored.push_back(onDevice.add(f.input()));
            plain.push_back(onDevice.add(withoutFactorisation(f.input())));
        }
    for (int i = 0; i < job.warmup + job.frames; ++i) {
        bool back = false;
        const size_t k = size_t(cycledFrame(i, distinct, back));
        const FrameInput in = frames[k].input();
        for (Timed& t : timed) {
            const bool mara = t.name == "mara2017";
            if (job.deviceBuffers)
                t.filter->denoise(mara ? factored[k] : plain[k]);
            else
                t.filter->denoise(mara ? in : withoutFactorisation(in));
            if (i >= job.warmup) t.log.add(t.filter->lastStats().times);
        }
        frameDone();
    }
    nlohmann::json r = {{"backend", job.backend}, {"preset", job.preset}, {"frames", job.frames}};
    if (job.deviceBuffers) r["input"] = "device buffers";
    if (cpu) r["cpu_path"] = cpu::isaName(cpu::activeIsa());
    if (floor > 0) r["single_pass_floor_ms"] = floor;
    double bmfrMs = 0;
    for (const Timed& t : timed)
        if (t.name == "bmfr") bmfrMs = t.log.totalMedian();
    for (const Timed& t : timed) {
        nlohmann::json f = {
            {"total_ms", t.log.totalMedian()}, {"stages", t.log.medians()}, {"line", t.log.line()}};
        if (bmfrMs > 0) f["x_bmfr"] = t.log.totalMedian() / bmfrMs;
        if (floor > 0) f["x_floor"] = t.log.totalMedian() / floor;
        r["filters"][t.name] = f;
    }
    return r;
}

void printFilterTable(const BenchJob& job, const std::string& size, const nlohmann::json& r) {
    std::string how = r.value("cpu_path", "");
    if (!how.empty()) how = " (" + how + " path)";
    if (r.contains("input")) how += ", input in device buffers";
    fmt::print("{} on {}{}, {} preset, median of {} frames, interleaved:\n", size, job.backend, how,
               job.preset, job.frames);
    fmt::print("  {:<9} {:>9} {:>7} {:>8}   stages (ms)\n", "filter", "ms", "x bmfr", "x floor");
    for (const std::string& name : job.filters) {
        const nlohmann::json& f = r["filters"][name];
        auto ratio = [&f](const char* key) {
            return f.contains(key) ? fmt::format("{:.2f}", f[key].get<double>()) : "-";
        };
        std::string stages = f["line"].get<std::string>();
        stages = stages.substr(0, stages.rfind(" | total")); // the total has its own column
        fmt::print("  {:<9} {:>9.2f} {:>7} {:>8}   {}\n", name, f["total_ms"].get<double>(),
                   ratio("x_bmfr"), ratio("x_floor"), stages);
    }
    if (r.contains("single_pass_floor_ms"))
        fmt::print("  single-pass floor (inputs and float history once): {:.2f} ms\n",
                   r["single_pass_floor_ms"].get<double>());
    std::fflush(stdout);
}

} // namespace bmfr::app
