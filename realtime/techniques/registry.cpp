// The registry of real-time techniques. Adding a technique is adding its folder
// (realtime/techniques/<name>/, whose <name>.cpp defines `TechniqueInfo <name>_technique()`)
// and one line here.
#include "giq/realtime/technique.h"

#define GIQ_TECHNIQUES(X) \
  X(direct)               \
  X(pt)                   \
  X(rsm)                  \
  X(lpv)                  \
  X(vct)                  \
  X(ddgi)                 \
  X(hybrid)               \
  X(gi1)

namespace giq::realtime {

#define GIQ_DECLARE(name) TechniqueInfo name##_technique();
GIQ_TECHNIQUES(GIQ_DECLARE)
#undef GIQ_DECLARE

const std::vector<TechniqueInfo>& techniques() {
#define GIQ_ENTRY(name) name##_technique(),
  static const std::vector<TechniqueInfo> all = {GIQ_TECHNIQUES(GIQ_ENTRY)};
#undef GIQ_ENTRY
  return all;
}

}  // namespace giq::realtime
