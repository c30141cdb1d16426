#include "render/scene/gltf_animation.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <utility>

#include "render/scene/gltf_accessors.h"
#include "render/scene/gltf_checks.h"
#include "render/scene/gltf_nodes.h"

namespace lgh::gltf {
namespace {

// The rest transform of every node and its parent.
std::vector<RigNode> restNodes(const tinygltf::Model& model) {
  std::vector<RigNode> nodes(model.nodes.size());
  for (size_t i = 0; i < model.nodes.size(); ++i) {
    const tinygltf::Node& src = model.nodes[i];
    RigNode& node = nodes[i];
    for (int child : src.children) nodes[size_t(child)].parent = int(i);
    if (!src.matrix.empty()) {
      node.hasMatrix = true;
      for (int k = 0; k < 16; ++k) node.matrix[k / 4][k % 4] = src.matrix[size_t(k)];  // both column-major
      continue;
    }
    if (src.translation.size() == 3) node.translation = {src.translation[0], src.translation[1], src.translation[2]};
    if (src.rotation.size() == 4) {
      const glm::dquat q(src.rotation[3], src.rotation[0], src.rotation[1], src.rotation[2]);
      node.rotation = q / glm::length(q);  // displayedNodes rejected a zero quaternion
    }
    if (src.scale.size() == 3) node.scale = {src.scale[0], src.scale[1], src.scale[2]};
  }
  return nodes;
}

struct PathInfo {
  AnimationPath path;
  int components;
};

// The sampler's keys as the channel's path needs them: the input times and the output values, checked.
AnimationChannel readChannel(const tinygltf::Model& model, const tinygltf::AnimationSampler& sampler,
                             const PathInfo& target, const std::string& what) {
  AnimationChannel channel;
  channel.path = target.path;
  if (sampler.interpolation == "LINEAR")
    channel.interpolation = Interpolation::Linear;
  else if (sampler.interpolation == "STEP")
    channel.interpolation = Interpolation::Step;
  else if (sampler.interpolation == "CUBICSPLINE")
    channel.interpolation = Interpolation::CubicSpline;
  else
    fail(what + " has interpolation '" + sampler.interpolation + "' (expected LINEAR, STEP or CUBICSPLINE)");

  const tinygltf::Accessor& input = accessor(model, sampler.input, what + " input");
  if (input.type != TINYGLTF_TYPE_SCALAR || input.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT || input.normalized)
    fail(what + " input (accessor " + std::to_string(sampler.input) + ") is " + typeName(input.type) + " " +
         componentTypeName(input.componentType) + "; glTF requires SCALAR FLOAT times");
  for (const glm::vec1& t : readAccessor<1>(model, sampler.input, what + " input")) channel.times.push_back(t.x);
  const bool cubic = channel.interpolation == Interpolation::CubicSpline;
  if (channel.times.empty() || (cubic && channel.times.size() < 2))
    fail(what + " input has " + std::to_string(channel.times.size()) + " times; " + sampler.interpolation +
         " needs at least " + (cubic ? "2" : "1"));
  for (size_t k = 0; k < channel.times.size(); ++k) {
    if (!std::isfinite(channel.times[k]))
      fail(what + " input time " + std::to_string(k) + " is not finite (NaN or Inf)");
    if (k > 0 && !(channel.times[k] > channel.times[k - 1]))
      fail(what + " input times are not strictly increasing: time " + std::to_string(k) + " is " +
           number(channel.times[k]) + " after " + number(channel.times[k - 1]));
  }

  const tinygltf::Accessor& output = accessor(model, sampler.output, what + " output");
  const bool rotation = target.path == AnimationPath::Rotation;
  const bool floats = output.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT && !output.normalized;
  const bool normalizedInts = output.normalized && (output.componentType == TINYGLTF_COMPONENT_TYPE_BYTE ||
                                                    output.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                                    output.componentType == TINYGLTF_COMPONENT_TYPE_SHORT ||
                                                    output.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
  if (componentCount(output.type) != target.components || !(floats || (rotation && normalizedInts)))
    fail(what + " output (accessor " + std::to_string(sampler.output) + ") is " + typeName(output.type) + " " +
         (output.normalized ? "normalized " : "") + componentTypeName(output.componentType) + "; glTF allows " +
         (rotation ? "VEC4 FLOAT or normalized BYTE, UNSIGNED_BYTE, SHORT, UNSIGNED_SHORT for rotation"
                   : "VEC3 FLOAT for translation and scale"));
  if (rotation)
    channel.keys = readAccessor<4>(model, sampler.output, what + " output");
  else
    for (const glm::vec3& v : readAccessor<3>(model, sampler.output, what + " output"))
      channel.keys.push_back(glm::vec4(v, 0.0f));
  const size_t expected = channel.times.size() * (cubic ? 3 : 1);
  if (channel.keys.size() != expected)
    fail(what + " output has " + std::to_string(channel.keys.size()) + " values for " +
         std::to_string(channel.times.size()) + " times; " + sampler.interpolation + " needs " +
         std::to_string(expected));
  for (size_t k = 0; k < channel.keys.size(); ++k) {
    const glm::vec4& v = channel.keys[k];
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z) || !std::isfinite(v.w))
      fail(what + " output value " + std::to_string(k) + " is not finite (NaN or Inf)");
    // A rotation value (not a tangent) must be a quaternion that can be normalised.
    if (rotation && (!cubic || k % 3 == 1) && !(glm::length(glm::dvec4(v)) > 0.0))
      fail(what + " output value " + std::to_string(k) + " is a zero quaternion, which is no rotation");
  }
  return channel;
}

}  // namespace

