// The C API (bmfr.h) against the C++ API it wraps: an engine-shaped frame (RGBA16F colour and
// albedo, octahedral normals, view depth, motion in UV units with y up and without the jitter)
// gives the float path's result within a stated tolerance; exact conversions give the same
// bits; the decoders against hand-computed values; errors carry the C++ API's messages.
#include "capi/shared_image.h"
#include "core/half.h"
#include "core/image.h"
#include "core/mat4.h"
#include "core/octahedral.h"
#include "path_traced_box.h"
#include "test_support.h"
#include <algorithm>
#include <bmfr/bmfr.h>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <gtest/gtest.h>

namespace bmfr {
namespace {

/// Errors a device reported through its callback, in order.
struct Reported {
    std::vector<std::pair<BMFRError, std::string>> errors;
};
void record(void* user, BMFRError code, const char* message) {
    static_cast<Reported*>(user)->errors.emplace_back(code, message);
}

/// The frames' buffers as an engine keeps them.
struct EngineFrame {
    std::vector<uint16_t> color, albedo; ///< RGBA16F
    std::vector<float> normal;           ///< octahedral, 2 floats
    std::vector<float> depth;            ///< clip w
    std::vector<uint16_t> motion;        ///< RG16F: UV units, y up, between unjittered positions
};

EngineFrame engineFrame(const FrameData& f, const float previousJitter[2]) {
    const int w = f.color.width, h = f.color.height;
    EngineFrame e;
    e.color.resize(size_t(w) * h * 4);
    e.albedo.resize(size_t(w) * h * 4);
    e.normal.resize(size_t(w) * h * 2);
    e.depth.resize(size_t(w) * h);
    e.motion.resize(size_t(w) * h * 2);
    for (long i = 0; i < long(w) * h; ++i) {
        for (int c = 0; c < 3; ++c) {
            e.color[4 * i + c] = floatToHalfBits(f.color.data()[3 * i + c]);
            e.albedo[4 * i + c] = floatToHalfBits(f.albedo.data()[3 * i + c]);
        }
        e.color[4 * i + 3] = e.albedo[4 * i + 3] = floatToHalfBits(1.0f);
        const float* n = &f.normal.data()[3 * i];
        const Vec2 o = octahedralEncode({n[0], n[1], n[2]});
        e.normal[2 * i] = o.x, e.normal[2 * i + 1] = o.y;
        const float* p = &f.position.data()[3 * i];
        e.depth[i] = transformPoint(f.viewProjection, {p[0], p[1], p[2]}).w;
        const float* m = &f.motion.data()[f.motion.channels * i];
        e.motion[2 * i] = floatToHalfBits((m[0] - (f.jitter[0] - previousJitter[0])) / float(w));
        e.motion[2 * i + 1] =
            floatToHalfBits(-(m[1] - (f.jitter[1] - previousJitter[1])) / float(h));
    }
    return e;
}

/// The renderer's two motion channels, packed (the engine frame has no depth offset either).
ImageF motionXY(const FrameData& f) {
    ImageF m(f.color.width, f.color.height, 2);
    for (long i = 0; i < m.pixelCount(); ++i)
        for (int c = 0; c < 2; ++c)
            m.data()[2 * i + c] = f.motion.data()[f.motion.channels * i + c];
    return m;
}

/// Shares a packed 64x48 image.
void setImage(BMFRFilter filter, const char* name, const void* data, BMFRFormat format) {
    bmfrSetFilterImage(filter, name, const_cast<void*>(data), format, 64, 48, 0, 0, 0);
}

/// The frame's camera: its view-projection and jitter.
void setCamera(BMFRFilter filter, const FrameData& f) {
    bmfrSetFilterMatrix(filter, "viewProjection", &f.viewProjection.m[0][0]);
    bmfrSetFilterFloat(filter, "jitterX", f.jitter[0]);
    bmfrSetFilterFloat(filter, "jitterY", f.jitter[1]);
}

BMFRFilter newFilter(BMFRDevice device, const char* type) {
    BMFRFilter filter = bmfrNewFilter(device, type);
    bmfrSetFilterInt(filter, "maxWidth", 64);
    bmfrSetFilterInt(filter, "maxHeight", 48);
    bmfrCommitFilter(filter);
    return filter;
}

float rmsOf(const std::vector<float>& a) {
    double s = 0;
    for (float v : a) s += double(v) * v;
    return float(std::sqrt(s / double(a.size())));
}

float rmsDifference(const std::vector<float>& a, const std::vector<float>& b) {
    double s = 0;
    for (size_t i = 0; i < a.size(); ++i) s += double(a[i] - b[i]) * (a[i] - b[i]);
    return float(std::sqrt(s / double(a.size())));
}

class CApi : public ::testing::Test {
  protected:
    void SetUp() override {
        device = bmfrNewDevice(BMFR_DEVICE_TYPE_CPU);
        bmfrSetDeviceInt(device, "threads", 2);
        bmfrSetDeviceErrorFunction(device, record, &reported);
        bmfrCommitDevice(device);
        ASSERT_EQ(bmfrGetDeviceError(device, nullptr), BMFR_ERROR_NONE);
    }
    void TearDown() override { bmfrReleaseDevice(device); }
    BMFRDevice device = nullptr;
    Reported reported;
};

const std::vector<FrameData>& boxFrames() {
    static const std::vector<FrameData> frames = test::pathTracedBox(64, 48, 6, 7, 0.05f);
    return frames;
}

TEST_F(CApi, EngineShapedFramesGiveTheFloatResultWithinTolerance) {
    const std::vector<FrameData>& frames = boxFrames();
    for (const char* name : {"bmfr", "svgf", "walr"}) {
        SCOPED_TRACE(name);
        Device cpp(Backend::Cpu, 2);
        auto reference = cpp.makeFilter(name);
        BMFRFilter filter = newFilter(device, name);
        bmfrSetFilterFloat(filter, "motionScaleX", 64.0f);
        bmfrSetFilterFloat(filter, "motionScaleY", 48.0f);
        bmfrSetFilterBool(filter, "motionYUp", true);
        bmfrSetFilterBool(filter, "motionIncludesJitter", false);
        float previousJitter[2] = {0, 0};
        float worst = 0;
        std::vector<uint16_t> out(64 * 48 * 4);
        for (size_t i = 0; i < frames.size(); ++i) {
            const FrameData& f = frames[i];
            FrameInput in;
            in.color = view(f.color), in.albedo = view(f.albedo), in.normal = view(f.normal);
            in.position = view(f.position);
            const ImageF mxy = motionXY(f);
            in.motion = view(mxy);
            in.viewProjection = f.viewProjection;
            in.jitter[0] = f.jitter[0], in.jitter[1] = f.jitter[1];
            const ImageView expected = reference->denoise(in);
            std::vector<float> want(expected.data, expected.data + 64 * 48 * 3);

            const EngineFrame e = engineFrame(f, previousJitter);
            setImage(filter, "color", e.color.data(), BMFR_FORMAT_HALF4);
            setImage(filter, "albedo", e.albedo.data(), BMFR_FORMAT_HALF4);
            setImage(filter, "normal", e.normal.data(), BMFR_FORMAT_FLOAT2);
            setImage(filter, "depth", e.depth.data(), BMFR_FORMAT_FLOAT);
            setImage(filter, "motion", e.motion.data(), BMFR_FORMAT_HALF2);
            setImage(filter, "output", out.data(), BMFR_FORMAT_HALF4);
            setCamera(filter, f);
            bmfrExecuteFilter(filter);
            ASSERT_TRUE(reported.errors.empty()) << reported.errors[0].second;
            previousJitter[0] = f.jitter[0], previousJitter[1] = f.jitter[1];

            std::vector<float> got(64 * 48 * 3);
            for (int p = 0; p < 64 * 48; ++p)
                for (int c = 0; c < 3; ++c) got[3 * p + c] = halfBitsToFloat(out[4 * p + c]);
            // Half colour and albedo, half motion and an octahedral normal round the inputs by
            // about 1e-3 relative; the result moves by about as much (docs/c-api.md).
            const float ratio = rmsDifference(got, want) / rmsOf(want);
            EXPECT_LT(ratio, 0.01f) << "frame " << i;
            worst = std::max(worst, ratio);
        }
        std::printf("%s: the engine-shaped frames' RMS difference is at most %.4f%% of the "
                    "output's RMS\n",
                    name, 100.0 * worst);
        bmfrReleaseFilter(filter);
    }
}

TEST_F(CApi, ExactConversionsGiveTheSameBits) {
    // Inputs that half holds exactly, as HALF4 and as padded FLOAT4 rows, against the C++ API
    // on packed floats: the same bits, every filter.
    const std::vector<FrameData>& frames = boxFrames();
    for (const char* name : {"bmfr", "svgf", "walr", "mara2017"}) {
        SCOPED_TRACE(name);
        Device cpp(Backend::Cpu, 2);
        auto reference = cpp.makeFilter(name);
        BMFRFilter half = newFilter(device, name);
        BMFRFilter padded = newFilter(device, name);
        for (size_t i = 0; i < 3; ++i) {
            FrameData f = frames[i];
            std::vector<uint16_t> h16[3];
            std::vector<float> rows[3];
            ImageF* images[3] = {&f.color, &f.albedo, &f.normal};
            const char* names[3] = {"color", "albedo", "normal"};
            const size_t rowFloats = 64 * 4 + 8; // RGBA and 32 bytes of padding per row
            for (int k = 0; k < 3; ++k) {
                h16[k].assign(64 * 48 * 4, 0);
                rows[k].assign(rowFloats * 48, -1.0f);
                for (int p = 0; p < 64 * 48; ++p)
                    for (int c = 0; c < 3; ++c) {
                        float& v = images[k]->data()[3 * p + c];
                        v = roundToHalf(v);
                        h16[k][4 * p + c] = floatToHalfBits(v);
                        rows[k][size_t(p / 64) * rowFloats + 4 * size_t(p % 64) + c] = v;
                    }
                setImage(half, names[k], h16[k].data(), BMFR_FORMAT_HALF4);
                bmfrSetFilterImage(padded, names[k], rows[k].data(), BMFR_FORMAT_FLOAT3, 64, 48, 0,
                                   16, rowFloats * 4);
            }
            FrameInput in;
            in.color = view(f.color), in.albedo = view(f.albedo), in.normal = view(f.normal);
            in.position = view(f.position);
            in.viewProjection = f.viewProjection;
            in.jitter[0] = f.jitter[0], in.jitter[1] = f.jitter[1];
            const ImageView expected = reference->denoise(in);
            std::vector<float> outs[2];
            BMFRFilter both[2] = {half, padded};
            for (int k = 0; k < 2; ++k) {
                outs[k].assign(64 * 48 * 3, 0.0f);
                setImage(both[k], "position", f.position.data(), BMFR_FORMAT_FLOAT3);
                setImage(both[k], "output", outs[k].data(), BMFR_FORMAT_FLOAT3);
                setCamera(both[k], f);
                bmfrExecuteFilter(both[k]);
                ASSERT_TRUE(reported.errors.empty()) << reported.errors[0].second;
                EXPECT_EQ(std::memcmp(outs[k].data(), expected.data, outs[k].size() * 4), 0)
                    << (k ? "padded FLOAT3" : "HALF4") << ", frame " << i;
            }
        }
        bmfrReleaseFilter(half);
        bmfrReleaseFilter(padded);
    }
}

TEST(CApiDecoders, DepthGivesTheRenderersPositions) {
    // The renderer's own positions, through their clip w and the camera, come back.
    const FrameData& f = boxFrames()[3];
    std::vector<float> depth(64 * 48), buffer;
    for (int p = 0; p < 64 * 48; ++p) {
        const float* x = &f.position.data()[3 * p];
        depth[size_t(p)] = transformPoint(f.viewProjection, {x[0], x[1], x[2]}).w;
    }
    capi::SharedImage image{
        reinterpret_cast<unsigned char*>(depth.data()), BMFR_FORMAT_FLOAT, 64, 48, 4, 64 * 4};
    const ImageView got = capi::positionsFromDepth(image, f.viewProjection, f.jitter, buffer);
    float worst = 0;
    for (int i = 0; i < 64 * 48 * 3; ++i)
        worst = std::max(worst, std::fabs(got.data[i] - f.position.data()[i]));
    EXPECT_LT(worst, 2e-4f); // the box is about 2 units across, 3.4 units away
    Mat4 ortho;              // clip w = 1: depth cannot be the view depth
    EXPECT_NE(testing::errorOf([&] {
                  capi::positionsFromDepth(image, ortho, f.jitter, buffer);
              }).find("orthographic"),
              std::string::npos);
}

TEST(CApiDecoders, OctahedralNormalsAndMotionByHand) {
    // Encoded and decoded normals of every octant and the poles.
    const float normals[][3] = {
        {0, 0, 1}, {0, 0, -1}, {0.6f, 0, 0.8f}, {-0.48f, 0.6f, -0.64f}, {0.36f, -0.48f, -0.8f},
        {-1, 0, 0}};
    std::vector<float> enc, unorm, buffer;
    for (const auto& n : normals) {
        const Vec2 e = octahedralEncode({n[0], n[1], n[2]});
        enc.push_back(e.x), enc.push_back(e.y);
        unorm.push_back(0.5f * e.x + 0.5f), unorm.push_back(0.5f * e.y + 0.5f);
    }
    for (int variant = 0; variant < 2; ++variant) {
        std::vector<float>& data = variant ? unorm : enc;
        capi::SharedImage image{
            reinterpret_cast<unsigned char*>(data.data()), BMFR_FORMAT_FLOAT2, 6, 1, 8, 48};
        const ImageView got = capi::decodeOctahedralNormals(image, variant == 1, buffer);
        for (int i = 0; i < 6; ++i)
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(got.data[3 * i + c], normals[i][c], 1e-6f);
    }
    // (0.25, 0.1) in UV of a 200x100 image, y up, jitter (0.3, -0.2) now and (-0.1, 0.4) before:
    // 50 pixels right, 10 pixels up (y down: -10), plus the jitter's change (0.4, -0.6).
    float mv[3] = {0.25f, 0.1f, -0.5f}, jitter[2] = {0.3f, -0.2f}, previous[2] = {-0.1f, 0.4f};
    capi::SharedImage image{reinterpret_cast<unsigned char*>(mv), BMFR_FORMAT_FLOAT3, 1, 1, 12, 12};
    capi::MotionConvention convention;
    convention.scale[0] = 200, convention.scale[1] = 100;
    convention.yUp = true;
    convention.includesJitter = false;
    const ImageView got = capi::convertMotion(image, convention, jitter, previous, buffer);
    ASSERT_EQ(got.channels, 3);
    EXPECT_FLOAT_EQ(got.data[0], 50.4f);
    EXPECT_FLOAT_EQ(got.data[1], -10.6f);
    EXPECT_FLOAT_EQ(got.data[2], -0.5f); // the depth offset as given
}

TEST_F(CApi, RestartsAndSkippedFramesDropTheHistoryAsAResetDoes) {
    const std::vector<FrameData>& frames = boxFrames();
    Device cpp(Backend::Cpu, 2);
    auto reference = cpp.makeFilter("bmfr");
    BMFRFilter filter = newFilter(device, "bmfr");
    std::vector<float> out(64 * 48 * 3);
    const long indices[] = {10, 11, 12, 14, 15, 16}; // 13 skipped
    for (size_t i = 0; i < frames.size(); ++i) {
        const FrameData& f = frames[i];
        FrameInput in = f.input();
        in.emission = {}, in.motion = {};
        in.reset = i == 2 || i == 3; // a restart at 12, the skip at 14
        const ImageView expected = reference->denoise(in);
        setImage(filter, "color", f.color.data(), BMFR_FORMAT_FLOAT3);
        setImage(filter, "albedo", f.albedo.data(), BMFR_FORMAT_FLOAT3);
        setImage(filter, "normal", f.normal.data(), BMFR_FORMAT_FLOAT3);
        setImage(filter, "position", f.position.data(), BMFR_FORMAT_FLOAT3);
        setImage(filter, "output", out.data(), BMFR_FORMAT_FLOAT3);
        setCamera(filter, f);
        bmfrSetFilterInt(filter, "frameIndex", int(indices[i]));
        if (i == 2) bmfrSetFilterInt(filter, "accumulationMode", BMFR_ACCUMULATION_MODE_RESTART);
        bmfrExecuteFilter(filter);
        ASSERT_TRUE(reported.errors.empty()) << reported.errors[0].second;
        EXPECT_EQ(std::memcmp(out.data(), expected.data, out.size() * 4), 0) << "frame " << i;
        EXPECT_EQ(bmfrGetFilterInt(filter, "accumulationMode"), BMFR_ACCUMULATION_MODE_CONTINUE);
    }
    bmfrReleaseFilter(filter);
}

TEST_F(CApi, ErrorsHaveCodesAndTheCppMessages) {
    const char* message = nullptr;
    // The C++ API's own words for an unknown filter.
    const std::string cppUnknown = testing::errorOf([] { makeFilter("bmfx"); });
    EXPECT_EQ(bmfrNewFilter(device, "bmfx"), nullptr);
    EXPECT_EQ(bmfrGetDeviceError(device, &message), BMFR_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(std::string(message), cppUnknown);
    ASSERT_EQ(reported.errors.size(), 1u);
    EXPECT_EQ(reported.errors[0].first, BMFR_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(reported.errors[0].second, cppUnknown);
    EXPECT_EQ(bmfrGetDeviceError(device, &message), BMFR_ERROR_NONE); // read once
    EXPECT_EQ(message, nullptr);

    BMFRFilter filter = bmfrNewFilter(device, "bmfr");
    bmfrExecuteFilter(filter);
    EXPECT_EQ(bmfrGetDeviceError(device, &message), BMFR_ERROR_INVALID_OPERATION);
    EXPECT_NE(std::string(message).find("bmfrCommitFilter"), std::string::npos);

    bmfrSetFilterInt(filter, "blocksize", 16);
    EXPECT_EQ(bmfrGetDeviceError(device, &message), BMFR_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(message).find("did you mean 'blockSize'"), std::string::npos) << message;
    bmfrSetFilterInt(filter, "blockSize", 7); // out of range: the C++ API's message at commit
    bmfrCommitFilter(filter);
    const std::string cppRange = testing::errorOf([] { makeFilter("bmfr", {{"blockSize", "7"}}); });
    EXPECT_EQ(bmfrGetDeviceError(device, &message), BMFR_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(std::string(message), cppRange);
    bmfrSetFilterInt(filter, "blockSize", 16);
    bmfrCommitFilter(filter);
    EXPECT_EQ(bmfrGetFilterInt(filter, "blockSize"), 16);
    EXPECT_EQ(bmfrGetFilterBool(filter, "taa"), true);

    // A frame with a mismatched albedo: the C++ frame checks' message, and nothing written.
    const FrameData& f = boxFrames()[0];
    std::vector<float> small(32 * 48 * 3, 0.5f), out(64 * 48 * 3, -7.0f);
    setImage(filter, "color", f.color.data(), BMFR_FORMAT_FLOAT3);
    bmfrSetFilterImage(filter, "albedo", small.data(), BMFR_FORMAT_FLOAT3, 32, 48, 0, 0, 0);
    setImage(filter, "normal", f.normal.data(), BMFR_FORMAT_FLOAT3);
    setImage(filter, "depth", f.position.data(), BMFR_FORMAT_HALF2);
    EXPECT_EQ(bmfrGetDeviceError(device, &message), BMFR_ERROR_NONE); // checked at execute
    setImage(filter, "output", out.data(), BMFR_FORMAT_FLOAT3);
    bmfrSetFilterMatrix(filter, "viewProjection", &f.viewProjection.m[0][0]);
    bmfrExecuteFilter(filter);
    EXPECT_EQ(bmfrGetDeviceError(device, &message), BMFR_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(message).find("'depth' is BMFR_FORMAT_HALF2 (2 channels)"),
              std::string::npos)
        << message;
    bmfrUnsetFilterImage(filter, "depth");
    setImage(filter, "position", f.position.data(), BMFR_FORMAT_FLOAT3);
    bmfrExecuteFilter(filter);
    EXPECT_EQ(bmfrGetDeviceError(device, &message), BMFR_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(message).find("albedo"), std::string::npos) << message;
    EXPECT_EQ(out[0], -7.0f);

    bmfrSetFilterImage(filter, "colour", small.data(), BMFR_FORMAT_FLOAT3, 32, 48, 0, 0, 0);
    EXPECT_EQ(bmfrGetDeviceError(device, &message), BMFR_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(message).find("did you mean 'color'"), std::string::npos) << message;
    bmfrSetFilterImage(filter, "color", small.data(), BMFR_FORMAT_FLOAT3, 32, 48, 0, 8, 0);
    EXPECT_EQ(bmfrGetDeviceError(device, &message), BMFR_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(message).find("bytePixelStride 8"), std::string::npos) << message;
    bmfrReleaseFilter(filter);

    // Without a device: the thread's own slot.
    bmfrCommitDevice(nullptr);
    EXPECT_EQ(bmfrGetDeviceError(nullptr, &message), BMFR_ERROR_INVALID_ARGUMENT);
    EXPECT_STREQ(message, "the device handle is NULL");
}

TEST(CApiDevice, ACudaDeviceWithoutAGpuIsUnsupportedHardware) {
    // Without the cuda backend built in, or without a GPU: the same code, the C++ API's message.
    BMFRDevice device = bmfrNewDevice(BMFR_DEVICE_TYPE_CUDA);
    bmfrCommitDevice(device);
    const char* message = nullptr;
    const BMFRError code = bmfrGetDeviceError(device, &message);
    const std::string got = message ? message : "";
    bmfrReleaseDevice(device);
    const std::string cpp = testing::errorOf([] { Device d(Backend::Cuda); });
    if (code == BMFR_ERROR_NONE) GTEST_SKIP() << "this machine has a CUDA device";
    EXPECT_EQ(code, BMFR_ERROR_UNSUPPORTED_HARDWARE);
    EXPECT_EQ(got, cpp);
}

TEST(CApiDevice, OnlyACudaDeviceTakesAGpuBeforeItsCommit) {
    const char* message = nullptr;
    BMFRDevice cpu = bmfrNewDevice(BMFR_DEVICE_TYPE_CPU);
    bmfrSetDeviceInt(cpu, "cudaDevice", 1);
    EXPECT_EQ(bmfrGetDeviceError(cpu, &message), BMFR_ERROR_INVALID_ARGUMENT);
    EXPECT_STREQ(message, "'cudaDevice' is for a BMFR_DEVICE_TYPE_CUDA device");
    EXPECT_EQ(bmfrGetDeviceInt(cpu, "cudaDevice"), 0);
    bmfrReleaseDevice(cpu);

    BMFRDevice gpu = bmfrNewDevice(BMFR_DEVICE_TYPE_CUDA);
    bmfrSetDeviceInt(gpu, "cudaDevice", -1);
    EXPECT_EQ(bmfrGetDeviceError(gpu, &message), BMFR_ERROR_INVALID_ARGUMENT);
    EXPECT_STREQ(message, "cudaDevice -1 is below 0");
    bmfrSetDeviceInt(gpu, "cudaDevice", 1000);
    EXPECT_EQ(bmfrGetDeviceError(gpu, &message), BMFR_ERROR_NONE);
    EXPECT_EQ(bmfrGetDeviceInt(gpu, "cudaDevice"), 1000);
    // No machine has GPU 1000: the commit says so, as the C++ API does.
    bmfrCommitDevice(gpu);
    EXPECT_EQ(bmfrGetDeviceError(gpu, &message), BMFR_ERROR_UNSUPPORTED_HARDWARE);
    const std::string got = message ? message : "";
    EXPECT_EQ(got, testing::errorOf([] { Device d(Backend::Cuda, 0, 1000); }));
    EXPECT_NE(got.find("no CUDA device"), std::string::npos) << got;
    bmfrReleaseDevice(gpu);
}

} // namespace
} // namespace bmfr
