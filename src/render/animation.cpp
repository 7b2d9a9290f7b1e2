#include "render/animation.h"
#include <algorithm>
#include <bmfr/error.h>
#include <cmath>
#include <functional>

namespace bmfr::render {

namespace {

Quat multiply(Quat a, Quat b) {
    return {a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
            a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
            a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w,
            a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z};
}

Quat axisAngle(Vec3 axis, float radians) {
    const float s = std::sin(0.5f * radians);
    return {axis.x * s, axis.y * s, axis.z * s, std::cos(0.5f * radians)};
}

Mat4 rotationMatrix(Quat q) {
    const float x = q.x, y = q.y, z = q.z, w = q.w;
    Mat4 m;
    m.m[0][0] = 1 - 2 * (y * y + z * z), m.m[0][1] = 2 * (x * y - z * w),
    m.m[0][2] = 2 * (x * z + y * w);
    m.m[1][0] = 2 * (x * y + z * w), m.m[1][1] = 1 - 2 * (x * x + z * z),
    m.m[1][2] = 2 * (y * z - x * w);
    m.m[2][0] = 2 * (x * z - y * w), m.m[2][1] = 2 * (y * z + x * w),
    m.m[2][2] = 1 - 2 * (x * x + y * y);
    return m;
}

Mat4 translationMatrix(Vec3 t) {
    Mat4 m;
    m.m[0][3] = t.x, m.m[1][3] = t.y, m.m[2][3] = t.z;
    return m;
}

Mat4 scaleMatrix(Vec3 s) {
    Mat4 m;
    m.m[0][0] = s.x, m.m[1][1] = s.y, m.m[2][2] = s.z;
    return m;
}

Vec3 point3(const Mat4& m, Vec3 p) {
    const Vec4 h = transformPoint(m, p);
    return {h.x, h.y, h.z};
}

} // namespace

Quat quatFromEulerDegrees(Vec3 d) {
    const float k = 3.14159265358979f / 180.0f;
    const Quat qx = axisAngle({1, 0, 0}, d.x * k), qy = axisAngle({0, 1, 0}, d.y * k),
               qz = axisAngle({0, 0, 1}, d.z * k);
    return multiply(qz, multiply(qy, qx));
}

Quat slerp(Quat a, Quat b, float t) {
    float c = a.x * b.x + a.y * b.y + a.z * b.z + a.w * b.w;
    if (c < 0) b = {-b.x, -b.y, -b.z, -b.w}, c = -c;
    float wa = 1 - t, wb = t;
    if (c < 0.9995f) {
        const float angle = std::acos(c), s = std::sin(angle);
        wa = std::sin((1 - t) * angle) / s, wb = std::sin(t * angle) / s;
    }
    Quat q{wa * a.x + wb * b.x, wa * a.y + wb * b.y, wa * a.z + wb * b.z, wa * a.w + wb * b.w};
    const float n = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
    return {q.x / n, q.y / n, q.z / n, q.w / n};
}

Mat4 ObjectAnimation::at(float frame) const {
    RigidKey k = keys.front();
    if (frame >= keys.back().frame) {
        k = keys.back();
    } else if (frame > keys.front().frame) {
        const auto next =
            std::upper_bound(keys.begin(), keys.end(), frame,
                             [](float f, const RigidKey& key) { return f < key.frame; });
        const RigidKey &a = *(next - 1), &b = *next;
        const float t = (frame - a.frame) / (b.frame - a.frame);
        k.translation = lerp(a.translation, b.translation, t);
        k.scale = lerp(a.scale, b.scale, t);
        k.rotation = slerp(a.rotation, b.rotation, t);
    }
    return multiply(translationMatrix(k.translation + pivot),
                    multiply(rotationMatrix(k.rotation),
                             multiply(scaleMatrix(k.scale), translationMatrix(-1.0f * pivot))));
}

SceneAnimator::SceneAnimator(const Scene& rest, std::vector<ObjectAnimation> animations,
                             float fileFps)
    : rest_(rest), animations_(std::move(animations)), fileFps_(fileFps),
      animationOf_(rest.objectNames.size(), -1), moves_(rest.objectNames.size(), 0),
      restInverse_(rest.objectNames.size()) {
    if (fileFps_ > 0) {
        if (rest.nodeChannels.empty())
            throw Error("scene description: \"gltf_animation\" asks to play the mesh's "
                        "animations, but it has none");
        // An object moves when a channel targets its node or an ancestor.
        std::vector<char> animatedNode(rest.nodes.size(), 0);
        for (const NodeChannel& c : rest.nodeChannels) animatedNode[size_t(c.node)] = 1;
        const std::vector<Mat4> restWorld = nodeWorlds(-1);
        for (size_t o = 0; o < rest.objectNames.size(); ++o) {
            for (int n = rest.objectNode[o]; n >= 0 && !moves_[o]; n = rest.nodes[size_t(n)].parent)
                moves_[o] = animatedNode[size_t(n)];
            if (moves_[o] && !invert(restWorld[size_t(rest.objectNode[o])], restInverse_[o]))
                throw Error("glTF: the node of object '" + rest.objectNames[o] +
                            "' has a singular transform");
        }
    }
    for (size_t a = 0; a < animations_.size(); ++a) {
        bool found = false;
        for (size_t o = 0; o < rest.objectNames.size(); ++o)
            if (rest.objectNames[o] == animations_[a].object) {
                if (animationOf_[o] >= 0)
                    throw Error("scene description: object '" + animations_[a].object +
                                "' is animated twice");
                animationOf_[o] = int(a), moves_[o] = 1, found = true;
            }
        if (!found) {
            std::vector<std::string> names = rest.objectNames;
            std::sort(names.begin(), names.end());
            names.erase(std::unique(names.begin(), names.end()), names.end());
            std::string list;
            for (size_t i = 0; i < names.size() && i < 40; ++i) list += (i ? ", " : "") + names[i];
            if (names.size() > 40) list += ", ...";
            throw Error("scene description: animation of '" + animations_[a].object +
                        "', but the scene has no such object (objects: " + list + ")");
        }
    }
    animated_ = std::find(moves_.begin(), moves_.end(), char(1)) != moves_.end();
}

std::vector<Mat4> SceneAnimator::nodeWorlds(float seconds) const {
    const size_t n = rest_.nodes.size();
    std::vector<Vec3> t(n), sc(n);
    std::vector<Quat> r(n);
    for (size_t i = 0; i < n; ++i)
        t[i] = rest_.nodes[i].translation, r[i] = rest_.nodes[i].rotation,
        sc[i] = rest_.nodes[i].scale;
    if (seconds >= 0)
        for (const NodeChannel& c : rest_.nodeChannels) {
            // The keys around `seconds`, held outside the range.
            const size_t count = c.times.size();
            size_t k =
                size_t(std::upper_bound(c.times.begin(), c.times.end(), seconds) - c.times.begin());
            size_t a = k == 0 ? 0 : k - 1, b = std::min(k, count - 1);
            float f = a == b ? 0.0f : (seconds - c.times[a]) / (c.times[b] - c.times[a]);
            if (c.step) f = 0.0f;
            const float* va = &c.values[a * (c.path == NodeChannel::Path::Rotation ? 4 : 3)];
            const float* vb = &c.values[b * (c.path == NodeChannel::Path::Rotation ? 4 : 3)];
            const size_t node = size_t(c.node);
            if (c.path == NodeChannel::Path::Rotation)
                r[node] = slerp({va[0], va[1], va[2], va[3]}, {vb[0], vb[1], vb[2], vb[3]}, f);
            else
                (c.path == NodeChannel::Path::Translation ? t : sc)[node] =
                    lerp(Vec3{va[0], va[1], va[2]}, Vec3{vb[0], vb[1], vb[2]}, f);
        }
    std::vector<Mat4> world(n);
    std::vector<char> done(n, 0);
    // Parents before children, whatever the file's order (glTF trees are acyclic).
    std::function<const Mat4&(size_t)> of = [&](size_t i) -> const Mat4& {
        if (done[i]) return world[i];
        Mat4 local;
        if (rest_.nodes[i].hasMatrix) {
            for (int row = 0; row < 4; ++row)
                for (int col = 0; col < 4; ++col)
                    local.m[row][col] = rest_.nodes[i].matrix[col * 4 + row];
        } else {
            local = multiply(translationMatrix(t[i]),
                             multiply(rotationMatrix(r[i]), scaleMatrix(sc[i])));
        }
        const int parent = rest_.nodes[i].parent;
        world[i] = parent >= 0 ? multiply(of(size_t(parent)), local) : local;
        done[i] = 1;
        return world[i];
    };
    for (size_t i = 0; i < n; ++i) of(i);
    return world;
}

std::vector<Mat4> SceneAnimator::objectMatrices(float frame) const {
    std::vector<Mat4> m(rest_.objectNames.size());
    std::vector<Mat4> worlds;
    if (fileFps_ > 0) worlds = nodeWorlds(std::max(0.0f, frame / fileFps_));
    for (size_t o = 0; o < m.size(); ++o) {
        if (fileFps_ > 0 && moves_[o] && rest_.objectNode[o] >= 0)
            m[o] = multiply(worlds[size_t(rest_.objectNode[o])], restInverse_[o]);
        if (animationOf_[o] >= 0)
            m[o] = multiply(animations_[size_t(animationOf_[o])].at(frame), m[o]);
    }
    return m;
}

void SceneAnimator::pose(float frame, Scene& posed) const {
    const std::vector<Mat4> m = objectMatrices(frame);
    std::vector<Mat4> normalMatrix(m.size());
    for (size_t o = 0; o < m.size(); ++o) {
        Mat4 inv;
        if (!invert(m[o], inv))
            throw Error("scene description: the animation of '" + rest_.objectNames[o] +
                        "' is singular at frame " + std::to_string(frame));
        normalMatrix[o] = transpose(inv);
    }
    for (size_t t = 0; t < rest_.triangleCount(); ++t) {
        const int o = rest_.triangleObject[t];
        if (!moves_[size_t(o)]) continue;
        for (size_t v = 3 * t; v < 3 * t + 3; ++v) {
            posed.positions[v] = point3(m[size_t(o)], rest_.positions[v]);
            const Vec3 n = transformVector(normalMatrix[size_t(o)], rest_.normals[v]);
            posed.normals[v] = length(n) > 0 ? normalize(n) : rest_.normals[v];
        }
    }
}

void SceneAnimator::toPrevious(float frame, std::vector<Mat4>& points,
                               std::vector<Mat4>& normals) const {
    const std::vector<Mat4> now = objectMatrices(frame), before = objectMatrices(frame - 1);
    points.assign(now.size(), Mat4{});
    normals.assign(now.size(), Mat4{});
    for (size_t o = 0; o < now.size(); ++o) {
        if (!moves_[o]) continue;
        Mat4 inv, back;
        if (!invert(now[o], inv))
            throw Error("scene description: the animation of '" + rest_.objectNames[o] +
                        "' is singular at frame " + std::to_string(frame));
        points[o] = multiply(before[o], inv);
        if (!invert(points[o], back))
            throw Error("scene description: the animation of '" + rest_.objectNames[o] +
                        "' is singular at frame " + std::to_string(frame - 1));
        normals[o] = transpose(back);
    }
}

} // namespace bmfr::render
