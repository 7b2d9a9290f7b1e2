#include "render/sequence_renderer.h"
#include "core/mat4.h"
#include "core/stopwatch.h"
#include "io/atomic_file.h"
#include "io/output_folder.h"
#include "render/frame_renderer.h"
#include <bmfr/error.h>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <nlohmann/json.hpp>

namespace bmfr::render {

namespace {

namespace fs = std::filesystem;

void add(std::string& s, Vec3 v) {
    s += fmt::format("{},{},{};", v.x, v.y, v.z);
}

/// True when `dir` holds nothing but locks and other writers' half-written fingerprint files:
/// the parts of one render, started at once, each find the folder so.
bool onlyClaimsUnderWay(const std::string& dir) {
    const std::string half = std::string(kRenderFingerprintFile) + ".";
    std::error_code ec;
    for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
        const std::string name = e.path().filename().string();
        const bool lock = name.rfind(kOutputLockFile, 0) == 0;
        const bool claim = name.rfind(half, 0) == 0 && e.path().extension() == ".part";
        if (!lock && !claim) return false;
    }
    return true;
}

/// Claims `dir` for this render, or refuses it. Returns false when the finished frames must be
/// rendered again (a new or overwritten folder).
bool claimFolder(const std::string& dir, const std::string& fingerprint, bool overwrite,
                 const nlohmann::json& about) {
    const fs::path marker = fs::path(dir) / kRenderFingerprintFile;
    std::error_code ec;
    const bool empty = !fs::exists(dir, ec) || onlyClaimsUnderWay(dir);
    if (fs::exists(marker, ec)) {
        std::ifstream in(marker);
        std::string found;
        try {
            found = nlohmann::json::parse(in).at("fingerprint").get<std::string>();
        } catch (const std::exception&) {
        }
        if (found == fingerprint) return true;
        if (!overwrite)
            throw Error(dir + " holds a sequence of another scene, settings or layout (its " +
                        kRenderFingerprintFile +
                        " differs); refusing to mix them. Use another folder, or --overwrite to "
                        "replace it");
    } else if (!empty && !overwrite) {
        throw Error(dir + " is not empty and was not rendered by bmfr render (no " +
                    kRenderFingerprintFile +
                    "); refusing to write into it. Use another folder, or --overwrite");
    }
    fs::create_directories(dir);
    if (!empty) { // a replaced sequence's frame list, whole and in parts
        fs::remove_all(fs::path(dir) / kFramePartsFolder, ec);
        fs::remove(fs::path(dir) / "sequence.json", ec);
    }
    nlohmann::json record = about;
    record["fingerprint"] = fingerprint;
    writeFileAtomically(marker.string(), record.dump(1) + "\n");
    return false;
}

} // namespace

std::string renderFingerprint(const SceneDescription& d, const std::string& layout) {
    std::string s = layout + ";" + d.mesh + ";";
    std::error_code ec;
    if (d.mesh.rfind("builtin:", 0) != 0 && fs::exists(d.mesh, ec))
        s += fmt::format("{};{};", fs::file_size(d.mesh, ec),
                         fs::last_write_time(d.mesh, ec).time_since_epoch().count());
    s += fmt::format("{}x{};{};{};{};{};{};", d.width, d.height, d.referenceSpp, d.bounces, d.seed,
                     d.jitter, d.roughnessOverride);
    if (d.diffuseIndirectOnly) s += "diffuse-indirect;";
    if (d.factoredDirectSpp > 0) s += fmt::format("mara:{};", d.factoredDirectSpp);
    add(s, d.environment.sky);
    add(s, d.environment.sun.direction);
    add(s, d.environment.sun.irradiance);
    s += fmt::format("{};", d.environment.sun.angularDiameter);
    for (const QuadLightSpec& q : d.quadLights) {
        for (Vec3 v : {q.centre, q.edgeU, q.edgeV, q.radiance}) add(s, v);
        for (const auto& [frame, centre] : q.path) {
            s += fmt::format("{}:", frame);
            add(s, centre);
        }
    }
    for (const CameraKey& k : d.cameraKeys) {
        s += fmt::format("{}:{}:", k.frame, k.pose.fovY);
        for (Vec3 v : {k.pose.position, k.pose.target, k.pose.up}) add(s, v);
    }
    s += d.gltfCamera;
    for (const std::string& o : d.hiddenObjects) s += "hide:" + o + ";";
    if (d.lightSampling == LightSampling::Split) s += "split-lights;";
    if (d.gltfAnimationFps > 0) s += fmt::format("gltf@{};", d.gltfAnimationFps);
    for (const ObjectAnimation& a : d.animations) {
        s += a.object + ":";
        add(s, a.pivot);
        for (const RigidKey& k : a.keys) {
            s += fmt::format("{}:{},{},{},{}:", k.frame, k.rotation.x, k.rotation.y, k.rotation.z,
                             k.rotation.w);
            add(s, k.translation);
            add(s, k.scale);
        }
    }
    uint64_t h = 1469598103934665603ull; // FNV-1a
    for (unsigned char c : s) h = (h ^ c) * 1099511628211ull;
    return fmt::format("{:016x}", h);
}

