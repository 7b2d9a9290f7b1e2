// Renders a whole sequence from a scene description into either layout, resuming finished frames.
#pragma once
#include "render/scene_description.h"
#include <atomic>
#include <functional>
#include <string>

namespace bmfr::render {

inline constexpr const char* kRenderFingerprintFile = ".bmfr-render.json";

/// A digest of everything that decides a frame's pixels: scene, camera, lights, size, samples,
/// seed, layout and the mesh file's size and time. The frame count is not part of it: a longer
/// run of the same scene resumes.
std::string renderFingerprint(const SceneDescription& desc, const std::string& layout);

struct SequenceRenderOptions {
    std::string output;
    std::string layout = "manifest"; ///< "manifest" or "bmfr"
    bool quiet = false;
    /// Replace a folder that holds another scene's or layout's sequence (or one bmfr did not
    /// render) instead of refusing it; finished frames are rendered again.
    bool overwrite = false;
    /// A part of the sequence: frames [firstFrame, endFrame) only (manifest layout), recorded
    /// so that parts rendered at once, here or on other machines, make one sequence. -1: all.
    int firstFrame = 0, endFrame = -1;
};

struct SequenceRenderReport {
    int rendered = 0, skipped = 0;
    /// Frames of the whole sequence on disk after this run (other parts' included), and
    /// whether sequence.json lists them all.
    int framesIn = 0;
    bool complete = false;
    bool interrupted = false;
    uint64_t rays = 0;
    double inputSeconds = 0, referenceSeconds = 0, loadSeconds = 0;
    size_t triangles = 0;
};

/// Renders every frame not already on disk. `progress(done, total)` is called per frame.
/// Stops cleanly (no partial files) when `cancel` becomes true. A folder is resumed only when
/// its render fingerprint (kRenderFingerprintFile: the scene and settings, written with the
/// first frame) matches; any other non-empty folder is refused unless options.overwrite.
/// Metadata (sequence.json, camera_matrices.h) is written after the frames it describes; for a
/// part, once every frame of the sequence is in.
SequenceRenderReport renderSequence(const SceneDescription& desc,
                                    const SequenceRenderOptions& options,
                                    const std::atomic<bool>* cancel,
                                    const std::function<void(int, int)>& progress,
                                    const std::function<void(const std::string&)>& warn);

} // namespace bmfr::render
