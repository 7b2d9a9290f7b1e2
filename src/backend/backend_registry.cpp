// The only file that names the backends. A new backend adds its factories here (and one line
// to tests/conformance/conformance_test.cpp).
#include "backend/backend_registry.h"
#include "backend/cpu/isa.h"
#include "backend/cuda/cuda_device.h"
#include <bmfr/error.h>
#include <cstring>
#include <string>
#include <type_traits>

namespace bmfr {

const char* backendName(Backend b) {
    switch (b) {
    case Backend::Reference:
        return "reference";
    case Backend::Cpu:
        return "cpu";
    case Backend::Cuda:
        return "cuda";
    }
    return "?";
}

Backend parseBackend(const char* name) {
    for (Backend b : {Backend::Reference, Backend::Cpu, Backend::Cuda})
        if (std::strcmp(name, backendName(b)) == 0) return b;
    throw Error(std::string("unknown backend '") + name + "' (expected reference, cpu or cuda)");
}

std::vector<std::string> compiledBackends() {
    if (cuda::built()) return {"reference", "cpu", "cuda"};
    return {"reference", "cpu"};
}

void requireBackend(Backend b, int cudaDevice) {
    if (b == Backend::Cpu) cpu::activeIsa();
    if (b == Backend::Cuda) cuda::requireDevice(cudaDevice);
}

template <class S> std::unique_ptr<PassesFor<S>> makePasses(Backend b, int cudaDevice) {
    // Errors when the filter is made, not inside a pass: a bad BMFR_CPU_ISA, "no CUDA device:
    // ..." (in a build without CUDA too).
    requireBackend(b, cudaDevice);
    switch (b) {
    case Backend::Reference:
        return reference::makePasses<S>();
    case Backend::Cpu:
        return cpu::makePasses<S>();
    case Backend::Cuda:
#if defined(BMFR_HAVE_CUDA)
        return cuda::makePasses<S>(cudaDevice);
#endif
        break;
    }
    throw Error("unknown backend");
}

template std::unique_ptr<PassesFor<BmfrSettings>> makePasses<BmfrSettings>(Backend, int);
template std::unique_ptr<PassesFor<SvgfSettings>> makePasses<SvgfSettings>(Backend, int);
template std::unique_ptr<PassesFor<WalrSettings>> makePasses<WalrSettings>(Backend, int);
template std::unique_ptr<PassesFor<Mara2017Settings>> makePasses<Mara2017Settings>(Backend, int);

} // namespace bmfr
