// Built with --fmad=false: TAA must round as the reference backend does.
#include "backend/cuda/cuda_executor.h"
#include "backend/cuda/cuda_taa.h"
#include "temporal/taa_stage.h"

namespace bmfr::cuda {

void launchTaa(const TaaInputs& in, float* ycocg, float* out, bool enabled, cudaStream_t stream) {
    taaStage(CudaExecutor{stream}, in, ycocg, out, enabled);
}

} // namespace bmfr::cuda
