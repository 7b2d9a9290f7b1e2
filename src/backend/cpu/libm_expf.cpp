#include "backend/cpu/libm_expf.h"

namespace bmfr::cpu {

namespace {
BMFR_SIMD_DISPATCH(void, expfRows, (const float* x, int n, float* out), (x, n, out)) {
    expfRun<kIsa>(x, n, out);
}
} // namespace

void expfOnActivePath(const float* x, int n, float* out) {
    expfRows(x, n, out);
}

} // namespace bmfr::cpu
