#include "peers/oidn_filter.h"
#include "core/stopwatch.h"
#include "peers/oidn_library.h"
#include "temporal/frame_checks.h"
#include <algorithm>
#include <bmfr/error.h>
#include <cmath>
#include <fmt/core.h>
#include <memory>

namespace bmfr::oidn {

namespace {

/// A packed RGB float image that OIDN reads and writes in place.
struct Plane {
    std::vector<float> pixels;
    float* data() { return pixels.data(); }
};

/// Copies `v` (3 or 4 channels, any row stride) into `out` packed, multiplied by `scale` when
/// given (remodulation), non-finite values as 0; returns how many were not finite.
int64_t pack(const ImageView& v, const ImageView* scale, Plane& out) {
    out.pixels.resize(size_t(v.width) * v.height * 3);
    int64_t bad = 0;
    for (int y = 0; y < v.height; ++y)
        for (int x = 0; x < v.width; ++x)
            for (int c = 0; c < 3; ++c) {
                float f = v.data[y * v.stride() + long(x) * v.channels + c];
                if (scale) f *= scale->data[y * scale->stride() + long(x) * scale->channels + c];
                if (!std::isfinite(f)) {
                    f = 0.0f;
                    ++bad;
                }
                out.pixels[(size_t(y) * v.width + x) * 3 + c] = f;
            }
    return bad;
}

int qualityValue(const std::string& name) {
    if (name == "fast") return kQualityFast;
    if (name == "balanced") return kQualityBalanced;
    if (name == "high") return kQualityHigh;
    throw Error("OIDN quality '" + name + "' is not one of fast, balanced, high");
}

class PeerFilter final : public Filter {
  public:
    explicit PeerFilter(const PeerSettings& s) : settings_(s), api_(loadApi(s.library)) {
        checkCanRun();
        qualityValue(s.quality); // checked before the device is made
        const std::vector<std::string> p = prefilterNames();
        if (std::find(p.begin(), p.end(), s.prefilter) == p.end())
            throw Error("OIDN prefilter '" + s.prefilter + "' is not one of none, fast, accurate");
        if (s.threads < 0 || s.threads > 1024)
            throw Error(fmt::format("OIDN threads {} is outside [0, 1024]", s.threads));
        device_ = api_.newDevice(kDeviceCpu);
        if (!device_) {
            const char* message = nullptr; // OIDN keeps errors without a device per thread
            api_.getDeviceError(nullptr, &message);
            throw Error(fmt::format("OIDN ({}) made no CPU device: {}", api_.path,
                                    message ? message : "no reason given"));
        }
        try {
            if (s.threads) api_.setDeviceInt(device_, "numThreads", s.threads);
            api_.commitDevice(device_);
            check("making the CPU device");
            version_ = api_.getDeviceInt(device_, "version");
            threads_ = api_.getDeviceInt(device_, "numThreads");
            if (version_ < 20000)
                throw Error(fmt::format("{} is OIDN {}; the peer needs OIDN 2 or later", api_.path,
                                        versionText()));
        } catch (...) {
            api_.releaseDevice(device_); // the destructor does not run for a throwing constructor
            throw;
        }
    }
    PeerFilter(const PeerFilter&) = delete;
    PeerFilter& operator=(const PeerFilter&) = delete;
    ~PeerFilter() override {
        for (FilterHandle f : {main_, albedoFilter_, normalFilter_})
            if (f) api_.releaseFilter(f);
        if (device_) api_.releaseDevice(device_);
    }

