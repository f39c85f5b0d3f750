#pragma once
// The camera shared by every renderer, so a pixel of `giq reference` and of `giq realtime`
// look through the same ray: a pinhole, or an orthographic camera (glTF 2.0 spec, 3.10.3).

#include <glm/glm.hpp>
#include <string>

namespace giq::scenes {

struct Camera {
  glm::vec3 position{0.0f};  // local frame (see Scene::origin)
  glm::vec3 forward{0.0f, 0.0f, -1.0f};  // unit; orthonormal with up and right
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  glm::vec3 right{1.0f, 0.0f, 0.0f};  // cross(forward, up)
  float yfov = 0.785398163397448f;    // vertical field of view, radians (perspective)
  // > 0: orthographic, and this is half the image's height in metres (glTF's ymag); every ray
  // then runs along forward from its own point of the plane through position. 0: pinhole.
  float ymag = 0.0f;
  float znear = 0.01f;                // rasteriser near plane; the path tracer ignores it
  float zfar = 0.0f;                  // 0 = infinite

  // Builds an orthonormal camera looking from eye to target; throws std::invalid_argument
  // when eye == target or up is parallel to the view direction.
  static Camera look_at(glm::vec3 eye, glm::vec3 target, glm::vec3 up, float yfov_radians);

  // Unit direction through the image point (px, py), in pixels of a width x height image:
  // x to the right, y down, pixel (i, j) covering [i, i+1) x [j, j+1), its centre at +0.5.
  // The aspect ratio is the image's (width / height); yfov spans the image height.
  glm::vec3 ray_direction(float px, float py, int width, int height) const;
  // Where that ray starts: position, or for an orthographic camera its point of the image
  // plane through position.
  glm::vec3 ray_origin(float px, float py, int width, int height) const;

  bool orthographic() const { return ymag > 0.0f; }
};

// The camera's rays through one image size, with the constants of the image (the tangent of
// half the field of view or the half height, the aspect ratio) computed once rather than per
// ray. Gives exactly Camera::ray_direction and ray_origin, which are defined through it.
class ImageRays {
 public:
  ImageRays(const Camera& camera, int width, int height);
  glm::vec3 direction(float px, float py) const {
    if (orthographic_) return glm::vec3(forward_);
    return glm::vec3(glm::normalize(forward_ + plane(px, py)));
  }
  // The ray's start relative to the camera's position: zero for a pinhole.
  glm::vec3 origin_offset(float px, float py) const {
    return orthographic_ ? glm::vec3(plane(px, py)) : glm::vec3(0.0f);
  }

 private:
  // The point (px, py) on the image plane, relative to its centre: the plane at distance 1
  // for a pinhole, the plane through the camera for an orthographic camera.
  glm::dvec3 plane(float px, float py) const {
    const double x = (2.0 * double(px) / width_ - 1.0) * half_height_ * aspect_;
    const double y = (1.0 - 2.0 * double(py) / height_) * half_height_;
    return x * right_ + y * up_;
  }
  glm::dvec3 forward_, right_, up_;
  bool orthographic_;
  double half_height_, aspect_, width_, height_;
};

struct View {
  std::string name;
  Camera camera;
  int node = -1;  // glTF node carrying the camera; -1 for a view from extras or the CLI
};

}  // namespace giq::scenes
