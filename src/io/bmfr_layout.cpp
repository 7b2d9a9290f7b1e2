// The original BMFR dataset layout (Koskela et al. 2019 supplementary data).
#include "core/mat4.h"
#include "io/atomic_file.h"
#include "io/exr.h"
#include "io/sequence.h"
#include <bmfr/error.h>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <sstream>

namespace bmfr {

namespace fs = std::filesystem;

namespace {

std::string stripComments(const std::string& s) {
    std::string out;
    for (size_t i = 0; i < s.size(); ++i) {
        if (s.compare(i, 2, "//") == 0) {
            while (i < s.size() && s[i] != '\n') ++i;
            out += '\n';
        } else if (s.compare(i, 2, "/*") == 0) {
            size_t e = s.find("*/", i + 2);
            i = e == std::string::npos ? s.size() : e + 1;
            out += ' ';
        } else {
            out += s[i];
        }
    }
    return out;
}

bool isIdentChar(char c) {
    return std::isalnum((unsigned char)c) || c == '_';
}

/// Position just after the identifier `name` as a whole word, or npos.
size_t findIdentifier(const std::string& s, const std::string& name) {
    size_t pos = 0;
    while ((pos = s.find(name, pos)) != std::string::npos) {
        bool before = pos == 0 || !isIdentChar(s[pos - 1]);
        bool after = pos + name.size() >= s.size() || !isIdentChar(s[pos + name.size()]);
        if (before && after) return pos + name.size();
        pos += name.size();
    }
    return std::string::npos;
}

/// Numbers inside the brace initializer starting after the '=' that follows `from`.
std::vector<float> initializerNumbers(const std::string& s, size_t from, const std::string& what,
                                      const std::string& source) {
    size_t eq = s.find('=', from);
    if (eq == std::string::npos) throw Error(source + ": '" + what + "' has no initializer");
    size_t open = s.find_first_not_of(" \t\r\n", eq + 1);
    std::vector<float> out;
    if (open == std::string::npos || s[open] != '{') {
        // Scalar: one number before ';'.
        size_t end = s.find(';', eq);
        std::string body =
            s.substr(eq + 1, end == std::string::npos ? std::string::npos : end - eq - 1);
        char* e = nullptr;
        float v = std::strtof(body.c_str(), &e);
        if (e == body.c_str()) throw Error(source + ": '" + what + "' is not a number");
        out.push_back(v);
        return out;
    }
    int depth = 0;
    size_t i = open;
    for (; i < s.size(); ++i) {
        char c = s[i];
        if (c == '{')
            ++depth;
        else if (c == '}') {
            if (--depth == 0) break;
        } else if (std::isdigit((unsigned char)c) || c == '-' || c == '+' || c == '.') {
            char* e = nullptr;
            float v = std::strtof(s.c_str() + i, &e);
            if (e == s.c_str() + i) throw Error(source + ": bad number in '" + what + "'");
            out.push_back(v);
            i = size_t(e - s.c_str());
            if (i < s.size() && (s[i] == 'f' || s[i] == 'F')) ++i;
            --i;
        } else if (!std::isspace((unsigned char)c) && c != ',') {
            throw Error(source + ": unexpected '" + std::string(1, c) + "' in '" + what + "'");
        }
    }
    if (depth != 0) throw Error(source + ": unterminated initializer of '" + what + "'");
    return out;
}

/// Declared array extents after the name, e.g. [60][4][4] -> {60, 4, 4}.
std::vector<long> extents(const std::string& s, size_t after) {
    std::vector<long> dims;
    size_t i = after;
    while (true) {
        i = s.find_first_not_of(" \t", i);
        if (i == std::string::npos || s[i] != '[') break;
        const size_t close = s.find(']', i);
        if (close == std::string::npos)
            throw Error("an array extent opens '[' and never closes it");
        const std::string text = s.substr(i + 1, close - i - 1);
        char* end = nullptr;
        const long v = std::strtol(text.c_str(), &end, 10);
        if (text.find_first_not_of(" \t") != std::string::npos &&
            (*end != '\0' || v < 0 || v > 100000000))
            throw Error("array extent '[" + text + "]' is not a count");
        dims.push_back(v);
        i = close + 1;
    }
    return dims;
}

class BmfrLayoutReader : public SequenceReader {
  public:
    explicit BmfrLayoutReader(const std::string& dir) {
        info_.layout = "bmfr";
        info_.directory = dir;
        info_.colorIsDemodulated = true;
        const fs::path camPath = fs::path(dir) / "camera_matrices.h";
        if (!fs::exists(camPath)) throw Error("missing file: " + camPath.string());
        std::ifstream in(camPath);
        std::stringstream text;
        text << in.rdbuf();
        camera_ = parseBmfrCameraFile(text.str(), camPath.string());
        info_.positionLimitSquared = camera_.positionLimitSquared;
        info_.normalLimitSquared = camera_.normalLimitSquared;
        int n = 0;
        while (fs::exists(path("color", n))) ++n;
        if (n == 0) throw Error(dir + ": no color0.exr");
        // A gap would end the sequence silently: every colorN.exr must follow without one.
        for (const fs::directory_entry& e : fs::directory_iterator(dir)) {
            const std::string name = e.path().filename().string();
            if (name.size() < 10 || name.rfind("color", 0) != 0 ||
                name.substr(name.size() - 4) != ".exr")
                continue;
            const std::string digits = name.substr(5, name.size() - 9);
            if (digits.empty() || digits.size() > 7 ||
                digits.find_first_not_of("0123456789") != std::string::npos)
                continue;
            const int k = std::stoi(digits);
            if (k > n)
                throw Error(dir + ": color" + std::to_string(n) + ".exr is missing, yet " + name +
                            " exists");
        }
        for (int k = 0; k < n; ++k)
            for (const char* stem : {"albedo", "shading_normal", "world_position"})
                if (!fs::exists(path(stem, k))) throw Error("missing file: " + path(stem, k));
        if (size_t(n) > camera_.matrices.size())
            throw Error(camPath.string() + ": " + std::to_string(camera_.matrices.size()) +
                        " camera matrices for " + std::to_string(n) + " frames");
        info_.frameCount = n;
        info_.hasReference = fs::exists(path("reference", 0));
        const ImageF first = readExr(path("color", 0), 3, "", ExrContent::Header);
        info_.width = first.width;
        info_.height = first.height;
    }

