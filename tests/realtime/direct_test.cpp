// `direct` against closed forms (punctual lights on a Lambertian plane, glTF's spot falloff and
// range window computed by the scene library), against `pt` for an unoccluded area light (the
// polygon integral is exact, so only pt's noise remains), shadows against ray casting, soft
// shadows of an area light against the closed form of the light's visible part (glowing
// particles: particle_lights_test.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "giq/realtime/renderer.h"
#include "polygon_irradiance.h"
#include "test_scenes.h"

namespace giq::realtime {
namespace {

using DirectTest = test::VulkanTest;

// The point of the plane y = 0 seen through pixel (x, y)'s centre.
glm::vec3 plane_point(const scenes::Camera& cam, int x, int y, int size) {
  const glm::vec3 d = cam.ray_direction(x + 0.5f, y + 0.5f, size, size);
  const glm::vec3 o = cam.ray_origin(x + 0.5f, y + 0.5f, size, size);
  return o + (-o.y / d.y) * d;
}

TEST_F(DirectTest, PunctualLightsOnAPlaneMatchTheClosedForm) {
  const float rho = 0.7f;
  scenes::Scene s = test::lambert_plane(rho);
  scenes::Light point;
  point.type = scenes::LightType::Point;
  point.position = {0.5f, 1.5f, 0.2f};
  point.intensity = 8.0f;
  point.color = {1.0f, 0.5f, 0.25f};
  point.range = 4.0f;  // the window cuts the far corners of the plane
  scenes::Light spot;
  spot.type = scenes::LightType::Spot;
  spot.position = {-0.8f, 2.0f, -0.5f};
  spot.direction = glm::normalize(glm::vec3(0.2f, -1.0f, 0.1f));
  spot.inner_cone = 0.3f;
  spot.outer_cone = 0.6f;
  spot.intensity = 20.0f;
  scenes::Light sun;
  sun.type = scenes::LightType::Directional;
  sun.direction = glm::normalize(glm::vec3(-0.4f, -1.0f, 0.3f));
  sun.intensity = 0.5f;
  s.lights = {point, spot, sun};
  s.derive();
  const int size = 48;
  // The same through an orthographic camera (a window of 5 m, inside the 8 m plane): the
  // rasteriser's orthographic projection must put each point on its pixel's ray.
  for (const bool orthographic : {false, true}) {
    SCOPED_TRACE(orthographic ? "orthographic" : "perspective");
    s.views[0].camera.ymag = orthographic ? 2.5f : 0.0f;
    const image::Image img = render(s, "direct", size, {"shadow_map_size=512"});
    const auto& cam = s.views[0].camera;
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        const glm::vec3 p = plane_point(cam, x, y, size);
        glm::vec3 expected(0.0f);
        for (const auto& l : s.lights) {
          if (l.type == scenes::LightType::Directional) {
            expected += l.radiant() * std::max(0.0f, -l.direction.y);
            continue;
          }
          const glm::vec3 to = l.position - p;
          const float d = glm::length(to);
          float f = scenes::range_window(d, l.range) / (d * d) * std::max(0.0f, to.y / d);
          if (l.type == scenes::LightType::Spot)
            f *= scenes::spot_attenuation(glm::dot(l.direction, -to / d), l.inner_cone, l.outer_cone);
          expected += l.radiant() * f;
        }
        expected *= rho / float(M_PI);
        const char* ch[3] = {"R", "G", "B"};
        for (int c = 0; c < 3; ++c) {
          // float32 evaluation of the same formulas: a few ulps of relative error.
          EXPECT_NEAR(img.at(ch[c], x, y), expected[c], 1e-4f * expected[c] + 1e-7f) << x << "," << y << " " << ch[c];
          EXPECT_EQ(img.at(std::string("indirect.") + ch[c], x, y), 0.0f);
          EXPECT_EQ(img.at(std::string("direct.") + ch[c], x, y), img.at(ch[c], x, y));
        }
      }
  }
}

TEST_F(DirectTest, UnoccludedAreaLightAgreesWithThePathTracer) {
  // A one-sided emissive quad, then a closed emissive cube (its faces outwards), above a
  // Lambertian plane, nothing in between: the polygon integral is exact, so direct and pt's
  // direct layer agree within pt's noise. The cube's shadow cube sits at its centre and must
  // leave the cube itself out, or its faces would shadow everything.
  for (const bool cube : {false, true}) {
    SCOPED_TRACE(cube ? "closed cube" : "quad");
    scenes::Scene s = test::lambert_plane(0.6f);
    const int light = test::add_material(s, glm::vec3(0.0f), glm::vec3(5.0f, 4.0f, 3.0f));
    if (!cube) {
      test::add_quad(s, {-0.5f, 1.0f, -0.3f}, {0.7f, 1.0f, -0.3f}, {0.7f, 1.0f, 0.4f}, {-0.5f, 1.0f, 0.4f}, light);
    } else {
      const glm::vec3 lo(-0.1f, 0.8f, -0.15f), hi(0.3f, 1.2f, 0.25f);
      auto corner = [&](int i) { return glm::vec3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z); };
      // Counter-clockwise seen from outside.
      const int faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
      for (const auto& f : faces) test::add_quad(s, corner(f[0]), corner(f[1]), corner(f[2]), corner(f[3]), light);
      // One closed mesh of the six faces.
      scenes::Mesh closed = s.meshes[1];
      for (size_t k = 2; k < s.meshes.size(); ++k) {
        const uint32_t base = uint32_t(closed.positions.size());
        const scenes::Mesh& q = s.meshes[k];
        closed.positions.insert(closed.positions.end(), q.positions.begin(), q.positions.end());
        closed.normals.insert(closed.normals.end(), q.normals.begin(), q.normals.end());
        for (const glm::uvec3& t : q.triangles) closed.triangles.push_back(t + glm::uvec3(base));
      }
      s.meshes.resize(1);
      s.meshes.push_back(closed);
    }
    s.derive();
    ASSERT_EQ(s.meshes[1].material, light);
    ASSERT_EQ(s.area_lights.size(), 1u);
    EXPECT_EQ(s.area_lights[0].flat, !cube);  // the cube's area vectors cancel: its centre is inside
    const int size = 24;
    const image::Image d = render(s, "direct", size, {"shadow_map_size=256"});
    const image::Image p = render(s, "pt", size, {"samples_per_frame=256", "max_bounces=1"});
    // Pixels that see the emitter (its emission, 4 in G) and their neighbours are left out:
    // pt averages over the pixel, direct evaluates its centre.
    auto near_light = [&](int x, int y) {
      for (int j = std::max(0, y - 1); j <= std::min(size - 1, y + 1); ++j)
        for (int i = std::max(0, x - 1); i <= std::min(size - 1, x + 1); ++i)
          if (d.at("G", i, j) >= 3.9f || p.at("direct.G", i, j) >= 3.9f) return true;
      return false;
    };
    size_t outliers = 0, compared = 0;
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        if (near_light(x, y)) continue;
        const double sigma = std::sqrt(p.at("variance.G", x, y));
        // The radiance varies smoothly, by under 0.1% across a pixel here.
        const double ref = p.at("direct.G", x, y);
        outliers += std::abs(d.at("G", x, y) - ref) > 4.0 * sigma + 2e-3 * ref;
        ++compared;
      }
    EXPECT_GT(compared, size_t(size * size / 2));
    EXPECT_LE(double(outliers), 0.005 * size * size) << outliers << " pixels beyond 4 sigma";
  }
}

