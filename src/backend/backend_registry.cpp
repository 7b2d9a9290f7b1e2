// The only file that names the backends. A new backend adds its factories here (and one line
// to tests/conformance/conformance_test.cpp).
#include "backend/backend_registry.h"
#include "backend/cpu/isa.h"
#include "backend/cuda/cuda_device.h"
#include <bmfr/error.h>
#include <cstring>
#include <string>

namespace bmfr {

namespace reference {
std::unique_ptr<BmfrPasses> makeBmfrPasses();
std::unique_ptr<SvgfPasses> makeSvgfPasses();
std::unique_ptr<WalrPasses> makeWalrPasses();
std::unique_ptr<MaraPasses> makeMaraPasses();
} // namespace reference
namespace cpu {
std::unique_ptr<BmfrPasses> makeBmfrPasses();
std::unique_ptr<SvgfPasses> makeSvgfPasses();
std::unique_ptr<WalrPasses> makeWalrPasses();
std::unique_ptr<MaraPasses> makeMaraPasses();
} // namespace cpu
#if defined(BMFR_HAVE_CUDA)
namespace cuda {
std::unique_ptr<BmfrPasses> makeBmfrPasses();
std::unique_ptr<SvgfPasses> makeSvgfPasses();
} // namespace cuda
#endif

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

namespace {
/// A CPU backend's passes, once the CPU path is known: a bad BMFR_CPU_ISA is an error when the
/// filter is made, not inside a pass.
template <class Make> auto onCpu(Make make) {
    cpu::activeIsa();
    return make();
}
/// The CUDA backend's passes, once a device is known to exist: "no CUDA device: ..." when the
/// filter is made, in a build without CUDA too.
template <class Make> auto onCuda(Make make) {
    cuda::requireDevice();
    return make();
}
[[noreturn]] void notOnCuda(const char* filter) {
    throw Error(std::string("the cuda backend runs bmfr and svgf; ") + filter +
                " runs on --backend cpu or reference");
}
} // namespace

std::unique_ptr<BmfrPasses> makeBmfrPasses(Backend b) {
    switch (b) {
    case Backend::Reference:
        return reference::makeBmfrPasses();
    case Backend::Cpu:
        return onCpu(cpu::makeBmfrPasses);
    case Backend::Cuda:
#if defined(BMFR_HAVE_CUDA)
        return onCuda(cuda::makeBmfrPasses);
#else
        cuda::requireDevice();
#endif
    }
    throw Error("unknown backend");
}

std::unique_ptr<SvgfPasses> makeSvgfPasses(Backend b) {
    switch (b) {
    case Backend::Reference:
        return reference::makeSvgfPasses();
    case Backend::Cpu:
        return onCpu(cpu::makeSvgfPasses);
    case Backend::Cuda:
#if defined(BMFR_HAVE_CUDA)
        return onCuda(cuda::makeSvgfPasses);
#else
        cuda::requireDevice();
#endif
    }
    throw Error("unknown backend");
}

std::unique_ptr<WalrPasses> makeWalrPasses(Backend b) {
    switch (b) {
    case Backend::Reference:
        return reference::makeWalrPasses();
    case Backend::Cpu:
        return onCpu(cpu::makeWalrPasses);
    case Backend::Cuda:
        notOnCuda("walr");
    }
    throw Error("unknown backend");
}

std::unique_ptr<MaraPasses> makeMaraPasses(Backend b) {
    switch (b) {
    case Backend::Reference:
        return reference::makeMaraPasses();
    case Backend::Cpu:
        return onCpu(cpu::makeMaraPasses);
    case Backend::Cuda:
        notOnCuda("mara2017");
    }
    throw Error("unknown backend");
}

} // namespace bmfr
