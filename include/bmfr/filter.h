// The interface every reconstruction filter offers (BMFR, SVGF, ...): the same inputs, the same
// output, the same debug views; and the registry that makes a filter from its name.
#pragma once
#include <bmfr/api.h>
#include <bmfr/frame.h>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace bmfr {

/// What a filter saw and decided in the last frame, filled when requested
/// (Filter::setDebugOutputs). Views stay valid until the next denoise call.
struct DebugBuffers {
    ImageView accumulatedNoisy; ///< temporally accumulated demodulated colour, 3 channels
    ImageView fitted;           ///< the spatial filter's output before the last temporal step
    ImageView historyLength;    ///< samples in the colour history (0..255), 1 channel
    ImageView discardMask;      ///< accepted bilinear taps (bit i = tap i), as 0..15, 1 channel
};

/// A temporal denoiser: owns its history; one instance per sequence; not thread-safe.
class BMFR_API Filter {
  public:
    virtual ~Filter() = default;
    /// Denoises one frame; returns linear HDR RGB (3 channels, packed) valid until the next
    /// call, in the memory the frame's buffers are in (device memory: the cuda backend only).
    /// Throws bmfr::Error for missing or mismatched buffers and broken matrices.
    virtual ImageView denoise(const FrameInput& frame) = 0;
    /// The same, with the result also written into `out` (same size; 3 or 4 channels, any
    /// row stride; a fourth channel is left as it was). `out` may be in host memory, or in
    /// device memory when the frame's buffers are.
    virtual ImageView denoise(const FrameInput& frame, const MutableImageView& out);
    /// Drops the history (as FrameInput::reset).
    virtual void reset() = 0;
    virtual const FrameStats& lastStats() const = 0;
    virtual const char* name() const = 0;
    /// Keeps the debug buffers of each frame (off by default: they cost a copy per frame).
    virtual void setDebugOutputs(bool enabled) = 0;
    /// Views into the debug buffers of the last frame (empty views when disabled).
    virtual DebugBuffers debug() const = 0;
};

class FrameLoop;

/// What every filter of this library shares: the frame loop behind Filter's calls, written once.
/// A filter class adds its constructor, settings and extras. Movable, not copyable.
class BMFR_API TemporalFilter : public Filter {
  public:
    ~TemporalFilter() override;
    TemporalFilter(TemporalFilter&&) noexcept;
    TemporalFilter& operator=(TemporalFilter&&) noexcept;
    ImageView denoise(const FrameInput& frame) override;
    ImageView denoise(const FrameInput& frame, const MutableImageView& out) override;
    void reset() override;
    const FrameStats& lastStats() const override;
    const char* name() const override;
    void setDebugOutputs(bool enabled) override;
    DebugBuffers debug() const override;

  protected:
    explicit TemporalFilter(std::unique_ptr<FrameLoop> loop);
    FrameLoop& loop() const { return *loop_; }

  private:
    std::unique_ptr<FrameLoop> loop_;
};

/// Settings as text, by the key of the filter's settings table: {{"blockSize", "16"}}.
using SettingValues = std::vector<std::pair<std::string, std::string>>;

/// One row of a filter's settings table.
struct SettingDoc {
    std::string key, flag, unit, range, defaultValue, help;
    std::string faithful; ///< the value the "faithful" preset gives it; empty: the default
    bool shared = false;  ///< one of the settings every filter has (TemporalSettings)
};

/// Makes the filter `name` ("bmfr", "svgf") with its defaults overridden by `values`. Throws
/// bmfr::Error for an unknown filter, an unknown key or a value out of range.
BMFR_API std::unique_ptr<Filter> makeFilter(const std::string& name,
                                            const SettingValues& values = {});
/// The registered filters' names, in registry order.
BMFR_API std::vector<std::string> filterNames();
/// The settings table of filter `name`: the shared settings first.
BMFR_API std::vector<SettingDoc> filterSettings(const std::string& name);
/// The named presets, in order: "quality" (the defaults: the papers' settings with the
/// improvements beyond them that measured better, each a setting of its own) and "faithful"
/// (the papers' settings alone, bit for bit the reproduction).
BMFR_API std::vector<std::string> presetNames();
/// The settings preset `preset` gives filter `name` (those of its improvements the filter has);
/// apply them before any others. Throws bmfr::Error for an unknown filter or preset.
BMFR_API SettingValues presetSettings(const std::string& name, const std::string& preset);

/// An optional input a filter reads (bmfr::filterInputs).
struct InputUse {
    std::string buffer; ///< its FrameInput name as bmfr.input_buffers() lists it, or "extras"
    /// What the filter does without it where that departs from the filter's design (for a
    /// warning); empty when a frame without it is simply a frame without it.
    std::string without;
};
/// The optional inputs filter `name` reads with `values` (as makeFilter takes them), in the
/// frame buffer table's order. A buffer not listed is ignored by it (only checked and counted).
BMFR_API std::vector<InputUse> filterInputs(const std::string& name,
                                            const SettingValues& values = {});

} // namespace bmfr