// A disc of `segments` triangles around `c` facing -y (lights below it), and a capsule: the
// segment c +- (half, 0, 0) swept by radius r, its rings over the polar angle split at the
// equator and pushed apart along x.
void add_disc(scenes::Scene& s, glm::vec3 c, float r, int segments, int material) {
  scenes::Mesh m;
  m.material = material;
  m.object_id = uint32_t(s.meshes.size() + 1);
  m.positions.push_back(c), m.normals.emplace_back(0.0f, -1.0f, 0.0f);
  for (int j = 0; j < segments; ++j) {
    const float a = 2.0f * float(M_PI) * float(j) / float(segments);
    m.positions.push_back(c + r * glm::vec3(std::cos(a), 0.0f, std::sin(a))), m.normals.emplace_back(0.0f, -1.0f, 0.0f);
    m.triangles.emplace_back(0u, uint32_t(1 + j), uint32_t(1 + (j + 1) % segments));
  }
  s.meshes.push_back(std::move(m));
}
void add_capsule(scenes::Scene& s, glm::vec3 c, float half, float r, int rings, int segments, int material) {
  scenes::Mesh m;
  m.material = material;
  m.object_id = uint32_t(s.meshes.size() + 1);
  for (int i = 0; i <= rings; ++i)
    for (int j = 0; j <= segments; ++j) {
      const float th = float(M_PI) * float(i) / float(rings), ph = 2.0f * float(M_PI) * float(j) / float(segments);
      const glm::vec3 n(std::cos(th), std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph));
      m.positions.push_back(c + r * n + glm::vec3(2 * i <= rings ? half : -half, 0.0f, 0.0f));
      m.normals.push_back(n);
    }
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const uint32_t a = uint32_t(i * (segments + 1) + j), b = a + 1, d = a + uint32_t(segments + 1), e = d + 1;
      m.triangles.push_back({a, d, b});
      m.triangles.push_back({b, d, e});
    }
  s.meshes.push_back(std::move(m));
}