SceneAnimation readAnimations(const tinygltf::Model& model, std::vector<std::string>& warnings) {
  SceneAnimation animation;
  if (!model.skins.empty())
    warnings.push_back(std::to_string(model.skins.size()) +
                       " skins are not played: skinned meshes are drawn as their nodes place them, unposed");
  size_t morphed = 0;
  for (const tinygltf::Mesh& mesh : model.meshes)
    for (const tinygltf::Primitive& p : mesh.primitives) morphed += p.targets.empty() ? 0 : 1;
  if (morphed > 0)
    warnings.push_back(std::to_string(morphed) +
                       " primitives have morph targets, which are not played (base shape drawn)");
  if (model.animations.empty()) return animation;

  static const std::map<std::string, PathInfo> paths = {{"translation", {AnimationPath::Translation, 3}},
                                                        {"rotation", {AnimationPath::Rotation, 4}},
                                                        {"scale", {AnimationPath::Scale, 3}}};
  std::map<std::pair<int, AnimationPath>, size_t> played;  // (node, path) -> channel index, across animations
  size_t weights = 0, overridden = 0;
  for (size_t a = 0; a < model.animations.size(); ++a) {
    const tinygltf::Animation& anim = model.animations[a];
    const std::string name = label("animation", a, anim.name);
    std::set<std::pair<int, std::string>> targets;  // of this animation
    for (size_t c = 0; c < anim.channels.size(); ++c) {
      const tinygltf::AnimationChannel& src = anim.channels[c];
      const std::string what = name + " channel " + std::to_string(c);
      if (src.sampler < 0 || size_t(src.sampler) >= anim.samplers.size())
        fail(what + " uses sampler " + std::to_string(src.sampler) + ", but the animation has " +
             std::to_string(anim.samplers.size()) + " samplers");
      if (src.target_node < 0) continue;  // glTF: a channel without a node is ignored (an extension may define it)
      if (size_t(src.target_node) >= model.nodes.size())
        fail(what + " targets node " + std::to_string(src.target_node) + ", but the file has " +
             std::to_string(model.nodes.size()) + " nodes");
      if (!targets.insert({src.target_node, src.target_path}).second)
        fail(what + ": another channel of the animation already targets the " + src.target_path + " of " +
             nodeLabel(model, size_t(src.target_node)));
      if (src.target_path == "weights") {
        ++weights;
        continue;
      }
      const auto path = paths.find(src.target_path);
      if (path == paths.end())
        fail(what + " has target path '" + src.target_path + "' (expected translation, rotation, scale or weights)");
      if (!model.nodes[size_t(src.target_node)].matrix.empty())
        fail(what + " animates " + nodeLabel(model, size_t(src.target_node)) +
             ", which has a matrix (glTF requires translation/rotation/scale on animated nodes)");
      AnimationChannel channel = readChannel(model, anim.samplers[size_t(src.sampler)], path->second,
                                             what + " sampler " + std::to_string(src.sampler));
      channel.node = src.target_node;
      const auto key = std::make_pair(channel.node, channel.path);
      if (const auto it = played.find(key); it != played.end()) {
        animation.channels[it->second] = std::move(channel);
        ++overridden;
      } else {
        played[key] = animation.channels.size();
        animation.channels.push_back(std::move(channel));
      }
    }
  }
  if (weights > 0)
    warnings.push_back(std::to_string(weights) + " animation channels of morph target weights are not played");
  if (overridden > 0)
    warnings.push_back(std::to_string(overridden) +
                       " animation channels move a node's property that an earlier animation moves; the later plays");
  if (animation.channels.empty()) return animation;

  animation.nodes = restNodes(model);
  animation.start = animation.channels.front().times.front();
  animation.end = animation.channels.front().times.back();
  for (const AnimationChannel& c : animation.channels) {
    animation.start = std::min(animation.start, double(c.times.front()));
    animation.end = std::max(animation.end, double(c.times.back()));
    animation.nodes[size_t(c.node)].moves = true;
  }
  // A node moves when an ancestor does: walk each chain up (a forest, checked by displayedNodes).
  for (size_t i = 0; i < animation.nodes.size(); ++i)
    for (int j = animation.nodes[i].parent; j >= 0 && !animation.nodes[i].moves; j = animation.nodes[size_t(j)].parent)
      animation.nodes[i].moves = animation.nodes[size_t(j)].moves;
  return animation;
}

}  // namespace lgh::gltf
