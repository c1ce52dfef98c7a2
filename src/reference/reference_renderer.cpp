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
float traceShadowRay(const EmbreeScene& scene, glm::vec3 point, glm::vec3 normal, glm::vec3 direction, float tfar,
                     TransparentShadows transparentShadows) {
    RayContext context = makeRayContext(RayKind::Shadow, transparentShadows);
    RTCRay ray = makeRay(point + normal * scene.rayEpsilonAt(point), direction, tfar);
    rtcOccluded1(scene.handle(), &context.embree, &ray);
    // rtcOccluded1 sets tfar to -inf when anything lies on the ray.
    return ray.tfar < 0.0f ? 0.0f : 1.0f;
}

}  // namespace

float visibility(const EmbreeScene& scene, glm::vec3 point, glm::vec3 normal, const gpu::GpuPunctualLight& light,
                 TransparentShadows transparentShadows) {
    const glm::vec3 origin = point + normal * scene.rayEpsilonAt(point);
    const glm::vec3 toLight = glm::vec3(light.positionInvRangeSq) - origin;
    const float distance = glm::length(toLight);
    if (!(distance > 0.0f)) return 1.0f;  // the light sits on the lifted point: nothing between
    return traceShadowRay(scene, point, normal, toLight / distance, distance * (1.0f - 1e-4f), transparentShadows);
}

float visibility(const EmbreeScene& scene, glm::vec3 point, glm::vec3 normal, const gpu::GpuDirectionalLight& sun,
                 TransparentShadows transparentShadows) {
    return traceShadowRay(scene, point, normal, glm::normalize(glm::vec3(sun.directionToLight)),
                          std::numeric_limits<float>::infinity(), transparentShadows);
}

std::array<uint8_t, 4> toneMapToRgba8(glm::vec3 radiance, float exposure) {
    const glm::vec3 display = gpu::linearToSrgb3(gpu::toneMapAces(radiance, exposure));
    auto quantise = [](float c) { return uint8_t(std::round(std::clamp(c, 0.0f, 1.0f) * 255.0f)); };
    return {quantise(display.x), quantise(display.y), quantise(display.z), 255};
}

ReferenceRenderer::ReferenceRenderer(const Scene& scene, const ReferenceSettings& settings)
    : scene_(scene), settings_(settings) {
    validateSettings(settings);
    checkCameraPrecision(scene.camera, settings.height, scene.source);  // as the GPU's renderer: one rule
    if (scene.vertices.empty() || scene.indices.empty() || scene.objects.empty()) {
        throw Error(scene.source, "no triangle meshes to draw");
    }
    for (const Mesh& mesh : scene.meshes) {
        if (mesh.material >= scene.materials.size()) throw Error(scene.source, "mesh '" + mesh.name + "' has no material");
    }
    for (const Material& material : scene.materials) {
        if (material.baseColorTexture.image >= int(scene.textures.size()) ||
            material.emissiveTexture.image >= int(scene.textures.size())) {
            throw Error(scene.source, "material '" + material.name + "' names a missing texture");
        }
    }

    for (const Mesh& mesh : scene.meshes) hasTransparency_ |= scene.materials[mesh.material].alphaMode == AlphaMode::Blend;

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
    lights_ = setupFrameLights(scene, view_, projection_, settings.maxLights);
}

ReferenceRenderer::~ReferenceRenderer() = default;

ReferenceRenderer::PixelRay ReferenceRenderer::pixelRay(double x, double y) const {
    // Unproject the point at depth 1 (near plane) and 0 (far plane) with the inverse of the GPU's
    // view-projection (Vulkan clip space: NDC y points down; reversed depth, see
    // Camera::projection). In double: the far point's w is tiny and a float inverse would bend
    // the ray visibly at 8k pixels.
    const double ndcX = x / settings_.width * 2.0 - 1.0;
    const double ndcY = y / settings_.height * 2.0 - 1.0;
    const glm::dvec4 nearH = inverseViewProjection_ * glm::dvec4(ndcX, ndcY, 1.0, 1.0);
    const glm::dvec4 farH = inverseViewProjection_ * glm::dvec4(ndcX, ndcY, 0.0, 1.0);
    const glm::dvec3 nearPoint = glm::dvec3(nearH) / nearH.w;
    const glm::dvec3 farPoint = glm::dvec3(farH) / farH.w;
    const double length = glm::length(farPoint - nearPoint);
    return {glm::vec3(nearPoint), glm::vec3((farPoint - nearPoint) / length), float(length)};
}

