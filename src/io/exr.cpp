#include "io/exr.h"
#include "io/atomic_file.h"
#include "io/exr_precheck.h"
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfInputPart.h>
#include <OpenEXR/ImfMultiPartInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfPartType.h>
#include <OpenEXR/ImfThreading.h>
#include <algorithm>
#include <bmfr/error.h>
#include <filesystem>
#include <thread>
#include <vector>

namespace bmfr {

namespace {

/// One channel of a file: which part holds it, its name in that part, its full name.
struct ChannelEntry {
    int part;
    std::string name, fullName;
};

void checkReadable(const std::string& path) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw Error("missing file: " + path);
    const auto fileBytes = std::filesystem::file_size(path, ec);
    if (ec) throw Error("unreadable EXR " + path + ": " + ec.message());
    precheckExr(path, fileBytes); // before OpenEXR sizes anything from the header
}

std::vector<ChannelEntry> listChannels(Imf::MultiPartInputFile& file) {
    std::vector<ChannelEntry> list;
    for (int p = 0; p < file.parts(); ++p) {
        const Imf::Header& h = file.header(p);
        const std::string prefix = file.parts() > 1 && h.hasName() ? h.name() + "." : "";
        for (auto it = h.channels().begin(); it != h.channels().end(); ++it) {
            const std::string n = it.name();
            list.push_back({p, n, n.rfind(prefix, 0) == 0 ? n : prefix + n});
        }
    }
    return list;
}

std::string joined(const std::vector<ChannelEntry>& list) {
    std::string s;
    for (const ChannelEntry& c : list) s += (s.empty() ? "" : ",") + c.fullName;
    return s;
}

/// The channels that fill `channels` slots from `layer` (empty: the unprefixed channels).
std::vector<const ChannelEntry*> pickChannels(const std::vector<ChannelEntry>& list, int channels,
                                              const std::string& layer) {
    auto find = [&](const std::string& suffix) -> const ChannelEntry* {
        const std::string want = layer.empty() ? suffix : layer + "." + suffix;
        for (const ChannelEntry& c : list)
            if (c.fullName == want) return &c;
        return nullptr;
    };
    auto all = [&](std::initializer_list<const char*> names) {
        std::vector<const ChannelEntry*> r;
        for (const char* n : names) {
            const ChannelEntry* c = find(n);
            if (!c) return std::vector<const ChannelEntry*>();
            r.push_back(c);
        }
        return r;
    };
    std::vector<const ChannelEntry*> r;
    if (channels == 3) {
        r = all({"R", "G", "B"});
        if (r.empty()) r = all({"X", "Y", "Z"});
    } else if (channels == 2) {
        r = all({"R", "G"});
        if (r.empty()) r = all({"X", "Y"});
    } else {
        for (const char* n : {"Y", "R", "V", "Z"})
            if (r.empty()) r = all({n});
        if (r.empty() && !layer.empty())
            for (const ChannelEntry& c : list)
                if (c.fullName == layer) r = {&c};
        if (r.empty() && layer.empty() && list.size() == 1) r = {&list[0]};
    }
    return r;
}

} // namespace

std::vector<std::string> exrChannelNames(const std::string& path) {
    checkReadable(path);
    try {
        Imf::MultiPartInputFile file(path.c_str());
        std::vector<std::string> names;
        for (const ChannelEntry& c : listChannels(file)) names.push_back(c.fullName);
        return names;
    } catch (const std::exception& e) {
        throw Error("unreadable EXR " + path + ": " + e.what());
    }
}

bool hasPlainChannels(const std::vector<std::string>& channelNames) {
    return std::any_of(channelNames.begin(), channelNames.end(),
                       [](const std::string& n) { return n.find('.') == std::string::npos; });
}

bool isLayerOfPass(const std::string& layer, const std::string& pass) {
    return layer == pass ||
           (layer.size() > pass.size() &&
            layer.compare(layer.size() - pass.size() - 1, std::string::npos, "." + pass) == 0);
}

std::string findExrLayer(const std::vector<std::string>& channelNames, const std::string& pass,
                         const std::string& path) {
    std::vector<std::string> layers;
    for (const std::string& n : channelNames) {
        const size_t dot = n.rfind('.');
        if (dot == std::string::npos) continue;
        const std::string layer = n.substr(0, dot);
        if (isLayerOfPass(layer, pass) &&
            std::find(layers.begin(), layers.end(), layer) == layers.end())
            layers.push_back(layer);
    }
    if (layers.size() > 1)
        throw Error(path + ": the pass '" + pass + "' is in several layers (" + layers[0] + ", " +
                    layers[1] + "); choose one with --channel");
    return layers.empty() ? std::string() : layers[0];
}

std::string findExrLayer(const std::string& path, const std::string& pass) {
    return findExrLayer(exrChannelNames(path), pass, path);
}

std::string imageLayer(const std::string& path) {
    const std::vector<std::string> names = exrChannelNames(path);
    if (hasPlainChannels(names)) return {};
    if (std::string layer = findExrLayer(names, "Combined", path); !layer.empty()) return layer;
    std::vector<std::string> layers;
    for (const std::string& n : names)
        if (std::string l = n.substr(0, n.rfind('.'));
            std::find(layers.begin(), layers.end(), l) == layers.end())
            layers.push_back(l);
    std::string list;
    for (size_t k = 0; k < layers.size() && k < 12; ++k) list += (k ? ", " : "") + layers[k];
    throw Error(path + ": no plain channels and no Combined pass; name a layer (" + list +
                (layers.size() > 12 ? ", ..." : "") + ")");
}

