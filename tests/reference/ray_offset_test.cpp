// Secondary rays leave a surface by an offset set by the triangle's own coordinates
// (ray_offset.h): they never find their own triangle again, and the light they find does not
// depend on how large the rest of the scene is.

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "embree_scene.h"
#include "giq/reference/ray_offset.h"
#include "giq/reference/renderer.h"
#include "giq/reference/sampling.h"
#include "scene_builder.h"

namespace giq::reference {
namespace {

TEST(RayOffset, MovesAFixedShareOfTheTrianglesLargestCoordinateAlongTheNormal) {
  const glm::vec3 n = glm::normalize(glm::vec3(0.3f, 0.9f, -0.2f));
  for (float size : {1e-3f, 1.0f, 1e4f})
    for (float dist : {0.0f, 1e-3f, 1.0f, 1e4f, 1e5f}) {
      const glm::vec3 a = glm::vec3(dist, -0.5f * dist, 0.25f * dist);
      const glm::vec3 p0 = a, p1 = a + glm::vec3(size, 0, 0), p2 = a + glm::vec3(0, 0, size);
      const glm::vec3 p = (p0 + p1 + p2) / 3.0f;
      const float offset = ray_offset(p0, p1, p2);
      const double largest = std::max(std::abs(double(dist) + size), 0.5 * dist);
      EXPECT_NEAR(offset, RayOffset::kUnits * std::ldexp(largest, -24), 1e-6 * offset) << size << " at " << dist;
      const glm::vec3 o = offset_ray_origin(p, n, offset);
      const double along = glm::dot(glm::dvec3(o) - glm::dvec3(p), glm::dvec3(n));
      // Rounding o to floats moves it by at most half a unit in the last place per axis.
      const double ulp = std::ldexp(1.0, std::ilogb(std::max(float(glm::length(p)), 1e-30f)) - 23);
      EXPECT_GT(along, 0.0) << size << " at " << dist;
      EXPECT_NEAR(along, offset, ulp) << size << " at " << dist;
    }
}

// A plate of two triangles, `width` wide, posed by `pose`, left by rays from points spread over
// it, on both sides, half of them cosine-distributed and half within 0.06° of grazing:
// none may meet the plate again. kUnits is 2.7 times the smallest multiple seen to be safe.
int self_hits(float width, const glm::mat4& pose, int rays) {
  scenes::Scene s;
  const int m = test::add_material(s, test::diffuse(glm::vec3(0.5f), glm::vec3(0.0f), true));
  const float h = 0.5f * width;
  glm::vec3 v[4] = {{-h, 0, -h}, {-h, 0, h}, {h, 0, h}, {h, 0, -h}};
  for (glm::vec3& x : v) x = glm::vec3(pose * glm::vec4(x, 1.0f));
  test::add_quad(s, m, v[0], v[1], v[2], v[3]);
  s.derive();
  const glm::vec3 centre(0.0f);  // the renderer's frame is the scene's, so pose moves off centre
  const EmbreeScene bvh(s, centre, false);
  const std::vector<glm::vec3>& pos = bvh.positions()[0];
  const glm::uvec3 tri[2] = {s.meshes[0].triangles[0], s.meshes[0].triangles[1]};
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  int hits = 0;
  for (int i = 0; i < rays; ++i) {
    const glm::uvec3 t = tri[i & 1];
    const glm::vec3 p0 = pos[t.x], p1 = pos[t.y], p2 = pos[t.z];
    const glm::vec2 b = square_to_triangle_barycentrics({uniform(rng), uniform(rng)});
    const glm::vec3 p = (1.0f - b.x - b.y) * p0 + b.x * p1 + b.y * p2;
    const glm::vec3 n = bvh.shapes()[0][i & 1].normal * (i & 2 ? 1.0f : -1.0f);
    const glm::vec3 o = offset_ray_origin(p, n, ray_offset(p0, p1, p2));
    const float u = uniform(rng), phi = 6.2831853f * uniform(rng);
    const float cos_t = i & 4 ? std::sqrt(u) : 1e-3f * u, sin_t = std::sqrt(1.0f - cos_t * cos_t);
    const Frame f = Frame::from_normal(n);
    const glm::vec3 d = f.to_world({sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t});
    hits += bvh.intersect(o, d).valid() ? 1 : 0;
  }
  return hits;
}

TEST(RayOffset, RaysNeverMeetTheirOwnPlateAtAnyScaleOrDistance) {
  for (float width : {0.01f, 160.0f, 1e4f})
    for (float shift : {0.0f, 1000.0f})
      for (int tilt = 0; tilt < 6; ++tilt) {
        glm::mat4 pose(1.0f);
        pose[3] = glm::vec4(shift, 0.3f * shift - 0.5f, 0.7f * shift, 1.0f);
        const glm::vec3 axis = glm::normalize(glm::vec3(1.0f, 0.3f * float(tilt), 0.2f - 0.1f * float(tilt)));
        const float c = std::cos(0.37f * float(tilt)), sn = std::sin(0.37f * float(tilt));
        // Rodrigues' rotation about `axis` by 0.37 * tilt radians.
        glm::mat3 r = c * glm::mat3(1.0f) + (1.0f - c) * glm::outerProduct(axis, axis);
        r += sn * glm::mat3(0, axis.z, -axis.y, -axis.z, 0, axis.x, axis.y, -axis.x, 0);
        pose = pose * glm::mat4(r);
        EXPECT_EQ(self_hits(width, pose, 20000), 0) << "width " << width << " shift " << shift << " tilt " << tilt;
      }
}

// The plate test: a Lambertian plate of albedo kRho, `width` wide, under a 1.2 x 0.8 m emitter
// 1 m above it, seen by a camera below the emitter. The radiance of every plate pixel is
// kRho / pi times the irradiance of Lambert's polygon formula; each estimator is compared on
// the mean over the pixels. For BSDF sampling its standard error is 0.033 %, and an offset
// scaled by the scene's width, as it used to be, made this view of the 160 m plate 0.26 %
// too bright (8 standard errors); MIS diluted that to 0.02 %.
constexpr float kRho = 0.5f;
constexpr float kRadiance = 4.0f;
constexpr int kSize = 48;
const glm::vec3 kEmitter[4] = {{-0.6f, 1.0f, -0.4f}, {0.6f, 1.0f, -0.4f}, {0.6f, 1.0f, 0.4f}, {-0.6f, 1.0f, 0.4f}};
const scenes::Camera kCamera = scenes::Camera::look_at({0.0f, 0.7f, 1.6f}, {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, 0.7f);

// Lambert (1760): the irradiance at q (normal +y) from a polygon of uniform radiance L is
// L/2 times the sum over its edges of the edge's angle seen from q times the cosine between
// the normal and the plane through q and the edge.
double polygon_irradiance(glm::dvec3 q, double radiance) {
  double sum = 0.0;
  for (int i = 0; i < 4; ++i) {
    const glm::dvec3 a = glm::normalize(glm::dvec3(kEmitter[i]) - q), b = glm::normalize(glm::dvec3(kEmitter[(i + 1) % 4]) - q);
    sum += std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0)) * glm::normalize(glm::cross(a, b)).y;
  }
  return 0.5 * radiance * std::abs(sum);
}

scenes::Scene plate_scene(float width) {
  scenes::Scene s;
  const int plate = test::add_material(s, test::diffuse(glm::vec3(kRho)));
  const int lamp = test::add_material(s, test::diffuse(glm::vec3(0.0f), glm::vec3(kRadiance)));
  const float h = 0.5f * width;
  test::add_quad(s, plate, {-h, 0, h}, {h, 0, h}, {h, 0, -h}, {-h, 0, -h}, 1);
  // Facing down.
  test::add_quad(s, lamp, kEmitter[0], kEmitter[1], kEmitter[2], kEmitter[3], 2);
  s.derive();
  return s;
}

void expect_plate_matches(float width, Estimator estimator, uint32_t spp) {
  const scenes::Scene s = plate_scene(width);
  RenderSettings rs;
  rs.width = rs.height = kSize;
  rs.max_bounces = 1;
  rs.estimator = estimator;
  rs.pixel_centre = true;
  Renderer r(s, kCamera, rs);
  Film f = r.make_film();
  r.render(f, spp);
  ASSERT_EQ(f.nonfinite_samples(), 0u);
  double rendered = 0.0, expected = 0.0, variance = 0.0;
  int pixels = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const glm::dvec3 d = kCamera.ray_direction(float(x) + 0.5f, float(y) + 0.5f, kSize, kSize);
      if (!(d.y < 0.0)) continue;
      const glm::dvec3 q = glm::dvec3(kCamera.position) + d * (-double(kCamera.position.y) / d.y);
      if (std::max(std::abs(q.x), std::abs(q.z)) > 0.5 * width) continue;
      const PixelAccumulator& p = f.pixels[size_t(y) * kSize + size_t(x)];
      rendered += p.mean[1];
      variance += p.variance_of_mean(1);
      expected += kRho / 3.14159265358979323846 * polygon_irradiance(q, kRadiance);
      ++pixels;
    }
  ASSERT_GT(pixels, kSize * kSize / 2);
  const double sigma = std::sqrt(variance);
  // The test must be able to see the old bias.
  EXPECT_LT(sigma / expected, 0.0005);
  // The offset's own bias is 2 * offset / distance at most, with the plate's largest
  // coordinate in the renderer's frame (centred on the scene) and the lamp 1 m away at least;
  // float precision of rays and hit points adds ~1e-6.
  const double bias = 2.0 * RayOffset::kUnits * std::ldexp(0.5 * width, -24) / 1.0;
  EXPECT_NEAR(rendered / expected, 1.0, 4.0 * sigma / expected + bias + 1e-6)
      << "plate " << width << " m, " << pixels << " pixels, standard error " << sigma / expected;
}

TEST(RayOffset, PlateUnderARectangularLampMatchesTheClosedFormAt10m) {
  expect_plate_matches(10.0f, Estimator::BsdfOnly, 8192);
  expect_plate_matches(10.0f, Estimator::LightOnly, 256);
  expect_plate_matches(10.0f, Estimator::Mis, 256);
}

TEST(RayOffset, PlateUnderARectangularLampMatchesTheClosedFormAt160m) {
  expect_plate_matches(160.0f, Estimator::BsdfOnly, 8192);
  expect_plate_matches(160.0f, Estimator::LightOnly, 256);
  expect_plate_matches(160.0f, Estimator::Mis, 256);
}

}  // namespace
}  // namespace giq::reference
