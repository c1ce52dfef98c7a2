#include "reference/reference_renderer.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <mutex>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/error.h"
#include "reference/texture_sampler.h"
#include "shading.h"

namespace punctual::reference {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

void validateSettings(const ReferenceSettings& settings) {
    constexpr uint32_t kMaxDimension = 8192;  // the GPU renderer's limit
    if (settings.width == 0 || settings.height == 0 || settings.width > kMaxDimension ||
        settings.height > kMaxDimension) {
        throw Error("--size", "width and height must be between 1 and " + std::to_string(kMaxDimension));
    }
    if (!(settings.exposure > 0.0f) || !std::isfinite(settings.exposure)) {
        throw Error("--exposure", "must be a finite number > 0");
    }
}

RTCRay makeRay(glm::vec3 origin, glm::vec3 direction, float tfar) {
    RTCRay ray{};
    ray.org_x = origin.x;
    ray.org_y = origin.y;
    ray.org_z = origin.z;
    ray.tnear = 0.0f;
    ray.dir_x = direction.x;
    ray.dir_y = direction.y;
    ray.dir_z = direction.z;
    ray.time = 0.0f;
    ray.tfar = tfar;
    ray.mask = 0xFFFFFFFFu;
    ray.flags = 0;
    return ray;
}

// One shadow ray from `point` towards `direction` over [0, tfar].
//
// The tnear/tfar rule. A ray leaving exactly from a hit point re-hits its own triangle at t ~ 0
// about half the time (the point is rounded to either side of the plane): "shadow acne". So:
//  - the origin is lifted off the surface along the geometric normal on the side the point is
//    seen from, by EmbreeScene::rayEpsilonAt() = 1e-4 x the point's largest coordinate (far above float
//    rounding, far below anything visible), and tnear = 0 from there. Lifting along the
//    geometric normal, not the interpolated one, keeps the origin on the right side of the
//    triangle's plane even where smooth normals tilt;
//  - towards a spot/point light, tfar = distance to the light x (1 - 1e-4): the ray stops just
//    short of the light, so geometry the light sits on (a lamp touching a wall) cannot block it;
//  - towards the directional light, tfar = infinity.
float traceShadowRay(const EmbreeScene& scene, glm::vec3 point, glm::vec3 normal, glm::vec3 direction, float tfar) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray = makeRay(point + normal * scene.rayEpsilonAt(point), direction, tfar);
    rtcOccluded1(scene.handle(), &context, &ray);
    // rtcOccluded1 sets tfar to -inf when anything lies on the ray.
    return ray.tfar < 0.0f ? 0.0f : 1.0f;
}

}  // namespace

float visibility(const EmbreeScene& scene, glm::vec3 point, glm::vec3 normal, const gpu::GpuPunctualLight& light) {
    const glm::vec3 origin = point + normal * scene.rayEpsilonAt(point);
    const glm::vec3 toLight = glm::vec3(light.positionInvRangeSq) - origin;
    const float distance = glm::length(toLight);
    if (!(distance > 0.0f)) return 1.0f;  // the light sits on the lifted point: nothing between
    return traceShadowRay(scene, point, normal, toLight / distance, distance * (1.0f - 1e-4f));
}

float visibility(const EmbreeScene& scene, glm::vec3 point, glm::vec3 normal, const gpu::GpuDirectionalLight& sun) {
    return traceShadowRay(scene, point, normal, glm::normalize(glm::vec3(sun.directionToLight)),
                          std::numeric_limits<float>::infinity());
}

std::array<uint8_t, 4> toneMapToRgba8(glm::vec3 radiance, float exposure) {
    const glm::vec3 display = gpu::linearToSrgb3(gpu::toneMapAces(radiance, exposure));
    auto quantise = [](float c) { return uint8_t(std::round(std::clamp(c, 0.0f, 1.0f) * 255.0f)); };
    return {quantise(display.x), quantise(display.y), quantise(display.z), 255};
}

ReferenceRenderer::ReferenceRenderer(const Scene& scene, const ReferenceSettings& settings)
    : scene_(scene), settings_(settings) {
    validateSettings(settings);
    if (scene.vertices.empty() || scene.indices.empty() || scene.objects.empty()) {
        throw Error(scene.source, "no triangle meshes to draw");
    }
    for (const Mesh& mesh : scene.meshes) {
        if (mesh.material >= scene.materials.size()) throw Error(scene.source, "mesh '" + mesh.name + "' has no material");
    }
    for (const Material& material : scene.materials) {
        if (material.baseColorTexture >= int(scene.textures.size())) {
            throw Error(scene.source, "material '" + material.name + "' names a missing texture");
        }
    }

    const Clock::time_point buildStart = Clock::now();
    embree_ = std::make_unique<EmbreeScene>(scene);
    buildSeconds_ = secondsSince(buildStart);

    for (const Object& object : scene.objects) {
        ObjectShading shading;
        shading.model = object.model;
        // The GPU computes glm::transpose(glm::inverse(model)) as a mat4 and uses its mat3 part.
        shading.normalMatrix = glm::mat3(glm::transpose(glm::inverse(object.model)));
        shading.mirrored = glm::determinant(glm::mat3(object.model)) < 0.0f;
        objects_.push_back(shading);
    }

    // The camera exactly as the GPU renderer sets it up.
    view_ = scene.camera.view;
    projection_ = scene.camera.projection(float(settings.width) / float(settings.height));
    inverseViewProjection_ = glm::inverse(glm::dmat4(projection_) * glm::dmat4(view_));
    cameraPosition_ = scene.camera.position();
    lights_ = setupFrameLights(scene, view_, projection_);
}

