// The BMFR denoiser: owns the temporal history and turns 1-spp frames into clean frames.
#pragma once
#include <bmfr/filter.h>
#include <bmfr/frame.h>
#include <bmfr/settings.h>
#include <memory>

namespace bmfr {

/// Debug buffers, filled when requested (Denoiser::setDebugOutputs).
struct DebugBuffers {
    ImageView accumulatedNoisy; ///< phase I output: accumulated demodulated colour, 3 channels
    ImageView fitted;           ///< phase II output: fitted frame before phase III, 3 channels
    ImageView historyLength;    ///< samples in the phase I history (1..255), 1 channel
    ImageView discardMask;      ///< accepted bilinear taps (bit i = tap i), as 0..15, 1 channel
};

/// Temporal BMFR reconstruction on the CPU. Not thread-safe; one instance per sequence.
class Denoiser final : public Filter {
  public:
    /// Throws bmfr::Error when settings are out of range.
    explicit Denoiser(const Settings& settings = {});
    ~Denoiser() override;
    Denoiser(Denoiser&&) noexcept;
    Denoiser& operator=(Denoiser&&) noexcept;

    /// Denoises one frame and returns the linear HDR result (3 channels), valid until the next
    /// call. Throws bmfr::Error for mismatched sizes, missing buffers or a broken matrix.
    ImageView denoise(const FrameInput& frame) override;

    /// Drops the history; the next frame starts from scratch (same as FrameInput::reset).
    void reset() override;

    void setDebugOutputs(bool enabled);
    /// Views into the debug buffers of the last frame (empty views when disabled).
    DebugBuffers debug() const;
    const FrameStats& lastStats() const override;
    const char* name() const override { return "bmfr"; }
    const Settings& settings() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace bmfr
