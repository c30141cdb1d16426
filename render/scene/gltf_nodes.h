#pragma once
// The node hierarchy of a glTF file's displayed scene: its nodes in drawing order and their world
// transforms. Internal to the loader (gltf_loader.cpp); problems are thrown as gltf::FileProblem
// (gltf_checks.h).
#include <tiny_gltf.h>

#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace lgh::gltf {

struct SceneNodes {
  // Per node of the file, in double so that a scene far from the origin keeps its precision until
  // the loader shifts it to scene space; identity for nodes outside the displayed scene.
  std::vector<glm::dmat4> world;
  std::vector<int> drawOrder;  // the displayed scene's nodes, depth first
};

// The nodes of the default scene (scene 0 without one; every root node when the file has no
// scenes). glTF requires the hierarchy to be a forest (one parent per node, no cycles, scene nodes
// are roots); tinygltf does not check, and a cycle would otherwise loop forever, so this fails on
// any of them, and on transforms that are not finite floats or not a translation/rotation/scale.
SceneNodes displayedNodes(const tinygltf::Model& model);

// "node 3 'lamp'", as messages name node i.
std::string nodeLabel(const tinygltf::Model& model, size_t i);

}  // namespace lgh::gltf
