#include "render/sequence_renderer.h"
#include "core/stopwatch.h"
#include "render/frame_renderer.h"
#include <bmfr/error.h>

namespace bmfr::render {

SequenceRenderReport renderSequence(const SceneDescription& d, const SequenceRenderOptions& o,
                                    const std::atomic<bool>* cancel,
                                    const std::function<void(int, int)>& progress,
                                    const std::function<void(const std::string&)>& warn) {
    SequenceRenderReport report;
    Stopwatch clock;
    Scene scene = loadScene(d.mesh);
    for (const std::string& w : scene.warnings) warn(w);
    if (d.roughnessOverride >= 0)
        for (Material& m : scene.materials) m.roughness = d.roughnessOverride;
    report.triangles = scene.triangleCount();

    bool anyEmitter = d.environment.sun.enabled() || !d.quadLights.empty() ||
                      d.environment.sky.x + d.environment.sky.y + d.environment.sky.z > 0;
    for (const Material& m : scene.materials)
        anyEmitter = anyEmitter || m.emission.x + m.emission.y + m.emission.z > 0;
    if (!anyEmitter)
        throw Error("scene '" + d.name +
                    "' has no light: no emissive material, sun, sky or quad light");

    std::vector<CameraKey> keys = d.cameraKeys;
    if (!d.gltfCamera.empty()) {
        const NamedCamera* found = nullptr;
        for (const NamedCamera& c : scene.cameras)
            if (c.name == d.gltfCamera) found = &c;
        if (!found) throw Error("camera '" + d.gltfCamera + "' not found in " + d.mesh);
        CameraKey k;
        k.pose.position = found->position;
        k.pose.target = found->position + found->forward;
        k.pose.up = found->up;
        k.pose.fovY = found->fovY;
        keys = {k};
    }
    const CameraPath path(keys);
    RayAccel accel(scene);
    report.loadSeconds = clock.elapsed() / 1000.0;
    FrameRenderer renderer(scene, accel, d.width, d.height, d.bounces, d.seed);

    // Matrices of all frames up front (the original layout's header lists them all); the
    // renderer's own matrices, so the header matches the frames exactly.
    std::vector<Mat4> matrices;
    std::vector<std::array<float, 2>> jitters;
    for (int i = 0; i < d.frames; ++i) {
        float j[2];
        frameJitter(i, d.jitter, j);
        jitters.push_back({j[0], j[1]});
        matrices.push_back(renderer.viewProjectionOf(path.at(float(i))));
    }
    SequenceInfo info;
    info.width = d.width, info.height = d.height, info.frameCount = d.frames;
    info.hasReference = d.referenceSpp > 0;
    info.positionLimitSquared = 0.01f;
    info.normalLimitSquared = 1.0f;
    info.extraNames = FrameRenderer::extraNames();
    std::unique_ptr<ManifestWriter> manifest;
    std::unique_ptr<BmfrLayoutWriter> original;
    if (o.layout == "manifest")
        manifest = std::make_unique<ManifestWriter>(o.output, info);
    else if (o.layout == "bmfr")
        original = std::make_unique<BmfrLayoutWriter>(o.output, matrices, jitters, 0.01f, 1.0f);
    else
        throw Error("--layout must be manifest or bmfr, got '" + o.layout + "'");

    FrameData frame;
    for (int i = 0; i < d.frames; ++i) {
        if (manifest ? manifest->hasFrame(i) : original->hasFrame(i)) {
            ++report.skipped;
            progress(i + 1, d.frames);
            continue;
        }
        std::vector<QuadLight> quads;
        for (const QuadLightSpec& q : d.quadLights) quads.push_back(q.at(float(i)));
        LightSet lights(scene, quads, d.environment);
        FrameRenderStats stats;
        bool done = renderer.render(i, path.at(float(i)), path.at(float(i - 1)), i > 0, lights,
                                    d.jitter, d.referenceSpp, frame, stats, cancel);
        report.rays += stats.rays;
        if (!done) {
            report.interrupted = true;
            break;
        }
        report.inputSeconds += stats.inputSeconds;
        report.referenceSeconds += stats.referenceSeconds;
        if (manifest)
            manifest->addFrame(i, frame);
        else
            original->addFrame(i, frame);
        ++report.rendered;
        progress(i + 1, d.frames);
        if (cancel && *cancel) {
            report.interrupted = i + 1 < d.frames;
            break;
        }
    }
    return report;
}

} // namespace bmfr::render
