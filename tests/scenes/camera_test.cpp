#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "giq/scenes/camera.h"

namespace giq::scenes {
namespace {

// Unit vectors built in double and rounded to float: a few ulps of 1.
constexpr float kTol = 2e-6f;

void expect_vec(glm::vec3 a, glm::vec3 b, float tol = kTol) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

TEST(Camera, LookAtBuildsOrthonormalBasis) {
  const Camera c = Camera::look_at({1, 2, 3}, {4, 6, 3}, {0, 1, 0}, 0.5f);
  expect_vec(c.position, {1, 2, 3}, 0.0f);
  expect_vec(c.forward, {0.6f, 0.8f, 0.0f});  // (3, 4, 0) / 5
  expect_vec(c.right, glm::normalize(glm::cross(c.forward, glm::vec3(0, 1, 0))));
  expect_vec(c.right, glm::cross(c.forward, c.up));
  EXPECT_NEAR(glm::dot(c.up, c.forward), 0.0f, kTol);
  EXPECT_NEAR(glm::length(c.up), 1.0f, kTol);
  EXPECT_GT(c.up.y, 0.0f);  // the roll follows the up hint
  EXPECT_FLOAT_EQ(c.yfov, 0.5f);
}

TEST(Camera, LookAtRejectsDegenerateInput) {
  EXPECT_THROW(Camera::look_at({1, 1, 1}, {1, 1, 1}, {0, 1, 0}, 1.0f), std::invalid_argument);
  EXPECT_THROW(Camera::look_at({0, 0, 0}, {0, 5, 0}, {0, 1, 0}, 1.0f), std::invalid_argument);
  EXPECT_THROW(Camera::look_at({0, 0, 0}, {0, -5, 0}, {0, 2, 0}, 1.0f), std::invalid_argument);
}

TEST(Camera, RayThroughCentrePixelIsForward) {
  const Camera c = Camera::look_at({0, 0, 0}, {1, -1, 2}, {0, 1, 0}, 0.9f);
  // 5 x 3 image: the centre pixel (2, 1) has its centre at (2.5, 1.5), the image centre.
  expect_vec(c.ray_direction(2.5f, 1.5f, 5, 3), c.forward);
  expect_vec(c.ray_direction(320.0f, 240.0f, 640, 480), c.forward);
}

TEST(Camera, RaysThroughEdgesAndCornersSpanTheFieldOfView) {
  const float yfov = 1.0f;
  const Camera c = Camera::look_at({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, yfov);
  const int w = 400, h = 200;  // aspect 2
  const double t = std::tan(0.5 * yfov);
  // Top edge (y = 0) in the middle: half the vertical field of view above the axis.
  const glm::vec3 top = c.ray_direction(w / 2.0f, 0.0f, w, h);
  EXPECT_NEAR(std::acos(glm::dot(top, c.forward)), 0.5 * yfov, 1e-6);
  EXPECT_GT(top.y, 0.0f);
  // Bottom edge: below the axis (y grows downwards in the image).
  EXPECT_LT(c.ray_direction(w / 2.0f, float(h), w, h).y, 0.0f);
  // Left edge: the horizontal half-angle is atan(aspect * tan(yfov / 2)).
  const glm::vec3 left = c.ray_direction(0.0f, h / 2.0f, w, h);
  EXPECT_NEAR(std::acos(glm::dot(left, c.forward)), std::atan(2.0 * t), 1e-6);
  EXPECT_LT(left.x, 0.0f);
  // Top-left corner: forward - aspect*t*right + t*up, normalised.
  const glm::vec3 corner = c.ray_direction(0.0f, 0.0f, w, h);
  const glm::vec3 expected = glm::normalize(glm::vec3(float(-2.0 * t), float(t), -1.0f));
  expect_vec(corner, expected);
  // Bottom-right corner mirrors it.
  expect_vec(c.ray_direction(float(w), float(h), w, h), {-expected.x, -expected.y, expected.z});
}

TEST(Camera, OrthographicRaysAreParallelAndSpanTheWindow) {
  Camera c = Camera::look_at({1, 2, 3}, {1, 2, -5}, {0, 1, 0}, 1.0f);
  c.ymag = 1.5f;
  const int w = 400, h = 200;  // aspect 2: the window is 6 x 3
  for (const glm::vec2 p : {glm::vec2(0, 0), glm::vec2(200, 100), glm::vec2(400, 200), glm::vec2(17.5f, 150.25f)})
    expect_vec(c.ray_direction(p.x, p.y, w, h), c.forward, 0.0f);
  expect_vec(c.ray_origin(200.0f, 100.0f, w, h), c.position, 0.0f);  // the centre: the camera
  expect_vec(c.ray_origin(0.0f, 0.0f, w, h), c.position + glm::vec3(-3.0f, 1.5f, 0.0f));  // top left
  expect_vec(c.ray_origin(400.0f, 200.0f, w, h), c.position + glm::vec3(3.0f, -1.5f, 0.0f));
  expect_vec(c.ray_origin(300.0f, 100.0f, w, h), c.position + glm::vec3(1.5f, 0.0f, 0.0f));
  // A pinhole's rays all start at its position.
  c.ymag = 0.0f;
  expect_vec(c.ray_origin(0.0f, 0.0f, w, h), c.position, 0.0f);
}

}  // namespace
}  // namespace giq::scenes
