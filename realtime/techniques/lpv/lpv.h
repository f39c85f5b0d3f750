#pragma once
// `lpv`: Light Propagation Volumes (seed 000, chapter III): VPLs of the reflective shadow maps
// injected as 2-band SH into a grid, propagated to the 6 face neighbours, looked up per pixel.
#include "giq/realtime/technique.h"

namespace giq::realtime {

TechniqueInfo lpv_technique();

}  // namespace giq::realtime
