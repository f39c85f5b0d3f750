// `direct`: the shared G-buffer and shadow-map passes, then one compute pass of direct
// lighting (direct_lighting.comp). Outputs: beauty = direct; indirect is black by definition.
// Parameters: shadow_map_size, pcf_radius, normal_offset, cascade_split_lambda,
// cache_static_shadows, gbuffer_ray_traced.
#include "techniques/direct/direct.h"

#include <glm/geometric.hpp>

#include "giq/realtime/context.h"
#include "giq/realtime/pipeline.h"
#include "giq/realtime/resources.h"
#include "giq/realtime/scene_gpu.h"
#include "giq/realtime/shader.h"
#include "giq/realtime/timer.h"
#include "passes/gbuffer.h"
#include "passes/shadow_maps.h"
#include "techniques/direct/direct_shared.h"

namespace giq::realtime {
namespace {

class Direct : public Technique {
 public:
  explicit Direct(const TechniqueCreateInfo& ci)
      : scene_(ci.scene), scene_gpu_(ci.scene_gpu), width_(ci.width), height_(ci.height),
        gbuffer_(ci.ctx, ci.compiler, ci.scene_gpu, ci.scene.features, ci.width, ci.height,
                 ci.parameters.get_int("gbuffer_ray_traced") != 0),
        shadows_(ci.ctx, ci.compiler, ci.scene_gpu, ci.scene.bounds, uint32_t(ci.parameters.get_int("shadow_map_size"))) {
    pcf_radius_ = float(ci.parameters.get_int("pcf_radius"));
    normal_offset_ = float(ci.parameters.get("normal_offset"));
    shadows_.set_split_lambda(float(ci.parameters.get("cascade_split_lambda")));
    shadows_.set_cache_static(ci.parameters.get_int("cache_static_shadows") != 0);

    std::vector<uint32_t> light_layer;
    for (const auto& l : ci.scene.lights)
      light_layer.push_back(l.type == scenes::LightType::Directional ? shadows_.add_cascades(l.direction)
                                                                      : shadows_.add_cube(l.position));
    build_area_lights(ci.scene);

    const ImageDesc d{width_, height_, 1, VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT};
    beauty_ = Image(ci.ctx, d);
    direct_ = Image(ci.ctx, d);
    indirect_ = Image(ci.ctx, d);
    light_layers_ = Buffer::storage(ci.ctx, light_layer);
    area_light_buffer_ = Buffer::storage(ci.ctx, area_lights_);
    area_triangle_buffer_ = Buffer::storage(ci.ctx, area_triangles_);

    auto bindings = SceneGpu::binding_types();
    bindings.insert(bindings.end(), {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                                     VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                                     VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                     VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                     VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                                     VK_DESCRIPTOR_TYPE_STORAGE_IMAGE});
    lighting_ = Pipeline::compute(ci.ctx,
                                  ci.compiler.compile("techniques/direct/direct_lighting.comp", feature_defines(ci.scene.features)),
                                  bindings, sizeof(gpu::DirectPush));
  }

  std::vector<std::string> passes() const override { return {"shadow_maps", "gbuffer", "direct_lighting"}; }

  void render(const FrameInput& in) override {
    const float aspect = float(width_) / float(height_);
    shadows_.record(in.cmd, in.camera, aspect, in.timer);
    gbuffer_.record(in.cmd, in.camera, in.timer);

    in.timer.begin(in.cmd, "direct_lighting");
    for (Image* i : {&beauty_, &direct_, &indirect_}) i->transition(in.cmd, VK_IMAGE_LAYOUT_GENERAL);
    lighting_.bind(in.cmd);
    auto d = scene_gpu_.descriptors();
    d.push_back(Descriptor::storage_image(gbuffer_.position()));
    d.push_back(Descriptor::storage_image(gbuffer_.normal()));
    d.push_back(Descriptor::storage_image(gbuffer_.ids()));
    d.push_back(Descriptor::sampled(shadows_.depth(), shadows_.sampler()));
    d.push_back(Descriptor::storage(shadows_.layers()));
    d.push_back(Descriptor::storage(area_light_buffer_));
    d.push_back(Descriptor::storage(area_triangle_buffer_));
    d.push_back(Descriptor::storage(light_layers_));
    d.push_back(Descriptor::storage_image(beauty_));
    d.push_back(Descriptor::storage_image(direct_));
    d.push_back(Descriptor::storage_image(indirect_));
    lighting_.push_descriptors(in.cmd, d);
    gpu::DirectPush pc{};
    pc.camera = gpu::make_gpu_camera(in.camera);
    pc.viewport = glm::vec4(float(width_), float(height_), normal_offset_, pcf_radius_);
    pc.environment = glm::vec4(scene_.environment, 0.0f);
    pc.counts = glm::uvec4(scene_gpu_.light_count(), uint32_t(area_lights_.size()), 0, 0);
    lighting_.push_constants(in.cmd, pc);
    lighting_.dispatch_2d(in.cmd, width_, height_);
    full_barrier(in.cmd);
    in.timer.end(in.cmd);
  }

