// Frame sequences on disk: auto-detected layout, frame loading, and writers for both layouts.
#pragma once
#include "core/image.h"
#include "io/exr.h"
#include "temporal/frame_buffers.h"
#include <array>
#include <bmfr/frame.h>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace bmfr {

/// One frame's buffers, owned.
struct FrameData {
    ImageF color, albedo, normal, position;
    std::vector<ImageF> extras; ///< 1-channel extra features, in SequenceInfo::extraNames order
    ImageF reference;           ///< empty (0x0) when the sequence has none
    ImageF emission; ///< first-hit emitted radiance (noise-free); empty when the layout has none
    /// FrameInput::motion (2 channels, or 3 with the depth offset), previousPosition,
    /// previousNormal and diffuseIndirect; empty when the sequence has none.
    ImageF motion, previousPosition, previousNormal, diffuseIndirect;
    /// FrameInput::visibility (1 channel); empty when the sequence has none.
    ImageF visibility;
    /// Mara et al. 2017's factorisation (FrameInput::matteIndirect ...); empty when absent.
    ImageF matteIndirect, glossyIndirect, directLight, specularF0, roughness, glossyHitDistance;
    ImageF sampleMask;  ///< FrameInput::sampleMask (1 channel); empty at 1 spp
    bool reset = false; ///< a camera cut: the history is dropped at this frame
    /// Further named outputs (depth, motion, direct/indirect, diffuse/glossy splits...).
    std::vector<std::pair<std::string, ImageF>> aovs;
    Mat4 viewProjection;
    float jitter[2] = {0, 0};

    /// f(row, image) for each row of BMFR_FRAME_BUFFERS, in order, with its image here.
    template <class F> void forEachBuffer(F&& f) {
        int k = 0;
#define BMFR_DATA_BUFFER(m, file, channels, staged, required, motion) f(kFrameBuffers[k++], m);
        BMFR_FRAME_BUFFERS(BMFR_DATA_BUFFER)
#undef BMFR_DATA_BUFFER
    }
    template <class F> void forEachBuffer(F&& f) const {
        const_cast<FrameData*>(this)->forEachBuffer(
            [&f](const FrameBuffer& b, const ImageF& image) { f(b, image); });
    }

    /// A view for Denoiser::denoise (valid while this object lives). Without `motion`, the
    /// motion vectors and previous positions and normals are left out: the filters then
    /// reproject by the cameras alone.
    FrameInput input(bool motion = true) const;
};

struct SequenceInfo {
    std::string layout; ///< "bmfr" (original dataset) or "manifest" (this project's)
    std::string directory;
    int frameCount = 0;
    int width = 0, height = 0;
    bool colorIsDemodulated = false;
    bool hasReference = false;
    std::optional<float> positionLimitSquared, normalLimitSquared;
    std::vector<std::string> extraNames;
};

/// Reads frames of a sequence; every frame is checked against the first one's size.
class SequenceReader {
  public:
    virtual ~SequenceReader() = default;
    const SequenceInfo& info() const { return info_; }
    /// Loads frame `index` (0-based). Throws bmfr::Error naming file and frame.
    void load(int index, FrameData& out) const { read(index, out, ExrContent::Pixels); }
    /// Reads the headers of frames [first, last) (files, sizes, channels, layers, cameras)
    /// without their pixels, so that a run fails before its first output rather than at a bad
    /// frame half way. Throws one bmfr::Error listing every frame that cannot be loaded.
    void checkFrames(int first, int last) const;

    /// Detects the layout of `directory` (sequence.json, or camera_matrices.h + color0.exr).
    static std::unique_ptr<SequenceReader> open(const std::string& directory);
    /// Also load FrameData::aovs (this project's layout only; off by default).
    void setLoadAovs(bool on) { loadAovs_ = on; }
    /// What a run should tell its user about how the input was read (as "colour is read from
    /// Cycles' Noisy Image"), each once; filled as frames are read or checked.
    std::vector<std::string> notes() const;
    /// Which layer of a multilayer EXR each buffer comes from ("albedo" -> "ViewLayer.DiffCol"),
    /// replacing the sequence's own choice and the default mapping (kDefaultPasses). Buffers:
    /// layeredBufferNames(). Throws bmfr::Error for another name, or for a layout without
    /// multilayer files (the original BMFR layout).
    virtual void setLayerOverrides(const std::map<std::string, std::string>& layers);

