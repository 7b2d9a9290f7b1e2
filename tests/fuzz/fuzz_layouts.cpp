// libFuzzer harness: both layouts' loaders. The first byte picks the layout; the rest is the
// layout's index file (sequence.json or camera_matrices.h) in a folder whose frame files are
// a valid 8x4 two-frame sequence, and every frame it declares is loaded.
#include "fuzz_common.h"
#include "io/sequence.h"
#include <filesystem>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size < 1) return 0;
    const bool manifest = data[0] & 1;
    const std::string dir = bmfr::fuzz::seedSequence(manifest);
    bmfr::fuzz::writeScratchAt(dir + (manifest ? "/sequence.json" : "/camera_matrices.h"), data + 1,
                               size - 1);
    bmfr::fuzz::expectCleanFailure([&] {
        auto reader = bmfr::SequenceReader::open(dir);
        bmfr::FrameData f;
        for (int i = 0; i < reader->info().frameCount && i < 4; ++i) reader->load(i, f);
    });
    return 0;
}
