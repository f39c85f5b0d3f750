#pragma once
// `pt`: the GPU progressive path tracer, the real-time module's own ground truth. Accumulated
// long enough it agrees with `giq reference` within noise.
#include "giq/realtime/technique.h"

namespace giq::realtime {

TechniqueInfo pt_technique();

}  // namespace giq::realtime
