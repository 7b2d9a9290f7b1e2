// libFuzzer harness: the scene description parser on arbitrary JSON text.
#include "fuzz_common.h"
#include "render/scene_description.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    bmfr::fuzz::expectCleanFailure([&] {
        const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
        if (j.is_discarded()) return;
        bmfr::render::parseSceneDescription(j, ".");
    });
    return 0;
}