void ReferenceRenderer::addUvFootprint(SurfaceHit& hit, uint32_t x, uint32_t y, const glm::vec3 corners[3],
                                       const glm::vec2 uv0[3], const glm::vec2 uv1[3]) const {
    const glm::dvec3 a(corners[0]);
    const glm::dvec3 edge1 = glm::dvec3(corners[1]) - a;
    const glm::dvec3 edge2 = glm::dvec3(corners[2]) - a;
    const glm::dvec3 normal = glm::cross(edge1, edge2);
    const double d00 = glm::dot(edge1, edge1), d01 = glm::dot(edge1, edge2), d11 = glm::dot(edge2, edge2);
    const double denominator = d00 * d11 - d01 * d01;
    if (!(std::abs(denominator) > 0.0)) return;
    // Barycentric coordinates of the point where a neighbouring pixel's ray meets the triangle's
    // plane (outside the triangle too: the plane is what the rasteriser's derivatives extend).
    const auto uvAt = [&](double px, double py, glm::vec2& outUv0, glm::vec2& outUv1) {
        const PixelRay ray = pixelRay(px, py);
        const double facing = glm::dot(glm::dvec3(ray.direction), normal);
        if (!(std::abs(facing) > 0.0)) return false;
        const double t = glm::dot(a - glm::dvec3(ray.origin), normal) / facing;
        const glm::dvec3 q = glm::dvec3(ray.origin) + t * glm::dvec3(ray.direction) - a;
        const double d20 = glm::dot(q, edge1), d21 = glm::dot(q, edge2);
        const float v = float((d11 * d20 - d01 * d21) / denominator);
        const float w = float((d00 * d21 - d01 * d20) / denominator);
        const float u = 1.0f - v - w;
        outUv0 = u * uv0[0] + v * uv0[1] + w * uv0[2];
        outUv1 = u * uv1[0] + v * uv1[1] + w * uv1[2];
        return std::isfinite(outUv0.x) && std::isfinite(outUv0.y) && std::isfinite(outUv1.x) && std::isfinite(outUv1.y);
    };
    glm::vec2 right0, right1, below0, below1;
    if (!uvAt(double(x) + 1.5, double(y) + 0.5, right0, right1) || !uvAt(double(x) + 0.5, double(y) + 1.5, below0, below1))
        return;
    hit.texCoords.dx[0] = right0 - hit.texCoords.uv[0];
    hit.texCoords.dx[1] = right1 - hit.texCoords.uv[1];
    hit.texCoords.dy[0] = below0 - hit.texCoords.uv[0];
    hit.texCoords.dy[1] = below1 - hit.texCoords.uv[1];
}

SurfaceHit ReferenceRenderer::traceSurface(uint32_t x, uint32_t y) const {
    const PixelRay ray = pixelRay(double(x) + 0.5, double(y) + 0.5);
    const glm::vec3 direction = ray.direction;

    // The GPU draws what lies between the near and far planes; so does the ray.
    RTCRayHit query{};
    query.ray = makeRay(ray.origin, direction, ray.length);
    query.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    query.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    RayContext context = makeRayContext(RayKind::Primary);
    context.embree.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;  // neighbouring pixels, similar rays
    rtcIntersect1(embree_->handle(), &context.embree, &query);
    return surfaceOf(query, x, y);
}

