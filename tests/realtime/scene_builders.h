#pragma once
// Scenes built in code (no glTF loader needed), shared by the real-time tests and the
// real-time benchmark.

#include <glm/glm.hpp>

#include "giq/scenes/scene.h"

namespace giq::test {

// Two triangles a, b, c, d (counter-clockwise seen from the side the normal points to).
void add_quad(scenes::Scene& s, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, int material);
int add_material(scenes::Scene& s, glm::vec3 albedo, glm::vec3 emissive = glm::vec3(0.0f));

// A closed Cornell-style box [-1,1]^3 open to nothing: white floor, ceiling and back wall,
// red left and green right walls, a 0.5 x 0.5 emissive quad just below the ceiling facing
// down, a short and a tall block; one view "front" from z = 3.4 looking down -z.
scenes::Scene cornell_box(glm::vec3 light_radiance = glm::vec3(17.0f, 12.0f, 4.0f));

// A Lambertian plane y = 0, [-half, half]^2 (albedo rho), seen from above by view "top"
// looking straight down from height `eye_height` with a 60 degree field of view.
scenes::Scene lambert_plane(float rho, float half = 4.0f, float eye_height = 3.0f);

// A UV sphere of `rings` x `segments` quads (2 * rings * segments - 2 * segments triangles).
void add_sphere(scenes::Scene& s, glm::vec3 centre, float radius, int rings, int segments, int material);

}  // namespace giq::test
