#include "io/sequence.h"
#include <algorithm>
#include <bmfr/error.h>
#include <cctype>
#include <filesystem>
#include <functional>
#include <map>

namespace bmfr {

namespace fs = std::filesystem;

FrameInput FrameData::input(bool motionInput) const {
    FrameInput in;
    forEachBuffer([&](const FrameBuffer& b, const ImageF& image) {
        if (b.required || (image.width && (motionInput || !b.motionInput)))
            in.*b.view = view(image);
    });
    for (const ImageF& e : extras) in.extras.push_back(view(e));
    in.reset = reset;
    in.viewProjection = viewProjection;
    in.jitter[0] = jitter[0];
    in.jitter[1] = jitter[1];
    return in;
}

const std::vector<DefaultPass> kDefaultPasses = {
    // With its denoiser on, Cycles writes its denoised result as Combined and the render as
    // Noisy Image: the noisy one is the input.
    {"color", {"Noisy Image", "Combined"}},
    {"albedo", {"Denoising Albedo", "DiffCol"}},
    {"normal", {"Normal", "Denoising Normal"}},
    {"position", {"Position"}},
    {"emission", {"Emit"}},
    {"reference", {"Combined"}},
    // Cycles' Vector pass, read only under "motion_convention": "cycles" (converted then).
    {"motion", {"Vector"}},
    // Cycles has no pass of the other buffers' conventions.
};

std::vector<std::string> layeredBufferNames() {
    std::vector<std::string> names;
    for (const FrameBuffer& b : kFrameBuffers) names.push_back(b.file);
    names.push_back("reference");
    return names;
}

void SequenceReader::setLayerOverrides(const std::map<std::string, std::string>& layers) {
    const std::vector<std::string> names = layeredBufferNames();
    for (const auto& [buffer, layer] : layers)
        if (std::find(names.begin(), names.end(), buffer) == names.end()) {
            std::string list;
            for (size_t k = 0; k < names.size(); ++k)
                list += (k == 0 ? "" : k + 1 == names.size() ? " or " : ", ") + names[k];
            throw Error("--channel " + buffer + "=" + layer + ": unknown buffer (" + list + ")");
        }
    if (!layers.empty() && info_.layout != "manifest")
        throw Error("--channel: the " + info_.layout +
                    " layout has no multilayer files; layers apply to sequence.json folders");
    layerOverrides_ = layers;
}

void SequenceReader::checkFrame(int index, const FrameData& f) const {
    auto check = [&](const ImageF& img, const char* name) {
        if (img.width != info_.width || img.height != info_.height)
            throw Error(info_.directory + ": frame " + std::to_string(index) + " " + name + " is " +
                        std::to_string(img.width) + "x" + std::to_string(img.height) +
                        ", the sequence is " + std::to_string(info_.width) + "x" +
                        std::to_string(info_.height));
    };
    f.forEachBuffer([&](const FrameBuffer& b, const ImageF& image) {
        if (b.required || image.width) check(image, b.file);
    });
    for (const ImageF& e : f.extras) check(e, "extra");
    if (f.reference.width) check(f.reference, "reference");
}

void SequenceReader::note(const std::string& text) const {
    const std::lock_guard<std::mutex> held(notesLock_);
    if (std::find(notes_.begin(), notes_.end(), text) == notes_.end()) notes_.push_back(text);
}

std::vector<std::string> SequenceReader::notes() const {
    const std::lock_guard<std::mutex> held(notesLock_);
    return notes_;
}

void checkEveryFrame(int first, int last, const std::string& what,
                     const std::function<void(int)>& check) {
    std::vector<std::string> problems;
    for (int i = first; i < last; ++i) {
        try {
            check(i);
        } catch (const Error& e) {
            problems.push_back(e.what());
        }
    }
    if (problems.empty()) return;
    constexpr size_t kListed = 20;
    std::string text = what + ": " + std::to_string(problems.size()) + " of " +
                       std::to_string(last - first) + " frames cannot be read:";
    for (size_t k = 0; k < std::min(problems.size(), kListed); ++k) text += "\n  " + problems[k];
    if (problems.size() > kListed)
        text += "\n  ... and " + std::to_string(problems.size() - kListed) + " more";
    throw Error(text);
}

void SequenceReader::checkFrames(int first, int last) const {
    FrameData f;
    checkEveryFrame(first, last, info_.directory, [&](int i) { read(i, f, ExrContent::Header); });
}

namespace {

/// ". It holds 12 .png files, display images, not ..." for a folder of 8-bit pictures.
std::string notLinearFramesHint(const std::string& directory) {
    std::map<std::string, int> pictures;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(directory, ec)) {
        std::string ext = e.path().extension().string();
        for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
        if (ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".tif" || ext == ".tiff" ||
            ext == ".bmp" || ext == ".exr")
            ++pictures[ext];
    }
    if (pictures.empty()) return "";
    std::string list;
    for (const auto& [ext, n] : pictures)
        list += (list.empty() ? "" : ", ") + std::to_string(n) + " " + ext;
    if (pictures.count(".exr"))
        return "; it holds " + list +
               " files, but no file that says which is which or gives "
               "the cameras";
    return "; it holds " + list + " files: display images, not linear radiance";
}

} // namespace

std::unique_ptr<SequenceReader> SequenceReader::open(const std::string& directory) {
    if (!fs::is_directory(directory)) throw Error("input directory not found: " + directory);
    if (fs::exists(fs::path(directory) / "sequence.json")) return openManifestLayout(directory);
    if (fs::exists(fs::path(directory) / "camera_matrices.h") ||
        fs::exists(fs::path(directory) / "color0.exr"))
        return openBmfrLayout(directory);
    throw Error(directory +
                ": not a sequence bmfr reads: no sequence.json (bmfr's layout) and "
                "no camera_matrices.h or color0.exr (the original BMFR dataset)" +
                notLinearFramesHint(directory) +
                ". bmfr needs linear EXR frames with noise-free features (albedo, normal, "
                "position) and each frame's camera; `bmfr render` and "
                "tools/blender/render_sequence.py write them, and docs/input-layouts.md "
                "describes the layouts");
}

} // namespace bmfr
