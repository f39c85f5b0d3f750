#include "giq/scenes/camera.h"

#include <cmath>
#include <glm/geometric.hpp>
#include <stdexcept>

namespace giq::scenes {

Camera Camera::look_at(glm::vec3 eye, glm::vec3 target, glm::vec3 up, float yfov_radians) {
  // Built in double so that a camera far from its target still gets an orthonormal basis to
  // float precision.
  const glm::dvec3 d = glm::dvec3(target) - glm::dvec3(eye);
  const double len = glm::length(d);
  if (!(len > 0.0) || !std::isfinite(len))
    throw std::invalid_argument("camera eye and target must be distinct finite points");
  const glm::dvec3 f = d / len;
  const glm::dvec3 r = glm::cross(f, glm::dvec3(up));
  const double rlen = glm::length(r);
  // sin(angle between up and forward) below 1e-6 leaves the roll undefined.
  if (!(rlen > 1e-6 * glm::length(glm::dvec3(up))) || !std::isfinite(rlen))
    throw std::invalid_argument("camera up vector must not be parallel to the view direction");
  Camera c;
  c.position = eye;
  c.forward = glm::vec3(f);
  c.right = glm::vec3(r / rlen);
  c.up = glm::vec3(glm::cross(r / rlen, f));
  c.yfov = yfov_radians;
  return c;
}

glm::vec3 Camera::ray_direction(float px, float py, int width, int height) const {
  return ImageRays(*this, width, height).direction(px, py);
}

glm::vec3 Camera::ray_origin(float px, float py, int width, int height) const {
  return position + ImageRays(*this, width, height).origin_offset(px, py);
}

// Pinhole: the image plane at distance 1 spans tan(yfov/2) above and below the axis.
// Orthographic: the plane through the camera spans ymag above and below it (glTF 2.0 spec,
// 3.10.3; like a pinhole's yfov, ymag spans the height, and the width follows the image's
// aspect). Horizontally both span aspect times that. (px, py) are continuous pixel
// coordinates, y down.
ImageRays::ImageRays(const Camera& camera, int width, int height)
    : forward_(camera.forward), right_(camera.right), up_(camera.up), orthographic_(camera.orthographic()),
      half_height_(camera.orthographic() ? double(camera.ymag) : std::tan(0.5 * double(camera.yfov))),
      aspect_(double(width) / double(height)), width_(double(width)), height_(double(height)) {}

}  // namespace giq::scenes
