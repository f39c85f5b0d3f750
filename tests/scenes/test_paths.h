#pragma once
#include <filesystem>
#include <glm/glm.hpp>
#include <string>

#include "giq/scenes/scene.h"

namespace giq::scenes::test {

inline std::filesystem::path data(const std::string& name) {
  return std::filesystem::path(GIQ_TEST_DATA) / "scenes" / name;
}

// World position of a local-frame point.
inline glm::dvec3 world(const Scene& s, glm::vec3 local) { return s.origin + glm::dvec3(local); }

}  // namespace giq::scenes::test
