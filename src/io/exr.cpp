#include "io/exr.h"
#include "io/atomic_file.h"
#include "io/exr_precheck.h"
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfThreading.h>
#include <bmfr/error.h>
#include <filesystem>
#include <thread>
#include <vector>

namespace bmfr {


ImageF readExr(const std::string& path, int channels) {
    if (channels < 1 || channels > 3)
        throw Error("readExr: " + std::to_string(channels) + " channels asked of " + path);
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw Error("missing file: " + path);
    const auto fileBytes = std::filesystem::file_size(path, ec);
    if (ec) throw Error("unreadable EXR " + path + ": " + ec.message());
    precheckExr(path, fileBytes); // before OpenEXR sizes anything from the header
    try {
        Imf::InputFile file(path.c_str());
        const Imath::Box2i dw = file.header().dataWindow();
        const long w = long(dw.max.x) - dw.min.x + 1, h = long(dw.max.y) - dw.min.y + 1;
        if (w <= 0 || h <= 0) throw Error(path + ": zero-size image");
        if (!file.isComplete())
            throw Error(path + ": truncated or incomplete EXR (pixel data missing)");
        std::vector<std::string> names;
        for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it)
            names.emplace_back(it.name());
        auto has = [&](const char* n) {
            for (auto& s : names)
                if (s == n) return true;
            return false;
        };
        std::vector<std::string> pick;
        if (channels == 3 && has("R") && has("G") && has("B"))
            pick = {"R", "G", "B"};
        else if (channels == 2 && has("R") && has("G"))
            pick = {"R", "G"};
        else if (channels == 1 && has("Y"))
            pick = {"Y"};
        else if (channels == 1 && has("R"))
            pick = {"R"};
        else if (channels == 1 && names.size() == 1)
            pick = {names[0]};
        else {
            std::string list;
            for (auto& s : names) list += (list.empty() ? "" : ",") + s;
            throw Error(path + ": has channels [" + list + "], expected " +
                        (channels == 3   ? "R,G,B"
                         : channels == 2 ? "R,G"
                                         : "Y or a single channel"));
        }
        ImageF img(int(w), int(h), channels);
        Imf::FrameBuffer fb;
        const size_t xs = sizeof(float) * channels, ys = xs * size_t(w);
        char* base =
            reinterpret_cast<char*>(img.data()) - dw.min.x * long(xs) - dw.min.y * long(ys);
        // The same source channel may feed several slots: read the first, copy afterwards.
        fb.insert(pick[0], Imf::Slice(Imf::FLOAT, base, xs, ys));
        for (int c = 1; c < channels; ++c)
            if (pick[c] != pick[0])
                fb.insert(pick[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), xs, ys));
        file.setFrameBuffer(fb);
        file.readPixels(dw.min.y, dw.max.y);
        for (int c = 1; c < channels; ++c)
            if (pick[c] == pick[0])
                for (long i = 0; i < w * h; ++i)
                    img.data()[i * channels + c] = img.data()[i * channels];
        return img;
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw Error("unreadable EXR " + path + ": " + e.what());
    }
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