  std::vector<std::pair<std::string, Image*>> outputs() override {
    return {{"", &beauty_}, {"direct", &direct_}, {"indirect", &indirect_}};
  }

 private:
  // One area light per emissive mesh; its representative point (for the shadow cube) is the
  // area-weighted centroid, moved a hair in front of the mesh along its mean normal so that
  // the emitter does not shadow itself.
  void build_area_lights(const scenes::Scene& scene) {
    std::vector<std::vector<const scenes::EmissiveTriangle*>> per_mesh(scene.meshes.size());
    for (const auto& e : scene.emissive_triangles)
      if (e.area > 0.0f && e.power > 0.0f) per_mesh[e.mesh].push_back(&e);
    const float offset = 1e-4f * std::max(glm::length(scene.bounds.extent()), 1e-6f);
    for (size_t m = 0; m < per_mesh.size(); ++m) {
      if (per_mesh[m].empty()) continue;
      const auto& mesh = scene.meshes[m];
      const bool two_sided = scene.materials[mesh.material].double_sided;
      glm::vec3 centroid(0.0f), normal(0.0f);
      float area = 0.0f;
      gpu::GpuAreaLight l;
      l.range = glm::uvec4(uint32_t(area_triangles_.size()), uint32_t(per_mesh[m].size()), 0, 0);
      for (const auto* e : per_mesh[m]) {
        const auto t = mesh.triangles[e->triangle];
        const glm::vec3 a = mesh.positions[t.x], b = mesh.positions[t.y], c = mesh.positions[t.z];
        centroid += e->area * (a + b + c) / 3.0f;
        normal += glm::cross(b - a, c - a);
        area += e->area;
        area_triangles_.push_back({glm::vec4(a, two_sided ? 1.0f : 0.0f), glm::vec4(b, 0.0f), glm::vec4(c, 0.0f),
                                   glm::vec4(e->radiance, 0.0f)});
      }
      centroid /= area;
      const float nl = glm::length(normal);
      if (!two_sided && nl > 0.0f) centroid += normal / nl * offset;
      l.position = glm::vec4(centroid, float(shadows_.add_cube(centroid)));
      area_lights_.push_back(l);
    }
  }

  const scenes::Scene& scene_;
  const SceneGpu& scene_gpu_;
  uint32_t width_, height_;
  float pcf_radius_ = 1.0f, normal_offset_ = 1.5f;
  GBufferPass gbuffer_;
  ShadowMaps shadows_;
  std::vector<gpu::GpuAreaLight> area_lights_;
  std::vector<gpu::GpuAreaTriangle> area_triangles_;
  Buffer light_layers_, area_light_buffer_, area_triangle_buffer_;
  Image beauty_, direct_, indirect_;
  Pipeline lighting_;
};

}  // namespace

TechniqueInfo direct_technique() {
  return {"direct",
          "direct light only: rasterised G-buffer, shadow maps (cube maps for point/spot and area lights, 3 cascades "
          "for the sun, PCF), exact area-light integration; no indirect light",
          {{"shadow_map_size", 2048, 64, 8192, true, "texels per side of every shadow-map layer"},
           {"pcf_radius", 1, 0, 4, true, "PCF kernel radius in texels ((2r+1)^2 taps)"},
           {"normal_offset", 1.5, 0, 8, false, "receiver offset along its normal, in shadow-map texels"},
           {"cascade_split_lambda", 0.5, 0, 1, false, "cascade splits: 0 uniform, 1 logarithmic"},
           {"cache_static_shadows", 1, 0, 1, true,
            "1: render cube shadow maps on the first frame only (geometry and punctual lights are static within a run)"},
           {"gbuffer_ray_traced", 0, 0, 1, true,
            "1: build the G-buffer by casting camera rays through the BVH in compute instead of rasterising (same contents)"}},
          [](const TechniqueCreateInfo& ci) { return std::make_unique<Direct>(ci); }};
}

}  // namespace giq::realtime
