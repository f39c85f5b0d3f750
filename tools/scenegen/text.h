#pragma once
// Numbers in the generated documentation: fixed decimals with trailing zeros dropped, in the
// C locale, so the text is the same on every machine.

#include <glm/glm.hpp>
#include <string>

namespace giq::scenegen {

std::string num(double v, int decimals = 4);
std::string vec(glm::dvec3 v, int decimals = 4);  // "(x, y, z)"

}  // namespace giq::scenegen
