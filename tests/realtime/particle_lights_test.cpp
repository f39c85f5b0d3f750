// Glowing particles as lights (shaders/octahedron_irradiance.glsl, the shared direct pass):
// lit one by one against their triangles integrated exactly, the irradiance function itself at
// every distance against Lambert's formula, each stage's particles and triangles as the
// shaders read them from the scene's vertices, and what a particle stage's shadow views leave
// out.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "giq/realtime/pipeline.h"
#include "giq/realtime/renderer.h"
#include "giq/realtime/resources.h"
#include "giq/realtime/scene_gpu.h"
#include "passes/direct_light.h"
#include "polygon_irradiance.h"
#include "scene_gpu_checks.h"
#include "test_scenes.h"

namespace giq::realtime {
namespace {

using ParticleLightsTest = test::VulkanTest;

// The fountain of tests/data/scenes at frame 20 on a Lambertian floor, lit by nothing but its
// glowing particles, made 5 cm in circumradius so that the floor, 0.3 to 3 m away, has pixels on
// both sides of the far field's 16 radii (80 cm). Particle by particle (shaders/
// octahedron_irradiance.glsl) against every triangle exactly: the same shadow cubes, so the
// images differ only by the far field, each face of a particle 16 circumradii or more away
// taken as a point. That errs by at most 0.29 % over 4,000 random placements at 16 r (less
// farther away), and a pixel's light is a sum of positive terms, so its relative error is at
// most the largest term's: bound 0.4 % (measured: 0.12 %), plus 1e-7 for the float rounding of
// the exact polygon sums, whose edge terms, each about the edge's angle times the radiance,
// cancel to the much smaller solid angle. A particle lost or counted twice moves a pixel by
// its whole share.
TEST_F(ParticleLightsTest, ParticlesLitOneByOneAgreeWithTheirTriangles) {
  scenes::Scene fountain = scenes::load(std::filesystem::path(GIQ_TEST_DATA) / "scenes" / "fountain.gltf");
  fountain.emitters[0].size = 0.05;
  scenes::Scene s = fountain.at_frame(20);
  for (scenes::Material& m : s.materials) m.metallic = 0.0f, m.specular = 0.0f;
  s.derive();
  ASSERT_FALSE(s.features.specular);
  size_t particles = 0;
  for (const scenes::Mesh& m : s.meshes)
    if (m.emitter >= 0) particles += m.positions.size() / 6;
  ASSERT_GT(particles, 50u);
  const int size = 64;
  const image::Image fast = render(s, "direct", size, {"shadow_map_size=256", "particle_lights=1", "particle_cut=0"});
  const image::Image exact = render(s, "direct", size, {"shadow_map_size=256", "particle_lights=0"});
  size_t lit = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x)
      for (const char* c : {"R", "G", "B"}) {
        const float a = fast.at(c, x, y), b = exact.at(c, x, y);
        ASSERT_TRUE(std::isfinite(a)) << x << "," << y;
        EXPECT_LE(std::abs(a - b), 4e-3f * b + 1e-7f) << c << " at " << x << "," << y;
        lit += c[0] == 'G' && b > 1e-4f;
      }
  EXPECT_GT(lit, size_t(size * size / 4));  // the floor, half the image, takes their light
}

// octahedron_irradiance itself, run by a small compute shader for particles 8 to 1,000
// circumradii from a receiver (log-uniform, random directions and receiver normals, above the
// horizon), against Lambert's formula over the faces that look at the receiver in double
// precision. The three ways it takes (each face integrated, each face a point from 16 r, the
// whole particle one point with its projected area from 160 r) are all exercised, and each errs
// by at most 0.29 % (the faces as points at 16 r; the whole particle at 160 r: 0.25 %), so the
// bound is the particle test's 0.4 %. Swapping 160 r for 16 r fails it (2.2 %).
TEST_F(ParticleLightsTest, ParticleIrradianceAgreesWithItsFacesAtEveryDistance) {
  const std::string src = R"(#version 460
#extension GL_GOOGLE_include_directive : require
#include "shaders/octahedron_irradiance.glsl"
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer In { vec4 placements[]; };
layout(std430, binding = 1) writeonly buffer Out { float irradiance[]; };
layout(push_constant) uniform Push { uint count; } pc;
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  vec4 c = placements[2u * i], n = placements[2u * i + 1u];
  irradiance[i] = octahedron_irradiance(c.xyz, c.w, n.xyz);
}
)";
  const auto s = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  Pipeline pipeline = Pipeline::compute(*ctx, compiler->compile_source("tests/octahedron_irradiance.comp", src), {s, s}, 4);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> g;
  const auto unit = [&] {
    const glm::dvec3 v(g(rng), g(rng), g(rng));
    return glm::normalize(v);
  };
  std::vector<glm::vec4> in;
  std::vector<double> exact, distance;
  while (exact.size() < 6000) {
    const double r = std::pow(10.0, -3.0 + 3.0 * u(rng));  // 1 mm to 1 m
    const double k = 8.0 * std::pow(125.0, u(rng));         // 8 to 1,000 circumradii
    const glm::dvec3 c = unit() * (k * r), n = unit();
    if (glm::dot(c, n) < r) continue;  // the faces' clipping is the particle test's
    double e = 0.0;
    for (const glm::dvec3 sign : {glm::dvec3(1, 1, 1), glm::dvec3(-1, 1, 1), glm::dvec3(1, -1, 1), glm::dvec3(-1, -1, 1),
                                  glm::dvec3(1, 1, -1), glm::dvec3(-1, 1, -1), glm::dvec3(1, -1, -1), glm::dvec3(-1, -1, -1)}) {
      const std::vector<glm::dvec3> face = {c + glm::dvec3(r * sign.x, 0, 0), c + glm::dvec3(0, r * sign.y, 0), c + glm::dvec3(0, 0, r * sign.z)};
      if (glm::dot(sign, c + (r / 3.0) * sign) < 0.0) e += test::polygon_irradiance(glm::dvec3(0.0), n, face);  // it looks at the receiver
    }
    in.emplace_back(glm::vec3(c), float(r));
    in.emplace_back(glm::vec3(n), 0.0f);
    exact.push_back(e);
    distance.push_back(k);
  }
  Buffer input = Buffer::storage(*ctx, in);
  Buffer output(*ctx, exact.size() * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  ctx->submit_and_wait([&](VkCommandBuffer cmd) {
    pipeline.bind(cmd);
    pipeline.push_descriptors(cmd, {Descriptor::storage(input), Descriptor::storage(output)});
    const uint32_t count = uint32_t(exact.size());
    pipeline.push_constants(cmd, &count, sizeof(count));
    vkCmdDispatch(cmd, (count + 63) / 64, 1, 1);
  });
  const auto bytes = output.download();
  std::vector<float> gpu(exact.size());
  std::memcpy(gpu.data(), bytes.data(), gpu.size() * sizeof(float));
  double worst[3] = {0.0, 0.0, 0.0};  // faces integrated, faces as points, one point
  size_t taken[3] = {0, 0, 0};
  for (size_t i = 0; i < exact.size(); ++i) {
    const int way = distance[i] < 16.0 ? 0 : distance[i] < 160.0 ? 1 : 2;
    const double err = std::abs(double(gpu[i]) - exact[i]) / exact[i];
    ASSERT_TRUE(std::isfinite(gpu[i])) << i;
    EXPECT_LE(err, 4e-3) << "at " << distance[i] << " circumradii, r = " << in[2 * i].w;
    worst[way] = std::max(worst[way], err), ++taken[way];
  }
  for (int way = 0; way < 3; ++way) EXPECT_GT(taken[way], 500u) << way;
  std::printf("largest relative error: faces %.2e, faces as points %.2e, one point %.2e\n", worst[0], worst[1], worst[2]);
}

