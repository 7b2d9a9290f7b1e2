#include "metrics/basic_metrics.h"
#include "core/color.h"
#include <bmfr/error.h>
#include <cmath>

namespace bmfr {

namespace {

void checkPair(const ImageF& a, const ImageF& b) {
    if (a.width != b.width || a.height != b.height || a.channels != b.channels || a.width == 0)
        throw Error("metric: images differ in size or channels (" + std::to_string(a.width) + "x" +
                    std::to_string(a.height) + "x" + std::to_string(a.channels) + " vs " +
                    std::to_string(b.width) + "x" + std::to_string(b.height) + "x" +
                    std::to_string(b.channels) + ")");
}

template <typename F> double meanOver(const ImageF& a, const ImageF& b, F&& f) {
    checkPair(a, b);
    double s = 0;
    const size_t n = a.pixels.size();
    for (size_t i = 0; i < n; ++i) s += f(a.pixels[i], b.pixels[i]);
    return s / double(n);
}

} // namespace

double rmseToneMapped(const ImageF& a, const ImageF& r) {
    return std::sqrt(meanOver(a, r, [](float x, float y) {
        double d = double(gammaEncode(x)) - gammaEncode(y);
        return d * d;
    }));
}

double rmseLinear(const ImageF& a, const ImageF& r) {
    return std::sqrt(meanOver(a, r, [](float x, float y) {
        double d = double(x) - y;
        return d * d;
    }));
}

double relMseLinear(const ImageF& a, const ImageF& r) {
    return meanOver(a, r, [](float x, float y) {
        double d = double(x) - y;
        return d * d / (double(y) * y + 0.01);
    });
}

double psnr(const ImageF& a, const ImageF& r, double range) {
    double e = rmseLinear(a, r);
    return e > 0 ? 20.0 * std::log10(range / e) : INFINITY;
}

double psnrToneMapped(const ImageF& a, const ImageF& r) {
    double e = rmseToneMapped(a, r);
    return e > 0 ? -20.0 * std::log10(e) : INFINITY;
}

namespace {
/// Tone-mapped luminance of pixel k: the display transform per channel, then Rec. 709 weights.
double displayLuminance(const ImageF& img, long k) {
    return luminance(gammaEncode(load3(img.data(), k)));
}
} // namespace

double temporalError(const ImageF& cur, const ImageF& prev) {
    checkPair(cur, prev);
    if (cur.channels != 3) throw Error("temporal error needs RGB images");
    double s = 0;
    for (long i = 0; i < cur.pixelCount(); ++i)
        s += std::fabs(displayLuminance(cur, i) - displayLuminance(prev, i));
    return s / double(cur.pixelCount());
}

double temporalChangeError(const ImageF& cur, const ImageF& prev, const ImageF& ref,
                           const ImageF& prevRef) {
    checkPair(cur, prev);
    checkPair(cur, ref);
    checkPair(cur, prevRef);
    if (cur.channels != 3) throw Error("temporal change error needs RGB images");
    double s = 0;
    for (long i = 0; i < cur.pixelCount(); ++i)
        s += std::fabs((displayLuminance(cur, i) - displayLuminance(prev, i)) -
                       (displayLuminance(ref, i) - displayLuminance(prevRef, i)));
    return s / double(cur.pixelCount());
}

} // namespace bmfr
