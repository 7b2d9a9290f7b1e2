// Renders a whole sequence from a scene description into either layout, resuming finished frames.
#pragma once
#include "render/scene_description.h"
#include <atomic>
#include <functional>
#include <string>

namespace bmfr::render {

struct SequenceRenderOptions {
    std::string output;
    std::string layout = "manifest"; ///< "manifest" or "bmfr"
    bool quiet = false;
};

struct SequenceRenderReport {
    int rendered = 0, skipped = 0;
    bool interrupted = false;
    uint64_t rays = 0;
    double inputSeconds = 0, referenceSeconds = 0, loadSeconds = 0;
    size_t triangles = 0;
};

/// Renders every frame not already on disk. `progress(done, total)` is called per frame.
/// Stops cleanly (no partial files) when `cancel` becomes true.
SequenceRenderReport renderSequence(const SceneDescription& desc,
                                    const SequenceRenderOptions& options,
                                    const std::atomic<bool>* cancel,
                                    const std::function<void(int, int)>& progress,
                                    const std::function<void(const std::string&)>& warn);

} // namespace bmfr::render