// A stage's particles and triangles as every pass reads them (passes/area_light_parts.glsl),
// from the octahedra the GPU simulation wrote and the area lights DirectLightPass made, are the
// scene library's: each triangle's corners those of the stage mesh's triangle (the GPU's
// float closed form against the CPU's double one: within 1e-5 m on the fountain's 2 m, the
// simulation's agreement being about 1e-7 of that), its radiance and sidedness the stage's,
// and each particle at its octahedron's centre with the emitter's circumradius. Reading one
// particle further on, or the faces in another order, fails it.
TEST_F(ParticleLightsTest, AStagesPartsAreItsParticlesOctahedra) {
  const scenes::Scene s = scenes::load(std::filesystem::path(GIQ_TEST_DATA) / "scenes" / "fountain.gltf").at_frame(20);
  SceneGpu gpu(*ctx, *compiler, s);
  const ParameterValues values(DirectLightPass::parameters(), {"shadow_map_size=64"});
  DirectLightPass direct(TechniqueCreateInfo{*ctx, *compiler, s, gpu, 16, 16, values});
  const std::string src = R"(#version 460
#extension GL_GOOGLE_include_directive : require
#include "shaders/scene.glsl"
#include "passes/direct_light_shared.h"
layout(local_size_x = 64) in;
layout(std430, binding = GIQ_SCENE_BINDING_COUNT + 0) readonly buffer AreaLights { GpuAreaLight area_lights[]; };
layout(std430, binding = GIQ_SCENE_BINDING_COUNT + 1) readonly buffer AreaTriangles { GpuAreaTriangle area_triangles[]; };
layout(std430, binding = GIQ_SCENE_BINDING_COUNT + 2) writeonly buffer Triangles { GpuAreaTriangle triangles_out[]; };
layout(std430, binding = GIQ_SCENE_BINDING_COUNT + 3) writeonly buffer Particles { GpuParticleLight particles_out[]; };
#include "passes/area_light_parts.glsl"
layout(push_constant) uniform Push { uint light; } pc;
void main() {
  uint k = gl_GlobalInvocationID.x;
  GpuAreaLight l = area_lights[pc.light];
  if (k < l.range.y) triangles_out[k] = area_triangle(l, k);
  if (k < l.range.w) particles_out[k] = stage_particle(l, k);
}
)";
  auto bindings = SceneGpu::binding_types();
  bindings.insert(bindings.end(), 4, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  Pipeline pipeline = Pipeline::compute(*ctx, compiler->compile_source("tests/area_light_parts.comp", src), bindings, 4);
  size_t stages = 0;
  for (uint32_t i = 0; i < s.area_lights.size(); ++i) {
    const scenes::Mesh& mesh = s.meshes[s.area_lights[i].mesh];
    const gpu::GpuAreaLight& l = direct.area_lights()[i];
    if (mesh.emitter < 0 || mesh.triangles.empty()) continue;
    ++stages;
    const uint32_t n = uint32_t(mesh.positions.size() / 6);
    ASSERT_EQ(l.range.w, n) << "light " << i;
    ASSERT_EQ(l.range.y, 8 * n) << "light " << i;
    Buffer triangles(*ctx, l.range.y * sizeof(gpu::GpuAreaTriangle), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    Buffer particles(*ctx, n * sizeof(gpu::GpuParticleLight), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    ctx->submit_and_wait([&](VkCommandBuffer cmd) {
      pipeline.bind(cmd);
      auto d = gpu.descriptors();
      d.insert(d.end(), {Descriptor::storage(direct.area_light_buffer()), Descriptor::storage(direct.area_triangle_buffer()),
                         Descriptor::storage(triangles), Descriptor::storage(particles)});
      pipeline.push_descriptors(cmd, d);
      pipeline.push_constants(cmd, &i, sizeof(i));
      vkCmdDispatch(cmd, (l.range.y + 63) / 64, 1, 1);
    });
    std::vector<gpu::GpuAreaTriangle> t(l.range.y);
    std::vector<gpu::GpuParticleLight> p(n);
    std::memcpy(t.data(), triangles.download().data(), t.size() * sizeof(t[0]));
    std::memcpy(p.data(), particles.download().data(), p.size() * sizeof(p[0]));
    const glm::vec3 radiance = s.materials[size_t(mesh.material)].emissive;
    const float two_sided = s.materials[size_t(mesh.material)].double_sided ? 1.0f : 0.0f;
    const std::vector<glm::vec3> centres = scenes::particle_centres(mesh);
    for (uint32_t k = 0; k < l.range.y; ++k) {
      const glm::uvec3 f = mesh.triangles[k];
      EXPECT_LE(glm::length(glm::vec3(t[k].a) - mesh.positions[f.x]), 1e-5f) << "light " << i << ", triangle " << k;
      EXPECT_LE(glm::length(glm::vec3(t[k].b) - mesh.positions[f.y]), 1e-5f) << "light " << i << ", triangle " << k;
      EXPECT_LE(glm::length(glm::vec3(t[k].c) - mesh.positions[f.z]), 1e-5f) << "light " << i << ", triangle " << k;
      EXPECT_EQ(glm::vec3(t[k].radiance), radiance) << "light " << i << ", triangle " << k;
      EXPECT_EQ(t[k].a.w, two_sided) << "light " << i << ", triangle " << k;
    }
    for (uint32_t k = 0; k < n; ++k) {
      EXPECT_LE(glm::length(glm::vec3(p[k].centre) - centres[k]), 1e-5f) << "light " << i << ", particle " << k;
      EXPECT_EQ(p[k].centre.w, float(s.emitters[0].size)) << "light " << i << ", particle " << k;
      EXPECT_EQ(glm::vec3(p[k].radiance), radiance) << "light " << i << ", particle " << k;
    }
  }
  EXPECT_GE(stages, 2u);
}

// What an area light's own views leave out (own_geometry): a mesh its own vertices and
// triangles; a stage of particles every particle, or the other stages' particles, next to the
// stage's centroid, would shadow the room in blotches metres wide.
TEST_F(ParticleLightsTest, AParticleStagesViewsLeaveOutEveryParticle) {
  const scenes::Scene s = scenes::load(std::filesystem::path(GIQ_TEST_DATA) / "scenes" / "fountain.gltf").at_frame(20);
  const FlatGeometry g = flatten(s);
  uint32_t first_vertex = ~0u, first_triangle = ~0u, vertices = 0, triangles = 0, stages = 0;
  for (uint32_t m = 0; m < s.meshes.size(); ++m) {
    if (s.meshes[m].emitter < 0) continue;
    first_vertex = std::min(first_vertex, g.mesh_first_vertex[m]);
    first_triangle = std::min(first_triangle, g.mesh_first_triangle[m]);
    vertices += uint32_t(s.meshes[m].positions.size());
    triangles += uint32_t(s.meshes[m].triangles.size());
    ++stages;
  }
  ASSERT_EQ(stages, 4u);
  ASSERT_GT(vertices, 0u);
  for (uint32_t m = 0; m < s.meshes.size(); ++m) {
    const glm::uvec4 own = own_geometry(s, g, m);
    if (s.meshes[m].emitter >= 0)
      EXPECT_EQ(own, glm::uvec4(first_vertex, vertices, first_triangle, triangles)) << "mesh " << m;
    else
      EXPECT_EQ(own, glm::uvec4(g.mesh_first_vertex[m], s.meshes[m].positions.size(), g.mesh_first_triangle[m], s.meshes[m].triangles.size())) << "mesh " << m;
  }
}

// A particle stage's shadow cube of particle_shadow_map_size texels sits in the corner of
// layers of shadow_map_size: in the corner of larger layers it gives the bits of layers its
// own size (the same projection, the same texels, PCF taps kept inside the corner).
TEST_F(ParticleLightsTest, ACubeInTheCornerOfLargerLayersGivesTheSameBits) {
  const scenes::Scene s = scenes::load(std::filesystem::path(GIQ_TEST_DATA) / "scenes" / "fountain.gltf").at_frame(20);
  const image::Image own = render(s, "direct", 48, {"shadow_map_size=128", "particle_shadow_map_size=128", "pcf_radius=2"});
  const image::Image corner = render(s, "direct", 48, {"shadow_map_size=512", "particle_shadow_map_size=128", "pcf_radius=2"});
  double sum = 0.0;
  for (size_t i = 0; i < own.pixel_count(); ++i) {
    ASSERT_EQ(own.channel("R")[i], corner.channel("R")[i]) << "pixel " << i;
    sum += own.channel("R")[i];
  }
  EXPECT_GT(sum, 0.0);
}

// Particles lit cluster by cluster through the light tree (direct_light.comp,
// particle_tree_light) against one by one (particle_cut=0), on the fountain at 10 times its
// rate (about 1,300 particles at frame 20), lit by nothing else. A cut of 1e-6 opens every
// cluster but those of coinciding particles: the same sum in another order, within float
// rounding (1e-5 of a pixel's light). With a cut c, a cluster of particles in a box of
// diagonal D < c d, d from its centroid, lights as all of them at the centroid, whose
// first-order error cancels. The second-order remainder of a point's irradiance cos / r^2,
// whose Hessian is at most 13 / r^4 times its projected area, with r >= d (1 - c) and a mean
// squared distance from the centroid of at most D^2 / 4, bounds each cluster's relative error,
// and so a pixel's, by 13/8 c^2 / (1 - c)^4. (The centroids themselves are checked in
// TheLightTreeHoldsEveryStagesParticles.)
// The particles are 2 mm across and no more than this many because lavapipe ends every loop
// of a shader invocation once 65,535 iterations have run in all of them (llvmpipe's
// LP_MAX_TGSI_LOOP_ITERATIONS): the walk over the stages' trees, the particle loop, and the
// face loops of the particles nearer than 16 radii all draw on that one budget.
TEST_F(ParticleLightsTest, ClustersOfParticlesErrOnlyInTheSecondOrder) {
  scenes::Scene fountain = scenes::load(std::filesystem::path(GIQ_TEST_DATA) / "scenes" / "fountain.gltf");
  scenes::Emitter& e = fountain.emitters[0];
  e.rate *= 10.0;
  e.max_particles = uint32_t(std::floor(e.rate * e.lifetime) + 1.0);
  e.size = 0.002;
  scenes::Scene s = fountain.at_frame(20, scenes::ParticleDetail::Counted);
  for (scenes::Material& m : s.materials) m.metallic = 0.0f, m.specular = 0.0f;
  s.derive();
  s.features.animation = false;  // this frame alone
  ASSERT_FALSE(s.features.specular);
  const int size = 64;
  auto direct = [&](const std::string& cut) {
    return render(s, "direct", size, {"shadow_map_size=256", "area_shadow_rays=0", "particle_cut=" + cut});
  };
  const image::Image exact = direct("0"), opened = direct("0.000001"), coarse = direct("0.2"), fine = direct("0.1");
  double error_coarse = 0.0, error_fine = 0.0;
  size_t lit = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x)
      for (const char* c : {"R", "G", "B"}) {
        const float b = exact.at(c, x, y);
        EXPECT_LE(std::abs(opened.at(c, x, y) - b), 1e-5f * b + 1e-9f) << c << " at " << x << "," << y;
        for (auto [cut, image, sum] : {std::tuple{0.2, &coarse, &error_coarse}, std::tuple{0.1, &fine, &error_fine}}) {
          const double err = std::abs(double(image->at(c, x, y)) - double(b));
          EXPECT_LE(err, 13.0 / 8.0 * cut * cut / std::pow(1.0 - cut, 4.0) * b + 1e-9) << c << " at " << x << "," << y << " cut " << cut;
          *sum += err;
        }
        lit += c[0] == 'G' && b > 1e-4f;
      }
  EXPECT_GT(lit, size_t(size * size / 4));
  EXPECT_GT(error_fine, 0.0);  // clusters were taken whole
  EXPECT_GT(error_coarse, error_fine);
}

// The light tree over the fountain's particles at 100 times its rate (about 13,000 at frame
// 20, several stages; LinearBvh::record_lights) as the GPU built it: each stage's subtree
// holds exactly the particles whose triangles have the stage's material, each once; every
// node's box holds its particles' octahedra and its count is theirs; and its centroid is the
// mean of their centres (vertices 0 and 1 of each octahedron).
// The centroid is a mean of the children's means, one rounding a level: within 2^-20 of the
// fountain's extent at its depth. Writing the box's centre, or a count one off, fails it.
TEST_F(ParticleLightsTest, TheLightTreeHoldsEveryStagesParticles) {
  scenes::Scene fountain = scenes::load(std::filesystem::path(GIQ_TEST_DATA) / "scenes" / "fountain.gltf");
  scenes::Emitter& e = fountain.emitters[0];
  e.rate *= 100.0;
  e.max_particles = uint32_t(std::floor(e.rate * e.lifetime) + 1.0);
  const scenes::Scene s = fountain.at_frame(20, scenes::ParticleDetail::Counted);
  SceneGpu gpu(*ctx, *compiler, s);
  const LinearBvh::LightTree* tree = gpu.particle_light_tree();
  ASSERT_NE(tree, nullptr);
  auto words = [](const Buffer& b) {
    const std::vector<uint8_t> bytes = b.download();
    std::vector<uint32_t> w(bytes.size() / 4);
    std::memcpy(w.data(), bytes.data(), w.size() * 4);
    return w;
  };
  const std::vector<uint32_t> roots = words(tree->stage_roots);
  const std::vector<uint8_t> node_bytes = tree->nodes.download(), cluster_bytes = tree->clusters.download();
  std::vector<BvhNode> nodes(node_bytes.size() / sizeof(BvhNode));
  std::memcpy(nodes.data(), node_bytes.data(), nodes.size() * sizeof(BvhNode));
  std::vector<glm::vec4> clusters(cluster_bytes.size() / sizeof(glm::vec4));
  std::memcpy(clusters.data(), cluster_bytes.data(), clusters.size() * sizeof(glm::vec4));
  const std::vector<gpu::GpuVertex> vertices = test::vertex_rows(gpu.vertices());
  const std::vector<uint8_t> triangle_bytes = gpu.triangles().download();
  const uint32_t first_vertex = gpu.first_particle_vertex(), first_triangle = gpu.geometry().mesh_first_triangle[2];
  auto centre = [&](uint32_t j) {
    return 0.5f * (glm::vec3(vertices[first_vertex + 6 * j].position) + glm::vec3(vertices[first_vertex + 6 * j + 1].position));
  };
  auto material = [&](uint32_t j) {
    gpu::GpuTriangle t;
    std::memcpy(&t, triangle_bytes.data() + (first_triangle + 8 * size_t(j)) * sizeof(t), sizeof(t));
    return t.v.w;
  };
  const float tolerance = 0x1p-20f * glm::length(s.bounds.extent());
  size_t stages = 0, particles = 0;
  for (size_t m = 0; m < s.meshes.size(); ++m) {
    const scenes::Mesh& mesh = s.meshes[m];
    if (mesh.emitter < 0) continue;
    const uint32_t root = roots.at(gpu.particle_light_slot(uint32_t(mesh.material)));
    if (mesh.particles == 0) {
      EXPECT_EQ(root, 0xffffffffu) << "mesh " << m;
      continue;
    }
    ++stages;
    particles += mesh.particles;
    // The subtree's nodes in depth-first order; each node's particles.
    std::vector<int> seen(size_t(gpu.particle_vertex_count() / 6), 0);
    std::function<std::vector<uint32_t>(uint32_t, uint32_t)> walk = [&](uint32_t i, uint32_t depth) -> std::vector<uint32_t> {
      const BvhNode& n = nodes.at(i);
      std::vector<uint32_t> leaves;
      if (n.count > 0) {
        leaves = {n.index / 8};
        ++seen.at(leaves[0]);
        EXPECT_EQ(material(leaves[0]), uint32_t(mesh.material)) << "particle " << leaves[0];
      } else {
        leaves = walk(i + 1, depth + 1);
        const std::vector<uint32_t> right = walk(n.index, depth + 1);
        leaves.insert(leaves.end(), right.begin(), right.end());
      }
      glm::dvec3 mean(0.0);
      for (uint32_t j : leaves) {
        const glm::vec3 c = centre(j);
        mean += glm::dvec3(c);
        EXPECT_TRUE(glm::all(glm::lessThanEqual(n.lo, c)) && glm::all(glm::lessThanEqual(c, n.hi))) << "node " << i;
      }
      mean /= double(leaves.size());
      EXPECT_EQ(clusters[i].w, float(leaves.size())) << "node " << i;
      EXPECT_LE(glm::length(glm::dvec3(clusters[i]) - mean), double(tolerance) * (depth + 1)) << "node " << i;
      return leaves;
    };
    EXPECT_EQ(walk(root, 0).size(), size_t(mesh.particles)) << "mesh " << m;
    EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), long(mesh.particles)) << "mesh " << m;
  }
  EXPECT_GE(stages, 3u);
  EXPECT_GT(particles, 10000u);
}

