// The C API's images as the C++ API's float views: a caller's image of any format and byte
// stride, and the encodings engines keep in their G-buffers (octahedral normals, view depth,
// motion vectors in their own units), decoded once per frame into buffers kept between frames.
#pragma once
#include <bmfr/frame.h>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace bmfr::capi {

/// A caller's image as bmfrSetFilterImage describes it; strides resolved (never 0).
struct SharedImage {
    unsigned char* data = nullptr; ///< the pointer plus the byte offset
    int format = 0;                ///< a BMFRFormat
    int width = 0, height = 0;
    size_t pixelStride = 0, rowStride = 0; ///< bytes
    int channels() const;
    bool isHalf() const;
    /// Channel c of pixel (x, y) as a float.
    float at(int x, int y, int c) const;
};

/// Channels of a BMFRFormat (0 for an unknown one) and the bytes of one of its channels.
int formatChannels(int format);
size_t formatChannelBytes(int format);
/// "BMFR_FORMAT_HALF4" and so on.
const char* formatName(int format);

/// True when the image is float channels with a pixel stride of exactly its channels and row
/// strides of whole floats: what the C++ API reads without a copy.
bool readsInPlace(const SharedImage& image);

/// The first `channels` channels of the image as packed floats in `buffer` (always a copy).
ImageView copyToFloats(const SharedImage& image, int channels, std::vector<float>& buffer);

/// The image as a float view, read in place (readsInPlace must hold).
ImageView inPlaceView(const SharedImage& image);

/// Unit normals from a two-channel octahedral encoding (Cigolle et al. 2014) in [-1, 1], or in
/// [0, 1] when `unorm` (as NRD packs them), into `buffer` (3 channels, packed).
ImageView decodeOctahedralNormals(const SharedImage& image, bool unorm, std::vector<float>& buffer);
/// World positions from view depth (the clip-space w of the point: its distance along the
/// camera's forward axis, scene units, > 0) at each pixel's sample position (its centre plus
/// the jitter), through the inverse of `viewProjection`, into `buffer` (3 channels, packed).
/// Throws bmfr::Error when the matrix has no inverse or is not a perspective projection.
ImageView positionsFromDepth(const SharedImage& depth, const Mat4& viewProjection,
                             const float jitter[2], std::vector<float>& buffer);

/// How an engine's motion vectors relate to bmfr's (FrameInput::motion): the vector times
/// `scale` is in pixels, y down unless `yUp`; without `includesJitter` the vector is between
/// unjittered positions and this frame's jitter minus the previous one's is added.
struct MotionConvention {
    float scale[2] = {1.0f, 1.0f};
    bool yUp = false;
    bool includesJitter = true;
    bool isIdentity() const {
        return scale[0] == 1.0f && scale[1] == 1.0f && !yUp && includesJitter;
    }
};

/// The engine's vectors in bmfr's convention (2 channels, and the depth offset as a third when
/// the image has one) into `buffer`, packed.
ImageView convertMotion(const SharedImage& motion, const MotionConvention& convention,
                        const float jitter[2], const float previousJitter[2],
                        std::vector<float>& buffer);

/// Writes a packed 3-channel float image into a caller's output image (3 or 4 channels, float
/// or half; a fourth channel is left as it was).
void writeShared(const ImageView& packedRgb, const SharedImage& out);

} // namespace bmfr::capi
