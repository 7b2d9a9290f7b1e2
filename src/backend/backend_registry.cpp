// The only file that names the backends. A new backend adds its factories here (and one line
// to tests/conformance/conformance_test.cpp).
#include "backend/backend_registry.h"
#include "backend/cpu/isa.h"
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
    return {"reference", "cpu"};
}

namespace {
/// A CPU backend's passes, once the CPU path is known: a bad BMFR_CPU_ISA is an error when the
/// filter is made, not inside a pass.
template <class Make> auto onCpu(Make make) {
    cpu::activeIsa();
    return make();
}
[[noreturn]] void unavailable(Backend b) {
    throw Error(std::string("backend '") + backendName(b) +
                "' is not available: this build of bmfr has no CUDA backend yet "
                "(use --backend cpu or reference)");
}
} // namespace

std::unique_ptr<BmfrPasses> makeBmfrPasses(Backend b) {
    switch (b) {
    case Backend::Reference:
        return reference::makeBmfrPasses();
    case Backend::Cpu:
        return onCpu(cpu::makeBmfrPasses);
    default:
        unavailable(b);
    }
}

std::unique_ptr<SvgfPasses> makeSvgfPasses(Backend b) {
    switch (b) {
    case Backend::Reference:
        return reference::makeSvgfPasses();
    case Backend::Cpu:
        return onCpu(cpu::makeSvgfPasses);
    default:
        unavailable(b);
    }
}

std::unique_ptr<WalrPasses> makeWalrPasses(Backend b) {
    switch (b) {
    case Backend::Reference:
        return reference::makeWalrPasses();
    case Backend::Cpu:
        return onCpu(cpu::makeWalrPasses);
    default:
        unavailable(b);
    }
}

std::unique_ptr<MaraPasses> makeMaraPasses(Backend b) {
    switch (b) {
    case Backend::Reference:
        return reference::makeMaraPasses();
    case Backend::Cpu:
        return onCpu(cpu::makeMaraPasses);
    default:
        unavailable(b);
    }
}

} // namespace bmfr