SurfaceHit ReferenceRenderer::surfaceOf(const RTCRayHit& query, uint32_t x, uint32_t y) const {
    const glm::vec3 direction(query.ray.dir_x, query.ray.dir_y, query.ray.dir_z);
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
    hit.texCoords.uv[0] = hit.uv;
    hit.texCoords.uv[1] = w * v0.uv1 + u * v1.uv1 + v * v2.uv1;
    const Material& material = scene_.materials[mesh.material];
    if (material.baseColorTexture.present() || material.emissiveTexture.present()) {
        const glm::vec3 corners[3] = {glm::vec3(shading.model * glm::vec4(v0.position, 1.0f)),
                                      glm::vec3(shading.model * glm::vec4(v1.position, 1.0f)),
                                      glm::vec3(shading.model * glm::vec4(v2.position, 1.0f))};
        const glm::vec2 uv0[3] = {v0.uv, v1.uv, v2.uv};
        const glm::vec2 uv1[3] = {v0.uv1, v1.uv1, v2.uv1};
        addUvFootprint(hit, x, y, corners, uv0, uv1);
    }

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
    return material.baseColorFactor * sampleMaterialTexture(scene_, material.baseColorTexture, hit.texCoords);
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
        radiance *= visibility(*embree_, hit.position, hit.geometricNormal, lights_.sun, settings_.transparentShadows);
        ++rays;
    }
    for (const gpu::GpuPunctualLight& light : lights_.packed) {
        float lightVisibility = 1.0f;
        if (settings_.shadows && gpu::punctualAttenuation(light, hit.position) > 0.0f) {
            lightVisibility = visibility(*embree_, hit.position, hit.geometricNormal, light, settings_.transparentShadows);
            ++rays;
        }
        radiance += gpu::shadePunctualLight(surface, light, lightVisibility);
    }
    // Emission last, as forward.frag adds it.
    radiance += material.emission() * glm::vec3(sampleMaterialTexture(scene_, material.emissiveTexture, hit.texCoords));
    if (shadowRays) *shadowRays += rays;
    return radiance;
}

glm::vec3 ReferenceRenderer::shadePixel(uint32_t x, uint32_t y, const SurfaceHit& hit, uint64_t* shadowRays) const {
    glm::vec3 radiance = shade(hit, shadowRays);
    if (!hasTransparency_) return radiance;
    // The transparent surfaces in front of the opaque one (or of the far plane), nearest first: the
    // ray goes on from each hit until it reaches the opaque surface.
    const PixelRay ray = pixelRay(double(x) + 0.5, double(y) + 0.5);
    const float end = hit.hit ? hit.distance : ray.length;
    std::vector<SurfaceHit> layers;
    float from = 0.0f;
    constexpr size_t kMaxLayers = 64;  // a bound on the walk: more panes than any test scene holds
    while (layers.size() < kMaxLayers) {
        RTCRayHit query{};
        query.ray = makeRay(ray.origin, ray.direction, end);
        query.ray.tnear = from;
        query.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        query.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        RayContext context = makeRayContext(RayKind::TransparentLayers);
        rtcIntersect1(embree_->handle(), &context.embree, &query);
        if (query.hit.geomID == RTC_INVALID_GEOMETRY_ID || !(query.ray.tfar < end)) break;
        layers.push_back(surfaceOf(query, x, y));
        // On past this hit: a relative step, far below any gap between real panes.
        from = std::nextafter(query.ray.tfar * (1.0f + 1e-6f), std::numeric_limits<float>::infinity());
    }
    // Farthest first, each blended over what lies behind it, as the GPU's "over" blending does.
    for (auto layer = layers.rbegin(); layer != layers.rend(); ++layer) {
        const float alpha = baseColor(*layer).a;
        radiance = shade(*layer, shadowRays) * alpha + radiance * (1.0f - alpha);
    }
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
                const std::array<uint8_t, 4> rgba =
                    toneMapToRgba8(shadePixel(x, y, hit, &rowShadowRays), settings_.exposure);
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
