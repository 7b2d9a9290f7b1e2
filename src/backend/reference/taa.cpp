#include "backend/reference/reference_passes.h"
#include "core/color.h"
#include "core/reprojection.h"
#include <cstring>

namespace bmfr::reference {

void temporalAntiAliasing(ThreadPool& pool, const float* current, const float* hist,
                          const float* previousPixel, float* ycocg, float* out, int w, int h,
                          float alpha, bool enabled) {
    if (!enabled) {
        std::memcpy(out, current, size_t(w) * size_t(h) * 3 * sizeof(float));
        return;
    }
    // Each pixel's YCoCg once, instead of nine times in its neighbours' clamps.
    pool.parallelFor(h, 8, [&](long y0, long y1) {
        for (long i = y0 * w; i < y1 * w; ++i) store3(ycocg, i, rgbToYCoCg(load3(current, i)));
    });
    pool.parallelFor(h, 4, [&](long y0, long y1) {
        const float inf = INFINITY;
        for (long y = y0; y < y1; ++y) {
            for (int x = 0; x < w; ++x) {
                const long i = y * w + x;
                const Vec3 c = load3(current, i);
                Vec2 pp{previousPixel[2 * i], previousPixel[2 * i + 1]};
                BilinearFootprint fp = bilinearFootprint(pp);
                if (fp.x0 < -1 || fp.y0 < -1 || fp.x0 >= w || fp.y0 >= h) {
                    store3(out, i, c);
                    continue;
                }
                // Clamp box: mean of the 3x3 box and the 5-tap cross bounds, in YCoCg.
                Vec3 boxLo{inf, inf, inf}, boxHi{-inf, -inf, -inf}, crossLo = boxLo,
                                                                    crossHi = boxHi;
                const bool interior = x > 0 && y > 0 && x + 1 < w && y + 1 < h;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        const int sx = x + dx;
                        const long sy = y + dy;
                        if (!interior && (sx < 0 || sy < 0 || sx >= w || sy >= h)) continue;
                        const Vec3 v = load3(ycocg, sy * w + sx);
                        boxLo = vmin(boxLo, v), boxHi = vmax(boxHi, v);
                        if (dx == 0 || dy == 0)
                            crossLo = vmin(crossLo, v), crossHi = vmax(crossHi, v);
                    }
                // Bilinear history, renormalised at the image border.
                Vec3 old{};
                float total = 0.0f;
                for (int t = 0; t < 4; ++t) {
                    const int tx = tapX(fp, t), ty = tapY(fp, t);
                    if (tx < 0 || ty < 0 || tx >= w || ty >= h) continue;
                    old += fp.weight[t] * load3(hist, long(ty) * w + tx);
                    total += fp.weight[t];
                }
                if (total > 0.0f) old = old / total;
                Vec3 lo = 0.5f * (boxLo + crossLo), hi = 0.5f * (boxHi + crossHi);
                Vec3 clamped = yCoCgToRgb(clamp(rgbToYCoCg(old), lo, hi));
                store3(out, i, lerp(clamped, c, alpha));
            }
        }
    });
}

} // namespace bmfr::reference
