#include "giq/reference/reference_exr.h"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "giq/base/version.h"

namespace giq::reference {
namespace {

const char* estimator_name(Estimator e) {
  switch (e) {
    case Estimator::Mis: return "mis";
    case Estimator::LightOnly: return "light";
    case Estimator::BsdfOnly: return "bsdf";
  }
  return "?";
}

// Shortest decimal that reads back to the same float: headers stay readable and exact.
std::string exact(float v) {
  char b[32];
  for (int precision = 6; precision <= 9; ++precision) {
    std::snprintf(b, sizeof b, "%.*g", precision, double(v));
    if (std::strtof(b, nullptr) == v) break;
  }
  return b;
}

}  // namespace

std::string settings_json(const RenderSettings& s) {
  nlohmann::ordered_json j;
  j["width"] = s.width;
  j["height"] = s.height;
  j["seed"] = s.seed;
  j["max_bounces"] = s.max_bounces;
  j["estimator"] = estimator_name(s.estimator);
  j["sampler"] = sampler_name(s.sampler);
  if (s.sampler == Sampler::Sobol) j["sobol_block"] = s.sobol_block;
  j["pixel_filter"] = s.pixel_centre ? "point (pixel centre)" : "box";
  j["integrator"] = "path tracing, NEE + MIS (power heuristic), Russian roulette after bounce 3";
  return j.dump();
}

std::string describe_camera(const scenes::Camera& c) {
  const auto v = [](glm::vec3 x) { return exact(x.x) + "," + exact(x.y) + "," + exact(x.z); };
  return "position=" + v(c.position) + " forward=" + v(c.forward) + " up=" + v(c.up) +
         (c.orthographic() ? " ymag=" + exact(c.ymag) : " yfov_deg=" + exact(float(double(c.yfov) * 180.0 / 3.14159265358979323846)));
}

image::Image reference_image(const Film& film, const RenderSettings& settings, const ReferenceMetadata& meta) {
  image::Image img = film.to_image();
  img.metadata["giq.version"] = giq::version();
  img.metadata["giq.scene"] = meta.scene;
  img.metadata["giq.scene_hash"] = meta.scene_hash;
  img.metadata["giq.view"] = meta.view;
  img.metadata["giq.camera"] = describe_camera(meta.camera);
  if (!meta.camera_given.empty()) img.metadata["giq.camera_given"] = meta.camera_given;
  img.metadata["giq.frame"] = std::to_string(meta.frame);
  img.metadata["giq.spp"] = std::to_string(film.min_samples());
  img.metadata["giq.seed"] = std::to_string(settings.seed);
  img.metadata["giq.settings"] = settings_json(settings);
  img.metadata["giq.nonfinite_samples"] = std::to_string(film.nonfinite_samples());
  if (meta.render_seconds >= 0.0) {
    char b[32];
    std::snprintf(b, sizeof b, "%.3f", meta.render_seconds);
    img.metadata["giq.render_time"] = b;
  }
  return img;
}

}  // namespace giq::reference
