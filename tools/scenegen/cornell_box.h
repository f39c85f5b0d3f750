#pragma once
// The Cornell box as published by the Cornell Program of Computer Graphics ("Cornell Box
// Data", https://www.graphics.cornell.edu/online/box/data.html), in metres. Shared by the
// `cornell` and `movinglight` scenes.

#include <glm/glm.hpp>

#include "gltf_writer.h"

namespace giq::scenegen::cornell {

// Published coordinates are in millimetres.
constexpr glm::dvec3 mm(double x, double y, double z) {
  return {x / 1000.0, y / 1000.0, z / 1000.0};
}

// The published light is at the ceiling's height (548.8 mm). It is lowered by 1 mm so the two
// quads never share a plane: rasterisers would z-fight and ray tracers with a ~1e-4 m offset
// could hit the ceiling behind it.
constexpr double kLightDrop = 0.001;

// The published light rectangle, x 213..343 mm, z 227..332 mm.
constexpr glm::dvec3 kLightMin = mm(213.0, 548.8, 227.0);
constexpr glm::dvec3 kLightMax = mm(343.0, 548.8, 332.0);
// Radiance of the light (W/(m^2 sr) per RGB channel): the usual RGB fit of the published
// spectrum, as in the cornell-box scene of Bitterli's "Rendering Resources" (2016) that ships
// for pbrt-v3 and Mitsuba.
constexpr glm::dvec3 kLightRadiance{17.0, 12.0, 4.0};
// Reflectances: the usual RGB fits of the published spectra, same source.
constexpr glm::dvec3 kWhite{0.725, 0.71, 0.68};
constexpr glm::dvec3 kRed{0.63, 0.065, 0.05};
constexpr glm::dvec3 kGreen{0.14, 0.45, 0.091};
// The published camera: 35 mm focal length on a 25 mm x 25 mm film.
constexpr double kFocalLengthMm = 35.0;
constexpr double kFilmMm = 25.0;

// Vertical field of view of the published camera, degrees.
double yfov_deg();

// Adds the box: floor, ceiling, back wall, red (x = 552.8..556 mm) and green (x = 0) walls, the
// short and tall blocks, and (when `ceiling_light`) the emissive light quad; the published
// camera as the camera node `front` and the extras view `corner`.
void add_box(GltfWriter& gltf, bool ceiling_light);

}  // namespace giq::scenegen::cornell