ReferenceRenderer::~ReferenceRenderer() = default;

SurfaceHit ReferenceRenderer::traceSurface(uint32_t x, uint32_t y) const {
    // Unproject the pixel centre at depth 1 (near plane) and 0 (far plane) with the inverse of
    // the GPU's view-projection (Vulkan clip space: NDC y points down; reversed depth, see
    // Camera::projection). In double: the far point's w is tiny and a float inverse would bend
    // the ray visibly at 8k pixels.
    const double ndcX = (double(x) + 0.5) / settings_.width * 2.0 - 1.0;
    const double ndcY = (double(y) + 0.5) / settings_.height * 2.0 - 1.0;
    const glm::dvec4 nearH = inverseViewProjection_ * glm::dvec4(ndcX, ndcY, 1.0, 1.0);
    const glm::dvec4 farH = inverseViewProjection_ * glm::dvec4(ndcX, ndcY, 0.0, 1.0);
    const glm::dvec3 nearPoint = glm::dvec3(nearH) / nearH.w;
    const glm::dvec3 farPoint = glm::dvec3(farH) / farH.w;
    const double length = glm::length(farPoint - nearPoint);
    const glm::vec3 direction = glm::vec3((farPoint - nearPoint) / length);

    // The GPU draws what lies between the near and far planes; so does the ray.
    RTCRayHit query{};
    query.ray = makeRay(glm::vec3(nearPoint), direction, float(length));
    query.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    query.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;  // neighbouring pixels, similar rays
    rtcIntersect1(embree_->handle(), &context, &query);

    SurfaceHit hit;
    if (query.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
    hit.hit = true;
    hit.object = query.hit.geomID;
    hit.triangle = query.hit.primID;
    hit.distance = query.ray.tfar;

    const Object& object = scene_.objects[hit.object];
    const Mesh& mesh = scene_.meshes[object.mesh];
    const ObjectShading& shading = objects_[hit.object];
    const uint32_t* triangle = &scene_.indices[mesh.firstIndex + 3 * size_t(hit.triangle)];
    const Vertex& v0 = scene_.vertices[mesh.vertexOffset + triangle[0]];
    const Vertex& v1 = scene_.vertices[mesh.vertexOffset + triangle[1]];
    const Vertex& v2 = scene_.vertices[mesh.vertexOffset + triangle[2]];
    // Embree's barycentrics: attribute = (1 - u - v) a0 + u a1 + v a2. Over a triangle these are
    // exactly the perspective-correct weights the rasteriser interpolates with.
    const float u = query.hit.u;
    const float v = query.hit.v;
    const float w = 1.0f - u - v;
    hit.position = glm::vec3(shading.model * glm::vec4(w * v0.position + u * v1.position + v * v2.position, 1.0f));
    hit.uv = w * v0.uv + u * v1.uv + v * v2.uv;

    // Front or back: Embree's Ng points to the counter-clockwise side of the world-space
    // triangle, so the viewer sees the CCW side when dot(Ng, dir) < 0. A mirrored transform
    // reverses the world winding of the mesh's faces, hence the XOR, exactly like the forward
    // shader's `gl_FrontFacing != mirrored`.
    const glm::vec3 ng = EmbreeScene::geometricNormal(query.hit);
    const bool ccwSideSeen = glm::dot(ng, direction) < 0.0f;
    hit.backFace = ccwSideSeen == shading.mirrored;
    hit.geometricNormal = glm::normalize(ccwSideSeen ? ng : -ng);

    // The vertex shader transforms each vertex normal by mat3(normalMatrix), the rasteriser
    // interpolates, the fragment shader normalises and flips on back faces.
    glm::vec3 normal = w * (shading.normalMatrix * v0.normal) + u * (shading.normalMatrix * v1.normal) +
                       v * (shading.normalMatrix * v2.normal);
    const float normalLength = glm::length(normal);
    // A zero or broken interpolated normal (degenerate input) would make the GPU shade NaN; the
    // reference falls back to the triangle's own normal instead.
    normal = normalLength > 0.0f && std::isfinite(normalLength) ? normal / normalLength
                                                                 : (hit.backFace ? -hit.geometricNormal : hit.geometricNormal);
    hit.normal = hit.backFace ? -normal : normal;
    return hit;
}

glm::vec4 ReferenceRenderer::baseColor(const SurfaceHit& hit) const {
    const Material& material = scene_.materials[scene_.meshes[scene_.objects[hit.object].mesh].material];
    glm::vec4 color = material.baseColorFactor;
    if (material.baseColorTexture >= 0) {
        color *= sampleBilinearRepeat(scene_.textures[size_t(material.baseColorTexture)], hit.uv);
    }
    return color;
}

glm::vec3 ReferenceRenderer::shade(const SurfaceHit& hit, uint64_t* shadowRays) const {
    if (!hit.hit) return glm::vec3(0.0f);
    const Material& material = scene_.materials[scene_.meshes[scene_.objects[hit.object].mesh].material];
    const glm::vec3 viewDir = glm::normalize(cameraPosition_ - hit.position);
    const gpu::Surface surface = gpu::makeSurface(hit.position, hit.normal, viewDir, glm::vec3(baseColor(hit)),
                                                  material.metallic, material.roughness);
    uint64_t rays = 0;
    // The same sum in the same order as forward.frag: the sun, then the packed lights. With
    // shadows off every factor is exactly 1, so the arithmetic is the GPU's operation for
    // operation.
    glm::vec3 radiance = gpu::shadeDirectionalLight(surface, lights_.sun);
    if (settings_.shadows && lights_.sun.directionToLight.w > 0.0f) {
        radiance *= visibility(*embree_, hit.position, hit.geometricNormal, lights_.sun);
        ++rays;
    }
    for (const gpu::GpuPunctualLight& light : lights_.packed) {
        float lightVisibility = 1.0f;
        if (settings_.shadows && gpu::punctualAttenuation(light, hit.position) > 0.0f) {
            lightVisibility = visibility(*embree_, hit.position, hit.geometricNormal, light);
            ++rays;
        }
        radiance += gpu::shadePunctualLight(surface, light, lightVisibility);
    }
    if (shadowRays) *shadowRays += rays;
    return radiance;
}

ImageRgba8 ReferenceRenderer::render(ReferenceStats* stats, std::vector<SurfaceHit>* surfaces) const {
    const uint32_t width = settings_.width;
    const uint32_t height = settings_.height;
    ImageRgba8 image;
    image.width = width;
    image.height = height;
    image.pixels.assign(size_t(width) * height * 4, 0);
    if (surfaces) surfaces->assign(size_t(width) * height, SurfaceHit{});

    std::atomic<uint64_t> shadowRayCount{0};
    std::atomic<uint32_t> rowsDone{0};
    std::mutex progressMutex;
    uint32_t printedPercent = 0;
    const Clock::time_point start = Clock::now();

    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, height, 1), [&](const tbb::blocked_range<uint32_t>& rows) {
        for (uint32_t y = rows.begin(); y != rows.end(); ++y) {
            uint64_t rowShadowRays = 0;
            for (uint32_t x = 0; x < width; ++x) {
                const SurfaceHit hit = traceSurface(x, y);
                const std::array<uint8_t, 4> rgba = toneMapToRgba8(shade(hit, &rowShadowRays), settings_.exposure);
                std::copy(rgba.begin(), rgba.end(), image.at(x, y));
                if (surfaces) (*surfaces)[size_t(y) * width + x] = hit;
            }
            shadowRayCount += rowShadowRays;
            const uint32_t done = ++rowsDone;
            if (settings_.showProgress) {
                // Whichever thread finishes a row may advance the line; the others never wait.
                const std::unique_lock<std::mutex> lock(progressMutex, std::try_to_lock);
                const uint32_t percent = uint32_t(uint64_t(done) * 100 / height);
                if (lock.owns_lock() && percent > printedPercent) {
                    printedPercent = percent;
                    std::fprintf(stderr, "\rreference: %3u%% (%u of %u rows)", percent, done, height);
                    std::fflush(stderr);
                }
            }
        }
    });
    if (settings_.showProgress) std::fputs("\r\033[K", stderr);  // clear the progress line

    if (stats) {
        stats->seconds = secondsSince(start);
        stats->buildSeconds = buildSeconds_;
        stats->primaryRays = uint64_t(width) * height;
        stats->shadowRays = shadowRayCount.load();
    }
    return image;
}

ImageRgba8 renderReference(const Scene& scene, const ReferenceSettings& settings, ReferenceStats* stats) {
    const ReferenceRenderer renderer(scene, settings);
    return renderer.render(stats);
}

}  // namespace punctual::reference
