// glTF 2.0 -> Scene: tinygltf parses the file; this walks the default scene's node graph and
// converts materials, textures, primitives, the camera and KHR_lights_punctual lights.
#include "scene/gltf_loader.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <tuple>
#include <set>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "core/error.h"
#include "core/log.h"
#include "scene/gltf_animation.h"
#include "scene/gltf_detail.h"

namespace punctual {
namespace {

using namespace gltf_detail;

std::string quoted(const std::string& name) { return "'" + name + "'"; }

std::string modeName(int mode) {
    switch (mode) {
        case TINYGLTF_MODE_POINTS: return "POINTS";
        case TINYGLTF_MODE_LINE: return "LINES";
        case TINYGLTF_MODE_LINE_LOOP: return "LINE_LOOP";
        case TINYGLTF_MODE_LINE_STRIP: return "LINE_STRIP";
        case TINYGLTF_MODE_TRIANGLE_STRIP: return "TRIANGLE_STRIP";
        case TINYGLTF_MODE_TRIANGLE_FAN: return "TRIANGLE_FAN";
        default: return "mode " + std::to_string(mode);
    }
}

bool finite(const glm::mat4& m) {
    for (int column = 0; column < 4; ++column)
        for (int row = 0; row < 4; ++row)
            if (!std::isfinite(m[column][row])) return false;
    return true;
}

// What a primitive without any material is drawn with. The glTF spec's default material is
// metallic 1, roughness 1: a rough white metal, which under punctual lights alone (no
// environment) looks nearly black from most angles. An untextured, unassigned surface is far
// more likely meant as a neutral matte one, so we use a white dielectric with medium roughness,
// as most viewers do. Materials that exist in the file but omit the factors still get the glTF
// defaults (metallic 1, roughness 1).
Material implicitDefaultMaterial() {
    Material material;
    material.name = "default";
    material.baseColorFactor = glm::vec4(1.0f);
    material.metallic = 0.0f;
    material.roughness = 0.5f;
    return material;
}

class SceneBuilder {
public:
    SceneBuilder(const tinygltf::Model& model, const std::string& path, const ImageDecoding& decoding,
                 const UriFiles& files, std::map<size_t, NodePose> poses)
        : model_(model), path_(path), decoding_(decoding), files_(files), poses_(std::move(poses)) {}

    Scene build() {
        scene_.source = path_;
        convertMaterials();
        const std::vector<Light> lightPrototypes = convertLights();
        walk(rootNodes(), lightPrototypes);
        if (scene_.objects.empty())
            fail(skippedPrimitives_.empty() ? "no triangle meshes to draw"
                                            : "no triangle meshes to draw, only " + describeSkipped());
        if (scene_.materials.empty()) scene_.materials.push_back(implicitDefaultMaterial());
        scene_.computeBounds();
        // Finite but huge coordinates (e.g. 1e38) overflow the bounds' extent, and with it the
        // camera's far plane and every light's culling maths.
        if (!std::isfinite(scene_.bounds.radius()))
            fail("the scene's extent is too large for single-precision floats");
        placeCamera();
        warnAboutSkippedPrimitives();
        validateLights(scene_.lights, path_);
        scene_.animationSeconds = animationSeconds();
        return std::move(scene_);
    }

private:
    [[noreturn]] void fail(const std::string& problem) const { throw Error(path_, problem); }

    std::string meshLabel(size_t meshIndex) const {
        const std::string& name = model_.meshes[meshIndex].name;
        return name.empty() ? "mesh " + std::to_string(meshIndex) : "mesh " + quoted(name);
    }

    std::string meshName(size_t meshIndex) const {
        const std::string& name = model_.meshes[meshIndex].name;
        return name.empty() ? "mesh " + std::to_string(meshIndex) : name;
    }

    // --- materials and textures ------------------------------------------------------------

    void convertMaterials() {
        MaterialConverter converter(model_, path_, decoding_, files_, scene_.textures);
        for (size_t i = 0; i < model_.materials.size(); ++i) scene_.materials.push_back(converter.convert(i));
    }

    uint32_t defaultMaterial() {
        if (!defaultMaterialIndex_) {
            defaultMaterialIndex_ = uint32_t(scene_.materials.size());
            scene_.materials.push_back(implicitDefaultMaterial());
        }
        return *defaultMaterialIndex_;
    }

    // --- lights ------------------------------------------------------------------------------

