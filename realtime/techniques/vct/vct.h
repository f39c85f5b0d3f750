#pragma once
// `vct`: voxel cone tracing (seed 000 ch. IV; seed 001 "Voxel-based Global Illumination";
// Crassin et al. 2011). docs/techniques/vct.md describes the algorithm, the light types and
// the parameters.
#include "giq/realtime/technique.h"

namespace giq::realtime {

TechniqueInfo vct_technique();

}  // namespace giq::realtime
