#pragma once
// The scene model every renderer reads: a glTF 2.0 file posed at one instant, flattened to
// world-space triangles in a local frame, plus the toolkit's extras (views, sequence,
// leak regions, environment). See docs/scene-format.md for the extras schema and units.
//
// A Scene is a value: renderers only read it; Scene::at(t) returns the scene posed at another
// time. Tests may also build one in code: fill the content fields, then call derive().

#include <algorithm>
#include <filesystem>
#include <glm/glm.hpp>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "giq/scenes/camera.h"
#include "giq/scenes/features.h"
#include "giq/scenes/light.h"
#include "giq/scenes/material.h"
#include "giq/scenes/mesh.h"
#include "giq/scenes/particles.h"
#include "giq/scenes/texture.h"

namespace giq::scenes {

struct Bounds {
  glm::vec3 lo{std::numeric_limits<float>::infinity()};
  glm::vec3 hi{-std::numeric_limits<float>::infinity()};
  void extend(glm::vec3 p) { lo = glm::min(lo, p), hi = glm::max(hi, p); }
  bool empty() const { return lo.x > hi.x; }
  glm::vec3 extent() const { return empty() ? glm::vec3(0.0f) : hi - lo; }
  // The origin for an empty box, so that nothing derived from it is NaN.
  glm::vec3 centre() const { return empty() ? glm::vec3(0.0f) : 0.5f * (lo + hi); }
  // The diagonal's length, at least 1e-6, so that lengths scaled from it never vanish.
  float diagonal() const { return std::max(glm::length(extent()), 1e-6f); }
  // The largest side, at least 1e-6.
  float largest_side() const {
    const glm::vec3 e = extent();
    return std::max(std::max(e.x, std::max(e.y, e.z)), 1e-6f);
  }
};

// A view of all of a box: the eye in front of it (+z) and 20 degrees above its centre, far
// enough that its bounding sphere fits a vertical field of view of `yfov` radians with 5 % to
// spare. How `--camera auto` frames a scene nobody gave a view for.
struct Framing {
  glm::dvec3 eye{0.0}, target{0.0};
};
Framing frame_bounds(const Bounds& b, double yfov);

// Frames of a sequence: frame f shows the scene at time f / fps.
struct Sequence {
  int frames = 1;
  double fps = 30.0;
  int animation = -1;  // glTF animation that plays; -1 = none
  // What the scene declares for the temporal metrics (docs/metrics.md), so that every command
  // measures them over the same frames: the frame of its step change (lag's t0), and the
  // frames, first and last, over which flicker and lag are measured. The scene's author knows
  // what else moves: in a scene whose other content keeps moving after the step, a lag window
  // over every frame would measure that motion's drift rather than the response to the step.
  std::optional<int> step_frame;
  std::optional<std::pair<int, int>> flicker_frames, lag_frames;
};

// An emissive triangle as an area light; the reference picks these by power.
struct EmissiveTriangle {
  uint32_t mesh = 0;      // index into Scene::meshes
  uint32_t triangle = 0;  // index into that mesh's triangles
  float area = 0.0f;
  glm::vec3 radiance{0.0f};  // mean emitted radiance over the triangle (texture and coverage averaged: Scene::mean_emitted)
  float power = 0.0f;        // pi * area * luminance(radiance), times 2 when double-sided
};

// An emissive mesh as one area light: what the real-time passes shade and shadow as a unit (the
// reference samples its triangles one by one). Derived once from the emissive triangles.
struct AreaLight {
  uint32_t mesh = 0;                    // index into Scene::meshes
  std::vector<uint32_t> triangles;      // indices into Scene::emissive_triangles, in order
  bool two_sided = false;               // the material is double-sided
  float area = 0.0f;                    // sum of the triangles' areas
  glm::vec3 centroid{0.0f};             // area-weighted
  glm::vec3 intensity{0.0f};            // sum of radiance x area: W/sr along the normal of a flat emitter
  bool flat = false;                    // the triangles' area vectors do not cancel
  glm::vec3 normal{0.0f, -1.0f, 0.0f};  // unit mean normal (their area vectors' sum); -y when they cancel
  // Where the mesh is shadowed and seen from as a point: the centroid, moved 1e-4 of the
  // scene's diagonal in front of a one-sided flat emitter so that the emitter does not
  // shadow itself.
  glm::vec3 representative{0.0f};
  // For a closed emitter (not flat: its centroid is inside it), the radius of the sphere
  // around `representative` that holds the mesh, where rays towards that point must stop so
  // that the emitter does not shadow itself; 0 for a flat one.
  float extent = 0.0f;
  // The declared shape (Mesh::area_shape) fitted to the posed triangles (area_shape.cpp):
  // centre; sphere, disc and tube radius; a rectangle's two half-side vectors u and v; a disc's
  // unit normal v; a tube's half segment u (a capsule: the segment centre +- u, swept by the
  // radius). A disc or a rectangle that is not flat falls back to `Mesh`.
  AreaShape shape = AreaShape::Mesh;
  glm::vec3 shape_centre{0.0f};
  glm::vec3 shape_u{0.0f}, shape_v{0.0f};
  float shape_radius = 0.0f;
};

// Fits light `l`'s declared shape to its mesh's emissive triangles (the fields above).
void fit_area_shape(const Mesh& mesh, const std::vector<EmissiveTriangle>& emissive, AreaLight& l);

struct SceneStats {
  size_t triangles = 0;
  size_t vertices = 0;
  size_t degenerate_triangles_dropped = 0;  // zero-area or non-finite triangles in the file
  double total_light_power = 0.0;           // luminance-weighted, emissive + punctual (rough)
};

struct SceneSource;  // the parsed glTF document kept to pose the scene at other times

// How a posed scene holds its emitters' particles. Placed: each an octahedron of the stage
// mesh, the triangles the reference renders. Counted: each stage mesh holds its particle count
// (Mesh::particles) and no vertex, for a renderer that places the particles itself (the
// real-time module's GPU simulation): posing a million particles then costs nothing, and the
// scene lists no emissive triangle of theirs. A counted stage's area light has its area and
// intensity but sits at the emitting surface's centre with no extent, and the bounds leave the
// particles out, until that renderer completes them from where it placed them
// (realtime::SceneGpu::complete).
enum class ParticleDetail { Placed, Counted };

class Scene {
 public:
  // --- provenance
  std::filesystem::path path;  // empty for a scene built in code
  std::string content_hash;    // hash of the glTF and every file it references
  // What the file holds that giq dropped or approximated (points and lines, optional
  // extensions it ignores), one line each with the glTF path; commands print them and
  // `giq scene info` lists them.
  std::vector<std::string> warnings;
  // World position of the local frame every position below is relative to. Chosen at load
  // (the centre of the scene's bounds at t = 0, computed in double precision) and kept for
  // all times, so geometry far from the world origin keeps full float precision.
  glm::dvec3 origin{0.0};