    void read(int index, FrameData& f, ExrContent content) const override {
        if (index < 0 || index >= info_.frameCount)
            throw Error(info_.directory + ": frame " + std::to_string(index) + " out of range");
        f.color = readExr(path("color", index), 3, "", content);
        f.albedo = readExr(path("albedo", index), 3, "", content);
        f.normal = readExr(path("shading_normal", index), 3, "", content);
        f.position = readExr(path("world_position", index), 3, "", content);
        f.extras.clear();
        f.reference =
            info_.hasReference ? readExr(path("reference", index), 3, "", content) : ImageF();
        // Row vectors (clip = p * M) -> our column-vector convention.
        f.viewProjection = transpose(camera_.matrices[index]);
        if (!isUsableCameraMatrix(f.viewProjection))
            throw Error(info_.directory + "/camera_matrices.h: matrix of frame " +
                        std::to_string(index) + " is not finite or not invertible");
        // The authors' code reprojects into frame i-1 with pixel_offsets[i] mapped to
        // (x, 1 - y); we subtract the previous frame's jitter, so frame i carries offset i+1.
        const size_t k = std::min(size_t(index + 1), camera_.pixelOffsets.size() - 1);
        f.jitter[0] = camera_.pixelOffsets.empty() ? 0.0f : camera_.pixelOffsets[k][0] - 0.5f;
        f.jitter[1] = camera_.pixelOffsets.empty() ? 0.0f : 0.5f - camera_.pixelOffsets[k][1];
        checkFrame(index, f);
    }

  private:
    BmfrCameraFile camera_;
    std::string path(const char* stem, int n) const {
        return (fs::path(info_.directory) / (std::string(stem) + std::to_string(n) + ".exr"))
            .string();
    }
};

} // namespace

BmfrCameraFile parseBmfrCameraFile(const std::string& raw, const std::string& source) {
    const std::string s = stripComments(raw);
    BmfrCameraFile out;
    size_t at = findIdentifier(s, "camera_matrices");
    if (at == std::string::npos) throw Error(source + ": no camera_matrices array");
    std::vector<long> dims;
    try {
        dims = extents(s, at);
    } catch (const Error& e) {
        throw Error(source + ": camera_matrices: " + e.what());
    }
    std::vector<float> m = initializerNumbers(s, at, "camera_matrices", source);
    if (m.empty() || m.size() % 16 != 0)
        throw Error(source + ": camera_matrices has " + std::to_string(m.size()) +
                    " numbers, not a multiple of 16");
    if (!dims.empty() && dims[0] > 0 && size_t(dims[0]) * 16 != m.size())
        throw Error(source + ": camera_matrices is declared [" + std::to_string(dims[0]) +
                    "][4][4] but holds " + std::to_string(m.size() / 16) + " matrices");
    for (size_t k = 0; k < m.size() / 16; ++k) {
        Mat4 mat;
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c) mat.m[r][c] = m[k * 16 + r * 4 + c];
        out.matrices.push_back(mat);
    }
    size_t po = findIdentifier(s, "pixel_offsets");
    if (po != std::string::npos) {
        std::vector<float> o = initializerNumbers(s, po, "pixel_offsets", source);
        if (o.size() % 2 != 0) throw Error(source + ": pixel_offsets has an odd count");
        for (size_t k = 0; k < o.size() / 2; ++k)
            out.pixelOffsets.push_back({o[2 * k], o[2 * k + 1]});
    }
    for (const char* name : {"position_limit_squared", "normal_limit_squared"}) {
        size_t p = findIdentifier(s, name);
        if (p == std::string::npos) continue;
        std::vector<float> v = initializerNumbers(s, p, name, source);
        if (v.size() != 1 || !(v[0] > 0)) throw Error(source + ": bad " + name);
        (std::string(name) == "position_limit_squared" ? out.positionLimitSquared
                                                       : out.normalLimitSquared) = v[0];
    }
    return out;
}

