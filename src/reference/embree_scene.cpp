#include "reference/embree_scene.h"

#include <algorithm>
#include <cmath>
#include <mutex>

#include "core/error.h"
#include "materials.h"
#include "reference/material_sampling.h"

namespace punctual::reference {

// What the device's one error callback saw. Embree may call it from any thread (its builders run
// on TBB workers), hence the mutex. Only the first message is kept: later ones are usually
// consequences of it.
struct EmbreeScene::ErrorLog {
    std::mutex mutex;
    std::string firstMessage;
    bool any = false;

    static void onError(void* user, RTCError code, const char* message) {
        auto* log = static_cast<ErrorLog*>(user);
        const std::lock_guard<std::mutex> lock(log->mutex);
        if (log->any) return;
        log->any = true;
        log->firstMessage = std::string(message ? message : "no message") + " (code " +
                            std::to_string(static_cast<int>(code)) + ")";
    }
};

namespace {

const char* errorName(RTCError code) {
    switch (code) {
        case RTC_ERROR_NONE: return "no error";
        case RTC_ERROR_UNKNOWN: return "unknown error";
        case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
        case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
        case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
        case RTC_ERROR_UNSUPPORTED_CPU: return "unsupported CPU";
        case RTC_ERROR_CANCELLED: return "cancelled";
    }
    return "unrecognised error code";
}

// The smallest coordinate scale rayEpsilonAt uses: 1% of the scene's radius (points near the
// origin still get an offset that suits the scene's size).
float epsilonFloor(const Bounds& bounds) {
    if (bounds.empty()) return 1.0f;
    const float scale = 0.01f * bounds.radius();
    return scale > 0.0f && std::isfinite(scale) ? scale : 1.0f;
}

// The hit's texture coordinates from its barycentrics, as the primary ray's shading does.
bool alphaKept(const EmbreeScene::SurfaceFilter& filter, uint32_t triangle, float u, float v) {
    const Scene& scene = *filter.scene;
    const Mesh& mesh = scene.meshes[scene.objects[filter.object].mesh];
    const Material& material = scene.materials[mesh.material];
    const uint32_t* corner = &scene.indices[mesh.firstIndex + 3 * size_t(triangle)];
    const Vertex& a = scene.vertices[mesh.vertexOffset + corner[0]];
    const Vertex& b = scene.vertices[mesh.vertexOffset + corner[1]];
    const Vertex& c = scene.vertices[mesh.vertexOffset + corner[2]];
    const float w = 1.0f - u - v;
    const float alpha = baseColorAlpha(scene, material, w * a.uv + u * b.uv + v * c.uv, w * a.uv1 + u * b.uv1 + v * c.uv1);
    return gpu::alphaMaskKeeps(alpha, filter.blended ? kTransparentShadowCutoff : material.alphaCutoff);
}

const RayContext& rayContextOf(const RTCFilterFunctionNArguments* args) {
    return *reinterpret_cast<const RayContext*>(args->context);
}

// Embree calls these for every candidate hit on the object's triangles; valid[i] = 0 rejects one
// and the ray goes on.
void intersectFilter(const RTCFilterFunctionNArguments* args) {
    const auto& filter = *static_cast<const EmbreeScene::SurfaceFilter*>(args->geometryUserPtr);
    const RayKind kind = rayContextOf(args).kind;
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        if (filter.blended != (kind == RayKind::TransparentLayers)) {
            args->valid[i] = 0;  // primary rays pass transparent surfaces; layer rays see nothing else
            continue;
        }
        if (filter.singleSided) {
            // As traceSurface decides front and back: Ng points to the CCW side.
            const glm::vec3 ng(RTCHitN_Ng_x(args->hit, args->N, i), RTCHitN_Ng_y(args->hit, args->N, i),
                               RTCHitN_Ng_z(args->hit, args->N, i));
            const glm::vec3 direction(RTCRayN_dir_x(args->ray, args->N, i), RTCRayN_dir_y(args->ray, args->N, i),
                                      RTCRayN_dir_z(args->ray, args->N, i));
            const bool ccwSideSeen = glm::dot(ng, direction) < 0.0f;
            if (ccwSideSeen == filter.mirrored) {
                args->valid[i] = 0;
                continue;
            }
        }
        if (filter.masked && !alphaKept(filter, RTCHitN_primID(args->hit, args->N, i), RTCHitN_u(args->hit, args->N, i),
                                        RTCHitN_v(args->hit, args->N, i)))
            args->valid[i] = 0;
    }
}

void occludedFilter(const RTCFilterFunctionNArguments* args) {
    const auto& filter = *static_cast<const EmbreeScene::SurfaceFilter*>(args->geometryUserPtr);
    const TransparentShadows mode = rayContextOf(args).transparentShadows;
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        if (filter.blended && mode == TransparentShadows::On) continue;
        if (filter.blended && mode == TransparentShadows::Off) {
            args->valid[i] = 0;
            continue;
        }
        // Masked, or transparent clipped or dithered: the alpha test (dither's coverage follows
        // alpha, which its filtered shadow turns dark from 0.5 on).
        if (!alphaKept(filter, RTCHitN_primID(args->hit, args->N, i), RTCHitN_u(args->hit, args->N, i),
                       RTCHitN_v(args->hit, args->N, i)))
            args->valid[i] = 0;
    }
}

}  // namespace

