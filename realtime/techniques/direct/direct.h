#pragma once
// `direct`: direct light only, the baseline every GI technique must beat.
#include "giq/realtime/technique.h"

namespace giq::realtime {

TechniqueInfo direct_technique();

}  // namespace giq::realtime
