// This project's sequence layout: sequence.json naming per-frame EXR files.
#include "core/mat4.h"
#include "io/atomic_file.h"
#include "io/exr.h"
#include "io/json_fields.h"
#include "io/sequence.h"
#include <algorithm>
#include <bmfr/error.h>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

namespace bmfr {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

class ManifestReader : public SequenceReader {
  public:
    explicit ManifestReader(const std::string& dir) {
        info_.layout = "manifest";
        info_.directory = dir;
        const fs::path mp = fs::path(dir) / "sequence.json";
        std::ifstream in(mp);
        try {
            manifest_ = json::parse(in);
            if (manifest_.value("format", "") != "bmfr-sequence")
                throw Error(mp.string() + ": \"format\" is not \"bmfr-sequence\"");
            requireKnownKeys(manifest_,
                             {"format", "version", "width", "height", "color_is_demodulated",
                              "position_limit_squared", "normal_limit_squared", "extras", "layers",
                              "motion_convention", "frames", "generator"},
                             mp.string());
            std::vector<std::string> frameKeys = layeredBufferNames();
            for (const char* key : {"reset", "extras", "aovs", "view_projection", "jitter"})
                frameKeys.push_back(key);
            for (size_t k = 0; k < manifest_.at("frames").size(); ++k)
                requireKnownKeys(manifest_["frames"][k], frameKeys,
                                 mp.string() + " frame " + std::to_string(k));
            if (!manifest_.contains("width") || !manifest_.contains("height"))
                throw Error(mp.string() + ": needs \"width\" and \"height\"");
            info_.width = int(integerField(manifest_, "width", 0, 65536, 0, mp.string()));
            info_.height = int(integerField(manifest_, "height", 0, 65536, 0, mp.string()));
            if (info_.width <= 0 || info_.height <= 0)
                throw Error(mp.string() + ": zero-size frames (" + std::to_string(info_.width) +
                            "x" + std::to_string(info_.height) + ")");
            info_.colorIsDemodulated = manifest_.value("color_is_demodulated", false);
            const std::string convention = manifest_.value("motion_convention", "bmfr");
            if (convention != "bmfr" && convention != "cycles")
                throw Error(mp.string() + ": \"motion_convention\" is \"" + convention +
                            "\"; use \"bmfr\" (include/bmfr/frame.h) or \"cycles\" (Cycles' "
                            "Vector pass)");
            cyclesMotion_ = convention == "cycles";
            if (manifest_.contains("position_limit_squared"))
                info_.positionLimitSquared = floatValue(manifest_["position_limit_squared"],
                                                        mp.string() + ": position_limit_squared");
            if (manifest_.contains("normal_limit_squared"))
                info_.normalLimitSquared = floatValue(manifest_["normal_limit_squared"],
                                                      mp.string() + ": normal_limit_squared");
            if (manifest_.contains("extras"))
                info_.extraNames = manifest_["extras"].get<std::vector<std::string>>();
            if (manifest_.contains("layers")) {
                for (const auto& [buffer, layer] : manifest_["layers"].items())
                    layers_[buffer] = layer.get<std::string>();
                requireKnownKeys(manifest_["layers"], layeredBufferNames(),
                                 mp.string() + " \"layers\"");
            }
            info_.frameCount = int(manifest_.at("frames").size());
            if (info_.frameCount == 0) throw Error(mp.string() + ": no frames");
            info_.hasReference = manifest_["frames"][0].contains("reference");
            // Scoring needs every frame's reference or none: a mix is an error, not a silent
            // loss of the scores.
            for (size_t k = 0; k < manifest_["frames"].size(); ++k)
                if (manifest_["frames"][k].contains("reference") != info_.hasReference)
                    throw Error(mp.string() + ": frame " + std::to_string(k) +
                                (info_.hasReference ? " has no" : " has a") +
                                " \"reference\" but frame 0 " +
                                (info_.hasReference ? "has one" : "has none") +
                                "; give every frame a reference or none");
        } catch (const json::exception& e) {
            throw Error(mp.string() + ": " + jsonProblem(e));
        }
    }

