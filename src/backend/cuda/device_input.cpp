#include "backend/cuda/device_input.h"

namespace bmfr::cuda {

namespace {
const float* put(const float* host, int channels, long pixels, DeviceArray<float>& dev,
                 cudaStream_t stream) {
    if (!host) return nullptr;
    const size_t n = size_t(pixels) * size_t(channels);
    dev.resize(n);
    check(cudaMemcpyAsync(dev.data(), host, n * sizeof(float), cudaMemcpyHostToDevice, stream),
          "input upload");
    return dev.data();
}
} // namespace

const InputPlanes& DeviceInput::upload(const InputPlanes& h, cudaStream_t stream) {
    const long n = long(h.width) * h.height;
    InputPlanes& d = device_;
    d = InputPlanes{};
    d.width = h.width, d.height = h.height;
    // Each plane with its channel count (InputPlanes says which are not 3).
    struct Plane {
        const float* InputPlanes::*field;
        int channels;
    };
    static constexpr Plane kAll[kPlanes] = {{&InputPlanes::color, 3},
                                            {&InputPlanes::albedo, 3},
                                            {&InputPlanes::normal, 3},
                                            {&InputPlanes::position, 3},
                                            {&InputPlanes::emission, 3},
                                            {&InputPlanes::sampleMask, 1},
                                            {&InputPlanes::motion, 2},
                                            {&InputPlanes::motionDepth, 1},
                                            {&InputPlanes::diffuseIndirect, 3},
                                            {&InputPlanes::previousPosition, 3},
                                            {&InputPlanes::previousNormal, 3},
                                            {&InputPlanes::matteIndirect, 3},
                                            {&InputPlanes::glossyIndirect, 3},
                                            {&InputPlanes::directLight, 3},
                                            {&InputPlanes::specularF0, 3},
                                            {&InputPlanes::roughness, 1},
                                            {&InputPlanes::glossyHitDistance, 1}};
    for (int k = 0; k < kPlanes; ++k)
        d.*kAll[k].field = put(h.*kAll[k].field, kAll[k].channels, n, planes_[k], stream);
    d.extraCount = h.extraCount;
    for (int e = 0; e < h.extraCount; ++e) d.extras[e] = put(h.extras[e], 1, n, extras_[e], stream);
    return d;
}

} // namespace bmfr::cuda
