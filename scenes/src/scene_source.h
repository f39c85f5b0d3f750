#pragma once
// The parsed glTF document a Scene keeps (shared, immutable) so that Scene::at(t) re-poses
// nodes without reading any file again: validated geometry in each mesh's own frame, the
// node hierarchy with its rest transforms, cameras, lights and animations.

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <memory>
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
  // Morph targets and skin joints (glTF 2.0 spec, 3.7.2.2 and 3.7.3), with a copy of the rest
  // vertices that renderers deforming on their own read (Mesh::deformation); null for a rigid
  // primitive. Joint indices are into the node's skin's joints.
  std::shared_ptr<const DeformationRest> deformation;
};

// glTF 2.0 spec, 3.7.3 "Skins": joint nodes and their inverse bind matrices (identity when the
// file gives none).
struct SkinSource {
  std::vector<int> joints;
  std::vector<glm::dmat4> inverse_bind;
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
  int skin = -1;
  // Morph target weights of the node's mesh at rest: node.weights, else mesh.weights, else
  // zeros (glTF 2.0 spec, 3.7.2.2); one per target.
  std::vector<double> weights;
  int camera = -1;
  int light = -1;
  // EXT_mesh_gpu_instancing: the mesh is drawn once per matrix, in the node's frame; empty =
  // once, untransformed.
  std::vector<glm::dmat4> instances;
  size_t instance_count() const { return instances.empty() ? 1 : instances.size(); }
};

enum class Interpolation { Step, Linear, CubicSpline };
enum class AnimatedPath { Translation, Rotation, Scale, Weights };

// One animation channel with its sampler's keys (glTF 2.0 spec, 3.11 "Animations").
struct ChannelSource {
  int node = -1;
  AnimatedPath path = AnimatedPath::Translation;
  Interpolation interpolation = Interpolation::Linear;
  std::vector<double> times;  // strictly increasing
  // `width` numbers per key (CUBICSPLINE: in-tangent, value, out-tangent per key): 3 for a
  // translation or scale, 4 for a rotation quaternion stored (x, y, z, w) as in the file, one
  // per morph target for weights.
  int width = 3;
  std::vector<double> values;
  // Whether the channel's values are not all equal (it moves something).
  bool varies() const;
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
  std::vector<SkinSource> skins;
  std::vector<AreaShape> area_shapes;  // per mesh, declared in its extras
  std::vector<CameraSource> cameras;
  std::vector<Light> lights;  // as declared (unposed); name, type, colour, intensity, range, cones
  std::vector<AnimationSource> animations;
  std::vector<View> extra_views;  // views from extras, already in the local frame
};

// Value of one channel at time t (seconds), clamped to its first and last keys: `width`
// numbers.
std::vector<double> evaluate(const ChannelSource& channel, double t);

// The animated state of every node at time t with animation `animation` playing (-1: rest
// pose): world transforms, and the morph target weights of nodes with meshes.
struct NodePose {
  std::vector<glm::dmat4> world;
  std::vector<std::vector<double>> weights;
};
NodePose pose_nodes(const SceneSource& src, int animation, double t);

// Throws InputError when the scene instances more triangles than giq can hold.
void check_instanced_size(const SceneSource& src);

// World-space bounds (double) of every instantiated mesh vertex, skinned and morphed; lo > hi
// when there is none.
void world_bounds(const SceneSource& src, const NodePose& nodes, glm::dvec3& lo, glm::dvec3& hi);

// Fills out.meshes, out.lights and out.views (camera nodes, then extra_views) and
// out.stats.degenerate_triangles_dropped from the posed nodes, relative to out.origin.
// `was`: the nodes out.meshes were posed with (they are a pose of the same source, the
// particles' meshes after them); a mesh whose node's world transform is the same in both,
// and that neither skin nor morph targets deform, is then kept as it is instead of emitted
// anew, which gives the same mesh (emitting depends on nothing else).
void pose(const SceneSource& src, const NodePose& nodes, Scene& out, const NodePose* was = nullptr);

}  // namespace giq::scenes
