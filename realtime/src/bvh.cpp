#include "giq/realtime/bvh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace giq::realtime {

namespace {

struct Box {
  glm::vec3 lo{std::numeric_limits<float>::infinity()};
  glm::vec3 hi{-std::numeric_limits<float>::infinity()};
  void extend(glm::vec3 p) { lo = glm::min(lo, p), hi = glm::max(hi, p); }
  void extend(const Box& b) { lo = glm::min(lo, b.lo), hi = glm::max(hi, b.hi); }
  bool empty() const { return lo.x > hi.x; }
  float area() const {
    if (empty()) return 0.0f;
    const glm::vec3 e = hi - lo;
    return 2.0f * (e.x * e.y + e.y * e.z + e.z * e.x);
  }
};

struct Builder {
  const BvhOptions& opt;
  std::vector<Box> boxes;
  std::vector<glm::vec3> centroids;
  Bvh out;

  // Depth beyond which splits are forced to the object median, so the tree stays within the
  // GPU stack (kMaxDepth) whatever the geometry: median splits halve the count per level.
  static constexpr int kMedianDepth = 32;

  uint32_t build(uint32_t begin, uint32_t end, int depth) {
    out.depth = std::max(out.depth, depth + 1);
    const uint32_t node_index = uint32_t(out.nodes.size());
    out.nodes.emplace_back();
    Box bounds, cbounds;
    for (uint32_t i = begin; i < end; ++i) {
      bounds.extend(boxes[out.prims[i]]);
      cbounds.extend(centroids[out.prims[i]]);
    }
    out.nodes[node_index].lo = bounds.lo;
    out.nodes[node_index].hi = bounds.hi;
    const uint32_t n = end - begin;
    auto make_leaf = [&] {
      out.nodes[node_index].index = begin;
      out.nodes[node_index].count = n;
      return node_index;
    };
    if (n <= 1) return make_leaf();

    const glm::vec3 extent = cbounds.hi - cbounds.lo;
    int axis = 0;
    if (extent.y > extent[axis]) axis = 1;
    if (extent.z > extent[axis]) axis = 2;
    uint32_t mid = begin;
    if (!(extent[axis] > 0.0f) || depth >= kMedianDepth) {
      if (n <= uint32_t(opt.max_leaf_size) && !(extent[axis] > 0.0f)) return make_leaf();
      // Coincident centroids (or a forced median): split the list in half along the axis.
      mid = begin + n / 2;
      std::nth_element(out.prims.begin() + begin, out.prims.begin() + mid, out.prims.begin() + end,
                       [&](uint32_t a, uint32_t b) { return centroids[a][axis] < centroids[b][axis]; });
    } else {
      // Binned SAH over all three axes (Wald 2007, section 3).
      const int nb = opt.bins;
      float best_cost = std::numeric_limits<float>::infinity();
      int best_axis = -1, best_split = -1;
      for (int ax = 0; ax < 3; ++ax) {
        if (!(extent[ax] > 0.0f)) continue;
        const float k = float(nb) * (1.0f - 1e-6f) / extent[ax];
        std::vector<Box> bin_box(nb);
        std::vector<uint32_t> bin_count(nb, 0);
        for (uint32_t i = begin; i < end; ++i) {
          const uint32_t p = out.prims[i];
          const int b = std::clamp(int(k * (centroids[p][ax] - cbounds.lo[ax])), 0, nb - 1);
          bin_box[b].extend(boxes[p]);
          ++bin_count[b];
        }
        std::vector<float> right_area(nb, 0.0f);
        std::vector<uint32_t> right_count(nb, 0);
        Box acc;
        uint32_t cnt = 0;
        for (int b = nb - 1; b > 0; --b) {
          acc.extend(bin_box[b]);
          cnt += bin_count[b];
          right_area[b] = acc.area();
          right_count[b] = cnt;
        }
        acc = Box{};
        cnt = 0;
        for (int b = 0; b < nb - 1; ++b) {
          acc.extend(bin_box[b]);
          cnt += bin_count[b];
          if (cnt == 0 || right_count[b + 1] == 0) continue;
          const float cost = acc.area() * float(cnt) + right_area[b + 1] * float(right_count[b + 1]);
          if (cost < best_cost) best_cost = cost, best_axis = ax, best_split = b;
        }
      }
      // SAH: leaf cost n*C_i against C_t + (A_l n_l + A_r n_r) C_i / A.
      const float leaf_cost = float(n) * opt.intersection_cost;
      const float split_cost = opt.traversal_cost + best_cost * opt.intersection_cost / bounds.area();
      const bool small = n <= uint32_t(opt.max_leaf_size);
      if (small && (best_axis < 0 || leaf_cost <= split_cost)) return make_leaf();
      if (best_axis < 0) {
        mid = begin + n / 2;
        std::nth_element(out.prims.begin() + begin, out.prims.begin() + mid, out.prims.begin() + end,
                         [&](uint32_t a, uint32_t b) { return centroids[a][axis] < centroids[b][axis]; });
      } else {
        const float k = float(nb) * (1.0f - 1e-6f) / extent[best_axis];
        auto it = std::partition(out.prims.begin() + begin, out.prims.begin() + end, [&](uint32_t p) {
          return std::clamp(int(k * (centroids[p][best_axis] - cbounds.lo[best_axis])), 0, nb - 1) <= best_split;
        });
        mid = uint32_t(it - out.prims.begin());
      }
    }
    build(begin, mid, depth + 1);
    const uint32_t right = build(mid, end, depth + 1);
    out.nodes[node_index].index = right;
    out.nodes[node_index].count = 0;
    return node_index;
  }
};

}  // namespace

