// The cuda backend fed device buffers, as an engine hands over its G-buffer: the same bits as
// from host buffers, on the filter's own stream and on the caller's, and RGBA with padded rows
// giving the packed result. Reported skipped, with the reason, where there is no GPU.
#include "backend/cuda/cuda_device.h"
#include "needs_gpu.h"
#include "synth/procedural_scene.h"
#include <bmfr/bmfr.hpp>
#include <cstring>
#include <gtest/gtest.h>
#include <memory>
#include <vector>

namespace bmfr {
namespace {

std::vector<FrameData> frames(int w, int h, int n) {
    ProceduralSceneOptions o;
    o.width = w, o.height = h, o.frames = n, o.objectSpeed = 1.0f, o.motionVectors = true;
    ProceduralScene scene(o);
    std::vector<FrameData> out(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) scene.render(i, out[size_t(i)]);
    return out;
}

/// A frame's buffers copied to the device, optionally as RGBA with `pad` floats after each row.
struct OnDevice {
    std::vector<std::vector<float>> hostCopies;
    std::vector<std::unique_ptr<cuda::DeviceImageCopy>> copies;
    FrameInput input;
    OnDevice(const FrameInput& host, bool rgba, int pad) : input(host) {
        std::vector<ImageView*> all = {
            &input.color,          &input.albedo,           &input.normal,
            &input.position,       &input.emission,         &input.sampleMask,
            &input.visibility,     &input.motion,           &input.previousPosition,
            &input.previousNormal, &input.diffuseIndirect,  &input.matteIndirect,
            &input.glossyIndirect, &input.directLight,      &input.specularF0,
            &input.roughness,      &input.glossyHitDistance};
        for (ImageView& e : input.extras) all.push_back(&e);
        // Every buffer the frame has: a frame's buffers must all be in one memory.
        for (ImageView* v : all) {
            if (!v->data) continue;
            ImageView src = *v;
            if (rgba && v->channels == 3) {
                const long stride = long(v->width) * 4 + pad;
                std::vector<float>& c = hostCopies.emplace_back(size_t(stride) * v->height, 7.0f);
                for (long i = 0; i < long(v->width) * v->height; ++i)
                    std::memcpy(&c[size_t((i / v->width) * stride + (i % v->width) * 4)],
                                v->data + 3 * i, 3 * sizeof(float));
                src = ImageView{c.data(), v->width, v->height, 4, stride};
            }
            copies.push_back(std::make_unique<cuda::DeviceImageCopy>(src));
            *v = copies.back()->view();
        }
    }
};

std::vector<float> toHost(const ImageView& result, void* stream) {
    const ImageView host =
        result.memory == Memory::Cuda ? cuda::downloadRgb(result, stream) : result;
    return std::vector<float>(host.data, host.data + size_t(host.width) * host.height * 3);
}

using CudaDeviceBuffers = test::NeedsGpu;

TEST_F(CudaDeviceBuffers, SameBitsAsHostBuffersOnEitherStream) {
    const std::vector<FrameData> seq = frames(61, 37, 6);
    for (const char* name : {"bmfr", "svgf", "walr", "mara2017"}) {
        SCOPED_TRACE(name);
        auto host = makeFilter(name, {{"backend", "cuda"}});
        auto own = makeFilter(name, {{"backend", "cuda"}});
        auto caller = makeFilter(name, {{"backend", "cuda"}});
        auto rgba = makeFilter(name, {{"backend", "cuda"}});
        const cuda::CallerStream stream;
        for (size_t i = 0; i < seq.size(); ++i) {
            const FrameInput in = seq[i].input();
            const std::vector<float> a = toHost(host->denoise(in), nullptr);
            OnDevice d(in, false, 0), padded(in, true, 5);
            const ImageView ownView = own->denoise(d.input);
            EXPECT_EQ(ownView.memory, Memory::Cuda);
            const std::vector<float> b = toHost(ownView, nullptr);
            d.input.cudaStream = stream.get();
            const std::vector<float> c = toHost(caller->denoise(d.input), stream.get());
            const std::vector<float> e = toHost(rgba->denoise(padded.input), nullptr);
            EXPECT_EQ(a, b) << "own stream, frame " << i;
            EXPECT_EQ(a, c) << "caller's stream, frame " << i;
            EXPECT_EQ(a, e) << "RGBA with padded rows, frame " << i;
            EXPECT_EQ(own->lastStats().nonFiniteInputs, host->lastStats().nonFiniteInputs);
        }
    }
}

} // namespace
} // namespace bmfr
