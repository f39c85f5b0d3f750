#pragma once
// The parsed glTF document a Scene keeps (shared, immutable) so that Scene::at(t) re-poses
// nodes without reading any file again: validated geometry in each mesh's own frame, the
// node hierarchy with its rest transforms, cameras, lights and animations.

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <string>
#include <vector>

#include "giq/scenes/scene.h"

namespace giq::scenes {

// One glTF primitive expanded to triangles, in its mesh's frame.
struct PrimitiveSource {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  // empty: flat normals are generated when posed
  std::vector<glm::vec4> tangents;
  std::vector<glm::vec2> uvs, uvs2;  // Mesh::uvs, Mesh::uvs2
  std::vector<glm::vec4> colors;  // COLOR_0; empty: white
  std::vector<glm::uvec3> triangles;  // degenerate ones are dropped when posed
  size_t collapsed_triangles = 0;     // dropped when loaded: two equal corners, no area in any pose
  int material = 0;                   // index into Scene::materials
  bool dropped = false;               // points or lines: no Mesh is made from it
};

struct NodeSource {
  std::string name;  // as in the file ("" when unnamed)
  int parent = -1;
  std::vector<int> children;
  bool has_matrix = false;
  glm::dmat4 matrix{1.0};
  glm::dvec3 translation{0.0};
  glm::dquat rotation{1.0, 0.0, 0.0, 0.0};
  glm::dvec3 scale{1.0};
  int mesh = -1;
  int camera = -1;
  int light = -1;
  // EXT_mesh_gpu_instancing: the mesh is drawn once per matrix, in the node's frame; empty =
  // once, untransformed.
  std::vector<glm::dmat4> instances;
  size_t instance_count() const { return instances.empty() ? 1 : instances.size(); }
};

enum class Interpolation { Step, Linear, CubicSpline };
enum class AnimatedPath { Translation, Rotation, Scale };

// One animation channel with its sampler's keys (glTF 2.0 spec, 3.11 "Animations").
struct ChannelSource {
  int node = -1;
  AnimatedPath path = AnimatedPath::Translation;
  Interpolation interpolation = Interpolation::Linear;
  std::vector<double> times;       // strictly increasing
  std::vector<glm::dvec4> values;  // per key; CUBICSPLINE: in-tangent, value, out-tangent per key
  // Rotation quaternions are stored (x, y, z, w) as in the file.
};

struct AnimationSource {
  std::string name;
  std::vector<ChannelSource> channels;
  double end = 0.0;  // last key time over all channels
};

struct CameraSource {
  std::string name;
  float yfov = 0.0f;
  float ymag = 0.0f;  // > 0: orthographic (Camera::ymag), in the camera node's units
  float znear = 0.01f;
  float zfar = 0.0f;
};

struct SceneSource {
  std::string file;  // for messages
  std::vector<NodeSource> nodes;
  std::vector<int> roots;  // nodes of the displayed glTF scene, in file order
  std::vector<std::vector<PrimitiveSource>> meshes;
  std::vector<CameraSource> cameras;
  std::vector<Light> lights;  // as declared (unposed); name, type, colour, intensity, range, cones
  std::vector<AnimationSource> animations;
  std::vector<View> extra_views;  // views from extras, already in the local frame
};

// Value of one channel at time t (seconds), clamped to its first and last keys.
glm::dvec4 evaluate(const ChannelSource& channel, double t);

// World transform of every node at time t with animation `animation` playing (-1: rest pose).
std::vector<glm::dmat4> world_transforms(const SceneSource& src, int animation, double t);

// Throws InputError when the scene instances more triangles than giq can hold.
void check_instanced_size(const SceneSource& src);

// World-space bounds (double) of every instantiated mesh vertex; lo > hi when there is none.
void world_bounds(const SceneSource& src, const std::vector<glm::dmat4>& world, glm::dvec3& lo, glm::dvec3& hi);

// Fills out.meshes, out.lights and out.views (camera nodes, then extra_views) and
// out.stats.degenerate_triangles_dropped from the posed nodes, relative to out.origin.
void pose(const SceneSource& src, const std::vector<glm::dmat4>& world, Scene& out);

}  // namespace giq::scenes
