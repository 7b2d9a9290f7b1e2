// The interface every reconstruction filter offers (BMFR, SVGF): same inputs, same output.
#pragma once
#include <bmfr/frame.h>
#include <memory>
#include <string>

namespace bmfr {

/// A temporal denoiser: owns its history; one instance per sequence; not thread-safe.
class Filter {
  public:
    virtual ~Filter() = default;
    /// Denoises one frame; returns linear HDR RGB valid until the next call. Throws bmfr::Error
    /// for missing or mismatched buffers and broken matrices.
    virtual ImageView denoise(const FrameInput& frame) = 0;
    /// Drops the history (as FrameInput::reset).
    virtual void reset() = 0;
    virtual const FrameStats& lastStats() const = 0;
    virtual const char* name() const = 0;
};

struct Settings;
struct SvgfSettings;

/// "bmfr" or "svgf". Throws bmfr::Error for other names or invalid settings.
std::unique_ptr<Filter> makeFilter(const std::string& name, const Settings& bmfr,
                                   const SvgfSettings& svgf);

} // namespace bmfr