    void read(int index, FrameData& f, ExrContent content) const override {
        const std::string where = info_.directory + "/sequence.json frame " + std::to_string(index);
        if (index < 0 || index >= info_.frameCount) throw Error(where + ": out of range");
        try {
            const json& j = manifest_["frames"][size_t(index)];
            std::vector<Buffer> buffers;
            // An optional buffer a frame does not name is left empty, not kept from the last.
            f.forEachBuffer([&](const FrameBuffer& b, ImageF& image) {
                if (!b.required) image = ImageF();
                // Motion: 2 channels, or 3 when the file has the depth offset.
                const int channels = b.channels.lo == kMotion.lo ? 0 : b.staged;
                if (b.required || j.contains(b.file)) buffers.push_back({b.file, &image, channels});
            });
            f.reference = ImageF();
            if (info_.hasReference) buffers.push_back({"reference", &f.reference, 3});
            std::string motionLayer;
            readBuffers(j, buffers, where, content, motionLayer);
            f.reset = j.value("reset", false);
            f.extras.clear();
            if (j.contains("extras")) {
                for (const auto& e : j["extras"])
                    f.extras.push_back(
                        readExr((fs::path(info_.directory) / e.get<std::string>()).string(), 1, "",
                                content));
                if (f.extras.size() != info_.extraNames.size())
                    throw Error(where + ": " + std::to_string(f.extras.size()) +
                                " extra buffers, the sequence names " +
                                std::to_string(info_.extraNames.size()));
            }
            f.aovs.clear();
            if (loadAovs_ && j.contains("aovs"))
                for (const json& entry : j["aovs"]) {
                    requireKnownKeys(entry, {"name", "file", "channels"}, where + " aov");
                    const std::string path =
                        (fs::path(info_.directory) / entry.at("file").get<std::string>()).string();
                    if (!entry.contains("channels"))
                        throw Error(where + ": aov without \"channels\"");
                    const int channels =
                        int(integerField(entry, "channels", 1, 3, 0, where + " aov"));
                    f.aovs.emplace_back(entry.at("name").get<std::string>(),
                                        readExr(path, channels, "", content));
                }
            const json& m = j.at("view_projection");
            if (m.size() != 4) throw Error(where + ": view_projection must be 4 rows of 4");
            for (int r = 0; r < 4; ++r) {
                if (m[r].size() != 4) throw Error(where + ": view_projection must be 4 rows of 4");
                for (int c = 0; c < 4; ++c)
                    f.viewProjection.m[r][c] = floatValue(m[r][c], where + ": view_projection");
            }
            if (!isUsableCameraMatrix(f.viewProjection))
                throw Error(where + ": view_projection is not finite or not invertible");
            readJitter(j, where + ": jitter", f.jitter);
            if (f.motion.width) {
                const bool vectorPass = isLayerOfPass(motionLayer, "Vector");
                if (vectorPass && !cyclesMotion_)
                    throw Error(where + ": motion is read from '" + motionLayer +
                                "', Cycles' Vector pass (y up, without the jitter); set "
                                "\"motion_convention\": \"cycles\" in sequence.json so that it "
                                "is converted (docs/blender.md)");
                if (cyclesMotion_ && content == ExrContent::Pixels)
                    fromCyclesMotion(f, index, where);
            }
            if (cyclesMotion_ && content == ExrContent::Pixels && f.previousPosition.width)
                addPosition(f);
        } catch (const json::exception& e) {
            throw Error(where + ": " + jsonProblem(e));
        }
        checkFrame(index, f);
    }