RayContext makeRayContext(RayKind kind, TransparentShadows transparentShadows) {
    RayContext context;
    rtcInitIntersectContext(&context.embree);
    context.kind = kind;
    context.transparentShadows = transparentShadows;
    return context;
}

EmbreeScene::EmbreeScene(const Scene& scene) : errors_(std::make_unique<ErrorLog>()) {
    // rtcNewDevice reports its own failure only through rtcGetDeviceError(nullptr): there is no
    // device yet to hang a callback on.
    RTCDevice device = rtcNewDevice(nullptr);
    if (!device) throw Error("embree", std::string("cannot create a device: ") + errorName(rtcGetDeviceError(nullptr)));
    device_.reset(device);
    rtcSetDeviceErrorFunction(device, &ErrorLog::onError, errors_.get());

    scene_.reset(rtcNewScene(device));
    throwIfError("creating the scene");
    // ROBUST: watertight intersection. Without it a ray through the shared edge of two triangles
    // (the two halves of every box face) can slip between them: a black pixel, or light leaking
    // through a closed occluder, which a ground truth must never show.
    rtcSetSceneFlags(scene_.get(), RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(scene_.get(), RTC_BUILD_QUALITY_HIGH);

    Bounds bounds;
    for (const Object& object : scene.objects) {
        bounds.extend(scene.meshes.at(object.mesh).localBounds.transformed(object.model));
    }
    rayEpsilonFloor_ = epsilonFloor(bounds);

    filters_.reserve(scene.objects.size());
    for (uint32_t i = 0; i < scene.objects.size(); ++i) addObject(scene, i);
    rtcCommitScene(scene_.get());
    throwIfError("building the scene");
}

EmbreeScene::~EmbreeScene() = default;

void EmbreeScene::addObject(const Scene& scene, uint32_t objectIndex) {
    const Object& object = scene.objects[objectIndex];
    const Mesh& mesh = scene.meshes.at(object.mesh);
    if (size_t(mesh.vertexOffset) + mesh.vertexCount > scene.vertices.size() ||
        size_t(mesh.firstIndex) + mesh.indexCount > scene.indices.size() || mesh.indexCount % 3 != 0) {
        throw Error(scene.source, "mesh '" + mesh.name + "' lies outside the scene's vertex or index arrays");
    }
    if (mesh.indexCount == 0 || mesh.vertexCount == 0) return;  // nothing to hit; its geomID stays unused
    RTCGeometry geometry = rtcNewGeometry(device_.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
    throwIfError("creating a triangle geometry");
    // Embree copies into buffers it allocates (and pads for its SIMD loads), so nothing here has
    // to outlive the commit.
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.vertexCount));
    auto* indices = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), mesh.indexCount / 3));
    if (!vertices || !indices) {
        rtcReleaseGeometry(geometry);
        throwIfError("allocating geometry buffers");
        throw Error("embree", "cannot allocate geometry buffers");
    }
    // World space, exactly as the vertex shader computes it: model * vec4(position, 1).
    for (uint32_t v = 0; v < mesh.vertexCount; ++v) {
        const glm::vec4 world = object.model * glm::vec4(scene.vertices[mesh.vertexOffset + v].position, 1.0f);
        vertices[3 * v + 0] = world.x;
        vertices[3 * v + 1] = world.y;
        vertices[3 * v + 2] = world.z;
    }
    for (uint32_t k = 0; k < mesh.indexCount; ++k) {
        const uint32_t index = scene.indices[mesh.firstIndex + k];
        if (index >= mesh.vertexCount) {
            rtcReleaseGeometry(geometry);
            throw Error(scene.source, "mesh '" + mesh.name + "' has an index past its vertices");
        }
        indices[k] = index;
    }
    const Material& material = scene.materials.at(mesh.material);
    SurfaceFilter& filter = filters_.emplace_back();
    filter.scene = &scene;
    filter.object = objectIndex;
    filter.masked = material.alphaMode == AlphaMode::Mask;
    filter.blended = material.alphaMode == AlphaMode::Blend;
    filter.singleSided = !material.doubleSided;
    filter.mirrored = glm::determinant(glm::mat3(object.model)) < 0.0f;
    if (filter.masked || filter.blended || filter.singleSided) {
        rtcSetGeometryUserData(geometry, &filter);
        rtcSetGeometryIntersectFilterFunction(geometry, &intersectFilter);
        if (filter.masked || filter.blended) rtcSetGeometryOccludedFilterFunction(geometry, &occludedFilter);
    }
    rtcCommitGeometry(geometry);
    rtcAttachGeometryByID(scene_.get(), geometry, objectIndex);  // geomID == object index
    rtcReleaseGeometry(geometry);  // the scene holds its own reference
    throwIfError("adding object '" + object.name + "'");
    ++geometryCount_;
}

void EmbreeScene::throwIfError(const std::string& what) const {
    // rtcGetDeviceError also clears the code, so a reported error is not reported twice.
    const RTCError code = rtcGetDeviceError(device_.get());
    std::string message;
    {
        const std::lock_guard<std::mutex> lock(errors_->mutex);
        if (errors_->any) message = errors_->firstMessage;
        errors_->any = false;
        errors_->firstMessage.clear();
    }
    if (message.empty() && code != RTC_ERROR_NONE) message = errorName(code);
    if (!message.empty()) throw Error("embree", what + ": " + message);
}

}  // namespace punctual::reference