    // One Light per KHR_lights_punctual definition, positioned later per referencing node.
    // Validated here so an error names the light's index in the file.
    std::vector<Light> convertLights() const {
        std::vector<Light> lights;
        for (size_t i = 0; i < model_.lights.size(); ++i) {
            const tinygltf::Light& source = model_.lights[i];
            const std::string who = "light " + std::to_string(i) + (source.name.empty() ? "" : " " + quoted(source.name));
            Light light;
            light.name = source.name;
            if (source.type == "point") light.type = LightType::Point;
            else if (source.type == "spot") light.type = LightType::Spot;
            else if (source.type == "directional") light.type = LightType::Directional;
            else fail(who + " has unknown type " + quoted(source.type) + " (expected point, spot or directional)");
            if (!source.color.empty()) {
                if (source.color.size() != 3) fail(who + ": color must have 3 components");
                light.color = glm::vec3(float(source.color[0]), float(source.color[1]), float(source.color[2]));
            }
            light.intensity = float(source.intensity);
            if (light.type == LightType::Spot) {
                light.innerConeAngle = float(source.spot.innerConeAngle);
                light.outerConeAngle = float(source.spot.outerConeAngle);
            }
            if (light.type != LightType::Directional) {
                // tinygltf reports an absent range as 0; the spec says absent means infinite
                // (preflight has rejected a 0 or negative range written in the file). A range
                // no float can hold is infinite for every scene a float can describe.
                if (source.range == 0.0 || source.range > double(std::numeric_limits<float>::max())) {
                    light.range = derivedRange(light.intensity, light.color);
                    light.rangeDerived = true;
                } else {
                    light.range = float(source.range);
                }
            }
            lights.push_back(light);
        }
        validateLights(lights, path_);
        return lights;
    }

