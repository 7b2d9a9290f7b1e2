// libFuzzer harness: the command line's frame-range and crop parsers.
#include "fuzz_common.h"
#include "io/range_parsers.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size < 1) return 0;
    const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
    const int count = data[0] * 7 + 1;
    bmfr::fuzz::expectCleanFailure([&] {
        const auto [a, b] = bmfr::parseFrameRange(text, count);
        if (a < 0 || b > count || a >= b) __builtin_trap(); // a range it accepted must be valid
    });
    bmfr::fuzz::expectCleanFailure([&] { bmfr::parseCrop(text); });
    return 0;
}
