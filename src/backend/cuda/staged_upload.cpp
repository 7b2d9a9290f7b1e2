#include "backend/cuda/staged_upload.h"
#include "backend/cuda/device_buffer.h"
#include <cstring>

namespace bmfr::cuda {

StagedUpload::~StagedUpload() {
    for (Slot& s : slots_) {
        cudaEventSynchronize(s.copied);
        cudaEventDestroy(s.copied);
        cudaFreeHost(s.pinned);
    }
}

void StagedUpload::copy(void* device, const void* host, size_t bytes, cudaStream_t stream) {
    Slot* free = nullptr;
    for (Slot& s : slots_)
        if (cudaEventQuery(s.copied) == cudaSuccess) {
            free = &s;
            break;
        }
    if (!free) {
        Slot s;
        check(cudaEventCreateWithFlags(&s.copied, cudaEventDisableTiming), "cudaEventCreate");
        slots_.push_back(s);
        free = &slots_.back();
    }
    if (free->capacity < bytes) {
        check(cudaFreeHost(free->pinned), "cudaFreeHost");
        free->pinned = nullptr, free->capacity = 0;
        check(cudaMallocHost(&free->pinned, bytes), "cudaMallocHost");
        free->capacity = bytes;
    }
    std::memcpy(free->pinned, host, bytes);
    check(cudaMemcpyAsync(device, free->pinned, bytes, cudaMemcpyHostToDevice, stream), "upload");
    check(cudaEventRecord(free->copied, stream), "cudaEventRecord");
}

} // namespace bmfr::cuda