    void placeLight(const tinygltf::Node& node, size_t nodeIndex, const glm::mat4& world,
                    const std::vector<Light>& prototypes) {
        const auto extension = node.extensions.find("KHR_lights_punctual");
        if (extension == node.extensions.end()) return;
        const tinygltf::Value& value = extension->second;
        if (!value.IsObject() || !value.Has("light") || !value.Get("light").IsInt())
            fail("node " + std::to_string(nodeIndex) + ": KHR_lights_punctual has no integer 'light'");
        const int lightIndex = value.Get("light").GetNumberAsInt();
        if (lightIndex < 0 || size_t(lightIndex) >= prototypes.size())
            fail("node " + std::to_string(nodeIndex) + " refers to light " + std::to_string(lightIndex) +
                 ", which does not exist");
        Light light = prototypes[size_t(lightIndex)];
        if (light.name.empty()) light.name = node.name;
        light.position = glm::vec3(world * glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
        // A singular transform gives NaN here, which validateLights reports for spots and the sun.
        // A point light has no direction; its angle term (k = 0, offset 1) ignores it, but a NaN
        // would still poison the product, so a degenerate one becomes the node's default -Z.
        light.direction = glm::normalize(glm::mat3(world) * glm::vec3(0.0f, 0.0f, -1.0f));
        const bool finiteDirection = std::isfinite(light.direction.x) && std::isfinite(light.direction.y) &&
                                     std::isfinite(light.direction.z);
        if (light.type == LightType::Point && !finiteDirection) light.direction = glm::vec3(0.0f, 0.0f, -1.0f);
        scene_.lights.push_back(std::move(light));
    }

    // The last keyframe time of any animation, from the input accessors' "max" (which the spec
    // requires of animation inputs); a malformed animation is reported when a time poses it.
    double animationSeconds() const {
        double last = 0.0;
        for (const tinygltf::Animation& animation : model_.animations) {
            for (const tinygltf::AnimationSampler& sampler : animation.samplers) {
                if (sampler.input < 0 || size_t(sampler.input) >= model_.accessors.size()) continue;
                const std::vector<double>& max = model_.accessors[size_t(sampler.input)].maxValues;
                if (!max.empty() && std::isfinite(max[0])) last = std::max(last, max[0]);
            }
        }
        return last;
    }

    // --- node graph ----------------------------------------------------------------------------

    std::vector<int> rootNodes() const {
        if (!model_.scenes.empty()) {
            const int sceneIndex = model_.defaultScene >= 0 ? model_.defaultScene : 0;
            if (size_t(sceneIndex) >= model_.scenes.size())
                fail("default scene " + std::to_string(sceneIndex) + " does not exist (the file has " +
                     std::to_string(model_.scenes.size()) + (model_.scenes.size() == 1 ? " scene)" : " scenes)"));
            return model_.scenes[size_t(sceneIndex)].nodes;
        }
        // No scenes: draw every node that is nobody's child.
        std::vector<bool> isChild(model_.nodes.size(), false);
        for (const tinygltf::Node& node : model_.nodes)
            for (int child : node.children)
                if (child >= 0 && size_t(child) < isChild.size()) isChild[size_t(child)] = true;
        std::vector<int> roots;
        for (size_t i = 0; i < isChild.size(); ++i)
            if (!isChild[i]) roots.push_back(int(i));
        return roots;
    }

    // The node's transform: its matrix, or T x R x S from its stored translation, rotation and
    // scale, each replaced by its animated value where the scene is posed (poses_).
    glm::mat4 localTransform(const tinygltf::Node& node, size_t nodeIndex) const {
        const std::string who = "node " + std::to_string(nodeIndex);
        if (!node.matrix.empty()) {
            if (node.matrix.size() != 16) fail(who + ": matrix has " + std::to_string(node.matrix.size()) + " numbers, not 16");
            glm::mat4 matrix;  // glTF matrices are column-major, like glm's
            for (int i = 0; i < 16; ++i) matrix[i / 4][i % 4] = float(node.matrix[size_t(i)]);
            return matrix;
        }
        const auto posed = poses_.find(nodeIndex);
        const NodePose* pose = posed == poses_.end() ? nullptr : &posed->second;
        glm::mat4 transform(1.0f);
        if (pose && pose->translation) {
            transform[3] = glm::vec4(*pose->translation, 1.0f);
        } else if (!node.translation.empty()) {
            if (node.translation.size() != 3) fail(who + ": translation does not have 3 numbers");
            transform[3] = glm::vec4(float(node.translation[0]), float(node.translation[1]), float(node.translation[2]), 1.0f);
        }
        glm::quat rotation(1.0f, 0.0f, 0.0f, 0.0f);
        const bool rotated = (pose && pose->rotation) || !node.rotation.empty();
        if (pose && pose->rotation) {
            rotation = *pose->rotation;
        } else if (!node.rotation.empty()) {
            if (node.rotation.size() != 4) fail(who + ": rotation does not have 4 numbers");
            // glTF stores x, y, z, w; glm::quat's constructor takes w first.
            rotation = glm::quat(float(node.rotation[3]), float(node.rotation[0]), float(node.rotation[1]),
                                 float(node.rotation[2]));
        }
        if (rotated) {
            const float length = glm::length(rotation);
            if (!(length > 1e-6f)) fail(who + ": rotation is a zero quaternion");
            transform *= glm::mat4_cast(rotation / length);
        }
        if (pose && pose->scale) {
            transform = glm::scale(transform, *pose->scale);
        } else if (!node.scale.empty()) {
            if (node.scale.size() != 3) fail(who + ": scale does not have 3 numbers");
            transform = glm::scale(transform, glm::vec3(float(node.scale[0]), float(node.scale[1]), float(node.scale[2])));
        }
        return transform;
    }

    // Depth-first, pre-order, children in file order (so "the first camera" is well defined),
    // with an explicit stack so a deep hierarchy cannot overflow the call stack.
    void walk(const std::vector<int>& roots, const std::vector<Light>& lightPrototypes) {
        enum class State : uint8_t { Unvisited, OnPath, Done };
        std::vector<State> state(model_.nodes.size(), State::Unvisited);
        struct Step {
            int node;
            glm::mat4 parentWorld;
            bool leaving;  // pops the node off the current path
        };
        std::vector<Step> stack;
        for (auto root = roots.rbegin(); root != roots.rend(); ++root) {
            if (*root < 0 || size_t(*root) >= model_.nodes.size())
                fail("the scene refers to node " + std::to_string(*root) + ", which does not exist");
            stack.push_back({*root, glm::mat4(1.0f), false});
        }
        while (!stack.empty()) {
            const Step step = stack.back();
            stack.pop_back();
            const size_t index = size_t(step.node);
            if (step.leaving) {
                state[index] = State::Done;
                continue;
            }
            if (state[index] == State::OnPath) fail("node " + std::to_string(index) + " is its own ancestor");
            if (state[index] == State::Done)
                fail("node " + std::to_string(index) + " is reached twice (a glTF node may have only one parent)");
            state[index] = State::OnPath;

            const tinygltf::Node& node = model_.nodes[index];
            const glm::mat4 world = step.parentWorld * localTransform(node, index);
            if (!finite(world)) fail("node " + std::to_string(index) + " has a transform that is not finite");
            visit(node, index, world, lightPrototypes);

            stack.push_back({step.node, world, true});
            for (auto child = node.children.rbegin(); child != node.children.rend(); ++child) {
                if (*child < 0 || size_t(*child) >= model_.nodes.size())
                    fail("node " + std::to_string(index) + " has child " + std::to_string(*child) +
                         ", which does not exist");
                stack.push_back({*child, world, false});
            }
        }
    }

    void visit(const tinygltf::Node& node, size_t index, const glm::mat4& world, const std::vector<Light>& lightPrototypes) {
        if (node.mesh >= 0) addMeshInstance(node, index, world);
        if (node.camera >= 0) noteCamera(node, index, world);
        placeLight(node, index, world, lightPrototypes);
    }

    // --- meshes --------------------------------------------------------------------------------

    void addMeshInstance(const tinygltf::Node& node, size_t nodeIndex, const glm::mat4& world) {
        const size_t meshIndex = size_t(node.mesh);
        if (meshIndex >= model_.meshes.size())
            fail("node " + std::to_string(nodeIndex) + " refers to mesh " + std::to_string(node.mesh) +
                 ", which does not exist");
        const tinygltf::Mesh& mesh = model_.meshes[meshIndex];
        for (size_t p = 0; p < mesh.primitives.size(); ++p) {
            // glTF 2.0 3.7.2.2: a node's weights override its mesh's, and animated weights both.
            const auto posed = poses_.find(nodeIndex);
            const std::vector<double>& weights = posed != poses_.end() && posed->second.weights ? *posed->second.weights
                                                 : node.weights.empty()                           ? mesh.weights
                                                                                                  : node.weights;
            const std::optional<uint32_t> converted = meshOfPrimitive(meshIndex, p, weights);
            if (!converted) continue;
            Object object;
            object.name = !node.name.empty() ? node.name : !mesh.name.empty() ? mesh.name : "node " + std::to_string(nodeIndex);
            object.mesh = *converted;
            object.model = world;
            scene_.objects.push_back(std::move(object));
        }
    }

    // The punctual Mesh of a glTF primitive at the given morph weights, converted on first use so
    // a primitive instanced by several nodes in one pose is stored once. nullopt for primitives
    // that draw nothing we support.
    std::optional<uint32_t> meshOfPrimitive(size_t meshIndex, size_t primitiveIndex, const std::vector<double>& weights) {
        const bool morphed = !model_.meshes[meshIndex].primitives[primitiveIndex].targets.empty();
        const auto key = std::make_tuple(meshIndex, primitiveIndex, morphed ? weights : std::vector<double>{});
        if (const auto known = primitiveMeshes_.find(key); known != primitiveMeshes_.end()) return known->second;

        const tinygltf::Primitive& primitive = model_.meshes[meshIndex].primitives[primitiveIndex];
        const std::string label = meshLabel(meshIndex) + " primitive " + std::to_string(primitiveIndex);
        std::optional<uint32_t> result;
        if (!drawsTriangles(primitive.mode)) {
            ++skippedPrimitives_[primitive.mode];
        } else if (std::optional<Mesh> mesh =
                       appendPrimitive(model_, primitive, label, path_, std::get<2>(key), unmorphedTargets_,
                                       scene_.vertices, scene_.indices)) {
            if (primitive.material < 0) {
                mesh->material = defaultMaterial();
            } else if (size_t(primitive.material) < model_.materials.size()) {
                mesh->material = uint32_t(primitive.material);
            } else {
                fail(label + " uses material " + std::to_string(primitive.material) + ", which does not exist");
            }
            mesh->name = model_.meshes[meshIndex].primitives.size() > 1
                             ? meshName(meshIndex) + "#" + std::to_string(primitiveIndex)
                             : meshName(meshIndex);
            result = uint32_t(scene_.meshes.size());
            scene_.meshes.push_back(std::move(*mesh));
        }
        primitiveMeshes_[key] = result;
        return result;
    }

    // "3 primitive(s) that are not triangles (POINTS, LINES)", for the warning and the error.
    std::string describeSkipped() const {
        int total = 0;
        std::string modes;
        for (const auto& [mode, count] : skippedPrimitives_) {
            total += count;
            modes += (modes.empty() ? "" : ", ") + modeName(mode);
        }
        return std::to_string(total) + " primitive(s) that are not triangles (" + modes + ")";
    }

    // One line for the whole file, however many primitives and modes; one for unread morph targets.
    void warnAboutSkippedPrimitives() const {
        if (!skippedPrimitives_.empty()) log::warn(path_ + ": skipped " + describeSkipped() + ": punctual draws only triangles");
        if (unmorphedTargets_ > 0)
            log::warn(path_ + ": " + std::to_string(unmorphedTargets_) +
                      " weighted morph target(s) use sparse accessors, which punctual does not read: drawn without them");
    }

    // --- camera --------------------------------------------------------------------------------

    void noteCamera(const tinygltf::Node& node, size_t nodeIndex, const glm::mat4& world) {
        if (size_t(node.camera) >= model_.cameras.size())
            fail("node " + std::to_string(nodeIndex) + " refers to camera " + std::to_string(node.camera) +
                 ", which does not exist");
        if (cameraNode_) return;  // the first one in traversal order wins
        const tinygltf::Camera& camera = model_.cameras[size_t(node.camera)];
        if (camera.type != "perspective") {
            sawOtherCamera_ = true;
            return;
        }
        cameraNode_ = nodeIndex;
        cameraWorld_ = world;
    }

    void placeCamera() {
        if (!cameraNode_) {
            if (sawOtherCamera_)
                log::warn(path_ + ": orthographic cameras are not supported; using a view fitted to the scene");
            scene_.camera = fitCameraToBounds(scene_.bounds);
            scene_.cameraFromFile = false;
            return;
        }
        const tinygltf::Node& node = model_.nodes[*cameraNode_];
        const tinygltf::Camera& source = model_.cameras[size_t(node.camera)];
        const tinygltf::PerspectiveCamera& perspective = source.perspective;
        const std::string who = "camera " + std::to_string(node.camera);
        if (!(perspective.yfov > 0.0 && perspective.yfov < std::numbers::pi))
            fail(who + ": yfov must be between 0 and pi radians");
        if (!(perspective.znear > 0.0)) fail(who + ": znear must be greater than 0");
        if (perspective.zfar != 0.0 && !(perspective.zfar > perspective.znear))
            fail(who + ": zfar must be greater than znear");

        // The view ignores the node's scale: rebuild an orthonormal frame from its axes, keeping
        // the viewing direction (-Z) exact.
        const glm::vec3 back = glm::vec3(cameraWorld_[2]);
        const glm::vec3 upHint = glm::vec3(cameraWorld_[1]);
        const glm::vec3 rightUnnormalized = glm::cross(upHint, back);
        if (!(glm::length(back) > 1e-12f) || !(glm::length(rightUnnormalized) > 1e-20f))
            fail("node " + std::to_string(*cameraNode_) + " (camera) has a degenerate transform");
        const glm::vec3 z = glm::normalize(back);
        const glm::vec3 x = glm::normalize(glm::cross(upHint, z));
        const glm::vec3 y = glm::cross(z, x);
        glm::mat4 rigid(1.0f);
        rigid[0] = glm::vec4(x, 0.0f);
        rigid[1] = glm::vec4(y, 0.0f);
        rigid[2] = glm::vec4(z, 0.0f);
        rigid[3] = cameraWorld_[3];

        Camera camera;
        camera.name = !source.name.empty() ? source.name : node.name;
        camera.view = glm::inverse(rigid);
        camera.yfov = float(perspective.yfov);
        camera.znear = float(perspective.znear);
        if (perspective.zfar != 0.0) {
            camera.zfar = float(perspective.zfar);
        } else {
            // Infinite far plane in the file: reach just past the farthest corner of the scene.
            const glm::vec3 eye = glm::vec3(rigid[3]);
            float farthest = 0.0f;
            for (int corner = 0; corner < 8; ++corner) {
                const glm::vec3 p((corner & 1) ? scene_.bounds.max.x : scene_.bounds.min.x,
                                  (corner & 2) ? scene_.bounds.max.y : scene_.bounds.min.y,
                                  (corner & 4) ? scene_.bounds.max.z : scene_.bounds.min.z);
                farthest = std::max(farthest, glm::distance(eye, p));
            }
            camera.zfar = std::max(farthest * 1.1f, camera.znear * 10.0f);
        }
        if (!std::isfinite(camera.znear) || !std::isfinite(camera.zfar) || !finite(camera.view))
            fail(who + ": its clip planes or position are too large for single-precision floats");
        scene_.camera = camera;
        scene_.cameraFromFile = true;
    }

    const tinygltf::Model& model_;
    const std::string& path_;
    const ImageDecoding& decoding_;
    const UriFiles& files_;
    const std::map<size_t, NodePose> poses_;  // the animated nodes at GltfLoadOptions::time
    Scene scene_;
    std::map<std::tuple<size_t, size_t, std::vector<double>>, std::optional<uint32_t>> primitiveMeshes_;
    size_t unmorphedTargets_ = 0;  // weighted morph targets skipped (sparse accessors)
    std::map<int, int> skippedPrimitives_;  // mode -> count
    std::optional<uint32_t> defaultMaterialIndex_;
    std::optional<size_t> cameraNode_;
    glm::mat4 cameraWorld_{1.0f};
    bool sawOtherCamera_ = false;
};

// The extensions a file may require: those the loader implements. The spec requires refusing a
// file that requires any other (its data would otherwise surface as confusing accessor errors,
// or be silently drawn wrong). Checked before tinygltf sees the file, whose own complaints about
// data only such an extension explains would hide the real reason.
void checkRequiredExtensions(const nlohmann::json& gltf, const std::string& path) {
    static const std::set<std::string> supported = {
        "KHR_lights_punctual",     "KHR_mesh_quantization",          "KHR_draco_mesh_compression",
        "EXT_meshopt_compression", "KHR_materials_emissive_strength", "KHR_texture_transform",
        "EXT_texture_webp"};
    const auto required = gltf.find("extensionsRequired");
    if (required == gltf.end() || !required->is_array()) return;  // tinygltf reports a malformed one
    std::vector<std::string> missing;
    for (const nlohmann::json& name : *required)
        if (name.is_string() && !supported.count(name.get<std::string>())) missing.push_back(name.get<std::string>());
    if (missing.empty()) return;
    std::string names;
    for (const std::string& name : missing) names += (names.empty() ? "" : ", ") + name;
    throw Error(path, (missing.size() == 1 ? "requires the glTF extension " : "requires the glTF extensions ") + names +
                          (missing.size() == 1 ? ", which is not supported" : ", which are not supported"));
}

}  // namespace

Scene loadGltf(const std::string& path, const GltfLoadOptions& options) {
    SourceFile source = readSource(path);
    checkRequiredExtensions(source.json, path);
    // tinygltf refuses what the compression extensions rightly write (buffers without data, index
    // accessors without buffer views): it reads a version of the file without those, which the
    // checks below look at too, since it is what tinygltf acts on.
    std::optional<nlohmann::json> patched;
    addMeshoptPlaceholders(source.json, patched, source.binary, path);
    hideDracoIndices(source.json, patched);
    if (patched) source.bytes = withJson(source, *patched);
    const nlohmann::json& gltf = patched ? *patched : source.json;
    preflight(gltf, path);

    ImageDecoding decoding;
    decoding.wanted = colourImages(gltf);
    decoding.limit = options.textureLimit;
    decoding.source = path;
    UriFiles files(gltf, source.baseDir);
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(&decodeImage, &decoding);
    loader.SetFsCallbacks(files.callbacks());

    // We already hold the bytes (to detect the format and pre-check the JSON), so hand them to
    // tinygltf instead of letting LoadASCIIFromFile/LoadBinaryFromFile read the file again.
    tinygltf::Model model;
    std::string error;
    std::string warning;
    const auto size = static_cast<unsigned int>(source.bytes.size());
    const bool loaded =
        source.binary
            ? loader.LoadBinaryFromMemory(&model, &error, &warning, source.bytes.data(), size, source.baseDir)
            : loader.LoadASCIIFromString(&model, &error, &warning, reinterpret_cast<const char*>(source.bytes.data()),
                                         size, source.baseDir);
    for (const std::string& line : relevantWarnings(warning)) log::warn(path + ": " + line);
    if (!loaded) throw Error(path, describeLoadError(error, gltf));
    // tinygltf also appends non-fatal complaints to the error text of a successful load.
    for (const std::string& line : relevantWarnings(error)) log::warn(path + ": " + line);

    restoreDracoIndices(model, source.json);
    decodeMeshoptViews(model, source.json, path);
    std::map<size_t, NodePose> poses;
    if (options.time) {
        if (model.animations.empty()) log::warn(path + ": --time: the scene has no animations; drawn as stored");
        poses = animatedPoses(model, path, *options.time);
    }
    return SceneBuilder(model, path, decoding, files, std::move(poses)).build();
}

}  // namespace punctual
