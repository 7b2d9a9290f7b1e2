#include "backend/cuda/stage_events.h"
#include "backend/cuda/device_buffer.h"
#include <bmfr/error.h>

namespace bmfr::cuda {

StageEvents::StageEvents() {
    for (cudaEvent_t& e : events_) check(cudaEventCreate(&e), "cudaEventCreate");
}
StageEvents::~StageEvents() {
    for (cudaEvent_t e : events_) cudaEventDestroy(e);
}

void StageEvents::begin(cudaStream_t stream) {
    count_ = 0;
    check(cudaEventRecord(events_[0], stream), "cudaEventRecord");
}

void StageEvents::mark(const char* name, cudaStream_t stream) {
    if (count_ == StageTimes::kMaxStages) throw Error("internal: too many CUDA stages");
    names_[count_++] = name;
    check(cudaEventRecord(events_[count_], stream), "cudaEventRecord");
}

void StageEvents::report(StageTimes& times) const {
    for (int k = 0; k < count_; ++k) {
        float ms = 0;
        check(cudaEventElapsedTime(&ms, events_[k], events_[k + 1]), "cudaEventElapsedTime");
        times.add(names_[k], double(ms));
    }
}

} // namespace bmfr::cuda
