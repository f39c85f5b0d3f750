// glTF 2.0 (.gltf, .glb) into the Scene model. The file's bytes are checked first
// (gltf_document.cpp), tinygltf parses them, and everything below validates the document
// against glTF 2.0 and what giq supports before a single triangle is posed.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <cstdint>
#include <glm/gtc/matrix_transform.hpp>
#include <stdexcept>

#include "giq/base/error.h"
#include "giq/scenes/scene.h"
#include "gltf_accessors.h"
#include "gltf_deformation.h"
#include "gltf_document.h"
#include "gltf_draco.h"
#include "gltf_extras.h"
#include "particle_geometry.h"
#include "gltf_materials.h"
#include "gltf_meshopt.h"
#include "scene_source.h"
#include "tangent_space.h"

namespace giq::scenes {
namespace gltf {
namespace {

bool finite_all(const std::vector<double>& v) {
  return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

// EXT_mesh_gpu_instancing: the node's mesh drawn once per instance, each placed by its own
// translation, rotation and scale in the node's frame (instance = node world x T x R x S).
void load_instances(const Context& ctx, const tinygltf::Value& e, const std::string& w, NodeSource& n) {
  const std::string ew = w + ".extensions.EXT_mesh_gpu_instancing";
  if (!e.IsObject() || !e.Has("attributes") || !e.Get("attributes").IsObject()) ctx.fail(ew + ".attributes", "missing or not an object");
  const auto& attrs = e.Get("attributes");
  auto read = [&](const char* name, const AccessorRule& rule, size_t& count) -> AccessorData {
    if (!attrs.Has(name)) return {};
    const auto& a = attrs.Get(name);
    if (!a.IsInt()) ctx.fail(ew + ".attributes." + name, "must be an accessor index");
    AccessorData d = read_accessor(ctx, a.GetNumberAsInt(), ew + ".attributes." + name, rule);
    if (count != SIZE_MAX && d.count != count)
      ctx.fail(ew + ".attributes." + name, "has " + std::to_string(d.count) + " elements; the other instance attributes have " + std::to_string(count));
    count = d.count;
    return d;
  };
  size_t count = SIZE_MAX;
  const AccessorData t = read("TRANSLATION", {{TINYGLTF_TYPE_VEC3}}, count);
  const AccessorData r = read("ROTATION", {{TINYGLTF_TYPE_VEC4}, true, false, true}, count);
  const AccessorData s = read("SCALE", {{TINYGLTF_TYPE_VEC3}}, count);
  if (count == SIZE_MAX) ctx.fail(ew + ".attributes", "has none of TRANSLATION, ROTATION and SCALE");
  n.instances.reserve(count);
  for (size_t i = 0; i < count; ++i) {
    glm::dmat4 m(1.0);
    if (t.count) m = glm::translate(m, glm::dvec3(t.values[3 * i], t.values[3 * i + 1], t.values[3 * i + 2]));
    if (r.count) {
      const glm::dquat q(r.values[4 * i + 3], r.values[4 * i], r.values[4 * i + 1], r.values[4 * i + 2]);
      const double len = glm::length(q);
      if (!(len > 0.5 && len < 1.5)) ctx.fail(ew + ".attributes.ROTATION", "element " + std::to_string(i) + " has length " + std::to_string(len) + "; expected a unit quaternion");
      m *= glm::mat4_cast(q / len);
    }
    if (s.count) m = glm::scale(m, glm::dvec3(s.values[3 * i], s.values[3 * i + 1], s.values[3 * i + 2]));
    n.instances.push_back(m);
  }
}

void load_nodes(const Context& ctx, SceneSource& src) {
  const auto& m = ctx.model;
  src.nodes.resize(m.nodes.size());
  for (size_t i = 0; i < m.nodes.size(); ++i) {
    const auto& g = m.nodes[i];
    const std::string w = index_path("nodes", i);
    NodeSource& n = src.nodes[i];
    n.name = g.name;
    if (g.mesh >= 0 && size_t(g.mesh) >= m.meshes.size()) ctx.fail(w + ".mesh", "is " + std::to_string(g.mesh) + "; the file has " + std::to_string(m.meshes.size()) + " meshes");
    if (g.camera >= 0 && size_t(g.camera) >= m.cameras.size()) ctx.fail(w + ".camera", "is " + std::to_string(g.camera) + "; the file has " + std::to_string(m.cameras.size()) + " cameras");
    n.mesh = g.mesh, n.camera = g.camera;
    if (auto it = g.extensions.find("KHR_lights_punctual"); it != g.extensions.end()) {
      const auto& l = it->second;
      if (!l.Has("light") || !l.Get("light").IsInt()) ctx.fail(w + ".extensions.KHR_lights_punctual.light", "missing or not an integer");
      const int k = l.Get("light").GetNumberAsInt();
      if (k < 0 || size_t(k) >= m.lights.size())
        ctx.fail(w + ".extensions.KHR_lights_punctual.light", "is " + std::to_string(k) + "; the file has " + std::to_string(m.lights.size()) + " lights");
      n.light = k;
    }
    if (!g.matrix.empty()) {
      if (g.matrix.size() != 16 || !finite_all(g.matrix)) ctx.fail(w + ".matrix", "expected 16 finite numbers");
      n.has_matrix = true;
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) n.matrix[c][r] = g.matrix[size_t(4 * c + r)];  // column-major, as glTF stores it
    }
    if (!g.translation.empty()) {
      if (g.translation.size() != 3 || !finite_all(g.translation)) ctx.fail(w + ".translation", "expected 3 finite numbers");
      n.translation = {g.translation[0], g.translation[1], g.translation[2]};
    }
    if (!g.rotation.empty()) {
      if (g.rotation.size() != 4 || !finite_all(g.rotation)) ctx.fail(w + ".rotation", "expected a quaternion of 4 finite numbers");
      const glm::dquat q(g.rotation[3], g.rotation[0], g.rotation[1], g.rotation[2]);
      const double len = glm::length(q);
      if (!(len > 0.5 && len < 1.5)) ctx.fail(w + ".rotation", "has length " + std::to_string(len) + "; expected a unit quaternion");
      n.rotation = q / len;
    }
    if (!g.scale.empty()) {
      if (g.scale.size() != 3 || !finite_all(g.scale)) ctx.fail(w + ".scale", "expected 3 finite numbers");
      n.scale = {g.scale[0], g.scale[1], g.scale[2]};
    }
    n.children = g.children;
    if (auto it = g.extensions.find("EXT_mesh_gpu_instancing"); it != g.extensions.end()) load_instances(ctx, it->second, w, n);
  }
  // glTF 2.0 spec, 3.5.1: the node hierarchy is a set of disjoint trees.
  for (size_t i = 0; i < src.nodes.size(); ++i) {
    const std::string w = index_path("nodes", i) + ".children";
    for (int c : src.nodes[i].children) {
      if (c < 0 || size_t(c) >= src.nodes.size()) ctx.fail(w, "child " + std::to_string(c) + " is not a node index (the file has " + std::to_string(src.nodes.size()) + " nodes)");
      if (size_t(c) == i) ctx.fail(w, "node " + std::to_string(i) + " lists itself as a child; the node hierarchy must not have cycles");
      if (src.nodes[size_t(c)].parent >= 0)
        ctx.fail(w, "node " + std::to_string(c) + " is already a child of node " + std::to_string(src.nodes[size_t(c)].parent) + "; a node has at most one parent");
      src.nodes[size_t(c)].parent = int(i);
    }
  }
  // With at most one parent per node, a cycle is a parent chain that comes back on itself.
  // Each chain is walked once (linear time even for deep hierarchies): 0 = unvisited,
  // 1 = on the chain being walked, 2 = known to reach a root.
  std::vector<char> state(src.nodes.size(), 0);
  std::vector<int> chain;
  for (size_t i = 0; i < src.nodes.size(); ++i) {
    chain.clear();
    int k = int(i);
    while (k >= 0 && state[size_t(k)] == 0) {
      state[size_t(k)] = 1;
      chain.push_back(k);
      k = src.nodes[size_t(k)].parent;
    }
    if (k >= 0 && state[size_t(k)] == 1)
      ctx.fail(index_path("nodes", size_t(k)) + ".children", "node " + std::to_string(k) + " is its own ancestor; the node hierarchy must not have cycles");
    for (int c : chain) state[size_t(c)] = 2;
  }
  // The displayed scene: `scene`, else the first one, else every root node.
  int scene = m.defaultScene >= 0 ? m.defaultScene : (m.scenes.empty() ? -1 : 0);
  if (m.defaultScene >= 0 && size_t(m.defaultScene) >= m.scenes.size())
    ctx.fail("scene", "is " + std::to_string(m.defaultScene) + "; the file has " + std::to_string(m.scenes.size()) + " scenes");
  if (scene < 0) {
    for (size_t i = 0; i < src.nodes.size(); ++i)
      if (src.nodes[i].parent < 0) src.roots.push_back(int(i));
    return;
  }
  const std::string w = index_path("scenes", size_t(scene)) + ".nodes";
  for (int r : m.scenes[size_t(scene)].nodes) {
    if (r < 0 || size_t(r) >= src.nodes.size()) ctx.fail(w, "node " + std::to_string(r) + " is not a node index (the file has " + std::to_string(src.nodes.size()) + " nodes)");
    if (src.nodes[size_t(r)].parent >= 0) ctx.fail(w, "node " + std::to_string(r) + " is a child of node " + std::to_string(src.nodes[size_t(r)].parent) + "; scene nodes must be roots");
    if (std::find(src.roots.begin(), src.roots.end(), r) != src.roots.end()) ctx.fail(w, "node " + std::to_string(r) + " is listed twice");
    src.roots.push_back(r);
  }
}

// `w` is the primitive's path; `source` the field whose count is triangulated (indices, or
// POSITION for a non-indexed primitive).
std::vector<glm::uvec3> triangulate(const Context& ctx, int mode, const std::vector<uint32_t>& idx, const std::string& w, const std::string& source) {
  std::vector<glm::uvec3> t;
  const size_t n = idx.size();
  switch (mode) {
    case TINYGLTF_MODE_TRIANGLES:
      if (n % 3 != 0) ctx.fail(w + source, "count " + std::to_string(n) + " is not a multiple of 3 for TRIANGLES");
      for (size_t i = 0; i + 2 < n; i += 3) t.emplace_back(idx[i], idx[i + 1], idx[i + 2]);
      break;
    case TINYGLTF_MODE_TRIANGLE_STRIP:
      // glTF 2.0 spec, 3.7.2.1: triangle i is {v_i, v_(i+(1+i%2)), v_(i+(2-i%2))}.
      if (n < 3) ctx.fail(w + source, "count " + std::to_string(n) + "; a TRIANGLE_STRIP needs at least 3");
      for (size_t i = 0; i + 2 < n; ++i) t.emplace_back(idx[i], idx[i + 1 + i % 2], idx[i + 2 - i % 2]);
      break;
    case TINYGLTF_MODE_TRIANGLE_FAN:
      // glTF 2.0 spec, 3.7.2.1: triangle i is {v_(i+1), v_(i+2), v_0}.
      if (n < 3) ctx.fail(w + source, "count " + std::to_string(n) + "; a TRIANGLE_FAN needs at least 3");
      for (size_t i = 0; i + 2 < n; ++i) t.emplace_back(idx[i + 1], idx[i + 2], idx[0]);
      break;
    default:
      ctx.fail(w + ".mode", "is " + std::to_string(mode) + "; expected 0 to 6 (POINTS to TRIANGLE_FAN)");
  }
  return t;
}

bool uses_extension(const Context& ctx, const char* name) {
  const auto& used = ctx.model.extensionsUsed;
  return std::find(used.begin(), used.end(), name) != used.end();
}

// A normal-mapped primitive with normals but no TANGENT gets MikkTSpace's tangents in its
// rest pose (tangent_space.h), which skinning and morphing then carry as they carry a file's
// own. Without normals the flat normals make every triangle its own tangent frame, which the
// renderers take from the triangle's UVs.
void give_tangents(const Material& m, PrimitiveSource& p, DeformationRest& deformation) {
  const std::vector<glm::vec2>& uvs = m.uv2_slots & kNormalSlot ? p.uvs2 : p.uvs;
  if (m.normal_texture < 0 || !p.tangents.empty() || p.normals.empty() || uvs.empty()) return;
  GeneratedTangents g = generate_tangents(p.positions, p.normals, uvs, p.triangles);
  p.tangents = std::move(g.tangents);
  p.triangles = std::move(g.triangles);
  // Split vertices copy every attribute of the vertex they were split from.
  const size_t n = p.positions.size();
  auto extend = [&](auto& attribute) {
    if (attribute.empty()) return;
    attribute.resize(g.source.size());
    for (size_t i = n; i < g.source.size(); ++i) attribute[i] = attribute[g.source[i]];
  };
  extend(p.positions), extend(p.normals), extend(p.uvs), extend(p.uvs2), extend(p.colors);
  for (MorphTarget& t : deformation.targets) extend(t.positions), extend(t.normals), extend(t.tangents);
  for (auto& set : deformation.joints) extend(set);
  for (auto& set : deformation.weights) extend(set);
}

PrimitiveSource load_primitive(const Context& ctx, const tinygltf::Primitive& p, const std::string& w, std::vector<Material>& materials,
                               const std::vector<std::vector<UvMapping>>& uv_mappings, int& default_material) {
  PrimitiveSource out;
  const int mode = p.mode < 0 ? TINYGLTF_MODE_TRIANGLES : p.mode;
  if (mode >= TINYGLTF_MODE_POINTS && mode <= TINYGLTF_MODE_LINE_STRIP) {
    ctx.warn("points and lines", w + ".mode: a primitive of points or lines (mode " + std::to_string(mode) +
                                     ") was dropped; it has no surface to light or to shade");
    out.dropped = true;
    return out;
  }
  decode_draco_primitive(ctx, p, w);
  if (!ctx.decoded_accessors.empty() && mode != TINYGLTF_MODE_TRIANGLES)
    ctx.fail(w + ".mode", "is " + std::to_string(mode) + " on a Draco-compressed primitive; KHR_draco_mesh_compression holds points or TRIANGLES (4)");
  if (p.material >= 0) {
    if (size_t(p.material) >= ctx.model.materials.size())
      ctx.fail(w + ".material", "is " + std::to_string(p.material) + "; the file has " + std::to_string(ctx.model.materials.size()) + " materials");
    out.material = p.material;
  } else {
    // glTF 2.0 spec, 3.9.6 "Default Material".
    if (default_material < 0) {
      Material d;
      d.name = "default";
      materials.push_back(d);
      default_material = int(materials.size()) - 1;
    }
    out.material = default_material;
  }
  // KHR_mesh_quantization widens the component types of these attributes to 8- and 16-bit
  // integers, normalized or not (its table "Extending Mesh Attributes").
  const bool quantized = uses_extension(ctx, "KHR_mesh_quantization");
  const AccessorRule position_rule{{TINYGLTF_TYPE_VEC3}, true, quantized, quantized, false, quantized};
  const AccessorRule normal_rule{{TINYGLTF_TYPE_VEC3}, true, false, quantized};
  const AccessorRule tangent_rule{{TINYGLTF_TYPE_VEC4}, true, false, quantized};
  const AccessorRule uv_rule{{TINYGLTF_TYPE_VEC2}, true, true, quantized, false, quantized};
  auto it = p.attributes.find("POSITION");
  if (it == p.attributes.end()) ctx.fail(w + ".attributes.POSITION", "missing; every primitive needs positions");
  const AccessorData pos = read_accessor(ctx, it->second, w + ".attributes.POSITION", position_rule);
  const size_t n = pos.count;
  for (size_t i = 0; i < n; ++i) out.positions.emplace_back(pos.values[3 * i], pos.values[3 * i + 1], pos.values[3 * i + 2]);
  auto same_count = [&](const AccessorData& a, const std::string& name) {
    if (a.count != n) ctx.fail(w + ".attributes." + name, "has " + std::to_string(a.count) + " elements; POSITION has " + std::to_string(n));
  };
  if (auto a = p.attributes.find("NORMAL"); a != p.attributes.end()) {
    const AccessorData d = read_accessor(ctx, a->second, w + ".attributes.NORMAL", normal_rule);
    same_count(d, "NORMAL");
    for (size_t i = 0; i < n; ++i) out.normals.emplace_back(d.values[3 * i], d.values[3 * i + 1], d.values[3 * i + 2]);
  }
  if (auto a = p.attributes.find("TANGENT"); a != p.attributes.end()) {
    const AccessorData d = read_accessor(ctx, a->second, w + ".attributes.TANGENT", tangent_rule);
    same_count(d, "TANGENT");
    for (size_t i = 0; i < n; ++i) out.tangents.emplace_back(d.values[4 * i], d.values[4 * i + 1], d.values[4 * i + 2], d.values[4 * i + 3]);
    // glTF 2.0, 3.7.2.1: without normals "the provided tangents (if present) MUST be ignored".
    if (out.normals.empty()) out.tangents.clear();
  }
  // The UV sets the material's textures read, transformed (UvMapping): TEXCOORD_0 when they
  // say nothing.
  std::vector<UvMapping> mappings = size_t(out.material) < uv_mappings.size() ? uv_mappings[size_t(out.material)] : std::vector<UvMapping>{};
  if (mappings.empty()) mappings.push_back(UvMapping{});
  for (size_t k = 0; k < mappings.size(); ++k) {
    const UvMapping& uv = mappings[k];
    std::vector<glm::vec2>& uvs = k == 0 ? out.uvs : out.uvs2;
    const std::string uv_name = "TEXCOORD_" + std::to_string(uv.set);
    if (auto a = p.attributes.find(uv_name); a != p.attributes.end()) {
      const AccessorData d = read_accessor(ctx, a->second, w + ".attributes." + uv_name, uv_rule);
      same_count(d, uv_name);
      for (size_t i = 0; i < n; ++i) uvs.push_back(uv.apply(glm::vec2(d.values[2 * i], d.values[2 * i + 1])));
      if (std::any_of(uvs.begin(), uvs.end(), [](glm::vec2 t) { return !std::isfinite(t.x) || !std::isfinite(t.y); }))
        ctx.fail(uv.field + ".extensions.KHR_texture_transform", "maps " + w + ".attributes." + uv_name + " beyond the float range");
    }
  }
  if (auto a = p.attributes.find("COLOR_0"); a != p.attributes.end()) {
    // Linear RGB(A) multiplying the base colour, alpha included (glTF 2.0 spec, 3.7.2.1 and
    // 3.9.2). An all-white set changes nothing and is not kept.
    const AccessorData d = read_accessor(ctx, a->second, w + ".attributes.COLOR_0", {{TINYGLTF_TYPE_VEC3, TINYGLTF_TYPE_VEC4}, true, true});
    same_count(d, "COLOR_0");
    if (std::any_of(d.values.begin(), d.values.end(), [](double x) { return x != 1.0; }))
      for (size_t i = 0; i < n; ++i) {
        const double* c = &d.values[size_t(d.components) * i];
        out.colors.emplace_back(c[0], c[1], c[2], d.components == 4 ? c[3] : 1.0);
      }
  }
  DeformationRest deformation;
  load_deformation(ctx, p, w, quantized, out.positions.size(), deformation);
  std::vector<uint32_t> idx;
  if (p.indices >= 0) {
    const AccessorData d = read_accessor(ctx, p.indices, w + ".indices", {{TINYGLTF_TYPE_SCALAR}, false, false, false, true});
    idx.reserve(d.count);
    for (size_t i = 0; i < d.count; ++i) {
      if (d.values[i] >= double(n))
        ctx.fail(w + ".indices", "element " + std::to_string(i) + " is " + std::to_string(uint64_t(d.values[i])) + "; the primitive has " + std::to_string(n) + " vertices");
      idx.push_back(uint32_t(d.values[i]));
    }
  } else {
    for (size_t i = 0; i < n; ++i) idx.push_back(uint32_t(i));
  }
  out.triangles = triangulate(ctx, mode, idx, w, p.indices >= 0 ? ".indices" : ".attributes.POSITION");
  // A triangle with two equal corners (the same index, or bit-identical positions) has no
  // area under any transform, since equal inputs transform to equal outputs: dropped here
  // once, not per instance and per frame (a few sparse bytes can declare a million of them).
  // Equal positions may part under morph targets or joints, so there only equal indices count.
  const bool deforms = !deformation.targets.empty() || deformation.has_joints();
  std::erase_if(out.triangles, [&](const glm::uvec3& t) {
    const glm::vec3 &a = out.positions[t.x], &b = out.positions[t.y], &c = out.positions[t.z];
    const bool collapsed = t.x == t.y || t.y == t.z || t.x == t.z || (!deforms && (a == b || b == c || a == c));
    out.collapsed_triangles += collapsed;
    return collapsed;
  });
  if (!out.triangles.empty()) give_tangents(materials[size_t(out.material)], out, deformation);
  if (out.triangles.empty()) {
    out.positions.clear(), out.normals.clear(), out.tangents.clear(), out.uvs.clear(), out.uvs2.clear(), out.colors.clear();
  } else if (deforms) {
    deformation.positions = out.positions, deformation.normals = out.normals, deformation.tangents = out.tangents;
    deformation.triangles = out.triangles;
    out.deformation = std::make_shared<const DeformationRest>(std::move(deformation));
  }
  ctx.decoded_accessors.clear();
  return out;
}

void load_cameras(const Context& ctx, SceneSource& src) {
  for (size_t i = 0; i < ctx.model.cameras.size(); ++i) {
    const auto& c = ctx.model.cameras[i];
    const std::string w = index_path("cameras", i);
    if (c.type == "orthographic") {
      // glTF 2.0 spec, 5.14: xmag and ymag must not be zero and should not be negative;
      // zfar is required and beyond znear. The image's aspect ratio sets the width, as it
      // does for a perspective camera (xmag, like aspectRatio, is not used).
      const auto& o = c.orthographic;
      if (!(o.ymag != 0.0 && std::isfinite(o.ymag) && std::abs(o.ymag) < 1e30))
        ctx.fail(w + ".orthographic.ymag", "is " + std::to_string(o.ymag) + "; expected a finite non-zero half height");
      if (!(o.xmag != 0.0 && std::isfinite(o.xmag)))
        ctx.fail(w + ".orthographic.xmag", "is " + std::to_string(o.xmag) + "; expected a finite non-zero half width");
      if (o.ymag < 0.0)
        ctx.warn("negative ymag", w + ".orthographic.ymag is negative; its magnitude is used (a mirrored view is not rendered)");
      if (!(o.znear >= 0.0 && std::isfinite(o.znear))) ctx.fail(w + ".orthographic.znear", "is " + std::to_string(o.znear) + "; expected a distance >= 0");
      if (!(o.zfar > o.znear && std::isfinite(o.zfar))) ctx.fail(w + ".orthographic.zfar", "is " + std::to_string(o.zfar) + "; expected a distance beyond znear");
      CameraSource cs{c.name, 0.0f, float(std::abs(o.ymag)), float(o.znear), float(o.zfar)};
      src.cameras.push_back(cs);
      continue;
    }
    if (c.type != "perspective") ctx.fail(w + ".type", "is \"" + c.type + "\"; expected \"perspective\" or \"orthographic\"");
    const auto& p = c.perspective;
    if (!(p.yfov > 0.0 && p.yfov < std::numbers::pi)) ctx.fail(w + ".perspective.yfov", "is " + std::to_string(p.yfov) + "; expected radians in (0, pi)");
    if (!(p.znear > 0.0 && std::isfinite(p.znear))) ctx.fail(w + ".perspective.znear", "is " + std::to_string(p.znear) + "; expected a positive distance");
    if (p.zfar != 0.0 && !(p.zfar > p.znear && std::isfinite(p.zfar))) ctx.fail(w + ".perspective.zfar", "is " + std::to_string(p.zfar) + "; expected a distance beyond znear");
    src.cameras.push_back({c.name, float(p.yfov), 0.0f, float(p.znear), float(p.zfar)});
  }
}

void load_lights(const Context& ctx, SceneSource& src) {
  for (size_t i = 0; i < ctx.model.lights.size(); ++i) {
    const auto& g = ctx.model.lights[i];
    const std::string w = "extensions.KHR_lights_punctual.lights[" + std::to_string(i) + "]";
    Light l;
    l.name = g.name;
    if (g.type == "directional") l.type = LightType::Directional;
    else if (g.type == "point") l.type = LightType::Point;
    else if (g.type == "spot") l.type = LightType::Spot;
    else ctx.fail(w + ".type", "is \"" + g.type + "\"; expected directional, point or spot");
    if (!g.color.empty()) {
      if (g.color.size() != 3 || !finite_all(g.color) || std::any_of(g.color.begin(), g.color.end(), [](double x) { return x < 0.0; }))
        ctx.fail(w + ".color", "expected 3 non-negative numbers");
      l.color = glm::vec3(float(g.color[0]), float(g.color[1]), float(g.color[2]));
    }
    if (!(g.intensity >= 0.0 && g.intensity < 1e30)) ctx.fail(w + ".intensity", "is " + std::to_string(g.intensity) + "; expected a non-negative number");
    l.intensity = float(g.intensity);
    if (!(g.range >= 0.0 && std::isfinite(g.range))) ctx.fail(w + ".range", "is " + std::to_string(g.range) + "; expected a positive distance");
    l.range = float(g.range);
    if (l.type == LightType::Spot) {
      const double inner = g.spot.innerConeAngle, outer = g.spot.outerConeAngle;
      // KHR_lights_punctual, "spot": 0 <= innerConeAngle < outerConeAngle <= PI / 2.
      if (!(inner >= 0.0 && inner < outer)) ctx.fail(w + ".spot.innerConeAngle", "is " + std::to_string(inner) + "; expected 0 <= inner < outer (" + std::to_string(outer) + ")");
      if (!(outer > 0.0 && outer <= std::numbers::pi / 2 + 1e-6)) ctx.fail(w + ".spot.outerConeAngle", "is " + std::to_string(outer) + "; expected radians in (0, pi/2]");
      l.inner_cone = float(inner), l.outer_cone = float(outer);
    }
    src.lights.push_back(std::move(l));
  }
}

void load_animations(const Context& ctx, SceneSource& src) {
  for (size_t a = 0; a < ctx.model.animations.size(); ++a) {
    const auto& g = ctx.model.animations[a];
    AnimationSource anim;
    anim.name = g.name;
    for (size_t c = 0; c < g.channels.size(); ++c) {
      const auto& ch = g.channels[c];
      const std::string w = index_path("animations", a) + ".channels[" + std::to_string(c) + "]";
      if (ch.target_node < 0) continue;  // glTF 2.0 spec, 5.5: without a node the channel is ignored
      if (size_t(ch.target_node) >= src.nodes.size()) ctx.fail(w + ".target.node", "is " + std::to_string(ch.target_node) + "; the file has " + std::to_string(src.nodes.size()) + " nodes");
      if (src.nodes[size_t(ch.target_node)].has_matrix)
        ctx.fail(w + ".target.node", "node " + std::to_string(ch.target_node) + " has a matrix; animated nodes must use translation/rotation/scale (glTF 2.0 spec, 3.5.3)");
      ChannelSource out;
      out.node = ch.target_node;
      AccessorRule rule{{TINYGLTF_TYPE_VEC3}};
      if (ch.target_path == "translation") {
        out.path = AnimatedPath::Translation;
      } else if (ch.target_path == "scale") {
        out.path = AnimatedPath::Scale;
      } else if (ch.target_path == "rotation") {
        out.path = AnimatedPath::Rotation, out.width = 4, rule = {{TINYGLTF_TYPE_VEC4}, true, true, true};
      } else if (ch.target_path == "weights") {
        // One scalar per morph target of the node's mesh and per key (glTF 2.0 spec, 3.11).
        out.path = AnimatedPath::Weights, out.width = int(src.nodes[size_t(ch.target_node)].weights.size());
        rule = {{TINYGLTF_TYPE_SCALAR}, true, true, true};
        if (out.width == 0) ctx.fail(w + ".target.node", "node " + std::to_string(ch.target_node) + " has no mesh with morph targets; a weights channel needs one");
      } else {
        ctx.fail(w + ".target.path", "is \"" + ch.target_path + "\"; expected translation, rotation, scale or weights");
      }
      if (ch.sampler < 0 || size_t(ch.sampler) >= g.samplers.size())
        ctx.fail(w + ".sampler", "is " + std::to_string(ch.sampler) + "; the animation has " + std::to_string(g.samplers.size()) + " samplers");
      const auto& s = g.samplers[size_t(ch.sampler)];
      const std::string sw = index_path("animations", a) + ".samplers[" + std::to_string(ch.sampler) + "]";
      if (s.interpolation == "LINEAR") out.interpolation = Interpolation::Linear;
      else if (s.interpolation == "STEP") out.interpolation = Interpolation::Step;
      else if (s.interpolation == "CUBICSPLINE") out.interpolation = Interpolation::CubicSpline;
      else ctx.fail(sw + ".interpolation", "is \"" + s.interpolation + "\"; expected LINEAR, STEP or CUBICSPLINE");
      const AccessorData in = read_accessor(ctx, s.input, sw + ".input", {{TINYGLTF_TYPE_SCALAR}});
      for (size_t k = 0; k < in.count; ++k) {
        if (k > 0 && !(in.values[k] > in.values[k - 1]))
          ctx.fail(index_path("accessors", size_t(s.input)), "key time " + std::to_string(k) + " (" + std::to_string(in.values[k]) + ") does not increase; animation inputs must increase strictly");
        out.times.push_back(in.values[k]);
      }
      const AccessorData o = read_accessor(ctx, s.output, sw + ".output", rule);
      const size_t per_key = out.interpolation == Interpolation::CubicSpline ? 3 : 1;
      // A weights output holds `width` scalars per key; the others one element of `width`.
      const size_t elements = in.count * per_key * (out.path == AnimatedPath::Weights ? size_t(out.width) : 1);
      if (o.count != elements)
        ctx.fail(sw + ".output", "has " + std::to_string(o.count) + " elements; " + std::to_string(in.count) + " keys need " + std::to_string(elements));
      out.values = o.values;
      if (out.path == AnimatedPath::Rotation)
        for (size_t k = per_key == 3 ? 1 : 0; k < o.count; k += per_key) {
          const double* q = &out.values[4 * k];
          if (!(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3] > 0.0))
            ctx.fail(sw + ".output", "key " + std::to_string(k / per_key) + " is a zero quaternion; expected unit quaternions");
        }
      anim.end = std::max(anim.end, out.times.back());
      anim.channels.push_back(std::move(out));
    }
    src.animations.push_back(std::move(anim));
  }
}

}  // namespace
}  // namespace gltf

