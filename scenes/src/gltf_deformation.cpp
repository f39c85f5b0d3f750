#include "gltf_deformation.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace giq::scenes::gltf {

void load_deformation(const Context& ctx, const tinygltf::Primitive& p, const std::string& w, bool quantized, size_t n, DeformationRest& out) {
  auto count_of = [&](const AccessorData& d, const std::string& field) {
    if (d.count != n) ctx.fail(field, "has " + std::to_string(d.count) + " elements; POSITION has " + std::to_string(n));
  };
  // Displacements are FLOAT, or with KHR_mesh_quantization (signed) normalized or plain small
  // integers ("Extending Morph Target Attributes").
  const AccessorRule delta_rule{{TINYGLTF_TYPE_VEC3}, true, false, quantized, false, quantized};
  for (size_t k = 0; k < p.targets.size(); ++k) {
    MorphTarget t;
    const std::string tw = w + ".targets[" + std::to_string(k) + "]";
    for (const auto& [name, index] : p.targets[k]) {
      std::vector<glm::vec3>* into = name == "POSITION" ? &t.positions : name == "NORMAL" ? &t.normals : name == "TANGENT" ? &t.tangents : nullptr;
      if (into == nullptr) {
        ctx.warn("morph target attributes", tw + "." + name + ": only POSITION, NORMAL and TANGENT displacements are applied; " + name + " was ignored");
        continue;
      }
      const AccessorData d = read_accessor(ctx, index, tw + "." + name, delta_rule);
      count_of(d, tw + "." + name);
      for (size_t i = 0; i < n; ++i) into->emplace_back(d.values[3 * i], d.values[3 * i + 1], d.values[3 * i + 2]);
    }
    out.targets.push_back(std::move(t));
  }

  // JOINTS_0/WEIGHTS_0, JOINTS_1/WEIGHTS_1, ...: consecutive sets, each pair complete.
  for (size_t set = 0;; ++set) {
    const std::string jn = "JOINTS_" + std::to_string(set), wn = "WEIGHTS_" + std::to_string(set);
    const auto j = p.attributes.find(jn), wt = p.attributes.find(wn);
    if (j == p.attributes.end() && wt == p.attributes.end()) break;
    if (j == p.attributes.end() || wt == p.attributes.end())
      ctx.fail(w + ".attributes." + (j == p.attributes.end() ? jn : wn), "missing; " + (j == p.attributes.end() ? wn : jn) + " needs it");
    const AccessorData jd = read_accessor(ctx, j->second, w + ".attributes." + jn, {{TINYGLTF_TYPE_VEC4}, false, false, false, true});
    const AccessorData wd = read_accessor(ctx, wt->second, w + ".attributes." + wn, {{TINYGLTF_TYPE_VEC4}, true, true});
    count_of(jd, w + ".attributes." + jn);
    count_of(wd, w + ".attributes." + wn);
    std::vector<glm::uvec4> joints(n);
    std::vector<glm::vec4> weights(n);
    for (size_t i = 0; i < n; ++i)
      for (int c = 0; c < 4; ++c) {
        joints[i][c] = uint32_t(jd.values[4 * i + size_t(c)]);
        const double v = wd.values[4 * i + size_t(c)];
        if (!(v >= 0.0)) ctx.fail(w + ".attributes." + wn, "element " + std::to_string(i) + " has weight " + std::to_string(v) + "; expected weights >= 0");
        weights[i][c] = float(v);
      }
    out.joints.push_back(std::move(joints));
    out.weights.push_back(std::move(weights));
  }
  // Every JOINTS_n and WEIGHTS_n was read above: sets numbered from 0 without gaps.
  for (const auto& [name, index] : p.attributes)
    if (name.rfind("JOINTS_", 0) == 0 || name.rfind("WEIGHTS_", 0) == 0) {
      const std::string suffix = name.substr(name.find('_') + 1);
      bool read = false;
      for (size_t set = 0; set < out.joints.size(); ++set) read |= suffix == std::to_string(set);
      if (!read)
        ctx.fail(w + ".attributes." + name, "is not read: JOINTS_n/WEIGHTS_n pairs must be numbered from 0 without gaps, and the first " +
                                                std::to_string(out.joints.size()) + " complete pairs end before it");
    }

  // Weights summing to 1 (glTF 2.0 spec, 3.7.3.2 "Skinned Mesh Attributes").
  if (out.joints.empty()) return;
  size_t renormalised = 0, unweighted = 0;
  for (size_t i = 0; i < n; ++i) {
    double sum = 0.0;
    for (const auto& s : out.weights) sum += double(s[i].x) + s[i].y + s[i].z + s[i].w;
    if (sum == 0.0) {
      out.weights[0][i] = glm::vec4(1.0f, 0.0f, 0.0f, 0.0f);
      ++unweighted;
      continue;
    }
    // Normalized bytes carry 1/255 per weight, so a valid sum may be off by 4 / 510 per set.
    renormalised += std::abs(sum - 1.0) > 0.5 * 4.0 / 255.0 * double(out.weights.size());
    for (auto& s : out.weights) s[i] = glm::vec4(glm::dvec4(s[i]) / sum);
  }
  if (renormalised > 0)
    ctx.warn("skin weights", w + ": " + std::to_string(renormalised) + " vertices have skin weights that do not sum to 1; they were divided by their sum");
  if (unweighted > 0)
    ctx.warn("unweighted vertices", w + ": " + std::to_string(unweighted) + " vertices have skin weights that are all zero; they follow their first joint");
}

