// libFuzzer harness: the original layout's camera_matrices.h parser on arbitrary text.
#include "fuzz_common.h"
#include "io/sequence.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    bmfr::fuzz::expectCleanFailure([&] { bmfr::parseBmfrCameraFile(text, "camera_matrices.h"); });
    return 0;
}
