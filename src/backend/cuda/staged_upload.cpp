#include "backend/cuda/staged_upload.h"
#include "backend/cuda/device_buffer.h"
#include <cstring>

namespace bmfr::cuda {

StagedUpload::StagedUpload() {
    for (cudaEvent_t& e : copied_)
        check(cudaEventCreateWithFlags(&e, cudaEventDisableTiming), "cudaEventCreate");
}

StagedUpload::~StagedUpload() {
    for (int k = 0; k < 2; ++k) {
        cudaEventSynchronize(copied_[k]);
        cudaEventDestroy(copied_[k]);
        cudaFreeHost(pinned_[k]);
    }
}

void StagedUpload::copy(void* device, const void* host, size_t bytes, cudaStream_t stream) {
    const int k = next_;
    next_ = 1 - next_;
    // The slot's last copy, two frames ago: long done when frames follow one another.
    check(cudaEventSynchronize(copied_[k]), "cudaEventSynchronize");
    if (capacity_[k] < bytes) {
        check(cudaFreeHost(pinned_[k]), "cudaFreeHost");
        pinned_[k] = nullptr, capacity_[k] = 0;
        check(cudaMallocHost(&pinned_[k], bytes), "cudaMallocHost");
        capacity_[k] = bytes;
    }
    std::memcpy(pinned_[k], host, bytes);
    check(cudaMemcpyAsync(device, pinned_[k], bytes, cudaMemcpyHostToDevice, stream), "upload");
    check(cudaEventRecord(copied_[k], stream), "cudaEventRecord");
}

} // namespace bmfr::cuda
