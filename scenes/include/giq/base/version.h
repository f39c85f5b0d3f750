#pragma once

namespace giq {

// "0.1.0" plus the git commit the build was made from, when known ("0.1.0+g1a2b3c4").
const char* version();

}  // namespace giq
