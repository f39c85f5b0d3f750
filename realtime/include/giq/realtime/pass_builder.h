#pragma once
// How a pass that sees the scene from a viewpoint through a grid of texels is built:
// rasterised, or by casting one ray per texel centre through the BVH in a compute shader
// (same contents). The G-buffer (passes/gbuffer.h), the shadow maps (passes/shadow_maps.h)
// and the reflective shadow maps (passes/rsm.h) offer both. Auto picks by device: rays on GPUs, whose graphics units may be
// few (on the H100 and the H200 the rasterised passes take up to more than ten times as long
// as the same work in compute: bench/results/realtime-h100.md, dynamic-h200.md), the
// rasteriser on CPU implementations such as lavapipe, where tracing is the slower one. A run
// records which builder each pass used (timings.json "builders").

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "giq/realtime/technique.h"

namespace giq::realtime {

class Context;

enum class PassBuilder { Raster, RayTraced, Auto };

// The builder parameters there are, one per pass that has two builders.
const std::vector<std::string>& pass_builder_names();
// The integer parameter `name` (one of pass_builder_names(); -1 auto, the default; 0 raster;
// 1 rays) for techniques to list, describing the builder of `what`.
Parameter pass_builder_parameter(const std::string& name, const std::string& what);
PassBuilder pass_builder(const ParameterValues& parameters, const std::string& name);
// Whether `builder` casts rays on this device.
bool casts_rays(PassBuilder builder, const Context& ctx);
// {parameter: "rays" or "raster"} for every builder parameter among `declared`, as `values`
// and this device resolve it.
nlohmann::json resolved_builders(const std::vector<Parameter>& declared, const ParameterValues& values,
                                 const Context& ctx);

}  // namespace giq::realtime
