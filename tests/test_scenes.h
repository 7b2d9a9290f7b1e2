// Small hand-built frames for tests: a pinhole camera and planes at known depths.
#pragma once
#include "core/mat4.h"
#include "io/sequence.h"

namespace bmfr::test {

/// Camera at `eye` looking down -z, 90 degree vertical field of view.
inline Mat4 cameraAt(Vec3 eye, int w, int h) {
    return multiply(perspectiveYDown(1.5707963f, float(w) / float(h), 0.1f, 100.0f),
                    lookAt(eye, eye + Vec3{0, 0, -1}, {0, 1, 0}));
}

/// A frame seeing, through pixel centres (+jitter), a plane at z = depthAt(x, y) per pixel,
/// facing +z, with uniform colour and albedo 1.
template <typename DepthFn>
FrameData planeFrame(const Mat4& vp, int w, int h, Vec3 color, DepthFn depthAt) {
    FrameData f;
    f.viewProjection = vp;
    for (ImageF* img : {&f.color, &f.albedo, &f.normal, &f.position}) img->resize(w, h, 3);
    Mat4 inv;
    invert(vp, inv);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float sx = (x + 0.5f) / w * 2 - 1, sy = (y + 0.5f) / h * 2 - 1;
            Vec4 a = transformPoint(inv, {sx, sy, -1}), b = transformPoint(inv, {sx, sy, 1});
            Vec3 pa{a.x / a.w, a.y / a.w, a.z / a.w}, pb{b.x / b.w, b.y / b.w, b.z / b.w};
            float z = depthAt(x, y);
            float t = (z - pa.z) / (pb.z - pa.z);
            long i = long(y) * w + x;
            store3(f.position.data(), i, pa + t * (pb - pa));
            store3(f.normal.data(), i, {0, 0, 1});
            store3(f.color.data(), i, color);
            store3(f.albedo.data(), i, {1, 1, 1});
        }
    return f;
}

} // namespace bmfr::test
