#include "io/exr_precheck.h"
#include <algorithm>
#include <bmfr/error.h>
#include <cstring>
#include <fstream>
#include <vector>

namespace bmfr {

namespace {

struct Reader {
    std::ifstream in;
    const std::string& path;
    uint64_t size;

    uint64_t position() { return uint64_t(in.tellg()); }
    [[noreturn]] void fail(const std::string& why) {
        throw Error("unreadable EXR " + path + ": " + why);
    }
    std::string text(const char* what) {
        std::string s;
        for (char c; in.get(c);) {
            if (c == '\0') return s;
            if (s.size() >= 255) fail(std::string(what) + " longer than 255 bytes");
            s += c;
        }
        fail(std::string("the file ends inside a ") + what);
    }
    template <typename T> T value(const char* what) {
        T v{};
        if (!in.read(reinterpret_cast<char*>(&v), sizeof v))
            fail(std::string("the file ends in ") + what);
        return v; // EXR is little-endian, as every machine bmfr builds for
    }
};

/// The size OpenEXR reads for a fixed-size attribute type whatever the header declares (0 for
/// variable-size types): a declared size that differs would desynchronise its parse from ours.
int fixedSize(const std::string& type) {
    static const std::pair<const char*, int> kSizes[] = {{"box2i", 16},
                                                         {"box2f", 16},
                                                         {"v2i", 8},
                                                         {"v2f", 8},
                                                         {"v2d", 16},
                                                         {"v3i", 12},
                                                         {"v3f", 12},
                                                         {"v3d", 24},
                                                         {"int", 4},
                                                         {"float", 4},
                                                         {"double", 8},
                                                         {"compression", 1},
                                                         {"lineOrder", 1},
                                                         {"envmap", 1},
                                                         {"deepImageState", 1},
                                                         {"chromaticities", 32},
                                                         {"keycode", 28},
                                                         {"timecode", 8},
                                                         {"tiledesc", 9},
                                                         {"rational", 8},
                                                         {"m33f", 36},
                                                         {"m44f", 64},
                                                         {"m33d", 72},
                                                         {"m44d", 128}};
    for (const auto& [name, size] : kSizes)
        if (type == name) return size;
    return 0;
}

/// Lines per scanline chunk for each compression (OpenEXR's table).
int linesPerChunk(uint8_t compression) {
    switch (compression) {
    case 0: // none
    case 1: // RLE
    case 2: // ZIPS
        return 1;
    case 3: // ZIP
    case 5: // PXR24
        return 16;
    case 4: // PIZ
    case 6: // B44
    case 7: // B44A
    case 8: // DWAA
        return 32;
    case 9: // DWAB
        return 256;
    default:
        return -1;
    }
}

} // namespace

namespace {

/// Tiles in one level of a tiled part: OpenEXR allocates an offset-table entry for each.
double tilesIn(long w, long h, long tileX, long tileY) {
    return double((w + tileX - 1) / tileX) * double((h + tileY - 1) / tileY);
}

/// The level sizes of a mip- or rip-mapped part (OpenEXR's rounding: 0 down, 1 up).
long levelSize(long size, int level, int rounding) {
    const long scaled = rounding ? (size + (1L << level) - 1) >> level : size >> level;
    return std::max(scaled, 1L);
}
int levelCount(long size, int rounding) {
    int levels = 1;
    while (levelSize(size, levels - 1, rounding) > 1) ++levels;
    return levels;
}

std::string bytesText(double bytes) {
    const char* unit[] = {"bytes", "KiB", "MiB", "GiB"};
    int k = 0;
    for (; k < 3 && bytes >= 1024.0; ++k) bytes /= 1024.0;
    return std::to_string(long(bytes)) + " " + unit[k];
}

} // namespace

void precheckExr(const std::string& path, uint64_t fileBytes) {
    Reader r{std::ifstream(path, std::ios::binary), path, fileBytes};
    if (!r.in) throw Error("unreadable EXR " + path);
    const uint32_t magic = r.value<uint32_t>("the magic number");
    if (magic != 20000630u) r.fail("not an OpenEXR file (bad magic number)");
    const uint32_t version = r.value<uint32_t>("the version");
    if (version & 0x800) r.fail("deep images are not supported");
    const bool multipart = version & 0x1000;
    const size_t maxName = version & 0x400 ? 255 : 31; // long names are a version flag
    // What one chunk (a block of lines or a tile) may hold uncompressed: OpenEXR allocates a
    // buffer of that size per thread before reading a byte of pixel data.
    const double chunkCap =
        std::min(double(kMaxExrChunkBytes), double(kMaxExrCompressionRatio) * double(fileBytes));
    for (int part = 0;; ++part) {
        long w = 0, h = 0, tileX = 0, tileY = 0, declaredChunks = -1;
        int compression = -1, levelMode = 0, rounding = 0;
        // A single-part file is tiled by its version flag, a part of a multi-part file by its
        // "type" attribute.
        bool tiled = !multipart && (version & 0x200);
        double bytesPerPixel = 0;
        bool any = false;
        while (true) {
            const std::string name = r.text("attribute name");
            if (name.empty()) break;
            any = true;
            const std::string type = r.text("attribute type");
            if (name.size() > maxName || type.size() > maxName)
                r.fail("attribute name or type '" + name + "' longer than " +
                       std::to_string(maxName) + " bytes");
            const int32_t n = r.value<int32_t>("an attribute size");
            if (fixedSize(type) && n != fixedSize(type))
                r.fail("attribute '" + name + "' of type " + type + " declares " +
                       std::to_string(n) + " bytes, the type has " +
                       std::to_string(fixedSize(type)));
            if (n < 0 || uint64_t(n) > r.size - r.position())
                r.fail("attribute '" + name + "' claims " + std::to_string(n) +
                       " bytes, the file has " + std::to_string(r.size - r.position()) + " left");
            std::vector<char> v(static_cast<size_t>(n));
            if (n && !r.in.read(v.data(), n)) r.fail("the file ends in attribute '" + name + "'");
            auto i32 = [&](size_t at) {
                int32_t x = 0;
                if (at + 4 <= v.size()) std::memcpy(&x, v.data() + at, 4);
                return x;
            };
            if (name == "dataWindow" && type == "box2i" && n == 16) {
                w = long(i32(8)) - i32(0) + 1;
                h = long(i32(12)) - i32(4) + 1;
            } else if (name == "compression" && n == 1) {
                compression = uint8_t(v[0]);
            } else if (name == "tiles" && n == 9) {
                tileX = uint32_t(i32(0));
                tileY = uint32_t(i32(4));
                levelMode = uint8_t(v[8]) & 0xf;
                rounding = uint8_t(v[8]) >> 4;
            } else if (name == "type" && type == "string") {
                const std::string partType(v.begin(), v.end());
                if (partType == "deepscanline" || partType == "deeptile")
                    r.fail("deep images are not supported");
                if (partType != "scanlineimage" && partType != "tiledimage")
                    r.fail("unknown part type '" + partType + "'");
                tiled = partType == "tiledimage";
            } else if (name == "chunkCount" && type == "int") {
                declaredChunks = i32(0);
            } else if (type == "preview") {
                // Width and height, then 4 bytes per pixel: OpenEXR allocates what they say.
                const double pixels = double(uint32_t(i32(0))) * double(uint32_t(i32(4)));
                if (n < 8 || pixels * 4.0 + 8.0 != double(n))
                    r.fail("preview attribute '" + name + "' does not match its size");
            } else if (type == "stringvector") {
                for (size_t at = 0; at < v.size();) {
                    const int32_t len = i32(at);
                    if (at + 4 > v.size() || len < 0 || size_t(len) > v.size() - at - 4)
                        r.fail("malformed string vector '" + name + "'");
                    at += 4 + size_t(len);
                }
            } else if (type == "chlist") {
                if (v.empty() || v.back() != '\0') r.fail("malformed channel list");
                size_t at = 0;
                for (; at < v.size() && v[at] != '\0';) {
                    const size_t end = std::find(v.begin() + long(at), v.end(), '\0') - v.begin();
                    if (end + 17 > v.size()) r.fail("malformed channel list");
                    const int32_t pixelType = i32(end + 1);
                    if (name == "channels") bytesPerPixel += pixelType == 1 ? 2.0 : 4.0; // HALF: 2
                    at = end + 17;
                }
                if (at + 1 != v.size()) r.fail("malformed channel list");
            }
        }
        if (!any) {
            if (part == 0) r.fail("no header attributes");
            break; // the empty header that ends a multi-part file
        }
        const std::string where = multipart ? " (part " + std::to_string(part) + ")" : "";
        if (w <= 0 || h <= 0) r.fail("zero-size or missing data window" + where);
        if (w > kMaxExrSide || h > kMaxExrSide || w * h > kMaxExrPixels)
            throw Error(path + where + ": claims " + std::to_string(w) + "x" + std::to_string(h) +
                        " pixels, more than the " + std::to_string(kMaxExrPixels) + "-pixel limit");
        // Every chunk has an 8-byte entry in the offset table, which lives in the file; every
        // chunk's pixels are one buffer in memory.
        double chunks = 0, chunkBytes = 0;
        std::string chunkWhat;
        if (tiled) {
            if (tileX <= 0 || tileY <= 0 || tileX > kMaxExrSide || tileY > kMaxExrSide)
                r.fail("tile size " + std::to_string(tileX) + "x" + std::to_string(tileY) + where +
                       " is outside 1.." + std::to_string(kMaxExrSide));
            if (levelMode > 2 || rounding > 1) r.fail("unknown tile level mode" + where);
            const int levelsX =
                levelMode == 0 ? 1 : levelCount(levelMode == 1 ? std::max(w, h) : w, rounding);
            const int levelsY = levelMode == 2 ? levelCount(h, rounding) : 1;
            for (int lx = 0; lx < levelsX; ++lx)
                for (int ly = 0; ly < levelsY; ++ly) {
                    const int y = levelMode == 1 ? lx : ly; // mip-map levels shrink both sides
                    chunks += tilesIn(levelSize(w, lx, rounding), levelSize(h, y, rounding), tileX,
                                      tileY);
                }
            chunkBytes = double(tileX) * double(tileY) * bytesPerPixel;
            chunkWhat = "a tile of " + std::to_string(tileX) + "x" + std::to_string(tileY);
        } else if (linesPerChunk(uint8_t(compression)) > 0) {
            const int lines = linesPerChunk(uint8_t(compression));
            chunks = double((h + lines - 1) / lines);
            chunkBytes = double(lines) * double(w) * bytesPerPixel;
            chunkWhat = "a block of " + std::to_string(lines) + " lines of " + std::to_string(w);
        } else {
            r.fail("unknown compression" + where);
        }
        if (std::max(chunks, double(declaredChunks)) * 8.0 > double(r.size))
            throw Error(path + where + ": claims " + std::to_string(w) + "x" + std::to_string(h) +
                        " pixels in " +
                        std::to_string(long(std::max(chunks, double(declaredChunks)))) +
                        " chunks, but the file holds only " + std::to_string(r.size) +
                        " bytes: truncated or corrupt");
        if (double(w) * double(h) * bytesPerPixel >
            double(kMaxExrCompressionRatio) * double(r.size))
            throw Error(path + where + ": claims " + std::to_string(w) + "x" + std::to_string(h) +
                        " pixels, but the file holds only " + std::to_string(r.size) +
                        " bytes: truncated or corrupt");
        if (chunkBytes > chunkCap)
            throw Error(path + where + ": " + chunkWhat + " pixels of " +
                        std::to_string(long(bytesPerPixel)) + " bytes would need " +
                        bytesText(chunkBytes) + " at once, more than " + bytesText(chunkCap) +
                        (chunkCap < double(kMaxExrChunkBytes)
                             ? " (what a file of " + std::to_string(r.size) +
                                   " bytes can hold): corrupt or hostile"
                             : ", bmfr's limit per chunk: write it with fewer lines per chunk "
                               "(ZIP, 16) or fewer channels per part"));
        if (!multipart) break;
    }
}

} // namespace bmfr
