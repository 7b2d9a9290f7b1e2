// The bookkeeping every temporal filter carries between frames: the frame size, which of the
// two history slots is current, whether there is a history, and the previous camera.
#pragma once
#include <bmfr/frame.h>

namespace bmfr {

/// What the per-pixel reprojection needs of the previous frame (BMFR_HD kernels copy it).
struct PreviousFrame {
    bool valid = false; ///< there is a history to reproject into
    Mat4 viewProjection;
    float jitter[2] = {0, 0};
};

class TemporalHistory {
  public:
    int width = 0, height = 0;
    int cur = 0;         ///< history slot written this frame; 1 - cur holds the previous frame
    long frameIndex = 0; ///< frames since construction or the last reset
    PreviousFrame previous;

    /// Starts a frame: a new size or a reset drops the history; the slots swap. Returns true
    /// when the size changed, so the caller (re)allocates its buffers.
    bool begin(const FrameInput& frame) {
        const bool resized = frame.color.width != width || frame.color.height != height;
        if (resized) {
            width = frame.color.width;
            height = frame.color.height;
            previous.valid = false;
            cur = 0;
        }
        if (frame.reset) reset();
        cur = 1 - cur;
        return resized;
    }
    /// Ends a frame: it becomes the previous one.
    void end(const FrameInput& frame) {
        previous.valid = true;
        previous.viewProjection = frame.viewProjection;
        previous.jitter[0] = frame.jitter[0];
        previous.jitter[1] = frame.jitter[1];
        ++frameIndex;
    }
    /// Drops the history and restarts the frame count, so what follows matches a new filter.
    void reset() {
        previous.valid = false;
        frameIndex = 0;
    }
    bool hasHistory() const { return previous.valid; }
};

} // namespace bmfr
