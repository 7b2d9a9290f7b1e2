// What the fuzz harnesses share: scratch files, a valid seed sequence, and the rule that a
// rejected input ends in bmfr::Error and nothing else.
#pragma once
#include "io/sequence.h"
#include "synth/procedural_scene.h"
#include <array>
#include <bmfr/error.h>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <unistd.h>

namespace bmfr::fuzz {

/// This process's scratch folder, removed when the process exits normally (a crash keeps it).
inline std::string scratchDir() {
    struct Folder {
        std::string path =
            (std::filesystem::temp_directory_path() / ("bmfr_fuzz_" + std::to_string(::getpid())))
                .string();
        Folder() { std::filesystem::create_directories(path); }
        ~Folder() {
            std::error_code ignored;
            std::filesystem::remove_all(path, ignored);
        }
    };
    static const Folder folder;
    return folder.path;
}

inline void writeScratchAt(const std::string& path, const uint8_t* data, size_t size) {
    FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) __builtin_trap();
    if (size) std::fwrite(data, 1, size, f);
    std::fclose(f);
}

inline std::string writeScratch(const char* name, const uint8_t* data, size_t size) {
    const std::string path = scratchDir() + "/" + name;
    writeScratchAt(path, data, size);
    return path;
}

/// A valid 8x4, two-frame sequence of either layout, written once per process.
inline std::string seedSequence(bool manifest) {
    static const std::array<std::string, 2> dirs = [] {
        const std::array<std::string, 2> d = {scratchDir() + "/bmfr_layout",
                                              scratchDir() + "/manifest_layout"};
        ProceduralSceneOptions o;
        o.width = 8, o.height = 4, o.frames = 2;
        ProceduralScene scene(o);
        std::vector<FrameData> frames(2);
        for (int i = 0; i < 2; ++i) scene.render(i, frames[size_t(i)]);
        writeBmfrLayout(d[0], frames, 0.01f, 1.0f);
        ManifestWriter w(d[1], scene.info());
        for (int i = 0; i < 2; ++i) w.addFrame(i, frames[size_t(i)]);
        return d;
    }();
    return dirs[manifest ? 1 : 0];
}

/// Runs f; a bmfr::Error is a clean rejection. Any other exception is a finding.
template <typename F> void expectCleanFailure(F&& f) {
    try {
        f();
    } catch (const Error&) {
    }
}

} // namespace bmfr::fuzz
