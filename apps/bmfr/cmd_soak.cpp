// `bmfr soak`: many frames through one filter on a synthetic sequence, to show that memory stays
// flat and the output finite over a long run.
#include "commands.h"
#include "progress.h"
#include "synth/procedural_scene.h"
#include "usage.h"
#include <bmfr/bmfr.hpp>
#include <cmath>
#include <cstdio>
#include <fcntl.h>
#include <fmt/core.h>
#include <nlohmann/json.hpp>
#include <sstream>
#include <unistd.h>

namespace bmfr::app {

namespace {

/// Anonymous resident memory of this process, bytes (Linux /proc/self/statm: resident less
/// file-backed). The binary's code pages, faulted in as a path first runs on a later frame, are
/// not a leak. Reads into a stack buffer: the measurement itself must allocate nothing.
long long residentBytes() {
    char text[128] = {};
    const int fd = ::open("/proc/self/statm", O_RDONLY);
    if (fd < 0) return 0;
    const ssize_t n = ::read(fd, text, sizeof text - 1);
    ::close(fd);
    long long pages = 0, resident = 0, shared = 0;
    if (n <= 0 || std::sscanf(text, "%lld %lld %lld", &pages, &resident, &shared) != 3) return 0;
    return (resident - shared) * ::sysconf(_SC_PAGESIZE);
}

struct SoakJob {
    std::string filter = "bmfr", backend = "cpu", size = "64x48";
    int frames = 2000, threads = 0;
    bool json = false, quiet = false;
};

int runSoak(const SoakJob& job) {
    int w = 0, h = 0;
    char x = 0;
    std::istringstream in(job.size);
    if (!(in >> w >> x >> h) || x != 'x' || w < 1 || h < 1 || w > 4096 || h > 4096)
        throw UsageError("--size: '" + job.size + "' is not WxH within 4096x4096");
    if (job.frames < 1 || job.frames > 10000000) throw UsageError("--frames must be in [1, 1e7]");
    ProceduralSceneOptions o;
    o.width = w, o.height = h, o.frames = 16;
    ProceduralScene scene(o);
    std::vector<FrameData> frames(16);
    std::vector<FrameInput> inputs(16);
    for (int i = 0; i < 16; ++i) {
        scene.render(i, frames[size_t(i)]);
        inputs[size_t(i)] = frames[size_t(i)].input(); // made once: the loop allocates nothing
    }
    auto filter = makeFilter(job.filter,
                             {{"backend", job.backend}, {"threads", std::to_string(job.threads)}});
    Progress progress("soak", job.frames, job.quiet || job.json);
    long long start = 0, peak = 0;
    long long nonFinite = 0;
    for (int i = 0; i < job.frames; ++i) {
        // Forwards then backwards through the 16 frames, so the camera motion stays continuous.
        const int k = i % 30 < 16 ? i % 30 : 30 - i % 30;
        const ImageView out = filter->denoise(inputs[size_t(k)]);
        for (long p = 0; p < long(w) * h * 3; ++p) nonFinite += !std::isfinite(out.data[p]);
        if (i == 0) start = residentBytes(); // after the first frame's one-time allocations
        peak = std::max(peak, residentBytes());
        progress.step(i + 1);
    }
    progress.finish();
    const long long end = residentBytes();
    nlohmann::json r = {{"filter", job.filter},     {"backend", job.backend},
                        {"frames", job.frames},     {"size", job.size},
                        {"rss_start_bytes", start}, {"rss_end_bytes", end},
                        {"rss_peak_bytes", peak},   {"non_finite_outputs", nonFinite}};
    if (job.json)
        fmt::print("{}\n", r.dump());
    else if (!job.quiet)
        fmt::print("soak: {} frames of {} through {} ({} backend): RSS {:.1f} MB after the first "
                   "frame, {:.1f} MB at the end (peak {:.1f} MB); {} non-finite output values\n",
                   job.frames, job.size, job.filter, job.backend, double(start) / 1e6,
                   double(end) / 1e6, double(peak) / 1e6, nonFinite);
    return nonFinite ? 1 : 0;
}

} // namespace

void addSoakCommand(CLI::App& app, int& exitCode) {
    auto job = std::make_shared<SoakJob>();
    CLI::App* cmd = app.add_subcommand(
        "soak", "many frames through one filter: RSS at start and end, non-finite outputs");
    cmd->add_option("--filter", job->filter, "the filter")
        ->check(oneOf(filterNames()))
        ->default_val("bmfr");
    cmd->add_option("--backend", job->backend, "the backend")
        ->check(oneOf(backendNames()))
        ->default_val("cpu");
    cmd->add_option("--frames", job->frames, "frames to run")->default_val(2000);
    cmd->add_option("--size", job->size, "frame size WxH")->default_val("64x48");
    cmd->add_option("--threads", job->threads, "worker threads, 0 = all cores")->default_val(0);
    cmd->add_flag("--json", job->json, "print one JSON object");
    cmd->add_flag("-q,--quiet", job->quiet, "no progress or summary");
    cmd->callback([job, &exitCode] { exitCode = runSoak(*job); });
}

} // namespace bmfr::app