std::unique_ptr<SequenceReader> openBmfrLayout(const std::string& directory) {
    return std::make_unique<BmfrLayoutReader>(directory);
}

namespace {

/// A C++ float literal that parses back to exactly `v` ("1.0f", "0.25f", "1e-05f"): the authors'
/// code #includes camera_matrices.h, so "1f" (not a literal) would not compile.
std::string floatLiteral(float v) {
    if (!std::isfinite(v)) throw Error("camera_matrices.h: a matrix entry is not finite");
    std::string s = fmt::format("{}", v);
    if (s.find_first_of(".e") == std::string::npos) s += ".0";
    return s + "f";
}

} // namespace

BmfrLayoutWriter::BmfrLayoutWriter(const std::string& directory, const std::vector<Mat4>& matrices,
                                   const std::vector<std::array<float, 2>>& jitters,
                                   float positionLimitSquared, float normalLimitSquared)
    : dir_(directory) {
    fs::create_directories(directory);
    std::ostringstream h;
    h << "// Written by bmfr in the original BMFR dataset layout.\n";
    h << "const float position_limit_squared = " << floatLiteral(positionLimitSquared) << ";\n";
    h << "const float normal_limit_squared = " << floatLiteral(normalLimitSquared) << ";\n";
    h << "const float camera_matrices[" << matrices.size() << "][4][4] = {\n";
    for (const Mat4& m : matrices) {
        Mat4 rowVec = transpose(m);
        h << "  {";
        for (int r = 0; r < 4; ++r) {
            h << "{";
            for (int c = 0; c < 4; ++c) h << floatLiteral(rowVec.m[r][c]) << (c < 3 ? ", " : "");
            h << (r < 3 ? "}, " : "}");
        }
        h << "},\n";
    }
    h << "};\nconst float pixel_offsets[" << jitters.size() << "][2] = {\n";
    // Inverse of the reader's mapping: entry i holds frame i-1's jitter.
    for (size_t i = 0; i < jitters.size(); ++i) {
        const auto& j = jitters[i == 0 ? 0 : i - 1];
        h << "  {" << floatLiteral(j[0] + 0.5f) << ", " << floatLiteral(0.5f - j[1]) << "},\n";
    }
    h << "};\n";
    header_ = h.str();
}

void BmfrLayoutWriter::finish() {
    writeFileAtomically((fs::path(dir_) / "camera_matrices.h").string(), header_);
}

namespace {
std::string layoutPath(const std::string& dir, const char* stem, int n) {
    return (fs::path(dir) / (std::string(stem) + std::to_string(n) + ".exr")).string();
}
} // namespace

void BmfrLayoutWriter::addFrame(int i, const FrameData& f) {
    ImageF demod = f.color;
    for (long k = 0; k < demod.pixelCount() * 3; ++k)
        demod.data()[k] /= std::max(f.albedo.data()[k], 0.001f);
    writeExr(layoutPath(dir_, "albedo", i), f.albedo);
    writeExr(layoutPath(dir_, "shading_normal", i), f.normal);
    writeExr(layoutPath(dir_, "world_position", i), f.position);
    if (f.reference.width) writeExr(layoutPath(dir_, "reference", i), f.reference);
    writeExr(layoutPath(dir_, "color", i), demod); // last: its presence marks a complete frame
}

bool BmfrLayoutWriter::hasFrame(int index) const {
    return fs::exists(layoutPath(dir_, "color", index));
}

void writeBmfrLayout(const std::string& directory, const std::vector<FrameData>& frames,
                     float positionLimitSquared, float normalLimitSquared) {
    std::vector<Mat4> matrices;
    std::vector<std::array<float, 2>> jitters;
    for (const FrameData& f : frames)
        matrices.push_back(f.viewProjection), jitters.push_back({f.jitter[0], f.jitter[1]});
    BmfrLayoutWriter w(directory, matrices, jitters, positionLimitSquared, normalLimitSquared);
    for (size_t i = 0; i < frames.size(); ++i) w.addFrame(int(i), frames[i]);
    w.finish();
}

} // namespace bmfr
