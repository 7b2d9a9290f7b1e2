// What `bmfr bench` measures and feeds its filters: the job, the synthetic frames' helpers, and
// the all-filters table (bench_filters.cpp).
#pragma once
#include "backend/cuda/cuda_device.h"
#include "io/sequence.h"
#include <bmfr/bmfr.hpp>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace bmfr::app {

struct BenchJob {
    std::vector<std::string> sizes{"1280x720", "1920x1080", "3840x2160"};
    int warmup = 5, frames = 30, threads = 0;
    bool json = false, baseline = true, quiet = false;
    /// Moving objects with motion vectors; the baseline is then the same backend reprojecting
    /// by the camera alone, so the ratio is the cost of the motion-vector path.
    bool motion = false;
    /// The measured filter reads its input from CUDA device buffers (copied there once), as an
    /// engine hands them over: no upload, and the output stays on the device.
    bool deviceBuffers = false;
    std::string filter = "bmfr", backend = "cpu", baselineBackend = "reference";
    /// Another filter as the baseline (on baselineBackend), as WALR beside BMFR; "" = the same.
    std::string baselineFilter;
    std::vector<std::string> sets;         ///< "key=value" settings of the measured filter
    std::vector<std::string> baselineSets; ///< "key=value" settings of the baseline
    std::string preset = "quality", baselinePreset = "quality"; ///< presetSettings()
    /// Several filters timed together, interleaved (--filters); empty = the one-filter bench.
    std::vector<std::string> filters;
    const std::string& referenceFilter() const {
        return baselineFilter.empty() ? filter : baselineFilter;
    }
};

/// makeFilter for settings that all came from this command line: their errors are usage errors.
std::unique_ptr<Filter> makeFromCommandLine(const std::string& name, const SettingValues& values);

/// Distinct input frames cycled through: up to 8, fewer for large images (memory).
int distinctFrames(int w, int h);

/// Mara et al.'s factorisation on a synthetic frame: the colour split into direct, matte and
/// glossy light, dielectric F0 and a mid roughness, so that every Mara stage runs.
void addFactorisation(FrameData& f);

/// The input without the factorisation (what the other filters are timed on).
FrameInput withoutFactorisation(FrameInput in);

/// Frames' buffers copied once into CUDA device memory, as an engine hands them over
/// (--device-buffers); the copies live as long as this.
class DeviceFrames {
  public:
    /// `in` with every buffer replaced by its device copy.
    FrameInput add(FrameInput in);

  private:
    std::vector<std::unique_ptr<cuda::DeviceImageCopy>> copies_;
};

/// Index into `distinct` frames of the i-th frame run: the cycle goes forwards then backwards,
/// so the camera motion stays continuous. `back` is set on the way back.
int cycledFrame(int i, int distinct, bool& back);

/// Every filter of job.filters on job.backend, on the same frames, interleaved frame by frame,
/// beside the single-pass floor measured in the same run. One JSON object per size.
nlohmann::json benchFilters(const BenchJob& job, int w, int h,
                            const std::function<void()>& frameDone);
/// Prints benchFilters' result as a table.
void printFilterTable(const BenchJob& job, const std::string& size, const nlohmann::json& r);

} // namespace bmfr::app