Scene load(const std::filesystem::path& path) {
  gltf::Document doc = gltf::read_document(path);
  const tinygltf::Model model = gltf::parse_model(doc);
  gltf::Context decoding{doc.file, model};
  gltf::decode_meshopt_views(doc, decoding);
  const gltf::Context& ctx = decoding;
  auto src = std::make_shared<SceneSource>();
  src->file = doc.file;

  Scene s;
  s.path = path;
  s.content_hash = doc.content_hash;
  std::vector<std::vector<gltf::UvMapping>> uv_mappings;
  // Images decode on worker threads while the geometry is read.
  const std::unique_ptr<gltf::TextureDecoding> textures = gltf::load_materials(ctx, doc, s.materials, s.textures, uv_mappings);
  gltf::load_nodes(ctx, *src);
  int default_material = -1;
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    std::vector<PrimitiveSource> prims;
    for (size_t p = 0; p < model.meshes[m].primitives.size(); ++p)
      prims.push_back(gltf::load_primitive(ctx, model.meshes[m].primitives[p], gltf::index_path("meshes", m) + ".primitives[" + std::to_string(p) + "]",
                                           s.materials, uv_mappings, default_material));
    src->meshes.push_back(std::move(prims));
  }
  gltf::load_skins(ctx, *src);
  gltf::load_cameras(ctx, *src);
  gltf::load_lights(ctx, *src);
  gltf::load_animations(ctx, *src);
  textures->finish();
  s.warnings = doc.warnings;
  s.warnings.insert(s.warnings.end(), ctx.warnings.begin(), ctx.warnings.end());

  gltf::Extras extras = gltf::parse_extras(doc, *src);
  s.sequence = extras.sequence;
  s.environment = extras.environment;
  s.leak_regions = extras.leak_regions;
  s.leak_object_ids = extras.leak_object_ids;
  src->area_shapes = extras.area_shapes;

  check_instanced_size(*src);
  // The local frame: centre of the t = 0 bounds, in double (see Scene::origin).
  const NodePose nodes = pose_nodes(*src, s.sequence.animation, 0.0);
  glm::dvec3 lo, hi;
  world_bounds(*src, nodes, lo, hi);
  s.origin = lo.x <= hi.x ? 0.5 * (lo + hi) : glm::dvec3(0.0);
  if (lo.x <= hi.x && !std::isfinite(glm::length(hi - lo) + glm::length(s.origin)))
    throw InputError(doc.file, "nodes", "the scene's world bounds overflow double precision; expected transforms of finite scale");
  for (const auto& v : extras.views) {
    View view;
    view.name = v.name;
    try {
      view.camera = Camera::look_at(glm::vec3(v.eye - s.origin), glm::vec3(v.target - s.origin), glm::vec3(v.up), float(v.yfov_deg * std::numbers::pi / 180.0));
      view.camera.ymag = float(v.ymag);
    } catch (const std::invalid_argument& e) {
      throw InputError(doc.file, v.field, e.what());
    }
    src->extra_views.push_back(std::move(view));
  }
  pose(*src, nodes, s);
  // Emitters emit from their node's surface as posed now, and add their particles at t = 0.
  s.emitters = std::move(extras.emitters);
  for (size_t i = 0; i < s.emitters.size(); ++i) complete_emitter(s.emitters[i], s.meshes, s.materials, doc.file, extras.emitter_fields[i] + ".node");
  add_particle_meshes(s.emitters, 0.0, 1.0 / s.sequence.fps, ParticleDetail::Placed, s.meshes, doc.file);
  for (size_t i = 0; i < s.views.size(); ++i)
    for (size_t j = 0; j < i; ++j)
      if (s.views[i].name == s.views[j].name) {
        const size_t camera_views = s.views.size() - extras.views.size();
        const std::string field = i >= camera_views ? extras.views[i - camera_views].field + ".name" : "nodes[" + std::to_string(s.views[i].node) + "]";
        throw InputError(doc.file, field, "duplicate view name \"" + s.views[i].name + "\"; view names must be unique");
      }
  s.source_ = std::move(src);
  s.derive();
  return s;
}

}  // namespace giq::scenes
