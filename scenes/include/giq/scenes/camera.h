#pragma once
// Pinhole camera shared by every renderer, so a pixel of `giq reference` and of
// `giq realtime` look through the same ray.

#include <glm/glm.hpp>
#include <string>

namespace giq::scenes {

struct Camera {
  glm::vec3 position{0.0f};  // local frame (see Scene::origin)
  glm::vec3 forward{0.0f, 0.0f, -1.0f};  // unit; orthonormal with up and right
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  glm::vec3 right{1.0f, 0.0f, 0.0f};  // cross(forward, up)
  float yfov = 0.785398163397448f;    // vertical field of view, radians
  float znear = 0.01f;                // rasteriser near plane; the path tracer ignores it
  float zfar = 0.0f;                  // 0 = infinite

  // Builds an orthonormal camera looking from eye to target; throws std::invalid_argument
  // when eye == target or up is parallel to the view direction.
  static Camera look_at(glm::vec3 eye, glm::vec3 target, glm::vec3 up, float yfov_radians);

  // Unit direction through the image point (px, py), in pixels of a width x height image:
  // x to the right, y down, pixel (i, j) covering [i, i+1) x [j, j+1), its centre at +0.5.
  // The aspect ratio is the image's (width / height); yfov spans the image height.
  glm::vec3 ray_direction(float px, float py, int width, int height) const;
};

// The camera's rays through one image size, with the constants of the image (the tangent of
// half the field of view, the aspect ratio) computed once rather than per ray. Gives exactly
// Camera::ray_direction, which is defined through it.
class ImageRays {
 public:
  ImageRays(const Camera& camera, int width, int height);
  glm::vec3 direction(float px, float py) const {
    const double x = (2.0 * double(px) / width_ - 1.0) * tan_half_fov_ * aspect_;
    const double y = (1.0 - 2.0 * double(py) / height_) * tan_half_fov_;
    return glm::vec3(glm::normalize(forward_ + x * right_ + y * up_));
  }

 private:
  glm::dvec3 forward_, right_, up_;
  double tan_half_fov_, aspect_, width_, height_;
};

struct View {
  std::string name;
  Camera camera;
  int node = -1;  // glTF node carrying the camera; -1 for a view from extras or the CLI
};

}  // namespace giq::scenes