// Each declared shape (sphere, disc, rectangle, tube) 0.8 above a glossy metal plane
// (roughness 0.3), against `pt`'s direct light (one bounce, 512 paths): the representative
// point is an approximation, so the test holds what Karis 2013's normalisation is for, the
// reflected energy. Measured (sum over the plane of direct / pt): sphere 1.03, disc 0.97,
// rectangle 1.18, tube 1.01, where the triangles as their own lights give 0.91, 1.16, 1.34 and
// 1.84; per pixel, |direct - pt| / pt averages 0.45, 0.41, 0.35 and 0.43 for the shapes
// against 0.18, 0.22, 0.44 and 1.18 for the triangles (one point per light puts the highlight's
// energy less exactly than one point per triangle, at a fraction of the cost). A lost or doubled
// term moves the energy by a factor near 2; the bound is 25 %. The tube, whose thin triangles
// each widen their lobe by their own small size, is where the declared shape matters most.
TEST_F(DirectTest, DeclaredAreaLightShapesOnAGlossyPlane) {
  const scenes::AreaShape shapes[] = {scenes::AreaShape::Sphere, scenes::AreaShape::Disc, scenes::AreaShape::Rectangle,
                                      scenes::AreaShape::Tube};
  const char* names[] = {"sphere", "disc", "rectangle", "tube"};
  for (int k = 0; k < 4; ++k) {
    double energy[2] = {0.0, 0.0};
    for (const bool declared : {false, true}) {
      scenes::Scene s = test::lambert_plane(0.9f, 3.0f);
      scenes::Material& floor = s.materials[0];
      floor.metallic = 1.0f, floor.roughness = 0.3f, floor.specular = 1.0f;
      const int light = test::add_material(s, glm::vec3(0.0f), glm::vec3(4.0f));
      switch (shapes[k]) {
        case scenes::AreaShape::Sphere: test::add_sphere(s, {0.0f, 0.8f, -0.6f}, 0.25f, 16, 32, light); break;
        case scenes::AreaShape::Disc: add_disc(s, {0.0f, 0.8f, -0.6f}, 0.3f, 32, light); break;
        case scenes::AreaShape::Rectangle:
          test::add_quad(s, {-0.5f, 0.8f, -0.75f}, {0.5f, 0.8f, -0.75f}, {0.5f, 0.8f, -0.45f}, {-0.5f, 0.8f, -0.45f}, light);
          break;
        default: add_capsule(s, {0.0f, 0.8f, -0.6f}, 0.35f, 0.06f, 16, 16, light); break;
      }
      if (declared) s.meshes.back().area_shape = shapes[k];
      s.views.push_back({"side", scenes::Camera::look_at({0.0f, 1.2f, 2.2f}, {0.0f, 0.0f, -0.8f}, {0, 1, 0}, 0.9f), -1});
      s.derive();
      ASSERT_EQ(s.area_lights.size(), 1u);
      EXPECT_EQ(s.area_lights[0].shape, declared ? shapes[k] : scenes::AreaShape::Mesh) << names[k];
      const int size = 48;
      realtime::RenderOptions o;
      o.view = "side", o.width = o.height = size;
      o.technique = "direct", o.parameters = {"shadow_map_size=512"};
      const image::Image d = render_last(s, o);
      o.technique = "pt", o.parameters = {"samples_per_frame=512", "max_bounces=1"};
      const image::Image p = render_last(s, o);
      double err = 0.0, sum_d = 0.0, sum_p = 0.0;
      for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
          const double a = d.at("G", x, y), b = p.at("direct.G", x, y);
          ASSERT_TRUE(std::isfinite(a)) << names[k] << " pixel " << x << "," << y;
          if (a >= 3.9 || b >= 3.9) continue;  // the emitter itself, seen directly
          err += std::abs(a - b), sum_d += a, sum_p += b;
        }
      ASSERT_GT(sum_p, 0.0) << names[k];
      energy[declared] = sum_d / sum_p;
      std::printf("%s %s: mean |direct - pt| / mean pt %.3f, energy direct / pt %.3f\n", names[k],
                  declared ? "declared" : "triangles", err / sum_p, energy[declared]);
    }
    EXPECT_NEAR(energy[1], 1.0, 0.25) << names[k];
    if (shapes[k] == scenes::AreaShape::Tube) {
      EXPECT_LT(std::abs(energy[1] - 1.0), std::abs(energy[0] - 1.0));
    }
  }
}

