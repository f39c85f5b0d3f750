#include "passes/pass_builder.h"

#include "giq/realtime/context.h"

namespace giq::realtime {

Parameter pass_builder_parameter(const std::string& name, const std::string& what) {
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

}  // namespace giq::realtime