  // --- content at this instant
  double time = 0.0;
  std::vector<Mesh> meshes;
  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::vector<Light> lights;
  // Environment radiance: constant, or from the equirectangular map textures[environment_map]
  // (RGB radiance, nearest texel: scenes/environment.h), whose mean over the sphere is then
  // `environment` (the power estimate of renderers' light selection). 0 and -1 = none.
  glm::vec3 environment{0.0f};
  int environment_map = -1;
  std::vector<View> views;      // glTF camera nodes first, then the views from extras
  Sequence sequence;
  // Particle emitters declared in extras (particles.h): their particles alive at this instant
  // are meshes at the end of `meshes` (Mesh::emitter), made anew by at(t).
  std::vector<Emitter> emitters;
  std::vector<std::string> leak_regions;  // node names declared in extras
  std::vector<uint32_t> leak_object_ids;  // their object ids (Mesh::object_id)

  // --- derived by derive(); do not edit
  FeatureSet features;
  std::vector<EmissiveTriangle> emissive_triangles;
  // One per mesh with emissive triangles, in mesh order, and one per glowing stage of life of
  // an emitter's particles (AreaLight::area 0 when the stage has none at this instant).
  std::vector<AreaLight> area_lights;
  Bounds bounds;
  SceneStats stats;

  // Recomputes features, emissive triangles, area lights, bounds and stats from the content.
  void derive();

  // The scene posed at time t in seconds (animations evaluated, lights and cameras moved).
  // Same origin, materials and textures. For a scene without animation, a copy.
  Scene at(double t, ParticleDetail particles = ParticleDetail::Placed) const;
  // The same into `into`, a scene posed before (not this one), whose arrays are reused: a
  // renderer posing a large file frame after frame copies it instead of allocating it anew
  // (fresh pages, which the kernel hands out one fault at a time).
  void at(double t, ParticleDetail particles, Scene& into) const;
  Scene at_frame(int frame, ParticleDetail particles = ParticleDetail::Placed) const { return at(frame / sequence.fps, particles); }
  double duration() const;  // of the playing animation; 0 when static

  // Coverage (Material::coverage) of mesh m's triangle t at barycentrics (b1, b2): its
  // material's baseColorFactor.a times the base colour texture's alpha (with UVs) times
  // COLOR_0's alpha, through the alpha mode.
  float coverage(const Mesh& m, const glm::uvec3& t, float b1, float b2) const;

  // Mean radiance emitted over triangle t of mesh m, times its coverage (alpha modes);
  // EmissiveTriangle::radiance. At most (2 max_half_k)^2 lookups.
  glm::vec3 mean_emitted(const Mesh& m, const glm::uvec3& t, int max_half_k = 32) const;

  // Radiance arriving from direction `dir` (unit, pointing away from the scene).
  glm::vec3 environment_radiance(glm::vec3 dir) const;

  // A view by name, or by index when `name_or_index` is a number; throws InputError naming
  // the available views when there is no such view.
  const View& view(std::string_view name_or_index) const;

  // Light and views given from outside the file (the command line's --sun, --env, --camera),
  // in the local frame. They stay through at(t), after the file's own lights and views. A
  // light or an environment changes what the scene looks like, so it also changes
  // content_hash, which then names the scene as rendered (`description` says what was added,
  // e.g. "sun dir=0,-1,0 illuminance=3"); a view does not.
  void add_light(const Light& light, const std::string& description);
  void set_environment(glm::vec3 radiance, const std::string& description);
  // An equirectangular map of RGB radiance (rows top first, width x height, finite and not
  // negative) replacing the environment; the caller validates the pixels.
  void set_environment_map(int width, int height, const std::vector<glm::vec3>& radiance, const std::string& description);
  void add_view(const View& view);
  const std::vector<Light>& added_lights() const { return added_lights_; }
  const std::vector<View>& added_views() const { return added_views_; }

 private:
  void derive_area_lights();
  friend Scene load(const std::filesystem::path&);
  std::shared_ptr<const SceneSource> source_;
  std::vector<Light> added_lights_;
  std::vector<View> added_views_;
};

// Loads a .gltf or .glb file. Throws InputError (file, glTF path, what was expected) for
// anything malformed, hostile or unsupported; never crashes on bad input.
Scene load(const std::filesystem::path& path);

}  // namespace giq::scenes
