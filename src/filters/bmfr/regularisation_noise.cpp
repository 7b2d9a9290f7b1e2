#include "filters/bmfr/regularisation_noise.h"
#include "filters/bmfr/bmfr_passes.h"

namespace bmfr {

void fillRegularisationNoise(const BmfrSettings& s, long frameIndex, std::vector<float>& noise) {
    const int W = s.blockSize * s.blockSize;
    const int M = int(s.features.size());
    const uint32_t frame = uint32_t(frameIndex);
    noise.resize(size_t(M) * W);
    for (int f = 0; f < M; ++f) {
        const bool constant = s.features[size_t(f)].source == FeatureSource::One;
        for (int k = 0; k < W; ++k)
            noise[size_t(f) * W + k] =
                regularisationNoise(s.seed, frame, f, k, s.noiseAmplitude, constant);
    }
}

} // namespace bmfr