// `gi1`'s light grid weighs a stage of glowing particles through the light tree
// (techniques/gi1/gi1_particle_importance.glsl), here at points of a 5 x 5 x 5 lattice over
// the fountain at 100 times its rate (some among the particles, most around them) against the
// particles' sum in double precision, each particle its mean projected area sqrt(3) r^2 over
// its squared distance. A cut of 1e-6 opens every cluster: the same sum within float rounding
// (2^-23 a particle: each term's and each addition's). At the grid's cut each cluster, and so
// the sum of the positive terms, errs by at most c^2 + c^2 (2 + c)^2 / (1 - c)^2. A particle
// lost or counted twice moves a sum by its whole share.
TEST_F(ParticleLightsTest, GridImportanceOfParticlesByCluster) {
  scenes::Scene fountain = scenes::load(std::filesystem::path(GIQ_TEST_DATA) / "scenes" / "fountain.gltf");
  scenes::Emitter& e = fountain.emitters[0];
  e.rate *= 100.0;
  e.max_particles = uint32_t(std::floor(e.rate * e.lifetime) + 1.0);
  const scenes::Scene s = fountain.at_frame(20, scenes::ParticleDetail::Counted);
  SceneGpu gpu(*ctx, *compiler, s);
  ASSERT_NE(gpu.particle_light_tree(), nullptr);
  const ParameterValues values(DirectLightPass::parameters(), {"shadow_map_size=64"});
  DirectLightPass direct(TechniqueCreateInfo{*ctx, *compiler, s, gpu, 16, 16, values});
  const std::string src = R"(#version 460
#extension GL_GOOGLE_include_directive : require
#include "shaders/scene.glsl"
#include "shaders/sampling.glsl"
#include "passes/direct_light_shared.h"
layout(local_size_x = 64) in;
layout(std430, binding = GIQ_SCENE_BINDING_COUNT + 0) readonly buffer AreaLights { GpuAreaLight area_lights[]; };
layout(std430, binding = GIQ_SCENE_BINDING_COUNT + 1) readonly buffer ParticleTree { GpuBvhNode particle_tree[]; };
layout(std430, binding = GIQ_SCENE_BINDING_COUNT + 2) readonly buffer ParticleClusters { vec4 particle_clusters[]; };
layout(std430, binding = GIQ_SCENE_BINDING_COUNT + 3) readonly buffer StageRoots { uint stage_roots[]; };
layout(std430, binding = GIQ_SCENE_BINDING_COUNT + 4) readonly buffer Points { vec4 points[]; };
layout(std430, binding = GIQ_SCENE_BINDING_COUNT + 5) writeonly buffer Importance { vec4 importance[]; };
#include "techniques/gi1/gi1_particle_importance.glsl"
layout(push_constant) uniform Push { uint light, count; float near; } pc;
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  GpuAreaLight a = area_lights[pc.light];
  uint slot = uint(a.extent.w) - 1u;
  importance[i] = vec4(gi1_particle_importance(a, slot, points[i].xyz, pc.near, 1e-6),
                       gi1_particle_importance(a, slot, points[i].xyz, pc.near, kGi1ParticleImportanceCut),
                       kGi1ParticleImportanceCut, 0.0);
}
)";
  auto bindings = SceneGpu::binding_types();
  bindings.insert(bindings.end(), 6, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  struct Push {
    uint32_t light, count;
    float near;
  };
  Pipeline pipeline = Pipeline::compute(*ctx, compiler->compile_source("tests/gi1_particle_importance.comp", src), bindings, sizeof(Push));
  const std::vector<gpu::GpuVertex> vertices = test::vertex_rows(gpu.vertices());
  const uint32_t first_vertex = gpu.first_particle_vertex();
  const glm::vec3 lo = s.bounds.lo - 0.5f, hi = s.bounds.hi + 0.5f;
  std::vector<glm::vec4> points;
  for (int z = 0; z < 5; ++z)
    for (int y = 0; y < 5; ++y)
      for (int x = 0; x < 5; ++x) points.emplace_back(glm::mix(lo, hi, glm::vec3(x, y, z) / 4.0f), 0.0f);
  const Buffer point_buffer = Buffer::storage(*ctx, points);
  Buffer out(*ctx, points.size() * sizeof(glm::vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  const float near = 1e-3f;
  size_t stages = 0, clustered = 0;
  double worst = 0.0;
  for (uint32_t i = 0; i < s.area_lights.size(); ++i) {
    const scenes::Mesh& mesh = s.meshes[s.area_lights[i].mesh];
    const gpu::GpuAreaLight& l = direct.area_lights()[i];
    if (mesh.emitter < 0 || mesh.particles == 0) continue;
    ASSERT_GT(l.extent.w, 0.0f) << "light " << i;
    ++stages;
    ctx->submit_and_wait([&](VkCommandBuffer cmd) {
      pipeline.bind(cmd);
      auto d = gpu.descriptors();
      d.push_back(Descriptor::storage(direct.area_light_buffer()));
      for (const Descriptor& x : direct.particle_tree_descriptors()) d.push_back(x);
      d.insert(d.end(), {Descriptor::storage(point_buffer), Descriptor::storage(out)});
      pipeline.push_descriptors(cmd, d);
      const Push push{i, uint32_t(points.size()), near};
      pipeline.push_constants(cmd, &push, sizeof(push));
      vkCmdDispatch(cmd, uint32_t(points.size() + 63) / 64, 1, 1);
    });
    std::vector<glm::vec4> got(points.size());
    std::memcpy(got.data(), out.download().data(), got.size() * sizeof(got[0]));
    const double c = got[0].z, bound = c * c + c * c * (2.0 + c) * (2.0 + c) / ((1.0 - c) * (1.0 - c));
    const glm::dvec3 radiance(l.particle);
    const double r = l.particle.w, per_particle = glm::dot(radiance, glm::dvec3(0.2126, 0.7152, 0.0722)) * std::sqrt(3.0) * r * r * (l.extent.y != 0.0f ? 2.0 : 1.0);
    const uint32_t first = (l.range.z - first_vertex) / 6;
    for (size_t k = 0; k < points.size(); ++k) {
      double want = 0.0;
      for (uint32_t j = first; j < first + l.range.w; ++j) {
        const glm::dvec3 centre = 0.5 * (glm::dvec3(vertices[first_vertex + 6 * j].position) + glm::dvec3(vertices[first_vertex + 6 * j + 1].position));
        const glm::dvec3 to = centre - glm::dvec3(points[k]);
        want += per_particle / std::max(glm::dot(to, to), double(near) * near);
      }
      EXPECT_NEAR(got[k].x, want, 0x1p-23 * double(l.range.w) * want) << "light " << i << ", point " << k;
      EXPECT_NEAR(got[k].y, want, bound * want) << "light " << i << ", point " << k;
      worst = std::max(worst, std::abs(got[k].y - want) / want);
      clustered += got[k].y != got[k].x;
    }
  }
  std::printf("largest relative error at the grid's cut: %.2e\n", worst);
  EXPECT_GE(stages, 3u);
  EXPECT_GT(clustered, points.size());  // points where clusters were taken whole
}

}  // namespace
}  // namespace giq::realtime
