#pragma once
// glTF animations (glTF 2.0 section 3.11): channels that drive nodes' translation, rotation,
// scale and morph-target weights through keyframe samplers (scene/keyframes.h). The loader poses
// a scene at `--time T` with them (GltfLoadOptions::time): the animated nodes' properties replace
// their stored ones before the node graph is walked, so meshes, cameras and lights below an
// animated node move with it, and animated weights pick the morph pose drawn.
//
// Every animation of the file plays at once from time 0 (exporters commonly write one animation
// per object). Within one animation a node's property may be targeted once (the spec); where two
// animations drive the same property, the first in file order drives it and the loader warns
// once. A channel with no target node (one only an extension such as KHR_animation_pointer
// reads) is skipped with a warning.
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <tiny_gltf.h>

namespace punctual::gltf_detail {

// A node's animated properties at one time; the rest keep the node's stored values.
struct NodePose {
    std::optional<glm::vec3> translation;
    std::optional<glm::quat> rotation;  // unit
    std::optional<glm::vec3> scale;
    std::optional<std::vector<double>> weights;  // one per morph target of the node's mesh
};

// The poses of every animated node at `time` seconds, by node index. Throws Error(path, ...)
// naming the animation, channel or sampler for anything malformed: a missing sampler or node, an
// unknown path or interpolation, input times not strictly increasing, outputs of the wrong type
// or count, weights on a node whose mesh has no morph targets, an animated node with a matrix.
std::map<size_t, NodePose> animatedPoses(const tinygltf::Model& model, const std::string& path, double time);

}  // namespace punctual::gltf_detail
