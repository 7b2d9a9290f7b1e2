#include "io/png.h"
#include "core/color.h"
#include "io/atomic_file.h"
#include <bmfr/error.h>
#include <stb/stb_image_write.h>
#include <vector>

namespace bmfr {

void writePngToneMapped(const std::string& path, const ImageF& image, float scale) {
    const int ch = image.channels == 1 ? 1 : 3;
    std::vector<unsigned char> bytes(size_t(image.pixelCount()) * ch);
    for (long i = 0; i < image.pixelCount(); ++i)
        for (int c = 0; c < ch; ++c) {
            float v = image.data()[i * image.channels + c] * scale;
            bytes[size_t(i) * ch + c] = (unsigned char)(gammaEncode(v) * 255.0f + 0.5f);
        }
    std::string png;
    auto sink = [](void* ctx, void* data, int size) {
        static_cast<std::string*>(ctx)->append(static_cast<const char*>(data), size_t(size));
    };
    if (!stbi_write_png_to_func(sink, &png, image.width, image.height, ch, bytes.data(),
                                image.width * ch))
        throw Error("cannot encode PNG " + path);
    writeFileAtomically(path, png);
}

} // namespace bmfr
