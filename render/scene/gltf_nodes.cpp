#include "render/scene/gltf_nodes.h"

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "render/scene/gltf_checks.h"

namespace lgh::gltf {
namespace {

glm::dmat4 localTransform(const tinygltf::Model& model, size_t i) {
  const tinygltf::Node& node = model.nodes[i];
  glm::dmat4 m(1.0);
  for (const std::vector<double>* values : {&node.matrix, &node.translation, &node.rotation, &node.scale})
    for (double v : *values)
      if (!fitsFloat(v))
        fail(nodeLabel(model, i) + " has a transform number " + number(v) +
             " that is not a finite float (NaN, Inf or beyond 3.4e38)");
  if (!node.matrix.empty()) {
    if (!node.translation.empty() || !node.rotation.empty() || !node.scale.empty())
      fail(nodeLabel(model, i) + " has both a matrix and translation/rotation/scale (glTF allows one or the other)");
    if (node.matrix.size() != 16)
      fail(nodeLabel(model, i) + " has a matrix with " + std::to_string(node.matrix.size()) + " numbers, expected 16");
    m = glm::make_mat4(node.matrix.data());  // both column-major
    // A node matrix must be an affine TRS: a projective bottom row would be silently dropped.
    if (m[0][3] != 0.0 || m[1][3] != 0.0 || m[2][3] != 0.0 || m[3][3] != 1.0)
      fail(nodeLabel(model, i) +
           " has a matrix whose last row is not (0, 0, 0, 1): not decomposable to translation/rotation/scale");
  } else {
    auto check = [&](const std::vector<double>& v, size_t n, const char* what) {
      if (!v.empty() && v.size() != n)
        fail(nodeLabel(model, i) + " has a " + what + " with " + std::to_string(v.size()) + " numbers, expected " +
             std::to_string(n));
      return !v.empty();
    };
    if (check(node.translation, 3, "translation"))
      m = glm::translate(m, glm::dvec3(node.translation[0], node.translation[1], node.translation[2]));
    if (check(node.rotation, 4, "rotation")) {
      glm::dquat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);  // glTF: x, y, z, w
      const double length = glm::length(q);
      if (!(length > 0.0) || !std::isfinite(length))
        fail(nodeLabel(model, i) + " has a zero or non-finite rotation quaternion");
      m *= glm::mat4_cast(q / length);  // exporters round; renormalise instead of shearing
    }
    if (check(node.scale, 3, "scale")) m = glm::scale(m, glm::dvec3(node.scale[0], node.scale[1], node.scale[2]));
  }
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) fail(nodeLabel(model, i) + " has a non-finite (NaN or Inf) transform");
  return m;
}

}  // namespace

std::string nodeLabel(const tinygltf::Model& model, size_t i) { return label("node", i, model.nodes[i].name); }

SceneNodes displayedNodes(const tinygltf::Model& model) {
  const size_t n = model.nodes.size();
  std::vector<int> parent(n, -1);
  for (size_t i = 0; i < n; ++i) {
    for (int child : model.nodes[i].children) {
      if (child < 0 || size_t(child) >= n)
        fail(nodeLabel(model, i) + " has child " + std::to_string(child) + ", but the file has " + std::to_string(n) +
             " nodes");
      if (size_t(child) == i) fail("node hierarchy has a cycle: " + nodeLabel(model, i) + " is its own child");
      if (parent[child] >= 0)
        fail("node hierarchy is not a tree: " + nodeLabel(model, child) + " is a child of both " +
             nodeLabel(model, parent[child]) + " and " + nodeLabel(model, i));
      parent[child] = int(i);
    }
  }
  // With one parent per node, a cycle is a chain of parent links that never reaches a root.
  std::vector<char> state(n, 0);  // 0 = unvisited, 1 = on the current chain, 2 = reaches a root
  std::vector<int> chain;
  for (size_t i = 0; i < n; ++i) {
    chain.clear();
    int j = int(i);
    while (j >= 0 && state[j] == 0) {
      state[j] = 1;
      chain.push_back(j);
      j = parent[j];
    }
    if (j >= 0 && state[j] == 1) fail("node hierarchy has a cycle through " + nodeLabel(model, j));
    for (int k : chain) state[k] = 2;
  }

  std::vector<int> roots;
  if (!model.scenes.empty()) {
    const int s = model.defaultScene >= 0 ? model.defaultScene : 0;
    if (size_t(s) >= model.scenes.size())
      fail("the default scene is " + std::to_string(s) + ", but the file has " + std::to_string(model.scenes.size()) +
           " scenes");
    roots = model.scenes[s].nodes;
    for (int r : roots) {
      if (r < 0 || size_t(r) >= n)
        fail("scene " + std::to_string(s) + " lists node " + std::to_string(r) + ", but the file has " +
             std::to_string(n) + " nodes");
      if (parent[r] >= 0)
        fail("scene " + std::to_string(s) + " lists " + nodeLabel(model, r) + ", which is a child of " +
             nodeLabel(model, parent[r]) + " (scene nodes must be roots)");
    }
  } else {  // no scenes: show every root node
    for (size_t i = 0; i < n; ++i)
      if (parent[i] < 0) roots.push_back(int(i));
  }

  SceneNodes out;
  out.world.assign(n, glm::dmat4(1.0));
  std::vector<char> visited(n, 0);
  std::vector<int> stack(roots.rbegin(), roots.rend());
  for (int r : roots) out.world[r] = localTransform(model, r);
  while (!stack.empty()) {
    const int i = stack.back();
    stack.pop_back();
    if (visited[i]) fail("scene lists " + nodeLabel(model, i) + " more than once");
    visited[i] = 1;
    out.drawOrder.push_back(i);
    const auto& children = model.nodes[i].children;
    for (auto it = children.rbegin(); it != children.rend(); ++it) {
      out.world[*it] = out.world[i] * localTransform(model, *it);
      stack.push_back(*it);
    }
  }
  return out;
}

}  // namespace lgh::gltf
