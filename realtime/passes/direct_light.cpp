#include "passes/direct_light.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <glm/geometric.hpp>

#include "giq/realtime/context.h"
#include "giq/realtime/pass_builder.h"
#include "giq/realtime/scene_gpu.h"
#include "giq/realtime/shader.h"
#include "giq/realtime/timer.h"
#include "giq/scenes/particles.h"
#include "passes/gbuffer.h"

namespace giq::realtime {

std::vector<Parameter> DirectLightPass::parameters() {
  return {{"shadow_map_size", 2048, 64, 8192, true, "texels per side of every shadow-map layer"},
          {"pcf_radius", 1, 0, 4, true, "PCF kernel radius in texels ((2r+1)^2 taps)"},
          {"normal_offset", 1.5, 0, 8, false, "receiver offset along its normal, in shadow-map texels"},
          {"cascade_split_lambda", 0.5, 0, 1, false, "cascade splits: 0 uniform, 1 logarithmic"},
          {"cache_static_shadows", 1, 0, 1, true,
           "1: render cube shadow maps only when the geometry or the lights moved"},
          {"particle_lights", 1, 0, 1, true,
           "1: light a stage of glowing particles particle by particle, each face of one 16 circumradii away "
           "as a point (shaders/octahedron_irradiance.glsl); 0: every triangle exactly"},
          {"particle_cut", 0.05, 0, 1, false,
           "a cluster of glowing particles lights as one, from its centroid, where its box is smaller than this "
           "times its distance (relative error of order its square); 0: every particle alone"},
          {"area_shadow_rays", 0, 0, 1024, true,
           "0: an area light casts hard shadows from its representative point (its cube shadow map); N: soft "
           "shadows from N rays a pixel to points on the light, the share of its light they reach"},
          {"particle_shadow_map_size", 1024, 64, 8192, true,
           "texels per side of the cube shadow map of a stage of glowing particles (at most shadow_map_size): "
           "one point of a cloud of particles casts its shadows, so a coarser map than a lamp's does"},
          pass_builder_parameter("shadow_maps_ray_traced", "Shadow maps'")};
}

DirectLightPass::DirectLightPass(const TechniqueCreateInfo& ci)
    : ctx_(&ci.ctx), scene_gpu_(ci.scene_gpu), width_(ci.width), height_(ci.height),
      pcf_radius_(uint32_t(ci.parameters.get_int("pcf_radius"))),
      normal_offset_(float(ci.parameters.get("normal_offset"))),
      particle_lights_(ci.parameters.get_int("particle_lights") != 0),
      particle_cut_(float(ci.parameters.get("particle_cut"))),
      particle_shadow_size_(uint32_t(ci.parameters.get_int("particle_shadow_map_size"))),
      area_shadow_rays_(uint32_t(ci.parameters.get_int("area_shadow_rays"))),
      shadows_(ci.ctx, ci.compiler, ci.scene_gpu, ci.scene.bounds, uint32_t(ci.parameters.get_int("shadow_map_size")),
               casts_rays(pass_builder(ci.parameters, "shadow_maps_ray_traced"), ci.ctx)) {
  shadows_.set_split_lambda(float(ci.parameters.get("cascade_split_lambda")));
  shadows_.set_cache_static(ci.parameters.get_int("cache_static_shadows") != 0);
  build_area_lights(ci.scene);
  declare_shadows(ci.scene);
  direct_ = Image(ci.ctx, {width_, height_, 1, VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT});
  upload_area_lights(ci.ctx);

  auto bindings = GBufferPass::receiver_bindings();
  bindings.insert(bindings.end(), {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                                   VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                   VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                   VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                   VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
  pipeline_ = Pipeline::compute(
      ci.ctx, ci.compiler.compile("passes/direct_light.comp", feature_defines(ci.scene.features)), bindings,
      sizeof(gpu::DirectPush));
}

void DirectLightPass::declare_shadows(const scenes::Scene& scene) {
  // Shadow sources: the punctual lights in scene order, then one cube per area light.
  shadows_.clear();
  light_layer_.clear();
  for (const auto& l : scene.lights)
    light_layer_.push_back(l.type == scenes::LightType::Directional ? shadows_.add_cascades(l.direction) : shadows_.add_cube(l.position));
  // Each area light's cube leaves out the emitter itself (own_geometry). Lights shadowed by
  // rays have none.
  for (size_t i = 0; i < area_lights_.size() && area_shadow_rays_ == 0; ++i) {
    const uint32_t mesh = scene.area_lights[i].mesh;
    const uint32_t size = scene.meshes[mesh].emitter >= 0 ? particle_shadow_size_ : 0u;
    area_lights_[i].position.w = float(
        shadows_.add_cube(glm::vec3(area_lights_[i].position), own_geometry(scene, scene_gpu_.geometry(), mesh), size));
  }
  light_layer_buffer_ = Buffer::storage(*ctx_, light_layer_);
}

void DirectLightPass::upload_area_lights(Context& ctx) {
  area_light_buffer_ = Buffer::storage(ctx, area_lights_);
  area_triangle_buffer_ = Buffer::storage(ctx, area_triangles_);
}

void DirectLightPass::follow(const scenes::Scene& scene, SceneChange change) {
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const auto& l = scene.lights[i];
    shadows_.move(i, l.type == scenes::LightType::Directional ? l.direction : l.position);
  }
  if (change != SceneChange::Geometry) return;
  // Emissive meshes moved: rebuild the area lights, keeping each one's shadow layers while
  // there are as many (particles come and go by stage of life: then the shadow maps are
  // declared anew). A light's mesh may have moved in the vertex array or changed in size.
  std::vector<float> layers;
  for (const auto& a : area_lights_) layers.push_back(a.position.w);
  const size_t before = area_lights_.size();
  area_lights_.clear();
  area_triangles_.clear();
  build_area_lights(scene);
  shadows_.set_bounds(scene.bounds);
  if (area_lights_.size() == before) {
    for (size_t i = 0; i < area_lights_.size() && area_shadow_rays_ == 0; ++i) {
      const uint32_t mesh = scene.area_lights[i].mesh;
      area_lights_[i].position.w = layers[i];
      shadows_.move(scene.lights.size() + i, glm::vec3(area_lights_[i].position));
      shadows_.set_skip(scene.lights.size() + i, own_geometry(scene, scene_gpu_.geometry(), mesh));
    }
  } else {
    declare_shadows(scene);
  }
  upload_area_lights(*ctx_);
}

void DirectLightPass::record_shadows(const FrameInput& in) {
  if (in.change != SceneChange::None) follow(in.scene, in.change);
  shadows_.record(in.cmd, in.camera, float(width_) / float(height_), in.timer);
}

void DirectLightPass::record_lighting(const FrameInput& in, GBufferPass& gbuffer) {
  in.timer.begin(in.cmd, "direct_lighting");
  direct_.transition(in.cmd, VK_IMAGE_LAYOUT_GENERAL);
  pipeline_.bind(in.cmd);
  auto d = gbuffer.receiver_descriptors();
  d.push_back(Descriptor::sampled(shadows_.depth(), shadows_.sampler()));
  d.push_back(Descriptor::storage(shadows_.layers()));
  d.push_back(Descriptor::storage(area_light_buffer_));
  d.push_back(Descriptor::storage(area_triangle_buffer_));
  d.push_back(Descriptor::storage(light_layer_buffer_));
  d.push_back(Descriptor::storage_image(direct_));
  for (const Descriptor& x : particle_tree_descriptors()) d.push_back(x);
  pipeline_.push_descriptors(in.cmd, d);
  gpu::DirectPush pc{};
  pc.camera = gpu::make_gpu_camera(in.camera);
  pc.environment = glm::vec4(in.scene.environment, float(in.scene.environment_map));
  pc.size = glm::uvec2(width_, height_);
  pc.normal_offset = normal_offset_;
  pc.pcf_radius = pcf_radius_;
  pc.light_count = scene_gpu_.light_count();
  pc.area_light_count = uint32_t(area_lights_.size());
  pc.area_shadow_rays = area_shadow_rays_;
  pc.particle_cut = particle_cut_;
  pipeline_.push_constants(in.cmd, pc);
  pipeline_.dispatch_2d(in.cmd, width_, height_);
  full_barrier(in.cmd);
  in.timer.end(in.cmd);
}

std::array<Descriptor, 3> DirectLightPass::particle_tree_descriptors() const {
  // Without a light tree no light has a slot in it: any buffer stands in.
  const LinearBvh::LightTree* tree = scene_gpu_.particle_light_tree();
  return {Descriptor::storage(tree ? tree->nodes : area_light_buffer_),
          Descriptor::storage(tree ? tree->clusters : area_light_buffer_),
          Descriptor::storage(tree ? tree->stage_roots : area_light_buffer_)};
}

// One area light per emissive mesh (the scene's AreaLight), its triangles integrated exactly,
// or, for a stage of glowing particles, its particles one by one, read from the scene's
// vertices (passes/area_light_parts.glsl); its representative point is where the shadow cube
// sits. The shadow layer (position.w) is set by the caller.
void DirectLightPass::build_area_lights(const scenes::Scene& scene) {
  for (const scenes::AreaLight& a : scene.area_lights) {
    const scenes::Mesh& mesh = scene.meshes[a.mesh];
    gpu::GpuAreaLight l;
    l.range = glm::uvec4(uint32_t(area_triangles_.size()), uint32_t(a.triangles.size()), 0, 0);
    // Every triangle of a stage glows alike (one material, no texture), eight to a particle;
    // the scene may only count them (scenes::ParticleDetail::Counted).
    if (mesh.emitter >= 0 && mesh.particles > 0) {
      l.range.y = scenes::kParticleTriangles * mesh.particles;
      l.range.z = scene_gpu_.geometry().mesh_first_vertex[a.mesh];
      l.range.w = mesh.particles;
      l.particle = glm::vec4(scene.materials[size_t(mesh.material)].emissive, float(scene.emitters[size_t(mesh.emitter)].size));
    }
    for (size_t k = 0; k < a.triangles.size() && l.range.w == 0; ++k) {
      const uint32_t i = a.triangles[k];
      const scenes::EmissiveTriangle& e = scene.emissive_triangles[i];
      const auto t = mesh.triangles[e.triangle];
      area_triangles_.push_back({glm::vec4(mesh.positions[t.x], a.two_sided ? 1.0f : 0.0f),
                                 glm::vec4(mesh.positions[t.y], 0.0f), glm::vec4(mesh.positions[t.z], 0.0f),
                                 glm::vec4(e.radiance, 0.0f)});
    }
    l.position = glm::vec4(a.representative, 0.0f);
    l.extent = glm::vec4(a.extent, a.two_sided ? 1.0f : 0.0f, l.range.w > 0 && !particle_lights_ ? 1.0f : 0.0f, 0.0f);
    // Many particles are lit through the light tree, cluster by cluster, where the cut allows.
    if (l.range.w > 0 && particle_cut_ > 0.0f && scene_gpu_.particle_light_tree())
      l.extent.w = float(scene_gpu_.particle_light_slot(uint32_t(mesh.material)) + 1);
    static_assert(GIQ_AREA_MESH == int(scenes::AreaShape::Mesh) && GIQ_AREA_TUBE == int(scenes::AreaShape::Tube));
    l.shape = glm::vec4(a.shape_centre, float(int(a.shape)));
    l.shape_u = glm::vec4(a.shape_u, a.shape_radius);
    l.shape_v = glm::vec4(a.shape_v, std::sqrt(a.area / std::numbers::pi_v<float>));
    area_lights_.push_back(l);
  }
}

}  // namespace giq::realtime
