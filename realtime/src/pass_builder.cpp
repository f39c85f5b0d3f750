#include "giq/realtime/pass_builder.h"

#include <algorithm>
#include <stdexcept>

#include "giq/realtime/context.h"

namespace giq::realtime {

const std::vector<std::string>& pass_builder_names() {
  static const std::vector<std::string> names = {"gbuffer_ray_traced", "rsm_ray_traced", "shadow_maps_ray_traced"};
  return names;
}

Parameter pass_builder_parameter(const std::string& name, const std::string& what) {
  const auto& names = pass_builder_names();
  if (std::find(names.begin(), names.end(), name) == names.end())
    throw std::logic_error("pass_builder_parameter: '" + name + "' is not in pass_builder_names()");
  return {name, -1, -1, 1, true,
          what + " builder: 1 casts the texel-centre rays through the BVH in compute, 0 rasterises (same contents); "
                 "-1 picks rays on GPUs and the rasteriser on CPU devices"};
}

PassBuilder pass_builder(const ParameterValues& parameters, const std::string& name) {
  const int v = parameters.get_int(name);
  return v < 0 ? PassBuilder::Auto : v == 0 ? PassBuilder::Raster : PassBuilder::RayTraced;
}

bool casts_rays(PassBuilder builder, const Context& ctx) {
  return builder == PassBuilder::RayTraced || (builder == PassBuilder::Auto && ctx.info().type != "cpu");
}

nlohmann::json resolved_builders(const std::vector<Parameter>& declared, const ParameterValues& values,
                                 const Context& ctx) {
  nlohmann::json out = nlohmann::json::object();
  const auto& names = pass_builder_names();
  for (const Parameter& p : declared)
    if (std::find(names.begin(), names.end(), p.name) != names.end())
      out[p.name] = casts_rays(pass_builder(values, p.name), ctx) ? "rays" : "raster";
  return out;
}

}  // namespace giq::realtime