TEST_F(DirectTest, ShadowsMatchRayCastingAwayFromTheirEdges) {
  scenes::Scene s = test::lambert_plane(0.5f);
  const int m = test::add_material(s, glm::vec3(0.5f));
  // An occluder square 0.8 above the plane, under a point light at height 2.
  test::add_quad(s, {-0.4f, 0.8f, 0.4f}, {0.4f, 0.8f, 0.4f}, {0.4f, 0.8f, -0.4f}, {-0.4f, 0.8f, -0.4f}, m);
  scenes::Light l;
  l.type = scenes::LightType::Point;
  l.position = {0.1f, 2.0f, 0.0f};
  l.intensity = 10.0f;
  s.lights.push_back(l);
  s.derive();
  const int size = 64;
  const image::Image img = render(s, "direct", size, {"shadow_map_size=1024", "pcf_radius=1"});
  const auto& cam = s.views[0].camera;
  int checked = 0, wrong = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const glm::vec3 p = plane_point(cam, x, y, size);
      // Pixels whose camera ray meets the occluder (at height 0.8) do not see the plane.
      const glm::vec3 o = cam.position + (cam.position.y - 0.8f) / (cam.position.y - p.y) * (p - cam.position);
      if (std::abs(o.x) < 0.4f + 0.05f && std::abs(o.z) < 0.4f + 0.05f) continue;
      // Where the ray from the point to the light crosses the occluder's plane: inside the
      // square = shadowed. Skip points whose crossing is within 3 shadow texels of the edge
      // (PCF and the normal offset blur the boundary there).
      const float t = (0.8f - p.y) / (l.position.y - p.y);
      const glm::vec3 c = p + t * (l.position - p);
      const float edge = std::min(std::abs(std::abs(c.x) - 0.4f), std::abs(std::abs(c.z) - 0.4f));
      const float texel = 2.0f * 1.2f / 1024.0f;  // a 90-degree face is 2d wide at distance d ~ 1.2
      if (std::max(std::abs(c.x), std::abs(c.z)) < 0.4f + 3.0f * texel && edge < 3.0f * texel) continue;
      const bool shadowed = std::abs(c.x) < 0.4f && std::abs(c.z) < 0.4f;
      const glm::vec3 to = l.position - p;
      const float dd = glm::length(to);
      const float lit = 0.5f / float(M_PI) * l.intensity * (to.y / dd) / (dd * dd);
      const float v = img.at("G", x, y);
      ++checked;
      wrong += shadowed ? v > 0.01f * lit : std::abs(v - lit) > 1e-4f * lit;
    }
  EXPECT_GT(checked, size * size / 2);
  EXPECT_EQ(wrong, 0) << "of " << checked;
}