    void setLayerOverrides(const std::map<std::string, std::string>& layers) override {
        SequenceReader::setLayerOverrides(layers);
        // A layer for a buffer the frames do not name would be ignored: say so instead.
        for (const auto& [buffer, layer] : layers)
            if (!manifest_["frames"][0].contains(buffer))
                throw Error("--channel " + buffer + "=" + layer + ": " + info_.directory +
                            "/sequence.json names no " + buffer +
                            " file in its frames, so there is no file to read the layer from; "
                            "name one in each frame (\"" +
                            buffer + "\": \"frame_0001.exr\")");
    }

  private:
    /// Under "motion_convention": "cycles" the previous position is written as an offset from
    /// the position (render_sequence.py's AOV: a pixel no material writes, 0, is static).
    static void addPosition(FrameData& f) {
        ImageF& p = f.previousPosition;
        for (size_t i = 0; i < size_t(p.width) * size_t(p.height); ++i)
            for (int c = 0; c < 3; ++c)
                p.data()[i * size_t(p.channels) + size_t(c)] +=
                    f.position.data()[i * size_t(f.position.channels) + size_t(c)];
    }

    /// Cycles' Vector pass to FrameInput::motion: its X, Y are the previous frame's screen
    /// position minus this one's, pixels, y up, both through this frame's projection (so without
    /// the jitter, which render_sequence.py makes with the lens shift); bmfr's is y down with
    /// the jitter of both frames: (X, -Y) + jitter - previous jitter.
    void fromCyclesMotion(FrameData& f, int index, const std::string& where) const {
        float previous[2] = {f.jitter[0], f.jitter[1]};
        if (index > 0)
            readJitter(manifest_["frames"][size_t(index - 1)], where + ": previous frame's jitter",
                       previous);
        const float dx = f.jitter[0] - previous[0], dy = f.jitter[1] - previous[1];
        ImageF& m = f.motion;
        for (size_t p = 0; p < size_t(m.width) * size_t(m.height); ++p) {
            float* v = m.data() + p * size_t(m.channels);
            v[0] = v[0] + dx;
            v[1] = -v[1] + dy;
        }
    }
    /// A frame's "jitter" (0, 0 when it has none).
    static void readJitter(const json& frame, const std::string& where, float out[2]) {
        out[0] = out[1] = 0.0f;
        if (!frame.contains("jitter")) return;
        out[0] = floatValue(frame["jitter"].at(0), where);
        out[1] = floatValue(frame["jitter"].at(1), where);
    }

    json manifest_;
    bool cyclesMotion_ = false;                 ///< "motion_convention": "cycles"
    std::map<std::string, std::string> layers_; ///< the sequence's own "layers"

    struct Buffer {
        const char* key;
        ImageF* out;
        int channels; ///< 0: 2, or 3 when the file has a third (B) channel (motion's depth offset)
    };

    /// The image buffers of a frame. Each is a file name or {"file", "layer"}; the layer
    /// comes from --channel, then the entry, then the sequence's "layers", then kDefaultPasses
    /// when the file has only layered channels. Buffers in one file are read in one pass.
    void readBuffers(const json& frame, const std::vector<Buffer>& buffers,
                     const std::string& where, ExrContent content, std::string& motionLayer) const {
        std::map<std::string, std::vector<std::pair<const char*, ExrLayerRead>>> byFile;
        std::vector<std::string> order; // files in first-use order, for stable error messages
        for (const auto& [key, out, channels] : buffers) {
            const json& entry = frame.at(key);
            std::string name, layer;
            if (entry.is_object()) {
                requireKnownKeys(entry, {"file", "layer"}, where + " \"" + key + "\"");
                name = entry.at("file").get<std::string>();
                layer = entry.value("layer", "");
            } else {
                name = entry.get<std::string>();
            }
            if (auto it = layerOverrides_.find(key); it != layerOverrides_.end())
                layer = it->second;
            else if (auto it2 = layers_.find(key); layer.empty() && it2 != layers_.end())
                layer = it2->second;
            const std::string path = (fs::path(info_.directory) / name).string();
            if (!byFile.count(path)) order.push_back(path);
            byFile[path].push_back({key, ExrLayerRead{layer, channels, out}});
        }
        for (const std::string& path : order) {
            std::vector<ExrLayerRead> reads;
            std::vector<std::string> names;
            for (auto& [key, read] : byFile[path]) {
                if (read.layer.empty() || read.channels == 0)
                    if (names.empty()) names = exrChannelNames(path);
                if (read.layer.empty()) read.layer = defaultLayer(names, key, path);
                if (std::string(key) == "motion") motionLayer = read.layer;
                if (read.channels == 0) {
                    const std::string b = read.layer.empty() ? "B" : read.layer + ".B";
                    read.channels = std::find(names.begin(), names.end(), b) != names.end() ? 3 : 2;
                }
                reads.push_back(read);
            }
            readExrLayers(path, reads, content);
        }
    }

