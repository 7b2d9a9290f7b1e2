// Per-stage GPU times from CUDA events: recorded on the passes' stream between stages and read
// once the frame has synchronised, so timing adds no synchronisation of its own.
#pragma once
#include <bmfr/frame.h>
#include <cuda_runtime_api.h>

namespace bmfr::cuda {

class StageEvents {
  public:
    StageEvents();
    ~StageEvents();
    StageEvents(const StageEvents&) = delete;
    StageEvents& operator=(const StageEvents&) = delete;
    /// Starts a frame on `stream`.
    void begin(cudaStream_t stream);
    /// Ends the stage `name` (a string literal) at this point of the stream.
    void mark(const char* name, cudaStream_t stream);
    /// After the stream has synchronised: adds each stage's milliseconds to `times`.
    void report(StageTimes& times) const;

  private:
    cudaEvent_t events_[StageTimes::kMaxStages + 1] = {};
    const char* names_[StageTimes::kMaxStages] = {};
    int count_ = 0;
};

} // namespace bmfr::cuda
