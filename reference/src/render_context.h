#pragma once
// Everything the integrator reads for one render: the scene, its BVH and lights in the
// renderer's frame, the camera and the settings. Built once per Renderer, then shared
// read-only by all threads.

#include <glm/glm.hpp>

#include <vector>

#include "bsdf_params.h"
#include "embree_scene.h"
#include "giq/reference/renderer.h"
#include "lights.h"

namespace giq::reference {

struct RenderContext {
  RenderContext(const scenes::Scene& s, const scenes::Camera& cam, const RenderSettings& rs, glm::vec3 c, float radius)
      : scene(s), settings(rs), camera(cam), rays(cam, rs.width, rs.height), centre(c), eye(cam.position - c),
        bvh(s, c, s.features.alpha_mask), lights(s, bvh, c, radius) {
    for (const scenes::Material& m : s.materials) material_bsdf.push_back(bsdf_params<kSpecular>(m));
  }

  const scenes::Scene& scene;
  RenderSettings settings;
  scenes::Camera camera;
  scenes::ImageRays rays;  // the camera's rays through the settings' image
  glm::vec3 centre;  // the scene's local frame minus this is the renderer's frame
  glm::vec3 eye;     // camera position in the renderer's frame
  EmbreeScene bvh;
  LightSampler lights;
  std::vector<BsdfParams> material_bsdf;  // each material's without its textures, GGX lobe included
};

}  // namespace giq::reference