    /// "" when the file has plain channels, else the first of the buffer's default passes.
    std::string defaultLayer(const std::vector<std::string>& names, const char* key,
                             const std::string& path) const {
        if (hasPlainChannels(names)) return {};
        for (const DefaultPass& d : kDefaultPasses)
            if (d.buffer == std::string(key))
                for (const char* pass : d.passes)
                    if (std::string layer = findExrLayer(names, pass, path); !layer.empty()) {
                        if (std::string(pass) == "Noisy Image")
                            note("Cycles' own denoiser was on (the files have '" + layer +
                                 "' beside Combined, Cycles' denoised result): the colour is "
                                 "read from " +
                                 layer +
                                 ". Turn off the view layer's denoiser to render only the "
                                 "noisy image, or choose a layer with --channel color=LAYER");
                        return layer;
                    }
        throw Error(path + ": " + key +
                    ": no plain channels and none of the default passes; name the layer with "
                    "--channel " +
                    key + "=LAYER");
    }
};

} // namespace

std::unique_ptr<SequenceReader> openManifestLayout(const std::string& directory) {
    return std::make_unique<ManifestReader>(directory);
}

ManifestWriter::ManifestWriter(const std::string& directory, const SequenceInfo& info, bool resume,
                               bool part)
    : dir_(directory), info_(info), part_(part) {
    fs::create_directories(directory);
    const fs::path existing = fs::path(directory) / "sequence.json";
    if (resume && fs::exists(existing)) {
        try {
            std::ifstream in(existing);
            json doc = json::parse(in);
            if (doc.value("width", 0) != info.width || doc.value("height", 0) != info.height)
                throw Error(
                    existing.string() + " holds a " + std::to_string(doc.value("width", 0)) + "x" +
                    std::to_string(doc.value("height", 0)) + " sequence; refusing to mix it with " +
                    std::to_string(info.width) + "x" + std::to_string(info.height) + " frames");
            for (const json& f : doc.at("frames")) frameJson_.push_back(f.dump());
        } catch (const json::exception& e) {
            throw Error(existing.string() + ": " + jsonProblem(e));
        }
    }
    loadPartRecords();
}

void ManifestWriter::loadPartRecords() {
    const fs::path folder = fs::path(dir_) / kFramePartsFolder;
    std::error_code ec;
    for (const fs::directory_entry& e : fs::directory_iterator(folder, ec)) {
        const std::string name = e.path().filename().string();
        const size_t digits = name.find_first_not_of("0123456789");
        if (digits == 0 || digits > 9 || name.substr(digits) != ".json")
            continue; // another writer's temporary
        const size_t index = std::stoul(name.substr(0, digits));
        if (int64_t(index) >= info_.frameCount) continue; // a longer run's: not this sequence's
        try { // a part's record is newer than a manifest entry of the same frame
            std::ifstream in(e.path());
            const std::string record = json::parse(in).dump();
            if (index >= frameJson_.size()) frameJson_.resize(index + 1);
            frameJson_[index] = record;
        } catch (const json::exception& x) {
            throw Error(e.path().string() + ": " + jsonProblem(x));
        }
    }
}

