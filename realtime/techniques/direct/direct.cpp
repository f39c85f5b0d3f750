// `direct`: direct light only, the baseline every GI technique must beat: the deferred frame
// (passes/deferred_gi.h) with no indirect light of its own. Outputs: beauty = direct;
// indirect is black by definition.
#include "passes/deferred_gi.h"

namespace giq::realtime {

TechniqueInfo direct_technique() {
  FrameNeeds needs;
  needs.indirect = false;
  return deferred_technique<void>(
      "direct",
      "direct light only: rasterised G-buffer, shadow maps (cube maps for point/spot and area lights, 3 cascades "
      "for the sun, PCF), exact area-light integration; no indirect light",
      needs, {}, {"shadow_map_size", {256, 512, 1024, 2048, 4096}});
}

}  // namespace giq::realtime
