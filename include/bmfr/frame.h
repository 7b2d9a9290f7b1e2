// What the denoiser takes per frame and what it gives back.
#pragma once
#include <cstdint>
#include <vector>

namespace bmfr {

/// Where an image's pixels are: host memory, or CUDA device memory (a device pointer, for the
/// cuda backend, as engines hand over their G-buffer).
enum class Memory { Host, Cuda };

/// Read-only view of an interleaved float image, rows top to bottom: pixel (x, y), channel c is
/// data[y * rowStride + x * channels + c]. Colour buffers take 3 or 4 channels (RGBA, as engines
/// hand them over; the fourth is ignored).
struct ImageView {
    const float* data = nullptr;
    int width = 0;
    int height = 0;
    int channels = 3;
    /// Floats between the starts of two rows; 0 = packed (width * channels).
    long rowStride = 0;
    Memory memory = Memory::Host; ///< where `data` points; every buffer of a frame alike
    long stride() const { return rowStride ? rowStride : long(width) * channels; }
    /// True when the pixels are packed RGB: what the filters read without a copy.
    bool packedRgb() const { return channels == 3 && stride() == long(width) * 3; }
};

/// A caller's image that a filter writes its output into (same layout rules as ImageView; with
/// 4 channels the fourth is left as it was).
struct MutableImageView {
    float* data = nullptr;
    int width = 0;
    int height = 0;
    int channels = 3;
    long rowStride = 0;           ///< floats between rows; 0 = packed
    Memory memory = Memory::Host; ///< where `data` points
    long stride() const { return rowStride ? rowStride : long(width) * channels; }
};

/// A 4x4 matrix, row-major, acting on column vectors: clip = m * [x y z 1]^T.
/// NDC x grows to the right and NDC y grows downwards (row index), both in [-1, 1].
struct Mat4 {
    float m[4][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};
};

/// One frame of input. All images share one size; colour is linear RGB radiance.
struct FrameInput {
    ImageView color;    ///< noisy 1-spp colour, 3 or 4 channels (demodulated if settings say so)
    ImageView albedo;   ///< first-hit albedo, 3 or 4 channels, [0, 1]
    ImageView normal;   ///< first-hit shading normal, world space, unit length, 3 or 4 channels
    ImageView position; ///< first-hit world position, scene units, 3 or 4 channels
    /// Optional noise-free radiance emitted at the first hit (visible lights, sky), 3 or 4
    /// channels. When given it is taken out before filtering and added back before TAA, so emitters
    /// keep sharp edges and do not bleed into their blocks. Leave data null when unavailable.
    ImageView emission;
    /// Optional 1-channel mask, > 0.5 where this frame has a sample (fewer than 1 spp). SVGF
    /// keeps the history of unsampled pixels; BMFR ignores the mask. Leave data null for 1 spp.
    ImageView sampleMask;
    std::vector<ImageView> extras; ///< optional 1-channel feature buffers (BMFR's Feature::Extra)
    /// Optional noise-free visibility of the key light (a sun, a shadow-mapped main light) at
    /// the first hit, times the cosine: max(0, n . l) where the light is unshadowed, else 0;
    /// [0, 1], 1 channel. With BmfrSettings::visibilityFeature, BMFR fits it as one more
    /// feature, so a hard shadow edge across a block does not block up; with visibilityTaps no
    /// history crosses its edges. Leave data null when unavailable.
    ImageView visibility;
    /// Optional motion vectors, 2 to 4 channels: for pixel (x, y), the
    /// continuous pixel coordinate of the same surface point in the previous frame is
    /// (x + motion.x, y + motion.y), in pixels, x to the right and y downwards, where integer
    /// coordinates are the previous frame's sample positions. Both frames' jitter is therefore
    /// included: an engine's unjittered vector mv (previous minus current screen position, in
    /// pixels) becomes mv + jitter - previous jitter. With motion, every filter reprojects through
    /// it instead of the camera, so moving objects keep their history. A third channel, when
    /// present, is the depth offset: the surface's view depth in the previous frame minus its
    /// view depth in this one, scene units (WALR's depth test reads it; without it WALR projects
    /// the point with the previous camera). Leave data null to reproject by the cameras (static
    /// scenes).
    ImageView motion;
    /// Optional world position of this pixel's surface point in the previous frame, 3 or 4
    /// channels, scene units. The history discard test compares it with the previous frame's
    /// positions; without it the current position is compared (right for static surfaces only).
    /// Given without `motion`, the previous pixel is found by projecting it with the previous
    /// camera.
    ImageView previousPosition;
    /// Optional shading normal of this pixel's surface in the previous frame, 3 or 4 channels,
    /// unit length; compared with the previous frame's normals (else the current normal is).
    ImageView previousNormal;
    /// Optional diffuse indirect light at the first hit divided by the albedo, 3 or 4 channels,
    /// from the same sample as `color` (colour = albedo * diffuseIndirect + the rest). Needed
    /// only by WALR's `signal=diffuse-indirect`, the paper's own use, which filters this alone
    /// and adds the rest back unfiltered.
    ImageView diffuseIndirect;
    /// Optional buffers of Mara et al. 2017's BRDF factorisation (`bmfr render --paths mara`
    /// writes them; the mara2017 filter reads them, every other filter ignores them).
    /// matteIndirect: M, the mean indirect radiance arriving at the first hit over
    /// cosine-sampled directions, without albedo or Fresnel, 3 or 4 channels.
    ImageView matteIndirect;
    /// glossyIndirect: G, the GGX-sampled indirect light with the microfacet term g inside and
    /// the Fresnel factor outside, 3 or 4 channels.
    ImageView glossyIndirect;
    /// directLight: the direct light reflected at the first hit (not filtered, assumed noise
    /// free), without emission, 3 or 4 channels.
    ImageView directLight;
    /// specularF0: the normal-incidence Fresnel reflectance F0, [0, 1], 3 or 4 channels.
    ImageView specularF0;
    /// roughness: perceptual roughness (GGX alpha = roughness^2), [0, 1], 1 channel.
    ImageView roughness;
    /// glossyHitDistance: distance from the first hit to the glossy path's next hit, scene
    /// units, 1 channel (escaped rays: a scene size or more).
    ImageView glossyHitDistance;
    Mat4 viewProjection; ///< this frame's world-to-clip matrix
    /// Sub-pixel offset of this frame's primary rays from the pixel centre, pixels, [-0.5, 0.5].
    float jitter[2] = {0.0f, 0.0f};
    bool reset = false; ///< camera cut: drop all history before this frame
    /// With the buffers in CUDA device memory (Memory::Cuda): the cudaStream_t to run on, or
    /// null for the filter's own stream. On the caller's stream the filter never waits for the
    /// GPU: the output view (device memory) is ready when the stream reaches that point, and
    /// lastStats() then holds the times and counts of the latest earlier frame that had
    /// finished when this one was queued. The stream must still exist when the filter's next
    /// frame is given (the filter orders that frame after the work queued on it). Ignored for
    /// host buffers.
    void* cudaStream = nullptr;
};

/// Per-stage wall time of the last frame, milliseconds; each filter names its own stages.
struct StageTimes {
    static constexpr int kMaxStages = 12;
    const char* name[kMaxStages] = {};
    double ms[kMaxStages] = {};
    int count = 0;
    double total = 0;
    void clear() {
        count = 0;
        total = 0;
    }
    void add(const char* stage, double value) {
        if (count < kMaxStages) {
            name[count] = stage;
            ms[count++] = value;
        }
        total += value;
    }
};

/// Facts about the last frame.
struct FrameStats {
    StageTimes times;
    int64_t nonFiniteInputs = 0; ///< NaN/Inf input values replaced by 0 (or by the fallback)
    int64_t discardedPixels = 0; ///< pixels whose whole history was rejected (frame > 0)
};

} // namespace bmfr
