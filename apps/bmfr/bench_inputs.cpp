#include "bench_inputs.h"
#include "core/vec.h"
#include "temporal/frame_buffers.h"
#include "usage.h"
#include <algorithm>

namespace bmfr::app {

std::unique_ptr<Filter> makeFromCommandLine(const std::string& name, const SettingValues& values) {
    try {
        return makeFilter(name, values);
    } catch (const SettingError& e) {
        throw UsageError(describeForCli(e, name));
    }
}

FrameInput DeviceFrames::add(FrameInput in) {
    std::vector<ImageView*> views;
    for (const FrameBuffer& b : kFrameBuffers) views.push_back(&(in.*b.view));
    for (ImageView& e : in.extras) views.push_back(&e);
    for (ImageView* v : views) {
        if (!v->data) continue;
        copies_.push_back(std::make_unique<cuda::DeviceImageCopy>(*v));
        *v = copies_.back()->view();
    }
    return in;
}

int distinctFrames(int w, int h) {
    const double pixels = double(w) * h;
    return std::clamp(int(24e6 / pixels), 2, 8);
}

void addFactorisation(FrameData& f) {
    const int w = f.color.width, h = f.color.height;
    for (ImageF* img : {&f.matteIndirect, &f.glossyIndirect, &f.directLight, &f.specularF0})
        img->resize(w, h, 3);
    f.roughness.resize(w, h, 1), f.glossyHitDistance.resize(w, h, 1);
    for (long i = 0; i < long(w) * h; ++i) {
        const Vec3 c = load3(f.color.data(), i);
        store3(f.directLight.data(), i, 0.5f * c);
        store3(f.matteIndirect.data(), i, 0.4f * c);
        store3(f.glossyIndirect.data(), i, 0.1f * c);
        store3(f.specularF0.data(), i, {0.04f, 0.04f, 0.04f});
        f.roughness.data()[i] = 0.3f, f.glossyHitDistance.data()[i] = 1.0f;
    }
}

FrameInput withoutFactorisation(FrameInput in) {
    in.matteIndirect = in.glossyIndirect = in.directLight = in.specularF0 = {};
    in.roughness = in.glossyHitDistance = {};
    return in;
}

int cycledFrame(int i, int distinct, bool& back) {
    const int period = 2 * distinct - 2;
    int k = period > 0 ? i % period : 0;
    back = k >= distinct || (k == 0 && i > 0); // frame 0 comes after frame 1
    if (k >= distinct) k = period - k;
    return k;
}

} // namespace bmfr::app
