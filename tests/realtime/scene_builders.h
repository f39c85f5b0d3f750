#pragma once
// Scenes built in code (no glTF loader needed), shared by the real-time tests and the
// real-time benchmark.

#include <functional>
#include <glm/glm.hpp>

#include "giq/scenes/scene.h"

namespace giq::test {

// Two triangles a, b, c, d (counter-clockwise seen from the side the normal points to).
void add_quad(scenes::Scene& s, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, int material);
int add_material(scenes::Scene& s, glm::vec3 albedo, glm::vec3 emissive = glm::vec3(0.0f));

// A texture of w x h linear RGBA texels texel(x, y) (row y = 0 at v = 0); returns its index.
int add_texture(scenes::Scene& s, int w, int h, const std::function<glm::vec4(int, int)>& texel,
                scenes::Filter filter = scenes::Filter::Linear, scenes::Wrap wrap = scenes::Wrap::Repeat);
// add_quad with TEXCOORD_0 (0,0), (k,0), (k,k), (0,k) at a, b, c, d (k = uv_scale).
void add_textured_quad(scenes::Scene& s, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, int material,
                       float uv_scale = 1.0f);

// A closed Cornell-style box [-1,1]^3 open to nothing: white floor, ceiling and back wall,
// red left and green right walls, a 0.5 x 0.5 emissive quad just below the ceiling facing
// down, a short and a tall block; one view "front" from z = 3.4 looking down -z.
scenes::Scene cornell_box(glm::vec3 light_radiance = glm::vec3(17.0f, 12.0f, 4.0f));

// The Cornell box with every texture feature the real-time module renders: a base-colour
// checker on the floor (bilinear, repeating twice), a normal-mapped back wall with a
// metallic-roughness texture (tangents from the UVs), an emissive texture on the light, and a
// double-sided alpha-masked grating under the light whose cut-outs let light through.
scenes::Scene textured_box();

// The Cornell box also lit by a spot light and a sun: with its emitter, every kind of
// shadow-map and reflective-shadow-map layer (a cube, cascades or a window, an area light's
// cube without its own quad).
scenes::Scene cornell_box_every_light();

// textured_box() lit by a point light.
scenes::Scene lit_textured_box();

// `s` scaled by k about the origin: its geometry, its lights' places, its cameras' places and
// near planes.
scenes::Scene scaled(scenes::Scene s, float k);

// A Lambertian plane y = 0, [-half, half]^2 (albedo rho), seen from above by view "top"
// looking straight down from height `eye_height` with a 60 degree field of view.
scenes::Scene lambert_plane(float rho, float half = 4.0f, float eye_height = 3.0f);

// A UV sphere of `rings` x `segments` quads (2 * rings * segments - 2 * segments triangles).
void add_sphere(scenes::Scene& s, glm::vec3 centre, float radius, int rings, int segments, int material);

}  // namespace giq::test
