// bmfr::Device: filters made from one device share its threads and nothing else.
#include "test_support.h"
#include <bmfr/bmfr.hpp>
#include <cstring>
#include <gtest/gtest.h>

namespace bmfr {
namespace {

using testing::proceduralFrames;

std::vector<float> pixelsOf(const ImageView& v) {
    return {v.data, v.data + size_t(v.width) * size_t(v.height) * 3};
}

/// Each filter's outputs, frame by frame, when it runs alone on its own threads.
std::vector<std::vector<float>> alone(const std::string& name, const SettingValues& values,
                                      const std::vector<FrameData>& frames) {
    std::unique_ptr<Filter> f = makeFilter(name, values);
    std::vector<std::vector<float>> out;
    for (const FrameData& fd : frames) out.push_back(pixelsOf(f->denoise(fd.input())));
    return out;
}

TEST(Device, TwoFiltersOfOneDeviceDenoisingInTurnGiveTheirOwnBits) {
    const std::vector<FrameData> frames = proceduralFrames(72, 40, 5);
    const SettingValues a = {{"blockSize", "16"}, {"secondGrid", "true"}};
    const SettingValues b = {{"blockSize", "32"}, {"noiseAmplitude", "0.02"}};
    for (const char* backend : {"reference", "cpu"}) {
        SettingValues aAlone = a, bAlone = b;
        aAlone.emplace_back("backend", backend);
        bAlone.emplace_back("backend", backend);
        const std::vector<std::vector<float>> wantA = alone("bmfr", aAlone, frames);
        const std::vector<std::vector<float>> wantB = alone("bmfr", bAlone, frames);
        Device device(parseBackend(backend), 2);
        std::unique_ptr<Filter> fa = device.makeFilter("bmfr", a);
        std::unique_ptr<Filter> fb = device.makeFilter("bmfr", b);
        std::unique_ptr<Filter> fs = device.makeFilter("svgf");
        for (size_t k = 0; k < frames.size(); ++k) {
            EXPECT_EQ(pixelsOf(fa->denoise(frames[k].input())), wantA[k]) << backend << " " << k;
            fs->denoise(frames[frames.size() - 1 - k].input()); // a third filter in between
            EXPECT_EQ(pixelsOf(fb->denoise(frames[k].input())), wantB[k]) << backend << " " << k;
        }
        EXPECT_EQ(device.threadCount(), 2);
    }
}

TEST(Device, TheDevicesBackendAndThreadsAreNotSettings) {
    Device device(Backend::Reference, 1);
    EXPECT_NE(testing::errorOf([&] {
                  device.makeFilter("bmfr", {{"backend", "cpu"}});
              }).find("'backend' is the device's"),
              std::string::npos);
    EXPECT_NE(testing::errorOf([&] {
                  device.makeFilter("svgf", {{"threads", "4"}});
              }).find("'threads' is the device's"),
              std::string::npos);
    BmfrSettings s;
    s.backend = Backend::Cpu;
    EXPECT_EQ(testing::errorOf([&] { BmfrDenoiser d(s, device); }),
              "the bmfr settings say backend cpu, the device is reference");
    EXPECT_NE(testing::errorOf([&] { device.reserve(0, 10); }).find("at least 1x1"),
              std::string::npos);
    EXPECT_EQ(testing::errorOf([&] { device.makeFilter("nlm"); }).find("unknown filter 'nlm'"), 0u);
    std::unique_ptr<Filter> f = device.makeFilter("walr", {{"iterations", "2"}});
    EXPECT_STREQ(f->name(), "walr");
}

} // namespace
} // namespace bmfr