void readExrLayers(const std::string& path, const std::vector<ExrLayerRead>& reads,
                   ExrContent content) {
    for (const ExrLayerRead& r : reads)
        if (r.channels < 1 || r.channels > 3)
            throw Error("readExr: " + std::to_string(r.channels) + " channels asked of " + path);
    checkReadable(path);
    try {
        Imf::MultiPartInputFile file(path.c_str());
        const std::vector<ChannelEntry> list = listChannels(file);
        std::vector<std::vector<const ChannelEntry*>> picks;
        for (const ExrLayerRead& r : reads) {
            picks.push_back(pickChannels(list, r.channels, r.layer));
            const std::vector<const ChannelEntry*>& pick = picks.back();
            if (pick.empty()) {
                const std::string what = r.layer.empty() ? "" : " in layer '" + r.layer + "'";
                throw Error(path + ": has channels [" + joined(list) + "], expected " +
                            (r.channels == 3   ? "R,G,B (or X,Y,Z)"
                             : r.channels == 2 ? "R,G (or X,Y)"
                                               : "Y, R, V, Z or a single channel") +
                            what);
            }
            for (const ChannelEntry* c : pick)
                if (c->part != pick[0]->part)
                    throw Error(path + ": the channels of layer '" + r.layer +
                                "' span several parts");
        }
        // One frame buffer per part and round; a channel wanted twice waits for the next round.
        std::vector<bool> done(reads.size(), false);
        for (size_t remaining = reads.size(); remaining > 0;) {
            const int part = [&] {
                for (size_t k = 0; k < reads.size(); ++k)
                    if (!done[k]) return picks[k][0]->part;
                return 0;
            }();
            const Imf::Header& header = file.header(part);
            if (header.type() != Imf::SCANLINEIMAGE && header.type() != Imf::TILEDIMAGE)
                throw Error(path + ": deep images are not supported");
            const Imath::Box2i dw = header.dataWindow();
            const long w = long(dw.max.x) - dw.min.x + 1, h = long(dw.max.y) - dw.min.y + 1;
            if (w <= 0 || h <= 0) throw Error(path + ": zero-size image");
            if (!file.partComplete(part))
                throw Error(path + ": truncated or incomplete EXR (pixel data missing)");
            Imf::FrameBuffer fb;
            for (size_t k = 0; k < reads.size(); ++k) {
                if (done[k] || picks[k][0]->part != part) continue;
                bool clash = false;
                for (const ChannelEntry* c : picks[k]) clash = clash || fb.findSlice(c->name);
                if (clash) continue;
                const int ch = reads[k].channels;
                ImageF& img = *reads[k].out;
                done[k] = true;
                --remaining;
                if (content == ExrContent::Header) {
                    img = ImageF();
                    img.width = int(w), img.height = int(h), img.channels = ch;
                    continue;
                }
                img.resize(int(w), int(h), ch);
                const size_t xs = sizeof(float) * ch, ys = xs * size_t(w);
                char* base =
                    reinterpret_cast<char*>(img.data()) - dw.min.x * long(xs) - dw.min.y * long(ys);
                for (int c = 0; c < ch; ++c)
                    fb.insert(picks[k][size_t(c)]->name,
                              Imf::Slice(Imf::FLOAT, base + c * sizeof(float), xs, ys));
            }
            if (content == ExrContent::Header) continue;
            Imf::InputPart in(file, part);
            in.setFrameBuffer(fb);
            in.readPixels(dw.min.y, dw.max.y);
        }
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw Error("unreadable EXR " + path + ": " + e.what());
    }
}

ImageF readExr(const std::string& path, int channels, const std::string& layer,
               ExrContent content) {
    ImageF img;
    readExrLayers(path, {{layer, channels, &img}}, content);
    return img;
}

namespace {

/// OpenEXR compresses line blocks on its own thread pool once given one.
void useAllCoresForExr() {
    static const bool once = [] {
        Imf::setGlobalThreadCount(int(std::thread::hardware_concurrency()));
        return true;
    }();
    (void)once;
}

} // namespace

void writeExr(const std::string& path, const ImageF& image) {
    useAllCoresForExr();
    if (image.width <= 0 || image.height <= 0) throw Error("refusing to write empty image " + path);
    static const char* kNames[3][3] = {{"Y"}, {"R", "G"}, {"R", "G", "B"}};
    const int ch = image.channels;
    if (ch < 1 || ch > 3) throw Error("cannot write a " + std::to_string(ch) + "-channel EXR");
    const std::string tmp = temporaryPathFor(path);
    try {
        Imf::Header header(image.width, image.height);
        header.compression() = Imf::ZIP_COMPRESSION;
        // Level 1: most of the size gain of the default level 6 at a fraction of its time.
        header.zipCompressionLevel() = 1;
        for (int c = 0; c < ch; ++c)
            header.channels().insert(kNames[ch - 1][c], Imf::Channel(Imf::FLOAT));
        Imf::OutputFile file(tmp.c_str(), header);
        Imf::FrameBuffer fb;
        const size_t xs = sizeof(float) * ch, ys = xs * size_t(image.width);
        char* base = const_cast<char*>(reinterpret_cast<const char*>(image.data()));
        for (int c = 0; c < ch; ++c)
            fb.insert(kNames[ch - 1][c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), xs, ys));
        file.setFrameBuffer(fb);
        file.writePixels(image.height);
    } catch (const std::exception& e) {
        std::filesystem::remove(tmp);
        throw Error("cannot write EXR " + path + ": " + e.what());
    }
    commitTemporary(tmp, path);
}

} // namespace bmfr
