// Small per-frame host data (Mara 2017's tap tables) copied to the device in stream order
// without the host waiting for the stream, as a copy from pageable memory would: two pinned
// staging slots, each reused once its copy of two frames ago is done.
#pragma once
#include <cstddef>
#include <cuda_runtime_api.h>

namespace bmfr::cuda {

class StagedUpload {
  public:
    StagedUpload();
    ~StagedUpload();
    StagedUpload(const StagedUpload&) = delete;
    StagedUpload& operator=(const StagedUpload&) = delete;
    /// Copies `bytes` from `host` to `device`, ordered on `stream`; `host` may change on return.
    void copy(void* device, const void* host, size_t bytes, cudaStream_t stream);

  private:
    void* pinned_[2] = {};
    size_t capacity_[2] = {};
    cudaEvent_t copied_[2] = {};
    int next_ = 0;
};

} // namespace bmfr::cuda
