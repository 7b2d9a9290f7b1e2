// Every image buffer of a frame, written once: its FrameInput (and FrameData, InputPlanes)
// member, its name in sequence files, --channel and Python, the channels it takes, whether a
// frame needs it, and the channels the passes read. The frame checks, the staging, the sequence
// readers and writers, the Python keywords, bench and --channel's help all read this list.
#pragma once
#include <bmfr/frame.h>
#include <cstddef>

namespace bmfr {

/// Channels a buffer may have: [lo, hi].
struct ChannelRange {
    int lo, hi;
};
inline constexpr ChannelRange kRgb{3, 4}, kScalar{1, 1}, kMotion{2, 4};

// X(member, file name, accepted channels, staged channels, required, a motion input)
// A motion input is what `--no-motion` drops: the frame is then reprojected by the cameras.
#define BMFR_FRAME_BUFFERS(X)                                                                      \
    X(color, "color", kRgb, 3, true, false)                                                        \
    X(albedo, "albedo", kRgb, 3, true, false)                                                      \
    X(normal, "normal", kRgb, 3, true, false)                                                      \
    X(position, "position", kRgb, 3, true, false)                                                  \
    X(emission, "emission", kRgb, 3, false, false)                                                 \
    X(sampleMask, "sample_mask", kScalar, 1, false, false)                                         \
    X(motion, "motion", kMotion, 2, false, true)                                                   \
    X(previousPosition, "previous_position", kRgb, 3, false, true)                                 \
    X(previousNormal, "previous_normal", kRgb, 3, false, true)                                     \
    X(diffuseIndirect, "diffuse_indirect", kRgb, 3, false, false)                                  \
    X(matteIndirect, "matte_indirect", kRgb, 3, false, false)                                      \
    X(glossyIndirect, "glossy_indirect", kRgb, 3, false, false)                                    \
    X(directLight, "direct_light", kRgb, 3, false, false)                                          \
    X(specularF0, "specular_f0", kRgb, 3, false, false)                                            \
    X(roughness, "roughness", kScalar, 1, false, false)                                            \
    X(glossyHitDistance, "glossy_hit_distance", kScalar, 1, false, false)                          \
    X(visibility, "visibility", kScalar, 1, false, false)

/// A FrameInput member. An alias, because nvcc's front end rewrites the plain declaration with
/// parentheses that the host compiler then warns about.
using FrameMember = ImageView FrameInput::*;

/// One row of BMFR_FRAME_BUFFERS.
struct FrameBuffer {
    const char* member; ///< FrameInput's member: "previousPosition"
    const char* file;   ///< in sequence.json, file names, --channel and Python: "previous_position"
    FrameMember view;
    ChannelRange channels; ///< what the frame checks accept
    int staged;            ///< channels the passes read, from the first
    bool required;
    bool motionInput; ///< dropped with --no-motion
};

#define BMFR_FRAME_BUFFER_ROW(m, file, channels, staged, required, motion)                         \
    FrameBuffer{#m, file, &FrameInput::m, channels, staged, required, motion},
inline constexpr FrameBuffer kFrameBuffers[] = {BMFR_FRAME_BUFFERS(BMFR_FRAME_BUFFER_ROW)};
#undef BMFR_FRAME_BUFFER_ROW
inline constexpr int kFrameBufferCount = int(sizeof(kFrameBuffers) / sizeof(kFrameBuffers[0]));

} // namespace bmfr
