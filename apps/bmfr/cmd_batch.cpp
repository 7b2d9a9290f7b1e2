// bmfr batch: the Ray driver of tools/batch (Python, as Ray's API is), started with a Python
// that has Ray and this executable's own path, so that every task runs this same bmfr.
#include "commands.h"
#include "usage.h"
#include <bmfr/error.h>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <unistd.h>

namespace bmfr::app {

namespace {

namespace fs = std::filesystem;

struct BatchJob {
    std::string plan, output, cluster = "auto", python;
    int retries = 3;
    bool quiet = false;
};

fs::path thisExecutable() {
    std::error_code ec;
    const fs::path self = fs::read_symlink("/proc/self/exe", ec);
    if (ec) throw Error("cannot find bmfr's own path (/proc/self/exe): " + ec.message());
    return self;
}

/// The folder holding the bmfr_batch package: beside an installed bmfr, else the sources'.
fs::path packageFolder(const fs::path& self) {
    const fs::path installed = self.parent_path().parent_path() / "share" / "bmfr" / "batch";
    std::error_code ec;
    if (fs::exists(installed / "bmfr_batch" / "__main__.py", ec)) return installed;
    const fs::path source = BMFR_BATCH_SOURCE;
    if (fs::exists(source / "bmfr_batch" / "__main__.py", ec)) return source;
    throw Error(fmt::format("the batch driver (bmfr_batch) is in neither {} nor {}; install bmfr "
                            "again",
                            installed.string(), source.string()));
}

/// --python, then $BMFR_PYTHON, then the .venv/ Python configured at build time, then python3.
std::string pythonFor(const BatchJob& job) {
    if (!job.python.empty()) return job.python;
    if (const char* env = std::getenv("BMFR_PYTHON"); env && *env) return env;
    if (::access(BMFR_BATCH_PYTHON, X_OK) == 0) return BMFR_BATCH_PYTHON;
    return "python3";
}

int runBatch(const BatchJob& job) {
    const fs::path self = thisExecutable();
    const fs::path package = packageFolder(self);
    const std::string python = pythonFor(job);
    std::string path = package.string();
    if (const char* old = std::getenv("PYTHONPATH"); old && *old) path += std::string(":") + old;
    ::setenv("PYTHONPATH", path.c_str(), 1);
    std::vector<std::string> args = {
        python,     "-m",         "bmfr_batch", job.plan,    "-o",
        job.output, "--cluster",  job.cluster,  "--retries", std::to_string(job.retries),
        "--bmfr",   self.string()};
    if (job.quiet) args.push_back("-q");
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    std::fflush(stdout);
    ::execvp(python.c_str(), argv.data());
    throw Error(fmt::format("cannot run the batch driver with {}: {}; install Ray with "
                            "scripts/install-ray.sh, or name a Python that has it with --python",
                            python, std::strerror(errno)));
}

} // namespace

void addBatchCommand(CLI::App& app, int& exitCode) {
    auto job = std::make_shared<BatchJob>();
    CLI::App* cmd = app.add_subcommand(
        "batch", "render, denoise and score the sequences of a plan on a Ray cluster: parts of "
                 "renders, denoises and scores as tasks, resumable; one table across them");
    cmd->add_option("plan", job->plan,
                    "the plan: JSON naming sequences, methods and metrics "
                    "(docs/batch.md)")
        ->required();
    cmd->add_option("-o,--output", job->output,
                    "output folder: new, empty, or an earlier batch's (then it resumes); on "
                    "storage every node sees at the same path")
        ->required();
    cmd->add_option("--cluster", job->cluster,
                    "auto (the Ray cluster of $RAY_ADDRESS or of this machine, else one started "
                    "here), local (one started here) or ADDRESS (host:port of a head node)")
        ->default_val("auto");
    cmd->add_option("--retries", job->retries,
                    "attempts after the first of a task whose worker or bmfr was killed")
        ->check(integerIn(0, 100))
        ->default_val(3);
    cmd->add_option("--python", job->python,
                    "the Python with Ray (default: $BMFR_PYTHON, then .venv/ of the build, then "
                    "python3)");
    cmd->add_flag("-q,--quiet", job->quiet, "no progress or summary");
    cmd->callback([job, &exitCode] { exitCode = runBatch(*job); });
}

} // namespace bmfr::app