SequenceRenderReport renderSequence(const SceneDescription& d, const SequenceRenderOptions& o,
                                    const std::atomic<bool>* cancel,
                                    const std::function<void(int, int)>& progress,
                                    const std::function<void(const std::string&)>& warn) {
    SequenceRenderReport report;
    Stopwatch clock;
    Scene scene = loadScene(d.mesh);
    for (const std::string& w : scene.warnings) warn(w);
    scene.removeObjects(d.hiddenObjects);
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
    const SceneAnimator animator(scene, d.animations, d.gltfAnimationFps);
    RayAccel accel(scene);
    report.loadSeconds = clock.elapsed() / 1000.0;
    FrameRenderer renderer(scene, accel, d.width, d.height, d.bounces, d.seed);
    renderer.setDiffuseIndirectOnly(d.diffuseIndirectOnly);
    renderer.setFactoredPaths(d.factoredDirectSpp);
    // Moving objects: each frame traces its own posed copy, with its own BVH.
    Scene posed;
    if (animator.animated()) posed = scene;
    std::unique_ptr<RayAccel> posedAccel;
    ObjectMotion objects;

    // Matrices of all frames up front (the original layout's header lists them all); the
    // renderer's own matrices, so the header matches the frames exactly.
    std::vector<Mat4> matrices;
    std::vector<std::array<float, 2>> jitters;
    for (int i = 0; i < d.frames; ++i) {
        float j[2];
        frameJitter(i, d.jitter, j);
        jitters.push_back({j[0], j[1]});
        const CameraPose pose = path.at(float(i));
        const std::string problem = cameraPoseProblem(pose);
        if (!problem.empty())
            throw Error("scene '" + d.name + "': the camera of frame " + std::to_string(i) + " " +
                        problem);
        matrices.push_back(renderer.viewProjectionOf(pose));
        if (!isUsableCameraMatrix(matrices.back()))
            throw Error("scene '" + d.name + "': the camera matrix of frame " + std::to_string(i) +
                        " is not finite or not invertible");
    }
    if (o.layout != "manifest" && o.layout != "bmfr")
        throw Error("--layout must be manifest or bmfr, got '" + o.layout + "'");
    const bool part = o.endFrame >= 0;
    const int first = part ? o.firstFrame : 0;
    const int end = part ? o.endFrame : d.frames;
    if (part && (o.layout != "manifest" || first < 0 || first >= end || end > d.frames))
        throw Error(fmt::format("a part of a sequence is frames [A, B) with 0 <= A < B <= {} in "
                                "the manifest layout; got [{}, {}) in the {} layout",
                                d.frames, first, end, o.layout));
    // What `bmfr eval` reports about the input; the fingerprint alone decides resumption.
    nlohmann::json about{{"scene", d.name},
                         {"mesh", d.mesh},
                         {"reference_spp", d.referenceSpp},
                         {"bounces", d.bounces},
                         {"seed", d.seed},
                         {"jitter", d.jitter},
                         {"paths", d.factoredDirectSpp > 0 ? "mara" : "bmfr"}};
    if (d.factoredDirectSpp > 0) about["direct_spp"] = d.factoredDirectSpp;
    const bool resume = claimFolder(o.output, renderFingerprint(d, o.layout), o.overwrite, about);
    SequenceInfo info;
    info.width = d.width, info.height = d.height, info.frameCount = d.frames;
    info.hasReference = d.referenceSpp > 0;
    info.positionLimitSquared = 0.01f;
    info.normalLimitSquared = 1.0f;
    info.extraNames = FrameRenderer::extraNames();
    std::unique_ptr<ManifestWriter> manifest;
    std::unique_ptr<BmfrLayoutWriter> original;
    if (o.layout == "manifest")
        manifest = std::make_unique<ManifestWriter>(o.output, info, resume, part);
    else
        original = std::make_unique<BmfrLayoutWriter>(o.output, matrices, jitters, 0.01f, 1.0f);

    FrameData frame;
    for (int i = first; i < end; ++i) {
        if ((resume || part) && (manifest ? manifest->hasFrame(i) : original->hasFrame(i))) {
            ++report.skipped;
            progress(i + 1 - first, end - first);
            continue;
        }
        if (animator.animated()) {
            animator.pose(float(i), posed);
            posedAccel = std::make_unique<RayAccel>(posed);
            renderer.setGeometry(posed, *posedAccel);
            animator.toPrevious(float(i), objects.points, objects.normals);
        }
        std::vector<QuadLight> quads;
        for (const QuadLightSpec& q : d.quadLights) quads.push_back(q.at(float(i)));
        LightSet lights(animator.animated() ? posed : scene, quads, d.environment, d.lightSampling);
        FrameRenderStats stats;
        bool done = renderer.render(i, path.at(float(i)), path.at(float(i - 1)), i > 0, lights,
                                    d.jitter, d.referenceSpp, frame, stats, cancel,
                                    animator.animated() ? &objects : nullptr);
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
        progress(i + 1 - first, end - first);
        if (cancel && *cancel) {
            report.interrupted = i + 1 < end;
            break;
        }
    }
    if (original && report.rendered + report.skipped > 0)
        original->finish(); // the header last, for the frames on disk
    if (manifest) {
        report.framesIn = manifest->writeManifestIfComplete();
        report.complete = report.framesIn == d.frames;
    } else {
        report.framesIn = report.rendered + report.skipped;
        report.complete = report.framesIn == d.frames;
    }
    return report;
}

} // namespace bmfr::render
