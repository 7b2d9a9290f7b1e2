// The EXR pre-check (src/io/exr_precheck.cpp) on tiled and multi-part files: the headers that
// would make OpenEXR allocate gigabytes are refused before OpenEXR opens the file, and tiled
// files of every level mode, tiles larger than the image and multi-part tiled files still read.
#include "io/exr.h"
#include "test_support.h"
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfMultiPartOutputFile.h>
#include <OpenEXR/ImfPartType.h>
#include <OpenEXR/ImfTileDescriptionAttribute.h>
#include <OpenEXR/ImfTiledOutputFile.h>
#include <OpenEXR/ImfTiledOutputPart.h>
#include <filesystem>
#include <gtest/gtest.h>

namespace bmfr {
namespace {

namespace fs = std::filesystem;
using testing::errorOf;

fs::path corpus(const char* name) {
    return fs::path(BMFR_SOURCE_DIR) / "tests" / "fuzz" / "corpus" / "exr" / name;
}

TEST(ExrPrecheck, TilesAndChunksThatClaimGigabytesAreRefused) {
    struct Case {
        const char* file;
        const char* why;
    };
    for (const Case& c :
         {Case{"exr-tile-height-16M-alloc-1.6GB.min.exr", "tile size 8x16777224 is outside"},
          Case{"exr-multipart-tile-width-16M.min.exr", "tile size 16775952x16 (part 0)"},
          Case{"exr-320ch-65536x1-zip-20KB.exr",
               "a block of 16 lines of 65536 pixels of 1280 bytes would need 1 GiB at once"}}) {
        const std::string why = errorOf([&] { readExr(corpus(c.file).string(), 3); });
        EXPECT_NE(why.find(c.why), std::string::npos) << c.file << ": " << why;
    }
}

/// Level (lx, ly) of a tiled file: every pixel of channel c holds c + 10 lx + 100 ly.
template <class File> void writeLevels(File& file, int lx, int ly) {
    const int w = file.levelWidth(lx), h = file.levelHeight(ly);
    std::vector<float> px(size_t(w) * size_t(h) * 3);
    for (size_t i = 0; i < px.size(); ++i) px[i] = float(i % 3) + 10.0f * lx + 100.0f * ly;
    Imf::FrameBuffer fb;
    const char* names[] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c)
        fb.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(px.data() + c),
                                       3 * sizeof(float), 3 * sizeof(float) * size_t(w)));
    file.setFrameBuffer(fb);
    file.writeTiles(0, file.numXTiles(lx) - 1, 0, file.numYTiles(ly) - 1, lx, ly);
}

Imf::Header tiledHeader(int w, int h, int tile, Imf::LevelMode mode, Imf::LevelRoundingMode r) {
    Imf::Header header(w, h);
    for (const char* c : {"R", "G", "B"}) header.channels().insert(c, Imf::Channel(Imf::FLOAT));
    header.setTileDescription(Imf::TileDescription(unsigned(tile), unsigned(tile), mode, r));
    return header;
}

void expectLevelZero(const ImageF& img, int w, int h) {
    ASSERT_EQ(img.width, w);
    ASSERT_EQ(img.height, h);
    for (size_t i = 0; i < img.pixels.size(); ++i) ASSERT_EQ(img.pixels[i], float(i % 3)) << i;
}

TEST(ExrPrecheck, TiledFilesOfEveryLevelModeStillRead) {
    const fs::path dir = testing::freshDir("precheck", "tiled");
    struct Case {
        int w, h, tile;
        Imf::LevelMode mode;
        Imf::LevelRoundingMode rounding;
    };
    for (const Case& c : {Case{37, 23, 16, Imf::ONE_LEVEL, Imf::ROUND_DOWN},
                          Case{5, 3, 64, Imf::ONE_LEVEL, Imf::ROUND_DOWN}, // tile > image
                          Case{37, 23, 8, Imf::MIPMAP_LEVELS, Imf::ROUND_DOWN},
                          Case{37, 23, 8, Imf::MIPMAP_LEVELS, Imf::ROUND_UP},
                          Case{33, 17, 4, Imf::RIPMAP_LEVELS, Imf::ROUND_UP}}) {
        SCOPED_TRACE(std::to_string(c.w) + "x" + std::to_string(c.h) + " mode " +
                     std::to_string(int(c.mode)) + " rounding " + std::to_string(int(c.rounding)));
        const fs::path path = dir / "tiled.exr";
        {
            Imf::TiledOutputFile file(path.c_str(),
                                      tiledHeader(c.w, c.h, c.tile, c.mode, c.rounding));
            for (int lx = 0; lx < file.numXLevels(); ++lx)
                for (int ly = 0; ly < file.numYLevels(); ++ly)
                    if (c.mode == Imf::RIPMAP_LEVELS || lx == ly) writeLevels(file, lx, ly);
        }
        expectLevelZero(readExr(path.string(), 3), c.w, c.h);
    }
    // A tiled part in a multi-part file: tiled by its type, not the version flag.
    const fs::path multi = dir / "multi.exr";
    {
        Imf::Header headers[2] = {tiledHeader(19, 11, 8, Imf::MIPMAP_LEVELS, Imf::ROUND_DOWN),
                                  tiledHeader(19, 11, 32, Imf::ONE_LEVEL, Imf::ROUND_DOWN)};
        headers[0].setName("beauty");
        headers[1].setName("albedo");
        for (Imf::Header& h : headers) h.setType(Imf::TILEDIMAGE);
        Imf::MultiPartOutputFile file(multi.c_str(), headers, 2);
        for (int p = 0; p < 2; ++p) {
            Imf::TiledOutputPart part(file, p);
            for (int l = 0; l < part.numLevels(); ++l) writeLevels(part, l, l);
        }
    }
    expectLevelZero(readExr(multi.string(), 3, "beauty"), 19, 11);
}

} // namespace
} // namespace bmfr
