// Posing the parsed document at one instant: node transforms applied to geometry, lights and
// cameras, in the scene's local frame (world minus Scene::origin, subtracted in double).

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "giq/base/error.h"
#include "orthonormal_basis.h"
#include "placement.h"
#include "scene_source.h"

namespace giq::scenes {
namespace {

// Instantiated nodes in depth-first pre-order from the scene's roots: the order meshes,
// lights and camera views appear in, stable for every t.
std::vector<int> preorder(const SceneSource& src) {
  std::vector<int> order, stack(src.roots.rbegin(), src.roots.rend());
  while (!stack.empty()) {
    const int i = stack.back();
    stack.pop_back();
    order.push_back(i);
    const auto& ch = src.nodes[size_t(i)].children;
    for (auto it = ch.rbegin(); it != ch.rend(); ++it) stack.push_back(*it);
  }
  return order;
}

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

std::string node_label(const SceneSource& src, int i) {
  const auto& n = src.nodes[size_t(i)].name;
  return n.empty() ? "node" + std::to_string(i) : n;
}

void emit_mesh(const PrimitiveSource& p, const PlacedVertices& placed, glm::dvec3 origin, Mesh& m, size_t& dropped) {
  m.positions.clear(), m.normals.clear(), m.tangents.clear(), m.uvs.clear(), m.uvs2.clear(), m.colors.clear(), m.triangles.clear();
  dropped += p.collapsed_triangles;
  if (p.triangles.empty()) return;
  // A mirroring placement reverses the winding; swapping two corners restores the
  // counter-clockwise front face of glTF 2.0 spec, 3.7.2.1 ("front-facing ... counter-clockwise").
  const bool flip = placed.mirrored;

  // A deforming primitive keeps every vertex at its index in every frame, whatever triangles
  // collapse in this one, so that a vertex's previous position (motion vectors) is found at
  // the same index.
  const bool stable = p.deformation != nullptr;

  std::vector<glm::vec3> pos(placed.positions.size());
  for (size_t i = 0; i < pos.size(); ++i) {
    pos[i] = glm::vec3(placed.positions[i] - origin);
    if (stable && !finite(pos[i])) pos[i] = glm::vec3(0.0f);  // kept for its index only: no triangle uses it
  }

  std::vector<glm::uvec3> tris;
  std::vector<glm::vec3> face;
  std::vector<bool> kept;
  tris.reserve(p.triangles.size());
  for (glm::uvec3 t : p.triangles) {
    if (flip) std::swap(t.y, t.z);
    const glm::vec3 a = pos[t.x], b = pos[t.y], c = pos[t.z];
    const glm::vec3 n = glm::cross(b - a, c - a);
    const float len = glm::length(n);
    const bool ok = len > 0.0f && std::isfinite(len) && finite(a) && finite(b) && finite(c);
    if (!ok) ++dropped;  // zero-area, collapsed or overflowed: no surface to render
    if (!ok && !stable) continue;
    kept.push_back(ok);
    tris.push_back(t);
    face.push_back(ok ? n / len : glm::vec3(0.0f, 0.0f, 1.0f));
  }

  auto tangent = [&](size_t i, glm::vec3 normal) {
    const glm::dvec4 t = placed.tangents[i];
    glm::vec3 xyz = glm::vec3(glm::dvec3(t));
    xyz -= normal * glm::dot(normal, xyz);  // keep it in the tangent plane after non-uniform scale
    const float len = glm::length(xyz);
    xyz = len > 0.0f && std::isfinite(len) ? xyz / len : glm::vec3(any_perpendicular(glm::dvec3(normal)));
    // The bitangent is cross(N, T) * w, w already in the placement's handedness.
    return glm::vec4(xyz, float(t.w));
  };

  if (p.normals.empty()) {
    // No normals in the file: flat shading (glTF 2.0 spec, 3.7.2.1: "client implementations
    // MUST calculate flat normals"), which needs each triangle's own vertices.
    for (size_t k = 0; k < tris.size(); ++k) {
      const uint32_t base = uint32_t(m.positions.size());
      for (int c = 0; c < 3; ++c) {
        const uint32_t v = tris[k][c];
        m.positions.push_back(pos[v]);
        m.normals.push_back(face[k]);
        if (!p.uvs.empty()) m.uvs.push_back(p.uvs[v]);
        if (!p.uvs2.empty()) m.uvs2.push_back(p.uvs2[v]);
        if (!p.colors.empty()) m.colors.push_back(p.colors[v]);
      }
      if (kept[k]) m.triangles.emplace_back(base, base + 1, base + 2);
    }
    return;
  }
  // Indexed: keep only the vertices the remaining triangles use (every vertex when stable),
  // in their original order.
  std::vector<uint32_t> remap(pos.size(), stable ? 0u : UINT32_MAX);
  for (size_t k = 0; k < tris.size(); ++k)
    for (int c = 0; c < 3; ++c) remap[tris[k][c]] = 0;
  std::vector<glm::vec3> normal(pos.size());
  std::vector<bool> bad(pos.size(), false);
  for (size_t i = 0; i < pos.size(); ++i) {
    if (remap[i] == UINT32_MAX) continue;
    remap[i] = uint32_t(m.positions.size());
    m.positions.push_back(pos[i]);
    const glm::dvec3 n = placed.normals[i];
    const double len = glm::length(n);
    bad[i] = !(len > 0.0) || !std::isfinite(len);
    normal[i] = bad[i] ? glm::vec3(0.0f) : glm::vec3(n / len);
  }
  // A zero normal in the file (or one collapsed by the transform) takes the face normal; one
  // that no triangle gives a face (kept only for its index) any unit normal.
  for (size_t i = 0; i < pos.size(); ++i)
    if (bad[i]) normal[i] = glm::vec3(0.0f, 0.0f, 1.0f);
  for (size_t k = 0; k < tris.size(); ++k)
    for (int c = 0; c < 3; ++c)
      if (bad[tris[k][c]] && kept[k]) normal[tris[k][c]] = face[k];
  for (size_t i = 0; i < pos.size(); ++i) {
    if (remap[i] == UINT32_MAX) continue;
    m.normals.push_back(normal[i]);
    if (!p.uvs.empty()) m.uvs.push_back(p.uvs[i]);
    if (!p.uvs2.empty()) m.uvs2.push_back(p.uvs2[i]);
    if (!p.colors.empty()) m.colors.push_back(p.colors[i]);
    if (!p.tangents.empty()) m.tangents.push_back(tangent(i, normal[i]));
  }
  for (size_t k = 0; k < tris.size(); ++k)
    if (kept[k]) m.triangles.emplace_back(remap[tris[k].x], remap[tris[k].y], remap[tris[k].z]);
}

// What a renderer deforming on its own needs at this instant (Mesh::deformation).
Deformation deformation(const PrimitiveSource& p, const PlacedVertices& placed, const std::vector<double>& weights, glm::dvec3 origin) {
  Deformation d;
  d.rest = p.deformation;
  d.mirrored = placed.mirrored;
  d.skinned = placed.skinned;
  glm::dmat4 local(1.0);
  local[3] = glm::dvec4(-origin, 1.0);
  for (const glm::dmat4& J : placed.matrices) d.joints.push_back(glm::mat4(local * J));
  d.weights.assign(p.deformation->targets.size(), 0.0f);
  for (size_t k = 0; k < d.weights.size() && k < weights.size(); ++k) d.weights[k] = float(weights[k]);
  return d;
}

}  // namespace

void check_instanced_size(const SceneSource& src) {
  // Instancing multiplies geometry: a small file can name a mesh from many nodes. 2^25
  // triangles (about 5 GiB posed, and seconds of posing even when every one is degenerate) is
  // beyond what giq renders, so it is refused up front.
  constexpr size_t kMaxTriangles = size_t(1) << 25;
  size_t instanced = 0;
  for (int i : preorder(src)) {
    if (src.nodes[size_t(i)].mesh < 0) continue;
    for (const auto& p : src.meshes[size_t(src.nodes[size_t(i)].mesh)])
      instanced += (p.triangles.size() + p.collapsed_triangles) * src.nodes[size_t(i)].instance_count();
    if (instanced > kMaxTriangles)
      throw InputError(src.file, "nodes[" + std::to_string(i) + "].mesh", "the scene instances more than " + std::to_string(kMaxTriangles) + " triangles; too large");
  }
}

void world_bounds(const SceneSource& src, const NodePose& nodes, glm::dvec3& lo, glm::dvec3& hi) {
  lo = glm::dvec3(INFINITY), hi = glm::dvec3(-INFINITY);
  for (int i : preorder(src)) {
    const NodeSource& n = src.nodes[size_t(i)];
    if (n.mesh < 0) continue;
    for (size_t k = 0; k < n.instance_count(); ++k) {
      const glm::dmat4 M = n.instances.empty() ? nodes.world[size_t(i)] : nodes.world[size_t(i)] * n.instances[k];
      for (const auto& p : src.meshes[size_t(n.mesh)])
        for (const glm::dvec3& w : place(src, p, nodes, i, M, true).positions) lo = glm::min(lo, w), hi = glm::max(hi, w);
    }
  }
}

void pose(const SceneSource& src, const NodePose& nodes, Scene& out, const NodePose* was) {
  const std::vector<glm::dmat4>& world = nodes.world;
  // A still level under a walking character: its meshes are kept, not emitted anew each frame.
  std::vector<Mesh> before;
  if (was && was->world.size() == world.size()) before.swap(out.meshes);
  size_t next = 0;  // the mesh of `before` that the next one emitted was
  out.meshes.clear();
  out.lights.clear();
  out.views.clear();
  out.stats.degenerate_triangles_dropped = 0;
  for (int i : preorder(src)) {
    const NodeSource& n = src.nodes[size_t(i)];
    const glm::dmat4& M = world[size_t(i)];
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r)
        if (!std::isfinite(M[c][r]))
          throw InputError(src.file, "nodes[" + std::to_string(i) + "]", "the node's world transform overflows; expected transforms of finite scale");
    const glm::dmat3 L(M);
    const glm::dvec3 at = glm::dvec3(M[3]) - out.origin;
    if (n.mesh >= 0) {
      const auto& prims = src.meshes[size_t(n.mesh)];
      for (size_t instance = 0; instance < n.instance_count(); ++instance)
        for (size_t k = 0; k < prims.size(); ++k) {
          if (prims[k].dropped) continue;
          const size_t j = next++;
          if (j < before.size() && !prims[k].deformation && was->world[size_t(i)] == M && before[j].node == i &&
              before[j].mesh == n.mesh && before[j].primitive == int(k) && before[j].emitter < 0) {
            // What emit_mesh counted: the source's collapsed triangles and the faces it dropped
            // (all of them dropped: a mesh that nothing deforms keeps no degenerate face).
            out.stats.degenerate_triangles_dropped += prims[k].collapsed_triangles + (prims[k].triangles.size() - before[j].triangles.size());
            out.meshes.push_back(std::move(before[j]));
            continue;
          }
          Mesh m;
          m.name = node_label(src, i);
          m.node = i;
          m.mesh = n.mesh;
          m.primitive = int(k);
          m.object_id = uint32_t(i) + 1;
          m.material = prims[k].material;
          if (size_t(n.mesh) < src.area_shapes.size()) m.area_shape = src.area_shapes[size_t(n.mesh)];
          const PlacedVertices placed = place(src, prims[k], nodes, i, n.instances.empty() ? M : M * n.instances[instance]);
          emit_mesh(prims[k], placed, out.origin, m, out.stats.degenerate_triangles_dropped);
          if (prims[k].deformation) m.deformation = deformation(prims[k], placed, nodes.weights[size_t(i)], out.origin);
          out.meshes.push_back(std::move(m));
        }
    }
    if (n.light >= 0) {
      Light l = src.lights[size_t(n.light)];
      l.node = i;
      if (l.name.empty()) l.name = node_label(src, i);
      l.position = glm::vec3(at);
      // KHR_lights_punctual: lights shine along the node's local -Z.
      const glm::dvec3 d = L * glm::dvec3(0.0, 0.0, -1.0);
      const double len = glm::length(d);
      if (!(len > 0.0) || !std::isfinite(len)) {
        if (l.type != LightType::Point)
          throw InputError(src.file, "nodes[" + std::to_string(i) + "]", "the node's transform collapses the light's -Z direction; expected an invertible transform");
      } else {
        l.direction = glm::vec3(d / len);
      }
      out.lights.push_back(std::move(l));
    }
    if (n.camera >= 0) {
      const CameraSource& c = src.cameras[size_t(n.camera)];
      View v;
      v.name = !n.name.empty() ? n.name : !c.name.empty() ? c.name : "camera" + std::to_string(n.camera);
      v.node = i;
      // glTF 2.0 spec, 3.10.1: a camera looks along its node's -Z with +Y up.
      const glm::dvec3 f = L * glm::dvec3(0.0, 0.0, -1.0), u = L * glm::dvec3(0.0, 1.0, 0.0);
      const glm::dvec3 r = glm::cross(f, u);
      const double fl = glm::length(f), rl = glm::length(r);
      if (!(fl > 0.0) || !(rl > 0.0) || !std::isfinite(fl) || !std::isfinite(rl))
        throw InputError(src.file, "nodes[" + std::to_string(i) + "]", "the node's transform collapses the camera's axes; expected an invertible transform");
      v.camera.position = glm::vec3(at);
      v.camera.forward = glm::vec3(f / fl);
      v.camera.right = glm::vec3(r / rl);
      v.camera.up = glm::vec3(glm::cross(r / rl, f / fl));
      v.camera.yfov = c.yfov;
      // An orthographic window is in the camera node's units: it scales with the node.
      const double ul = glm::length(u);
      v.camera.ymag = float(double(c.ymag) * ul);
      if (c.ymag > 0.0f && !(v.camera.ymag > 0.0f && std::isfinite(v.camera.ymag)))
        throw InputError(src.file, "nodes[" + std::to_string(i) + "]", "the node's transform collapses the orthographic camera's window; expected an invertible transform");
      v.camera.znear = c.znear;
      v.camera.zfar = c.zfar;
      out.views.push_back(std::move(v));
    }
  }
  out.views.insert(out.views.end(), src.extra_views.begin(), src.extra_views.end());
}

}  // namespace giq::scenes
