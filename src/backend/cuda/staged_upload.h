// Small per-frame host data (Mara 2017's tap tables) copied to the device in stream order
// without the host waiting for the stream, as a copy from pageable memory would: pinned staging
// slots, each reused once its copy is done, and one more made while all are in flight (a
// caller's stream may hold several frames).
#pragma once
#include <cstddef>
#include <cuda_runtime_api.h>
#include <vector>

namespace bmfr::cuda {

class StagedUpload {
  public:
    StagedUpload() = default;
    ~StagedUpload();
    StagedUpload(const StagedUpload&) = delete;
    StagedUpload& operator=(const StagedUpload&) = delete;
    /// Copies `bytes` from `host` to `device`, ordered on `stream`; `host` may change on return.
    void copy(void* device, const void* host, size_t bytes, cudaStream_t stream);

  private:
    struct Slot {
        void* pinned = nullptr;
        size_t capacity = 0;
        cudaEvent_t copied = nullptr; ///< recorded after the slot's last copy
    };
    std::vector<Slot> slots_;
};

} // namespace bmfr::cuda
