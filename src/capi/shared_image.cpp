#include "capi/shared_image.h"
#include "core/half.h"
#include "core/mat4.h"
#include "core/octahedral.h"
#include <bmfr/bmfr.h>
#include <bmfr/error.h>
#include <cmath>
#include <cstring>

namespace bmfr::capi {

int formatChannels(int format) {
    if (format >= BMFR_FORMAT_FLOAT && format <= BMFR_FORMAT_FLOAT4) return format;
    if (format >= BMFR_FORMAT_HALF && format <= BMFR_FORMAT_HALF4)
        return format - BMFR_FORMAT_HALF + 1;
    return 0;
}

size_t formatChannelBytes(int format) {
    return format >= BMFR_FORMAT_HALF ? 2 : 4;
}

const char* formatName(int format) {
    static const char* const kFloat[] = {"BMFR_FORMAT_FLOAT", "BMFR_FORMAT_FLOAT2",
                                         "BMFR_FORMAT_FLOAT3", "BMFR_FORMAT_FLOAT4"};
    static const char* const kHalf[] = {"BMFR_FORMAT_HALF", "BMFR_FORMAT_HALF2",
                                        "BMFR_FORMAT_HALF3", "BMFR_FORMAT_HALF4"};
    const int c = formatChannels(format);
    if (c == 0) return "BMFR_FORMAT_UNDEFINED";
    return format >= BMFR_FORMAT_HALF ? kHalf[c - 1] : kFloat[c - 1];
}

int SharedImage::channels() const {
    return formatChannels(format);
}

bool SharedImage::isHalf() const {
    return format >= BMFR_FORMAT_HALF;
}

float SharedImage::at(int x, int y, int c) const {
    const unsigned char* p = data + size_t(y) * rowStride + size_t(x) * pixelStride;
    if (isHalf()) {
        uint16_t bits;
        std::memcpy(&bits, p + 2 * size_t(c), 2);
        return halfBitsToFloat(bits);
    }
    float v;
    std::memcpy(&v, p + 4 * size_t(c), 4);
    return v;
}

bool readsInPlace(const SharedImage& image) {
    return !image.isHalf() && image.pixelStride == size_t(image.channels()) * sizeof(float) &&
           image.rowStride % sizeof(float) == 0 &&
           reinterpret_cast<uintptr_t>(image.data) % alignof(float) == 0;
}

ImageView inPlaceView(const SharedImage& image) {
    return ImageView{reinterpret_cast<const float*>(image.data), image.width, image.height,
                     image.channels(), long(image.rowStride / sizeof(float))};
}

ImageView copyToFloats(const SharedImage& image, int channels, std::vector<float>& buffer) {
    buffer.resize(size_t(image.width) * size_t(image.height) * size_t(channels));
    float* out = buffer.data();
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            for (int c = 0; c < channels; ++c) *out++ = image.at(x, y, c);
    return ImageView{buffer.data(), image.width, image.height, channels, 0};
}

ImageView decodeOctahedralNormals(const SharedImage& image, bool unorm,
                                  std::vector<float>& buffer) {
    buffer.resize(size_t(image.width) * size_t(image.height) * 3);
    float* out = buffer.data();
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            Vec2 o{image.at(x, y, 0), image.at(x, y, 1)};
            if (unorm) o = Vec2{2.0f * o.x - 1.0f, 2.0f * o.y - 1.0f};
            const Vec3 n = octahedralDecode(o);
            *out++ = n.x;
            *out++ = n.y;
            *out++ = n.z;
        }
    return ImageView{buffer.data(), image.width, image.height, 3, 0};
}

ImageView positionsFromDepth(const SharedImage& depth, const Mat4& viewProjection,
                             const float jitter[2], std::vector<float>& buffer) {
    double m[4][4];
    if (!invert(viewProjection, m))
        throw Error("image 'depth': the viewProjection matrix has no inverse, so positions "
                    "cannot be reconstructed from depth");
    // A point at clip (ndc.x w, ndc.y w, z, w) is inverse * clip; z is the value that makes the
    // result's fourth component 1. Without a third column in that component (an orthographic
    // projection), clip w is not the view depth.
    const double c3 = m[3][2];
    double scale = 0;
    for (const auto& row : m)
        for (double v : row) scale = std::fmax(scale, std::fabs(v));
    if (std::fabs(c3) <= 1e-9 * scale)
        throw Error("image 'depth' needs a perspective viewProjection (clip w = view depth); "
                    "this one is orthographic: give 'position' instead");
    buffer.resize(size_t(depth.width) * size_t(depth.height) * 3);
    float* out = buffer.data();
    for (int y = 0; y < depth.height; ++y) {
        const double ny = (y + 0.5 + double(jitter[1])) / depth.height * 2.0 - 1.0;
        for (int x = 0; x < depth.width; ++x) {
            const double nx = (x + 0.5 + double(jitter[0])) / depth.width * 2.0 - 1.0;
            const double w = depth.at(x, y, 0);
            double a[4];
            for (int r = 0; r < 4; ++r) a[r] = m[r][0] * nx + m[r][1] * ny + m[r][3];
            const double z = (1.0 - w * a[3]) / c3;
            for (int r = 0; r < 3; ++r) *out++ = float(w * a[r] + z * m[r][2]);
        }
    }
    return ImageView{buffer.data(), depth.width, depth.height, 3, 0};
}

ImageView convertMotion(const SharedImage& motion, const MotionConvention& convention,
                        const float jitter[2], const float previousJitter[2],
                        std::vector<float>& buffer) {
    const int channels = motion.channels() >= 3 ? 3 : 2;
    const float sy = convention.yUp ? -convention.scale[1] : convention.scale[1];
    float add[2] = {0.0f, 0.0f};
    if (!convention.includesJitter) {
        add[0] = jitter[0] - previousJitter[0];
        add[1] = jitter[1] - previousJitter[1];
    }
    buffer.resize(size_t(motion.width) * size_t(motion.height) * size_t(channels));
    float* out = buffer.data();
    for (int y = 0; y < motion.height; ++y)
        for (int x = 0; x < motion.width; ++x) {
            *out++ = motion.at(x, y, 0) * convention.scale[0] + add[0];
            *out++ = motion.at(x, y, 1) * sy + add[1];
            if (channels == 3) *out++ = motion.at(x, y, 2);
        }
    return ImageView{buffer.data(), motion.width, motion.height, channels, 0};
}

void writeShared(const ImageView& in, const SharedImage& out) {
    for (int y = 0; y < in.height; ++y)
        for (int x = 0; x < in.width; ++x) {
            const float* src = in.data + (size_t(y) * size_t(in.width) + size_t(x)) * 3;
            unsigned char* dst = out.data + size_t(y) * out.rowStride + size_t(x) * out.pixelStride;
            for (int c = 0; c < 3; ++c) {
                if (out.isHalf()) {
                    const uint16_t bits = floatToHalfBits(src[c]);
                    std::memcpy(dst + 2 * size_t(c), &bits, 2);
                } else {
                    std::memcpy(dst + 4 * size_t(c), &src[c], 4);
                }
            }
        }
}

} // namespace bmfr::capi