Bvh build_bvh(const std::vector<glm::vec3>& positions, const std::vector<glm::uvec3>& triangles,
              const BvhOptions& options) {
  Builder b{options, {}, {}, {}};
  b.boxes.resize(triangles.size());
  b.centroids.resize(triangles.size());
  for (size_t i = 0; i < triangles.size(); ++i) {
    const auto t = triangles[i];
    Box box;
    box.extend(positions[t.x]);
    box.extend(positions[t.y]);
    box.extend(positions[t.z]);
    b.boxes[i] = box;
    b.centroids[i] = 0.5f * (box.lo + box.hi);
  }
  b.out.prims.resize(triangles.size());
  for (uint32_t i = 0; i < triangles.size(); ++i) b.out.prims[i] = i;
  if (!triangles.empty()) b.build(0, uint32_t(triangles.size()), 0);
  return std::move(b.out);
}

void refit_bvh(Bvh& bvh, const std::vector<glm::vec3>& positions, const std::vector<glm::uvec3>& triangles) {
  // Depth-first order puts children after their parent (left at i + 1, right at `index`), so
  // one backward sweep sees both children before the parent.
  for (size_t i = bvh.nodes.size(); i-- > 0;) {
    BvhNode& n = bvh.nodes[i];
    Box b;
    if (n.count > 0) {
      for (uint32_t k = n.index; k < n.index + n.count; ++k) {
        const glm::uvec3 t = triangles[bvh.prims[k]];
        b.extend(positions[t.x]), b.extend(positions[t.y]), b.extend(positions[t.z]);
      }
    } else {
      for (const BvhNode* c : {&bvh.nodes[i + 1], &bvh.nodes[n.index]}) b.extend(Box{c->lo, c->hi});
    }
    n.lo = b.lo, n.hi = b.hi;
  }
}

void refit_bvh(Bvh& bvh, const std::vector<glm::vec3>& positions, const std::vector<glm::uvec3>& triangles,
               const std::vector<uint8_t>& moved, std::vector<uint32_t>& refitted) {
  refitted.clear();
  std::vector<uint8_t> dirty(bvh.nodes.size(), 0);
  for (size_t i = bvh.nodes.size(); i-- > 0;) {
    BvhNode& n = bvh.nodes[i];
    Box b;
    if (n.count > 0) {
      bool any = false;
      for (uint32_t k = n.index; k < n.index + n.count && !any; ++k) any = moved[bvh.prims[k]] != 0;
      if (!any) continue;
      for (uint32_t k = n.index; k < n.index + n.count; ++k) {
        const glm::uvec3 t = triangles[bvh.prims[k]];
        b.extend(positions[t.x]), b.extend(positions[t.y]), b.extend(positions[t.z]);
      }
    } else {
      if (!dirty[i + 1] && !dirty[n.index]) continue;
      for (const BvhNode* c : {&bvh.nodes[i + 1], &bvh.nodes[n.index]}) b.extend(Box{c->lo, c->hi});
    }
    n.lo = b.lo, n.hi = b.hi;
    dirty[i] = 1;
    refitted.push_back(uint32_t(i));
  }
  std::reverse(refitted.begin(), refitted.end());
}

double sah_cost(const Bvh& bvh, const BvhOptions& options) {
  if (bvh.nodes.empty()) return 0.0;
  const double root = Box{bvh.nodes[0].lo, bvh.nodes[0].hi}.area();
  if (!(root > 0.0)) return 0.0;
  double cost = 0.0;
  for (const BvhNode& n : bvh.nodes) {
    const double a = Box{n.lo, n.hi}.area() / root;
    cost += a * (n.count > 0 ? double(n.count) * options.intersection_cost : options.traversal_cost);
  }
  return cost;
}

bool intersect_triangle(glm::vec3 org, glm::vec3 dir, glm::vec3 a, glm::vec3 b, glm::vec3 c, float tmax, BvhHit& hit) {
  // Woop, Benthin, Wald 2013, section 3: shear the ray to +z, test edge functions in 2D.
  int kz = 0;
  if (std::abs(dir.y) > std::abs(dir[kz])) kz = 1;
  if (std::abs(dir.z) > std::abs(dir[kz])) kz = 2;
  int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
  if (dir[kz] < 0.0f) std::swap(kx, ky);  // keep the winding
  const float sx = dir[kx] / dir[kz], sy = dir[ky] / dir[kz], sz = 1.0f / dir[kz];
  const glm::vec3 A = a - org, B = b - org, C = c - org;
  const float ax = A[kx] - sx * A[kz], ay = A[ky] - sy * A[kz];
  const float bx = B[kx] - sx * B[kz], by = B[ky] - sy * B[kz];
  const float cx = C[kx] - sx * C[kz], cy = C[ky] - sy * C[kz];
  const float U = cx * by - cy * bx, V = ax * cy - ay * cx, W = bx * ay - by * ax;
  if ((U < 0.0f || V < 0.0f || W < 0.0f) && (U > 0.0f || V > 0.0f || W > 0.0f)) return false;
  const float det = U + V + W;
  if (det == 0.0f) return false;
  const float T = U * (sz * A[kz]) + V * (sz * B[kz]) + W * (sz * C[kz]);
  if (det > 0.0f ? (T <= 0.0f || T >= tmax * det) : (T >= 0.0f || T <= tmax * det)) return false;
  const float inv = 1.0f / det;
  hit.t = T * inv;
  hit.u = V * inv;
  hit.v = W * inv;
  return true;
}

}  // namespace giq::realtime