// Soft shadows (area_shadow_rays): a 1 x 1 m light 2 m above a Lambertian floor, a 0.5 m bar
// across it 1 m up. From a floor point q the bar hides the light's strip
// x in [-0.5 - q.x, 0.5 - q.x], so the share of the light's irradiance that arrives is
// V(q) = 1 - E(strip) / E(light) (Lambert's polygon formula), 1 for |q.x| >= 1. The pass
// multiplies the exact unshadowed light by its estimate of V from N rays: where V = 1 every ray
// arrives and the pixel holds exactly the bits it holds without the bar; in the penumbra the
// estimate's error is the ratio estimator's, whose standard deviation is at most
// sqrt(r / 4N), r the largest over the mean weight of a point on the light (the irradiance
// integrand cos cos / d^2 varies at most 4-fold over the light for these floor points): 0.0625
// at N = 256. Checked: the RMS error over the penumbra below that, the mean error within 4
// standard errors of it, and the hard shadows of the cube map (N = 0) for contrast far off.
TEST_F(DirectTest, SoftShadowsOfAnAreaLightMatchTheVisiblePartOfTheLight) {
  scenes::Scene open = test::lambert_plane(0.6f);
  const int light = test::add_material(open, glm::vec3(0.0f), glm::vec3(4.0f));
  test::add_quad(open, {-0.5f, 2.0f, -0.5f}, {0.5f, 2.0f, -0.5f}, {0.5f, 2.0f, 0.5f}, {-0.5f, 2.0f, 0.5f}, light);  // faces down
  // A wide-angle camera under the bar, looking down: the floor from x = -1.4 to 1.4.
  open.views[0].camera = scenes::Camera::look_at({0.0f, 0.9f, 0.0f}, {0.0f, 0.0f, 0.0f}, {0, 0, -1}, 2.0f);
  open.derive();
  scenes::Scene barred = open;
  const int black = test::add_material(barred, glm::vec3(0.0f));
  barred.materials[size_t(black)].double_sided = true;
  test::add_quad(barred, {-0.25f, 1.0f, -3.0f}, {0.25f, 1.0f, -3.0f}, {0.25f, 1.0f, 3.0f}, {-0.25f, 1.0f, 3.0f}, black);
  barred.derive();
  ASSERT_EQ(barred.area_lights.size(), 1u);
  const int size = 48, rays = 256;
  const std::string soft = "area_shadow_rays=" + std::to_string(rays);
  const image::Image lit = render(open, "direct", size, {"shadow_map_size=256", soft});
  const image::Image shaded = render(barred, "direct", size, {"shadow_map_size=256", soft});
  const image::Image hard = render(barred, "direct", size, {"shadow_map_size=256"});
  const std::vector<glm::dvec3> whole = {{-0.5, 2, -0.5}, {0.5, 2, -0.5}, {0.5, 2, 0.5}, {-0.5, 2, 0.5}};
  const scenes::Camera& cam = open.views[0].camera;
  double sum = 0.0, sum2 = 0.0, hard2 = 0.0;
  int penumbra = 0, full = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const glm::dvec3 q(plane_point(cam, x, y, size));
      if (std::abs(q.x) > 1.4 || std::abs(q.z) > 1.4) continue;
      const float r0 = lit.at("G", x, y), r = shaded.at("G", x, y);
      ASSERT_GT(r0, 0.0f) << x << ", " << y;
      if (std::abs(q.x) >= 1.0 + 1e-3) {  // every ray arrives
        ++full;
        EXPECT_EQ(r, r0) << "pixel " << x << ", " << y << " sees all of the light";
        continue;
      }
      const double lo = std::max(-0.5, -0.5 - q.x), hi = std::min(0.5, 0.5 - q.x);
      const double v = 1.0 - test::polygon_irradiance(q, test::kUp, {{lo, 2, -0.5}, {hi, 2, -0.5}, {hi, 2, 0.5}, {lo, 2, 0.5}}) /
                                 test::polygon_irradiance(q, test::kUp, whole);
      if (v < 0.02 || v > 0.98) continue;
      const double e = double(r) / r0 - v;
      sum += e;
      sum2 += e * e;
      hard2 += std::pow(double(hard.at("G", x, y)) / r0 - v, 2);
      ++penumbra;
    }
  ASSERT_GT(penumbra, 300);
  ASSERT_GT(full, 100);
  const double sigma = std::sqrt(4.0 / (4.0 * rays)), rms = std::sqrt(sum2 / penumbra), mean = sum / penumbra;
  EXPECT_LT(rms, sigma) << penumbra << " penumbra pixels";
  EXPECT_LT(std::abs(mean), 4.0 * sigma / std::sqrt(double(penumbra)));
  EXPECT_GT(std::sqrt(hard2 / penumbra), 3.0 * sigma) << "hard shadows differ from the soft ones";
}

