// What a Device holds, for the library's filter constructors: the shared threads.
#pragma once
#include "core/parallel.h"
#include <bmfr/device.h>
#include <memory>

namespace bmfr {

struct Device::State {
    Backend backend = Backend::Cpu;
    std::shared_ptr<ThreadPool> pool;
    int cudaDevice = 0; ///< Backend::Cuda's GPU
    int reservedWidth = 0, reservedHeight = 0;
};

struct DeviceAccess {
    static const Device::State& state(const Device& d) { return *d.state_; }
};

} // namespace bmfr
