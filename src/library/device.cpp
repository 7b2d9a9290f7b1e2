#include "backend/backend_registry.h"
#include "library/device_state.h"
#include <bmfr/error.h>
#include <string>

namespace bmfr {

Device::Device(Backend backend, int threads, int cudaDevice) : state_(std::make_shared<State>()) {
    if (threads < 0 || threads > 1024)
        throw Error("threads " + std::to_string(threads) + " is outside [0, 1024]");
    if (cudaDevice != 0 && backend != Backend::Cuda)
        throw Error("cudaDevice " + std::to_string(cudaDevice) +
                    " is the cuda backend's; this "
                    "device's backend is " +
                    backendName(backend));
    // Its errors when the device is made, not when a filter is.
    requireBackend(backend, cudaDevice);
    state_->backend = backend;
    state_->cudaDevice = cudaDevice;
    state_->pool = std::make_shared<ThreadPool>(threads);
}
Device::~Device() = default;
Device::Device(const Device&) = default;
Device& Device::operator=(const Device&) = default;

Backend Device::backend() const {
    return state_->backend;
}
int Device::threadCount() const {
    return state_->pool->threadCount();
}
int Device::cudaDevice() const {
    return state_->cudaDevice;
}
void Device::reserve(int maxWidth, int maxHeight) {
    if (maxWidth == 0 && maxHeight == 0) { // drops the reservation
        state_->reservedWidth = state_->reservedHeight = 0;
        return;
    }
    if (maxWidth < 1 || maxHeight < 1)
        throw Error("reserve(" + std::to_string(maxWidth) + ", " + std::to_string(maxHeight) +
                    "): the size must be at least 1x1 (or 0x0, for none)");
    state_->reservedWidth = maxWidth;
    state_->reservedHeight = maxHeight;
}
int Device::reservedWidth() const {
    return state_->reservedWidth;
}
int Device::reservedHeight() const {
    return state_->reservedHeight;
}

} // namespace bmfr
