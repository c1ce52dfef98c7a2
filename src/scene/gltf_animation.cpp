#include "scene/gltf_animation.h"

#include <set>
#include <utility>

#include "core/error.h"
#include "core/log.h"
#include "scene/gltf_detail.h"
#include "scene/keyframes.h"

namespace punctual::gltf_detail {
namespace {

enum class Property { Translation, Rotation, Scale, Weights };

struct ChannelTarget {
    size_t node;
    Property property;
    bool operator<(const ChannelTarget& other) const {
        return std::make_pair(node, property) < std::make_pair(other.node, other.property);
    }
};

class AnimationReader {
public:
    AnimationReader(const tinygltf::Model& model, const std::string& path) : model_(model), path_(path) {}

    // Applies every channel of animation `a` that no earlier animation drives to `poses`.
    void apply(size_t a, double time, std::map<size_t, NodePose>& poses) {
        const tinygltf::Animation& animation = model_.animations[a];
        std::set<ChannelTarget> mine;
        for (size_t c = 0; c < animation.channels.size(); ++c) {
            const tinygltf::AnimationChannel& channel = animation.channels[c];
            const std::string who = "animation " + std::to_string(a) + " channel " + std::to_string(c);
            if (channel.target_node < 0) {
                log::warn(path_ + ": " + who + " has no target node (an extension's), skipped");
                continue;
            }
            const ChannelTarget target = targetOf(channel, who);
            if (!mine.insert(target).second) {
                fail(who + " animates the " + channel.target_path + " of node " + std::to_string(target.node) +
                     ", which another channel of the animation already does");
            }
            const KeyframeTrack track = trackOf(animation, channel, target, who);
            if (!driven_.insert(target).second) {
                if (warnedConflict_) continue;
                warnedConflict_ = true;
                log::warn(path_ + ": " + who + " animates the " + channel.target_path + " of node " +
                          std::to_string(target.node) + ", which an earlier animation drives: the first drives it");
                continue;
            }
            setPose(poses[target.node], target.property, sampleTrack(track, time));
        }
    }

private:
    [[noreturn]] void fail(const std::string& problem) const { throw Error(path_, problem); }

    ChannelTarget targetOf(const tinygltf::AnimationChannel& channel, const std::string& who) const {
        const size_t node = size_t(channel.target_node);
        if (node >= model_.nodes.size()) {
            fail(who + " targets node " + std::to_string(channel.target_node) + ", which does not exist");
        }
        if (!model_.nodes[node].matrix.empty()) {
            fail(who + " animates node " + std::to_string(node) + ", which has a matrix (an animated node has TRS only)");
        }
        static const std::pair<const char*, Property> kPaths[] = {
            {"translation", Property::Translation}, {"rotation", Property::Rotation},
            {"scale", Property::Scale}, {"weights", Property::Weights}};
        for (const auto& [name, property] : kPaths) {
            if (channel.target_path == name) return {node, property};
        }
        fail(who + " has target path '" + channel.target_path + "' (expected translation, rotation, scale or weights)");
    }

    // Morph targets of the node's mesh: the numbers a weights keyframe holds.
    size_t morphTargets(size_t node, const std::string& who) const {
        const int mesh = model_.nodes[node].mesh;
        if (mesh < 0 || size_t(mesh) >= model_.meshes.size() || model_.meshes[size_t(mesh)].primitives.empty() ||
            model_.meshes[size_t(mesh)].primitives[0].targets.empty()) {
            fail(who + " animates the weights of node " + std::to_string(node) + ", whose mesh has no morph targets");
        }
        return model_.meshes[size_t(mesh)].primitives[0].targets.size();
    }

    KeyframeTrack trackOf(const tinygltf::Animation& animation, const tinygltf::AnimationChannel& channel,
                          const ChannelTarget& target, const std::string& who) const {
        if (channel.sampler < 0 || size_t(channel.sampler) >= animation.samplers.size()) {
            fail(who + " uses sampler " + std::to_string(channel.sampler) + ", which does not exist");
        }
        const tinygltf::AnimationSampler& sampler = animation.samplers[size_t(channel.sampler)];
        const std::string samplerName = who + " sampler " + std::to_string(channel.sampler);
        KeyframeTrack track;
        track.interpolation = interpolationOf(sampler.interpolation, samplerName);
        track.rotation = target.property == Property::Rotation;
        int type = TINYGLTF_TYPE_VEC3;
        if (target.property == Property::Rotation) type = TINYGLTF_TYPE_VEC4;
        if (target.property == Property::Weights) type = TINYGLTF_TYPE_SCALAR;
        track.components = target.property == Property::Weights ? uint32_t(morphTargets(target.node, who))
                           : target.property == Property::Rotation ? 4u : 3u;
        const AccessorReader reader(model_, samplerName, path_);
        track.times = reader.readFloats(sampler.input, "input", TINYGLTF_TYPE_SCALAR, false);
        const bool normalizedIntegers = target.property == Property::Rotation || target.property == Property::Weights;
        track.values = reader.readFloats(sampler.output, "output", type, normalizedIntegers);
        if (const std::string problem = trackProblem(track); !problem.empty()) fail(samplerName + " " + problem);
        return track;
    }

    Interpolation interpolationOf(const std::string& name, const std::string& who) const {
        if (name.empty() || name == "LINEAR") return Interpolation::Linear;  // the spec's default
        if (name == "STEP") return Interpolation::Step;
        if (name == "CUBICSPLINE") return Interpolation::CubicSpline;
        fail(who + " has interpolation '" + name + "' (expected LINEAR, STEP or CUBICSPLINE)");
    }

    static void setPose(NodePose& pose, Property property, const std::vector<float>& v) {
        switch (property) {
            case Property::Translation: pose.translation = glm::vec3(v[0], v[1], v[2]); break;
            case Property::Rotation: pose.rotation = glm::quat(v[3], v[0], v[1], v[2]); break;  // glTF x, y, z, w
            case Property::Scale: pose.scale = glm::vec3(v[0], v[1], v[2]); break;
            case Property::Weights: pose.weights = std::vector<double>(v.begin(), v.end()); break;
        }
    }

    const tinygltf::Model& model_;
    const std::string& path_;
    std::set<ChannelTarget> driven_;  // by any animation so far
    bool warnedConflict_ = false;
};

}  // namespace

std::map<size_t, NodePose> animatedPoses(const tinygltf::Model& model, const std::string& path, double time) {
    std::map<size_t, NodePose> poses;
    AnimationReader reader(model, path);
    for (size_t a = 0; a < model.animations.size(); ++a) reader.apply(a, time, poses);
    return poses;
}

}  // namespace punctual::gltf_detail