  protected:
    /// load() (Pixels) or checkFrames()'s pass over one frame (Header: images sized, not filled).
    virtual void read(int index, FrameData& out, ExrContent content) const = 0;
    SequenceInfo info_;
    bool loadAovs_ = false;
    mutable std::mutex notesLock_; ///< frames may be read from several threads (Python)
    mutable std::vector<std::string> notes_;
    /// Adds `text` to notes() unless it is there already.
    void note(const std::string& text) const;
    std::map<std::string, std::string> layerOverrides_;
    void checkFrame(int index, const FrameData& f) const;
};

/// Runs check(i) for every frame i in [first, last), then throws one bmfr::Error, headed
/// `what`, that lists every frame whose check threw (the first 20 of them).
void checkEveryFrame(int first, int last, const std::string& what,
                     const std::function<void(int)>& check);

/// Where a buffer is found in a multilayer EXR when neither the sequence nor the user names a
/// layer: the first of these passes that the file holds, under any view layer. These are the
/// names Blender's Cycles gives its passes; a buffer not listed has none.
struct DefaultPass {
    const char* buffer;
    std::vector<const char*> passes;
};
extern const std::vector<DefaultPass> kDefaultPasses;
/// The image buffers a layer can be named for: those of BMFR_FRAME_BUFFERS, then the reference.
std::vector<std::string> layeredBufferNames();

std::unique_ptr<SequenceReader> openBmfrLayout(const std::string& directory);
std::unique_ptr<SequenceReader> openManifestLayout(const std::string& directory);

/// Where writers of parts of one sequence record their frames (one `NNNN.json` per frame).
inline constexpr const char* kFramePartsFolder = ".bmfr-frames";

/// Writes this project's layout: EXRs per frame plus sequence.json (rewritten per frame, so a
/// stopped writer leaves a readable prefix). A writer of a part (several may run at once, on
/// other machines) records each frame in kFramePartsFolder instead; sequence.json is written
/// once every frame of the sequence is recorded, by whichever writer finds them all.
class ManifestWriter {
  public:
    /// With `resume`, keeps the frames of an existing sequence.json of the same size. Frames
    /// recorded by parts are kept either way (a replaced folder has had them removed).
    ManifestWriter(const std::string& directory, const SequenceInfo& info, bool resume = true,
                   bool part = false);
    void addFrame(int index, const FrameData& frame);
    /// True when frame `index` is recorded and all its files exist.
    bool hasFrame(int index) const;
    /// Writes sequence.json when frames [0, info.frameCount) are all recorded (here or by other
    /// parts); returns how many of them are.
    int writeManifestIfComplete();

  private:
    void loadPartRecords();
    void writeManifest() const;
    std::string dir_;
    SequenceInfo info_;
    bool part_;
    std::vector<std::string> frameJson_;
};

/// Writes the original BMFR dataset layout (colour demodulated by albedo, as that dataset is):
/// color{N}.exr, albedo{N}.exr, shading_normal{N}.exr, world_position{N}.exr,
/// reference{N}.exr and camera_matrices.h (written by finish(), after the frames).
class BmfrLayoutWriter {
  public:
    /// matrices/jitters of every frame of the sequence (the header lists them all).
    BmfrLayoutWriter(const std::string& directory, const std::vector<Mat4>& matrices,
                     const std::vector<std::array<float, 2>>& jitters, float positionLimitSquared,
                     float normalLimitSquared);
    void addFrame(int index, const FrameData& frame);
    /// True when the frame's last-written file exists (writes are atomic).
    bool hasFrame(int index) const;
    /// Writes camera_matrices.h (atomically). Call once the frames are on disk.
    void finish();

  private:
    std::string dir_;
    std::string header_;
};

/// All frames at once (BmfrLayoutWriter underneath).
void writeBmfrLayout(const std::string& directory, const std::vector<FrameData>& frames,
                     float positionLimitSquared, float normalLimitSquared);

/// Parsed content of an original-dataset camera_matrices.h.
struct BmfrCameraFile {
    std::vector<Mat4> matrices; ///< as written: row vectors, clip = [x y z 1] * M
    std::vector<std::array<float, 2>> pixelOffsets;
    std::optional<float> positionLimitSquared, normalLimitSquared;
};
/// Parses (never compiles) camera_matrices.h text. Throws bmfr::Error naming `source`.
BmfrCameraFile parseBmfrCameraFile(const std::string& text, const std::string& source);

} // namespace bmfr