void load_skins(const Context& ctx, SceneSource& src) {
  const auto& m = ctx.model;
  for (size_t s = 0; s < m.skins.size(); ++s) {
    const auto& g = m.skins[s];
    const std::string w = index_path("skins", s);
    SkinSource out;
    if (g.joints.empty()) ctx.fail(w + ".joints", "is empty; a skin needs at least one joint");
    for (int j : g.joints) {
      if (j < 0 || size_t(j) >= src.nodes.size()) ctx.fail(w + ".joints", "joint " + std::to_string(j) + " is not a node index (the file has " + std::to_string(src.nodes.size()) + " nodes)");
      out.joints.push_back(j);
    }
    out.inverse_bind.assign(out.joints.size(), glm::dmat4(1.0));
    if (g.inverseBindMatrices >= 0) {
      const AccessorData d = read_accessor(ctx, g.inverseBindMatrices, w + ".inverseBindMatrices", {{TINYGLTF_TYPE_MAT4}});
      if (d.count < out.joints.size())
        ctx.fail(w + ".inverseBindMatrices", "has " + std::to_string(d.count) + " matrices; the skin has " + std::to_string(out.joints.size()) + " joints");
      for (size_t j = 0; j < out.joints.size(); ++j)
        for (int c = 0; c < 4; ++c)
          for (int r = 0; r < 4; ++r) out.inverse_bind[j][c][r] = d.values[16 * j + size_t(4 * c + r)];  // column-major
    }
    src.skins.push_back(std::move(out));
  }

  // Morph targets: a mesh's primitives agree on their number (3.7.2.2), and weights have one
  // entry per target.
  std::vector<size_t> targets(src.meshes.size(), 0);
  for (size_t k = 0; k < src.meshes.size(); ++k) {
    const auto& prims = src.meshes[k];
    const std::string w = index_path("meshes", k);
    for (size_t p = 0; p < prims.size(); ++p) {
      const size_t t = m.meshes[k].primitives[p].targets.size();
      if (p > 0 && t != targets[k])
        ctx.fail(w + ".primitives[" + std::to_string(p) + "].targets", "has " + std::to_string(t) + " targets; primitives[0] has " + std::to_string(targets[k]) + " (every primitive of a mesh must have the same number)");
      targets[k] = t;
    }
    if (!m.meshes[k].weights.empty() && m.meshes[k].weights.size() != targets[k])
      ctx.fail(w + ".weights", "has " + std::to_string(m.meshes[k].weights.size()) + " entries; the mesh has " + std::to_string(targets[k]) + " morph targets");
  }
  for (size_t i = 0; i < src.nodes.size(); ++i) {
    NodeSource& n = src.nodes[i];
    const auto& g = m.nodes[i];
    const std::string w = index_path("nodes", i);
    if (n.mesh >= 0) {
      const size_t t = targets[size_t(n.mesh)];
      const std::vector<double>& given = !g.weights.empty() ? g.weights : m.meshes[size_t(n.mesh)].weights;
      if (!g.weights.empty() && g.weights.size() != t)
        ctx.fail(w + ".weights", "has " + std::to_string(g.weights.size()) + " entries; its mesh has " + std::to_string(t) + " morph targets");
      if (!std::all_of(given.begin(), given.end(), [](double x) { return std::isfinite(x); }))
        ctx.fail(w + ".weights", "has a number that is not finite; expected finite morph target weights");
      n.weights = given.empty() ? std::vector<double>(t, 0.0) : given;
    } else if (!g.weights.empty()) {
      ctx.fail(w + ".weights", "is given on a node without a mesh");
    }
    if (g.skin < 0) continue;
    if (size_t(g.skin) >= src.skins.size()) ctx.fail(w + ".skin", "is " + std::to_string(g.skin) + "; the file has " + std::to_string(src.skins.size()) + " skins");
    if (n.mesh < 0) ctx.fail(w + ".skin", "is given on a node without a mesh; a skin deforms its node's mesh");
    if (!n.instances.empty()) ctx.fail(w + ".extensions.EXT_mesh_gpu_instancing", "is given on a skinned node; a skinned mesh is drawn once, where its joints put it");
    n.skin = g.skin;
    const size_t joints = src.skins[size_t(g.skin)].joints.size();
    const auto& prims = src.meshes[size_t(n.mesh)];
    for (size_t p = 0; p < prims.size(); ++p) {
      const std::string pw = index_path("meshes", size_t(n.mesh)) + ".primitives[" + std::to_string(p) + "]";
      if (prims[p].dropped || prims[p].triangles.empty()) continue;
      const DeformationRest* d = prims[p].deformation.get();
      if (d == nullptr || !d->has_joints()) ctx.fail(pw + ".attributes.JOINTS_0", "missing; node " + std::to_string(i) + " skins this mesh, which needs JOINTS_0 and WEIGHTS_0");
      for (size_t set = 0; set < d->joints.size(); ++set)
        for (size_t v = 0; v < d->joints[set].size(); ++v)
          for (int c = 0; c < 4; ++c)
            if (d->joints[set][v][c] >= joints && d->weights[set][v][c] > 0.0f)
              ctx.fail(pw + ".attributes.JOINTS_" + std::to_string(set),
                       "element " + std::to_string(v) + " names joint " + std::to_string(d->joints[set][v][c]) + "; skins[" + std::to_string(g.skin) + "] has " + std::to_string(joints));
    }
  }
}

}  // namespace giq::scenes::gltf
