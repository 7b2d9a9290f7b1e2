#include "backend/reference/reference_taa.h"
#include "temporal/taa_stage.h"

namespace bmfr::reference {

void taaPass(ThreadPool& pool, const TaaInputs& in, float* ycocg, float* out, bool enabled) {
    taaStage(HostExecutor{pool}, in, ycocg, out, enabled);
}

} // namespace bmfr::reference
