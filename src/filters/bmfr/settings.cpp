#include <bmfr/error.h>
#include <bmfr/settings.h>
#include <cmath>
#include <string>

namespace bmfr {

namespace {

void checkRange(const char* name, double v, double lo, double hi, bool loOpen = false,
                const char* filter = "setting") {
    bool ok = std::isfinite(v) && (loOpen ? v > lo : v >= lo) && v <= hi;
    if (!ok)
        throw Error(std::string(filter) + " " + name + " = " + std::to_string(v) + " is outside " +
                    (loOpen ? "(" : "[") + std::to_string(lo) + ", " + std::to_string(hi) + "]");
}

} // namespace

void validate(const TemporalSettings& s, const char* filter) {
    checkRange("taaBlendAlpha", s.taaBlendAlpha, 0, 1, true, filter);
    checkRange("positionLimitSquared", s.positionLimitSquared, 0, 1e30, true, filter);
    checkRange("normalLimitSquared", s.normalLimitSquared, 0, 4, true, filter);
    checkRange("albedoEpsilon", s.albedoEpsilon, 1e-6, 1, false, filter);
    checkRange("threads", s.threads, 0, 1024, false, filter);
}

void validate(const Settings& s) {
    checkRange("blockSize", s.blockSize, 8, 64);
    if (s.blockSize % 2 != 0) throw Error("setting blockSize must be even");
    if (s.features.empty() || s.features.front().source != FeatureSource::One)
        throw Error("setting features: the first feature must be the constant 1");
    if (int(s.features.size()) > kMaxFeatures)
        throw Error("setting features: " + std::to_string(s.features.size()) +
                    " features, at most " + std::to_string(kMaxFeatures));
    if (int(s.features.size()) + 3 > s.blockSize * s.blockSize)
        throw Error("setting features: more features than pixels in a block");
    checkRange("noiseAmplitude", s.noiseAmplitude, 0, 1);
    checkRange("firstBlendAlpha", s.firstBlendAlpha, 0, 1, true);
    checkRange("secondBlendAlpha", s.secondBlendAlpha, 0, 1, true);
    validate(static_cast<const TemporalSettings&>(s), "setting");
}

} // namespace bmfr