bool ManifestWriter::hasFrame(int index) const {
    if (index < 0 || size_t(index) >= frameJson_.size() || frameJson_[size_t(index)].empty())
        return false;
    json j = json::parse(frameJson_[size_t(index)]);
    for (const char* key : {"color", "albedo", "normal", "position"})
        if (!j.contains(key) || !fs::exists(fs::path(dir_) / j[key].get<std::string>()))
            return false;
    if (j.contains("reference") && !fs::exists(fs::path(dir_) / j["reference"].get<std::string>()))
        return false;
    return true;
}

void ManifestWriter::addFrame(int index, const FrameData& f) {
    char stem[32];
    std::snprintf(stem, sizeof stem, "%04d", index);
    auto put = [&](const char* name, const ImageF& img) {
        std::string file = std::string(name) + "_" + stem + ".exr";
        writeExr((fs::path(dir_) / file).string(), img);
        return file;
    };
    json j;
    f.forEachBuffer([&](const FrameBuffer& b, const ImageF& image) {
        // "surface_roughness": the renderer's "roughness" extra already has the plain file name.
        const std::string file = std::string(b.file) == "roughness" ? "surface_roughness" : b.file;
        if (b.required || image.width) j[b.file] = put(file.c_str(), image);
    });
    if (f.reference.width) j["reference"] = put("reference", f.reference);
    if (f.reset) j["reset"] = true;
    if (!f.extras.empty()) {
        j["extras"] = json::array();
        for (size_t e = 0; e < f.extras.size(); ++e)
            j["extras"].push_back(put(info_.extraNames.at(e).c_str(), f.extras[e]));
    }
    if (!f.aovs.empty()) {
        j["aovs"] = json::array();
        for (const auto& [name, img] : f.aovs)
            j["aovs"].push_back(
                {{"name", name}, {"file", put(name.c_str(), img)}, {"channels", img.channels}});
    }
    json m = json::array();
    for (int r = 0; r < 4; ++r)
        m.push_back({f.viewProjection.m[r][0], f.viewProjection.m[r][1], f.viewProjection.m[r][2],
                     f.viewProjection.m[r][3]});
    j["view_projection"] = m;
    j["jitter"] = {f.jitter[0], f.jitter[1]};
    if (size_t(index) >= frameJson_.size()) frameJson_.resize(size_t(index) + 1);
    frameJson_[size_t(index)] = j.dump();
    if (!part_) {
        writeManifest();
        return;
    }
    // The record last: its presence says the frame's files are all in.
    const fs::path folder = fs::path(dir_) / kFramePartsFolder;
    fs::create_directories(folder);
    writeFileAtomically((folder / (std::string(stem) + ".json")).string(), j.dump() + "\n");
}

int ManifestWriter::writeManifestIfComplete() {
    loadPartRecords();
    int in = 0;
    for (int i = 0; i < info_.frameCount; ++i) in += hasFrame(i) ? 1 : 0;
    if (in == info_.frameCount && in > 0) writeManifest();
    return in;
}

/// The frames of the sequence recorded from 0 up to the first one missing: a frame's place in
/// the list is its index.
void ManifestWriter::writeManifest() const {
    json doc;
    doc["format"] = "bmfr-sequence";
    doc["version"] = 1;
    doc["width"] = info_.width;
    doc["height"] = info_.height;
    doc["color_is_demodulated"] = info_.colorIsDemodulated;
    if (info_.positionLimitSquared) doc["position_limit_squared"] = *info_.positionLimitSquared;
    if (info_.normalLimitSquared) doc["normal_limit_squared"] = *info_.normalLimitSquared;
    doc["extras"] = info_.extraNames;
    doc["frames"] = json::array();
    for (size_t i = 0; i < frameJson_.size() && int64_t(i) < info_.frameCount; ++i) {
        if (frameJson_[i].empty()) break;
        doc["frames"].push_back(json::parse(frameJson_[i]));
    }
    const fs::path path = fs::path(dir_) / "sequence.json";
    writeFileAtomically(path.string(), doc.dump(1) + "\n");
}

} // namespace bmfr
