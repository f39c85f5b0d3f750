#pragma once
// How a pass that sees the scene from a viewpoint through a grid of texels is built:
// rasterised, or by casting one ray per texel centre through the BVH in a compute shader
// (same contents). The G-buffer (passes/gbuffer.h) and the reflective shadow maps
// (passes/rsm.h) offer both. Auto picks by device: rays on GPUs, whose graphics units may be
// few (on the H100 and the H200 rasterised passes are more than ten times slower than the
// same work in compute: bench/results/realtime-h100.md, dynamic-h200.md), the rasteriser on
// CPU implementations such as lavapipe, where tracing is the slower one.

#include <string>

#include "giq/realtime/technique.h"

namespace giq::realtime {

class Context;

enum class PassBuilder { Raster, RayTraced, Auto };

// The integer parameter `name` (-1 auto, the default; 0 raster; 1 rays) for techniques to list,
// describing the builder of `what`.
Parameter pass_builder_parameter(const std::string& name, const std::string& what);
PassBuilder pass_builder(const ParameterValues& parameters, const std::string& name);
// Whether `builder` casts rays on this device.
bool casts_rays(PassBuilder builder, const Context& ctx);

}  // namespace giq::realtime
