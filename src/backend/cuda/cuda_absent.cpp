// The CUDA entry points of a build without nvcc: each says that this build has none.
#include "backend/cuda/cuda_device.h"
#include <bmfr/error.h>

namespace bmfr::cuda {

namespace {
[[noreturn]] void absent() {
    throw Error("no CUDA device: this build of bmfr has no CUDA backend (nvcc was not found "
                "when it was configured; rebuild with -DBMFR_CUDA=ON where the toolkit exists)");
}
} // namespace

bool built() {
    return false;
}
void requireDevice(int) {
    absent();
}
std::string deviceName(int) {
    absent();
}
int deviceCount() {
    absent();
}
int currentDevice() {
    absent();
}
DeviceScope::DeviceScope(int) {
    absent();
}
DeviceScope::~DeviceScope() = default;
double copyFloorMs(double, int) {
    absent();
}
void copyOutput(const ImageView&, const MutableImageView&, void*) {
    absent();
}
ImageView downloadRgb(const ImageView&, void*) {
    absent();
}
DeviceImageCopy::DeviceImageCopy(const ImageView&) {
    absent();
}
DeviceImageCopy::~DeviceImageCopy() = default;
CallerStream::CallerStream() {
    absent();
}
CallerStream::~CallerStream() = default;
void CallerStream::synchronize() const {
    absent();
}

} // namespace bmfr::cuda
