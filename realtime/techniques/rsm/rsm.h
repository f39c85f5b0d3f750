#pragma once
// `rsm`: Reflective Shadow Maps (seed 000, chapter II): one bounce of indirect diffuse light
// gathered from the virtual point lights of every light's reflective shadow map.
#include "giq/realtime/technique.h"

namespace giq::realtime {

TechniqueInfo rsm_technique();

}  // namespace giq::realtime
