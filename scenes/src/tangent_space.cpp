#include "tangent_space.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#include "orthonormal_basis.h"

namespace giq::scenes {
namespace {

// A vertex's position, normal and texture coordinate as bits, with -0 made +0 so that equal
// values weld.
using VertexKey = std::array<uint32_t, 8>;

// splitmix64's finaliser over the key's words (Steele et al. 2014, "Fast Splittable
// Pseudorandom Number Generators"): a spread good enough for linear probing.
uint64_t hash_of(const VertexKey& k) {
  uint64_t h = 0;
  for (const uint32_t w : k) {
    h = (h ^ w) + 0x9e3779b97f4a7c15ull;
    h = (h ^ (h >> 30)) * 0xbf58476d1ce4e5b9ull;
    h = (h ^ (h >> 27)) * 0x94d049bb133111ebull;
    h ^= h >> 31;
  }
  return h;
}

uint32_t bits_of(float x) {
  x += 0.0f;
  uint32_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

// One triangle's UV parameterisation.
struct Face {
  glm::dvec3 dpdu{0.0};     // unit
  bool degenerate = true;   // no UV area (or no extent along u): adds nothing to a tangent
  float sign = 1.0f;        // the bitangent's sign in glTF's convention (header)
};

Face face_of(const glm::dvec3 p[3], const glm::dvec2 t[3]) {
  const glm::dvec3 d1 = p[1] - p[0], d2 = p[2] - p[0];
  const glm::dvec2 t1 = t[1] - t[0], t2 = t[2] - t[0];
  const double area = t1.x * t2.y - t1.y * t2.x;  // twice the UV triangle's signed area
  const glm::dvec3 scaled = t2.y * d1 - t1.y * d2;  // dp/du times that area
  const double length = glm::length(scaled);
  Face f;
  f.sign = area < 0.0 ? 1.0f : -1.0f;
  if (area != 0.0 && length > 0.0 && std::isfinite(length)) {
    f.dpdu = scaled * (std::copysign(1.0, area) / length);
    f.degenerate = false;
  }
  return f;
}

glm::dvec3 unit_or_zero(const glm::dvec3& v) {
  const double l = glm::length(v);
  return l > 0.0 && std::isfinite(l) ? v / l : glm::dvec3(0.0);
}

glm::dvec3 in_plane(const glm::dvec3& v, const glm::dvec3& n) { return unit_or_zero(v - n * glm::dot(n, v)); }

// The tangent of a vertex no triangle with UV area gives one: any unit vector in the plane of
// its normal (unit or zero).
glm::dvec3 tangent_without_uvs(const glm::dvec3& normal) {
  return normal == glm::dvec3(0.0) ? glm::dvec3(1.0, 0.0, 0.0) : any_perpendicular(normal);
}

}  // namespace

GeneratedTangents generate_tangents(const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& normals,
                                    const std::vector<glm::vec2>& uvs, const std::vector<glm::uvec3>& triangles) {
  const size_t n = positions.size(), faces_n = triangles.size();
  // Weld: one id per distinct (position, normal, uv), numbered in order of first appearance,
  // through an open-addressed table of the first vertex of each (the loader welds millions).
  std::vector<uint32_t> weld(n);
  size_t welds = 0;
  {
    std::vector<VertexKey> keys(n);
    for (size_t i = 0; i < n; ++i) {
      const glm::vec3 &p = positions[i], &q = normals[i];
      const glm::vec2& t = uvs[i];
      keys[i] = {bits_of(p.x), bits_of(p.y), bits_of(p.z), bits_of(q.x), bits_of(q.y), bits_of(q.z), bits_of(t.x), bits_of(t.y)};
    }
    size_t size = 16;
    while (size < 2 * n) size *= 2;
    std::vector<uint32_t> table(size, UINT32_MAX);
    for (size_t i = 0; i < n; ++i)
      for (size_t slot = hash_of(keys[i]) & (size - 1);; slot = (slot + 1) & (size - 1)) {
        if (table[slot] == UINT32_MAX) {
          table[slot] = uint32_t(i), weld[i] = uint32_t(welds++);
          break;
        }
        if (keys[table[slot]] == keys[i]) {
          weld[i] = weld[table[slot]];
          break;
        }
      }
  }
  auto corner = [&](size_t f, int c) { return triangles[f][c]; };
  auto welded = [&](size_t f, int c) { return weld[triangles[f][c]]; };

  std::vector<Face> faces(faces_n);
  for (size_t f = 0; f < faces_n; ++f) {
    glm::dvec3 p[3];
    glm::dvec2 t[3];
    for (int c = 0; c < 3; ++c) p[c] = positions[corner(f, c)], t[c] = uvs[corner(f, c)];
    faces[f] = face_of(p, t);
  }

  // The corners at each welded vertex, in triangle order, with the welded vertices before
  // and after each corner in its triangle. The triangle across the edge a -> b of one
  // triangle is the first with the edge b -> a (consistently wound neighbours): the first
  // corner at a whose triangle comes to a from b.
  std::vector<uint32_t> first(welds + 1, 0), around(3 * faces_n), before(3 * faces_n), after(3 * faces_n);
  for (size_t f = 0; f < faces_n; ++f)
    for (int c = 0; c < 3; ++c) ++first[welded(f, c) + 1];
  for (size_t v = 0; v < welds; ++v) first[v + 1] += first[v];
  {
    std::vector<uint32_t> fill(first.begin(), first.end() - 1);
    for (size_t f = 0; f < faces_n; ++f)
      for (int c = 0; c < 3; ++c) {
        const uint32_t i = fill[welded(f, c)]++;
        around[i] = uint32_t(3 * f + size_t(c)), before[i] = welded(f, (c + 2) % 3), after[i] = welded(f, (c + 1) % 3);
      }
  }
  // The corner at a of the triangle across the edge a -> b (or b -> a when `reverse`), or -1.
  auto across = [&](uint32_t a, uint32_t b, bool reverse = false) -> int64_t {
    const std::vector<uint32_t>& from = reverse ? after : before;
    for (uint32_t i = first[a]; i < first[a + 1]; ++i)
      if (from[i] == b) return around[i];
    return -1;
  };

  // A triangle without UV area takes its orientation from a neighbour, breadth first from
  // those that have one (unreached ones keep +1).
  {
    std::vector<uint32_t> queue;
    std::vector<bool> known(faces_n);
    for (size_t f = 0; f < faces_n; ++f)
      if (!faces[f].degenerate) queue.push_back(uint32_t(f)), known[f] = true;
    for (size_t q = 0; q < queue.size(); ++q) {
      const uint32_t f = queue[q];
      for (int c = 0; c < 3; ++c) {
        const int64_t k = across(welded(f, c), welded(f, (c + 1) % 3));
        const size_t g = size_t(k) / 3;
        if (k >= 0 && !known[g]) faces[g].sign = faces[f].sign, known[g] = true, queue.push_back(uint32_t(g));
      }
    }
  }

  // Groups: around the welded vertex of each corner, the triangles reached across edges that
  // share the vertex, of the same orientation. group[3f + c] indexes group_tangent.
  std::vector<int32_t> group(3 * faces_n, -1);
  std::vector<glm::vec4> group_tangent;
  std::vector<uint32_t> members;
  for (size_t f0 = 0; f0 < faces_n; ++f0)
    for (int c0 = 0; c0 < 3; ++c0) {
      if (group[3 * f0 + size_t(c0)] >= 0) continue;
      const int32_t id = int32_t(group_tangent.size());
      const uint32_t v = welded(f0, c0);
      const float sign = faces[f0].sign;
      members.assign(1, uint32_t(3 * f0 + size_t(c0)));
      group[members[0]] = id;
      for (size_t m = 0; m < members.size(); ++m) {
        const uint32_t k = members[m];
        const size_t f = k / 3;
        const int c = int(k % 3);
        // Across the edges v -> next and previous -> v.
        for (const int64_t kg : {across(v, welded(f, (c + 1) % 3)), across(v, welded(f, (c + 2) % 3), true)})
          if (kg >= 0 && faces[size_t(kg) / 3].sign == sign && group[size_t(kg)] < 0) group[size_t(kg)] = id, members.push_back(uint32_t(kg));
      }
      const glm::dvec3 normal = unit_or_zero(glm::dvec3(normals[corner(f0, c0)]));
      glm::dvec3 sum(0.0);
      for (const uint32_t k : members) {
        const size_t f = k / 3;
        const int c = int(k % 3);
        if (faces[f].degenerate) continue;
        const glm::dvec3 at = positions[corner(f, c)];
        const glm::dvec3 e1 = in_plane(glm::dvec3(positions[corner(f, (c + 2) % 3)]) - at, normal);
        const glm::dvec3 e2 = in_plane(glm::dvec3(positions[corner(f, (c + 1) % 3)]) - at, normal);
        const double angle = std::acos(std::clamp(glm::dot(e1, e2), -1.0, 1.0));
        sum += angle * in_plane(faces[f].dpdu, normal);
      }
      glm::dvec3 t = unit_or_zero(sum);
      if (t == glm::dvec3(0.0)) t = tangent_without_uvs(normal);
      group_tangent.emplace_back(glm::vec3(t), sign);
    }

  // One tangent per vertex: a vertex whose corners fall in groups with different tangents is
  // split, its copies chained through `next`.
  GeneratedTangents out;
  out.tangents.assign(n, glm::vec4(0.0f));
  out.source.resize(n);
  for (size_t i = 0; i < n; ++i) out.source[i] = uint32_t(i);
  std::vector<bool> set(n);
  std::vector<uint32_t> next(n, UINT32_MAX);
  out.triangles = triangles;
  for (size_t f = 0; f < faces_n; ++f)
    for (int c = 0; c < 3; ++c) {
      const glm::vec4 t = group_tangent[size_t(group[3 * f + size_t(c)])];
      uint32_t i = corner(f, c);
      if (!set[i]) {
        out.tangents[i] = t, set[i] = true;
      } else {
        while (out.tangents[i] != t && next[i] != UINT32_MAX) i = next[i];
        if (out.tangents[i] != t) {
          const uint32_t copy = uint32_t(out.tangents.size());
          next[i] = copy;
          next.push_back(UINT32_MAX);
          out.tangents.push_back(t);
          out.source.push_back(out.source[i]);
          i = copy;
        }
      }
      out.triangles[f][c] = i;
    }
  // Vertices no triangle uses still get a unit tangent in their normal's plane.
  for (size_t i = 0; i < n; ++i)
    if (!set[i]) out.tangents[i] = glm::vec4(glm::vec3(tangent_without_uvs(unit_or_zero(glm::dvec3(normals[i])))), 1.0f);
  return out;
}

}  // namespace giq::scenes
