#pragma once
// glTF 2.0 node animation, played on the flattened scene: the loader keeps what moves (the node
// hierarchy's rest transforms, the animation channels, and the mesh-space vertices of the primitives
// under an animated node), and poseScene moves the scene's vertices, punctual lights and cameras to
// where they are at a time. Rigid node transforms only: skins and morph targets are not played (the
// loader warns). Memory follows what moves: a scene without animation keeps none of this.
//
// Sampling follows the glTF 2.0 specification, Appendix C ("Animation Sampler Interpolation Modes"):
// STEP holds key k over [t_k, t_k+1); LINEAR interpolates, rotations by spherical linear interpolation
// along the shorter arc; CUBICSPLINE is the cubic Hermite spline through the values with the file's
// tangents scaled by the key interval (rotations normalised after it). Before the first key a channel
// holds its first value, after the last its last.

#include <cstdint>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <vector>

namespace lgh {

struct Scene;

enum class AnimationPath { Translation, Rotation, Scale };
enum class Interpolation { Step, Linear, CubicSpline };

struct AnimationChannel {
  int node = -1;  // index into SceneAnimation::nodes (the file's node index)
  AnimationPath path = AnimationPath::Translation;
  Interpolation interpolation = Interpolation::Linear;
  std::vector<float> times;  // seconds, strictly increasing, at least one
  // One per time (CubicSpline: three per time, in-tangent, value, out-tangent). Translation and scale
  // in xyz; rotation a unit quaternion as glTF stores it, (x, y, z, w).
  std::vector<glm::vec4> keys;
};

// The channel's value at `time`: xyz for translation and scale, a unit quaternion (x, y, z, w) for rotation.
glm::vec4 sampleChannel(const AnimationChannel& channel, double time);

// A node's transform before animation: translation, rotation, scale, or a matrix (never animated:
// glTF forbids animating a node with a matrix).
struct RigNode {
  int parent = -1;
  glm::dvec3 translation{0.0};
  glm::dquat rotation{1.0, 0.0, 0.0, 0.0};
  glm::dvec3 scale{1.0};
  bool hasMatrix = false;
  glm::dmat4 matrix{1.0};
  bool moves = false;  // the node or one of its ancestors is animated
};

// The vertices of one primitive under a moving node: Scene vertices [firstVertex, firstVertex + count),
// in the node's mesh space.
struct MovingPrimitive {
  int node = -1;
  std::uint32_t firstVertex = 0, vertexCount = 0;
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  // empty: flat shading (3 vertices a triangle, face normals recomputed)
};

struct SceneAnimation {
  std::vector<RigNode> nodes;  // every node of the file (empty without animation)
  std::vector<AnimationChannel> channels;
  double start = 0.0, end = 0.0;  // the channels' time range, seconds
  std::vector<MovingPrimitive> primitives;
  std::vector<int> lightNodes, cameraNodes;  // the node of Scene::lights[i] and of Scene::cameras[i]

  bool empty() const { return channels.empty(); }
  // Node `node` (a file's node index; -1: none) or one of its ancestors is animated.
  bool moves(int node) const { return node >= 0 && size_t(node) < nodes.size() && nodes[size_t(node)].moves; }
  // Scene::lights[i] rides a moving node (lights added after loading ride none).
  bool carriesLight(size_t i) const { return i < lightNodes.size() && moves(lightNodes[i]); }
  // Every node's world transform at `time` (rest transforms with the channels' values in place).
  std::vector<glm::dmat4> worldTransforms(double time) const;
};

// What poseScene moved (what it set to the value it had is not counted: a still stretch keeps the history).
struct PoseChange {
  bool geometry = false;       // vertex positions and normals
  std::vector<size_t> lights;  // indices into Scene::lights
  bool cameras = false;
  void merge(const PoseChange& other);
};

// Moves the scene's moving vertices, lights and cameras to where the animation has them at `time`.
// Without animation it changes nothing.
PoseChange poseScene(Scene& scene, double time);

// The node transform's position and -Z axis in scene space (world minus `origin`); false where the
// axis is degenerate (a zero scale), leaving the outputs as they were.
bool lightPlacement(const glm::dmat4& world, const glm::dvec3& origin, glm::vec3& position, glm::vec3& direction);
// A camera's position and orthonormal orientation (right, up, back) from its node transform, the view
// along -Z and the up vector orthogonalised against it; false where the transform is degenerate.
bool cameraPlacement(const glm::dmat4& world, const glm::dvec3& origin, glm::vec3& position, glm::mat3& orientation);

}  // namespace lgh
