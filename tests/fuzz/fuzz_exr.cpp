// libFuzzer harness: the EXR reader on arbitrary bytes (through a file, as the reader opens
// paths). Every input must end in an image or a bmfr::Error, quickly and without a huge
// allocation.
#include "fuzz_common.h"
#include "io/exr.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = bmfr::fuzz::writeScratch("input.exr", data, size);
    for (int channels : {1, 3})
        bmfr::fuzz::expectCleanFailure([&] { bmfr::readExr(path, channels); });
    return 0;
}