TEST_F(DirectTest, CornellBoxDirectIsCloseToThePathTracersDirectLayer) {
  // The only approximation left in a diffuse scene is shadowing the area light from one
  // representative point: soft shadow edges become hard. Over the whole image the direct
  // light agrees with pt's to within a few percent (the penumbrae cover a small area).
  const scenes::Scene s = test::cornell_box();
  const int size = 32;
  const image::Image d = render(s, "direct", size, {"shadow_map_size=512"});
  const image::Image p = render(s, "pt", size, {"samples_per_frame=64", "max_bounces=1"});
  double sd = 0.0, sp = 0.0, var = 0.0;
  for (size_t i = 0; i < d.pixel_count(); ++i) {
    ASSERT_TRUE(std::isfinite(d.channel("G")[i]));
    sd += d.channel("G")[i];
    sp += p.channel("direct.G")[i];
    var += p.channel("variance.G")[i];
  }
  EXPECT_NEAR(sd / sp, 1.0, 0.05) << "image means " << sd << " vs " << sp << ", pt se " << std::sqrt(var);
}

TEST_F(DirectTest, RayTracedGBufferMatchesTheRasterisedOne) {
  // Both G-buffers store the pixel-centre camera ray's hit on the triangle's plane; they can
  // differ only where a pixel centre lies on a triangle edge (the rasteriser's tie-breaking
  // rule against the watertight test's) and in the last bits of the shading normal.
  scenes::Scene s = test::cornell_box();
  scenes::Light l;
  l.type = scenes::LightType::Spot;
  l.position = {0.5f, 0.8f, 0.5f};
  l.direction = glm::normalize(glm::vec3(-0.5f, -1.0f, -0.6f));
  l.intensity = 3.0f;
  s.lights.push_back(l);
  s.derive();
  const int size = 48;
  for (const bool orthographic : {false, true}) {
    SCOPED_TRACE(orthographic ? "orthographic" : "perspective");
    s.views[0].camera.ymag = orthographic ? 0.8f : 0.0f;
    const image::Image a = render(s, "direct", size, {"shadow_map_size=256"});
    const image::Image b = render(s, "direct", size, {"shadow_map_size=256", "gbuffer_ray_traced=1"});
    int differ = 0;
    for (size_t i = 0; i < a.pixel_count(); ++i) {
      const float x = a.channel("G")[i], y = b.channel("G")[i];
      differ += std::abs(x - y) > 1e-4f * std::max(x, y) + 1e-7f;
    }
    EXPECT_LE(differ, int(a.pixel_count() / 100)) << differ << " of " << a.pixel_count() << " pixels differ";
  }
}

