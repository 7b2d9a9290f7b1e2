// The smallest use of the library: only include/ and the bmfr library target (no renderer, no
// image I/O). Denoises a synthetic 64x32 frame of a flat wall and checks the result is finite.
#include <bmfr/bmfr.hpp>
#include <cmath>
#include <cstdio>
#include <vector>

int main() {
    const int w = 64, h = 32;
    std::vector<float> color(w * h * 3), albedo(w * h * 3, 0.5f), normal(w * h * 3),
        position(w * h * 3);
    for (int i = 0; i < w * h; ++i) {
        color[3 * i] = color[3 * i + 1] = color[3 * i + 2] = float((i * 7919) % 13) / 13.0f;
        normal[3 * i + 2] = 1.0f;                  // the wall faces the camera
        position[3 * i] = float(i % w) / w - 0.5f; // x in [-0.5, 0.5), y likewise, z = -2
        position[3 * i + 1] = float(i / w) / h - 0.5f;
        position[3 * i + 2] = -2.0f;
    }
    bmfr::FrameInput in;
    in.color = {color.data(), w, h, 3};
    in.albedo = {albedo.data(), w, h, 3};
    in.normal = {normal.data(), w, h, 3};
    in.position = {position.data(), w, h, 3};
    // A perspective camera at the origin looking down -z (clip w = -z).
    in.viewProjection.m[2][2] = -1.0f;
    in.viewProjection.m[2][3] = -0.2f;
    in.viewProjection.m[3][2] = -1.0f;
    in.viewProjection.m[3][3] = 0.0f;
    try {
        bmfr::BmfrDenoiser denoiser;
        const bmfr::ImageView out = denoiser.denoise(in);
        for (int i = 0; i < w * h * 3; ++i)
            if (!std::isfinite(out.data[i])) return 2;
        std::printf("denoised %dx%d in %.2f ms\n", out.width, out.height,
                    denoiser.lastStats().times.total);
    } catch (const bmfr::Error& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return 0;
}