    ImageView denoise(const FrameInput& frame) override {
        checkFrameInput(frame, 0, "oidn", false);
        stats_ = {};
        Stopwatch clock;
        const bool remodulate = settings_.colorIsDemodulated;
        stats_.nonFiniteInputs += pack(frame.color, remodulate ? &frame.albedo : nullptr, color_);
        stats_.nonFiniteInputs += pack(frame.albedo, nullptr, albedo_);
        stats_.nonFiniteInputs += pack(frame.normal, nullptr, normal_);
        if (frame.color.width != width_ || frame.color.height != height_)
            build(frame.color.width, frame.color.height);
        stats_.times.add("copy", clock.lap());
        if (albedoFilter_) {
            api_.executeFilter(albedoFilter_);
            check("prefiltering the albedo");
            api_.executeFilter(normalFilter_);
            check("prefiltering the normals");
            stats_.times.add("prefilter", clock.lap());
        }
        api_.executeFilter(main_);
        check("denoising");
        stats_.times.add("filter", clock.lap());
        return {output_.data(), width_, height_, 3};
    }
    using Filter::denoise;
    void reset() override {} // no history to drop
    const FrameStats& lastStats() const override { return stats_; }
    const char* name() const override { return "oidn"; }
    void setDebugOutputs(bool) override {} // no intermediate buffers worth showing
    DebugBuffers debug() const override { return {}; }

    int threads() const { return threads_; }
    std::string description() const {
        return fmt::format("OIDN {}, RT filter, CPU device ({} threads), quality {}, prefilter {}",
                           versionText(), threads_, settings_.quality, settings_.prefilter);
    }

  private:
    std::string versionText() const {
        return fmt::format("{}.{}.{}", version_ / 10000, version_ / 100 % 100, version_ % 100);
    }
    /// Throws the device's pending error, if any.
    void check(const char* what) {
        const char* message = nullptr;
        if (api_.getDeviceError(device_, &message))
            throw Error(fmt::format("OIDN failed {}: {}", what, message ? message : "no message"));
    }
    void image(FilterHandle f, const char* name, Plane& p, int width, int height) {
        api_.setSharedFilterImage(f, name, p.data(), kFormatFloat3, size_t(width), size_t(height),
                                  0, 3 * sizeof(float), 3 * sizeof(float) * size_t(width));
    }
    FilterHandle newFilter() {
        FilterHandle f = api_.newFilter(device_, "RT");
        check("making an RT filter");
        api_.setFilterInt(f, "quality", qualityValue(settings_.quality));
        return f;
    }
    /// The filters, for a frame size; the planes keep their addresses until the size changes.
    void build(int width, int height) {
        width_ = height_ = 0; // a size whose filters are not committed is not kept
        output_.pixels.assign(size_t(width) * height * 3, 0.0f);
        if (!main_) {
            main_ = newFilter();
            if (settings_.prefilter == "accurate") {
                albedoFilter_ = newFilter();
                normalFilter_ = newFilter();
            }
        }
        if (albedoFilter_) {
            image(albedoFilter_, "albedo", albedo_, width, height);
            image(albedoFilter_, "output", albedo_, width, height);
            api_.commitFilter(albedoFilter_);
            image(normalFilter_, "normal", normal_, width, height);
            image(normalFilter_, "output", normal_, width, height);
            api_.commitFilter(normalFilter_);
        }
        image(main_, "color", color_, width, height);
        image(main_, "albedo", albedo_, width, height);
        image(main_, "normal", normal_, width, height);
        image(main_, "output", output_, width, height);
        api_.setFilterBool(main_, "hdr", true);
        api_.setFilterBool(main_, "cleanAux", settings_.prefilter != "fast");
        api_.commitFilter(main_);
        check("setting up the filters");
        width_ = width;
        height_ = height;
    }

    PeerSettings settings_;
    const Api& api_;
    Device device_ = nullptr;
    FilterHandle main_ = nullptr, albedoFilter_ = nullptr, normalFilter_ = nullptr;
    int version_ = 0, threads_ = 0, width_ = 0, height_ = 0;
    Plane color_, albedo_, normal_, output_;
    FrameStats stats_;
};

} // namespace

std::vector<std::string> qualityNames() {
    return {"fast", "balanced", "high"};
}

std::vector<std::string> prefilterNames() {
    return {"none", "fast", "accurate"};
}

Peer makePeer(const PeerSettings& settings) {
    auto filter = std::make_unique<PeerFilter>(settings);
    std::string description = filter->description();
    const int threads = filter->threads();
    return {std::move(filter), std::move(description), threads};
}

} // namespace bmfr::oidn