// The shadow maps by rays (shadow_maps_ray_traced=1) store the depths the rasteriser stores,
// slope-scaled bias included, but where a texel centre's ray passes within the rasteriser's
// subpixel precision of a triangle's edge, and up to the rounding of the two depth
// computations: the shadow tests come out the same but at shadow edges. Every kind of layer (a
// spot light's cube, the sun's cascades, the area light's cube without its own quad), an
// alpha mask's cut-outs, and the millimetre and kilometre Cornell box: at most 1% of the
// pixels differ (measured: 0, 6, 0 and 0 of 2304, in the order below).
TEST_F(DirectTest, RayTracedShadowMapsMatchTheRasterisedOnes) {
  const scenes::Scene cornell = test::cornell_box_every_light();
  const std::vector<scenes::Scene> scenes = {cornell, test::lit_textured_box(), test::scaled(cornell, 1e-3f),
                                             test::scaled(cornell, 1e3f)};
  const int size = 48;
  for (size_t i = 0; i < scenes.size(); ++i) {
    SCOPED_TRACE("scene " + std::to_string(i));
    const image::Image a = render(scenes[i], "direct", size, {"shadow_map_size=256", "shadow_maps_ray_traced=0"});
    const image::Image b = render(scenes[i], "direct", size, {"shadow_map_size=256", "shadow_maps_ray_traced=1"});
    int differ = 0;
    double lit = 0.0;
    for (size_t p = 0; p < a.pixel_count(); ++p) {
      const float x = a.channel("G")[p], y = b.channel("G")[p];
      ASSERT_TRUE(std::isfinite(y)) << p;
      differ += std::abs(x - y) > 1e-4f * std::max(x, y) + 1e-7f;
      lit += x;
    }
    EXPECT_GT(lit, 0.0) << "the view sees the scene";
    EXPECT_LE(differ, int(a.pixel_count() / 100)) << differ << " of " << a.pixel_count() << " pixels differ";
  }
}

// glTF 2.0, 3.9.5: the camera does not see the back of a single-sided surface. A black card
// above a lit plane, its back to the camera and its shadow out of view: both G-buffer builders
// show the plane through it, as if it were not there; a double-sided card is seen (black).
TEST_F(DirectTest, TheBackOfASingleSidedSurfaceIsCulled) {
  for (const int card : {1, 2}) {  // single-sided, double-sided
    scenes::Scene plain = test::lambert_plane(0.6f);
    scenes::Light sun;
    sun.type = scenes::LightType::Directional;
    sun.direction = glm::normalize(glm::vec3(-1.0f, -0.3f, 0.0f));  // the card's shadow falls at x < -2.7
    sun.intensity = 2.0f;
    plain.lights = {sun};
    plain.derive();
    scenes::Scene s = plain;
    const int m = test::add_material(s, glm::vec3(0.0f));
    s.materials[size_t(m)].double_sided = card == 2;
    test::add_quad(s, {-0.6f, 1, -0.6f}, {0.6f, 1, -0.6f}, {0.6f, 1, 0.6f}, {-0.6f, 1, 0.6f}, m);  // faces down
    s.derive();
    for (const char* builder : {"gbuffer_ray_traced=0", "gbuffer_ray_traced=1"}) {
      const int size = 32;
      const image::Image a = render(plain, "direct", size, {"shadow_map_size=256", builder});
      const image::Image b = render(s, "direct", size, {"shadow_map_size=256", builder});
      const size_t centre = size_t(size / 2) * size + size / 2;
      ASSERT_GT(a.channel("G")[centre], 0.0f);
      if (card == 2) {
        EXPECT_EQ(b.channel("G")[centre], 0.0f) << builder;
        continue;
      }
      for (size_t i = 0; i < a.pixel_count(); ++i)
        ASSERT_NEAR(b.channel("G")[i], a.channel("G")[i], 1e-6f * a.channel("G")[i]) << builder << " pixel " << i;
    }
  }
}

TEST_F(DirectTest, CachedShadowMapsGiveTheSameFrames) {
  scenes::Scene s = test::cornell_box();
  scenes::Light l;
  l.type = scenes::LightType::Point;
  l.position = {0.3f, 0.5f, 0.2f};
  l.intensity = 2.0f;
  s.lights.push_back(l);
  s.derive();
  std::vector<image::Image> cached, fresh;
  RenderOptions o;
  o.technique = "direct";
  o.width = o.height = 16;
  o.frames = 3;
  o.parameters = {"shadow_map_size=128", "cache_static_shadows=1"};
  render_sequence(*ctx, *compiler, s, o, [&](RenderedFrame& f) { cached.push_back(std::move(f.image)); });
  o.parameters = {"shadow_map_size=128", "cache_static_shadows=0"};
  render_sequence(*ctx, *compiler, s, o, [&](RenderedFrame& f) { fresh.push_back(std::move(f.image)); });
  for (size_t k = 0; k < 3; ++k)
    for (size_t i = 0; i < cached[k].pixel_count(); ++i) ASSERT_EQ(cached[k].channel("R")[i], fresh[k].channel("R")[i]);
}

}  // namespace
}  // namespace giq::realtime
