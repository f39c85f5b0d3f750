#pragma once
// Environment maps: equirectangular (latitude-longitude) images of the radiance arriving from
// each direction, and the one mapping between directions and image coordinates every renderer
// uses (the GPU's shaders/environment.glsl says the same).
//
// With +Y up and glTF's forward -Z: u = 0.5 + atan2(x, -z) / 2pi runs round the horizon (the
// image's centre column looks along -Z, u grows towards +X), v = acos(y) / pi runs from the
// zenith (the top row, v = 0) to the nadir. A texel (i, j) of a W x H map covers the solid
// angle (2pi / W) (cos(pi j / H) - cos(pi (j + 1) / H)).

#include <glm/glm.hpp>

namespace giq::scenes {

// Image coordinates of a unit direction.
glm::vec2 equirect_uv(glm::vec3 dir);
// The unit direction at image coordinates (u, v).
glm::vec3 equirect_direction(glm::vec2 uv);

}  // namespace giq::scenes
