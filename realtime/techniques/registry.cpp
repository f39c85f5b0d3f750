// The registry of real-time techniques: adding a technique is adding its folder and one line
// here.
#include "giq/realtime/technique.h"
#include "techniques/direct/direct.h"
#include "techniques/lpv/lpv.h"
#include "techniques/pt/pt.h"
#include "techniques/rsm/rsm.h"
#include "techniques/vct/vct.h"

namespace giq::realtime {

const std::vector<TechniqueInfo>& techniques() {
  static const std::vector<TechniqueInfo> all = {
      direct_technique(),
      pt_technique(),
      rsm_technique(),
      lpv_technique(),
      vct_technique(),
  };
  return all;
}

}  // namespace giq::realtime
