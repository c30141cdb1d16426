#pragma once
// The file's animations read into a SceneAnimation (animation.h): the node hierarchy's rest transforms
// and every channel, validated. Internal to the loader (gltf_loader.cpp); problems are thrown as
// gltf::FileProblem (gltf_checks.h), what the renderer cannot play is a warning.
#include <tiny_gltf.h>

#include <string>
#include <vector>

#include "render/scene/animation.h"

namespace lgh::gltf {

// Every animation of the file, played together (a file's animations usually move different nodes;
// where two move the same node's same property, the later one wins, with a warning). Fails on what
// the glTF 2.0 specification forbids: a sampler or node index out of range, an unknown path or
// interpolation, input times that are not SCALAR FLOAT, not finite or not strictly increasing, outputs
// whose type or count does not match the path and the interpolation, non-finite keys, a zero rotation
// key, an animated node with a matrix, two channels of one animation on one node's same property.
// Returns an empty SceneAnimation when nothing is played. The hierarchy must have passed
// displayedNodes' checks (a forest of valid indices).
SceneAnimation readAnimations(const tinygltf::Model& model, std::vector<std::string>& warnings);

}  // namespace lgh::gltf
