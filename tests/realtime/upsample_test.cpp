// The shared upsample pass: bilinear reconstruction is exact for a linear signal on a plane
// (and the symmetric blur keeps it so), and the edge-aware weights never mix surfaces that
// meet at a right angle.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "giq/realtime/context.h"
#include "giq/realtime/scene_gpu.h"
#include "giq/realtime/timer.h"
#include "passes/gbuffer.h"
#include "passes/upsample.h"
#include "test_scenes.h"

namespace giq::realtime {
namespace {

class UpsampleTest : public test::VulkanTest {
 protected:
  // Renders the G-buffer of `scene`, fills the low-resolution image with value(full-resolution
  // pixel the low pixel stands for, G-buffer normal there), upsamples, and returns the output.
  template <class F>
  std::vector<float> run(const scenes::Scene& scene, uint32_t size, uint32_t k, bool blur, F value,
                         std::vector<float>* normals_out = nullptr) {
    SceneGpu gpu(*ctx, *compiler, scene);
    GBufferPass gbuffer(*ctx, *compiler, gpu, scene.features, size, size);
    UpsamplePass up(*ctx, *compiler, size, size, k, blur);
    GpuTimer timer(*ctx);
    const auto& camera = scene.views[0].camera;
    ctx->submit_and_wait([&](VkCommandBuffer cmd) {
      timer.reset(cmd);
      gbuffer.record(cmd, camera, timer);
    });
    const std::vector<float> normals = gbuffer.normal().read_floats();
    Image low(*ctx, {up.low_width(), up.low_height(), 1, VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT});
    std::vector<float> texels(4 * size_t(up.low_width()) * up.low_height());
    for (uint32_t y = 0; y < up.low_height(); ++y)
      for (uint32_t x = 0; x < up.low_width(); ++x) {
        const uint32_t fx = std::min(k * x + k / 2, size - 1), fy = std::min(k * y + k / 2, size - 1);
        const float* n = &normals[4 * (size_t(fy) * size + fx)];
        const glm::vec3 v = value(fx, fy, glm::vec3(n[0], n[1], n[2]));
        float* t = &texels[4 * (size_t(y) * up.low_width() + x)];
        t[0] = v.x, t[1] = v.y, t[2] = v.z, t[3] = 1.0f;
      }
    low.write_floats(texels);
    ctx->submit_and_wait([&](VkCommandBuffer cmd) {
      timer.reset(cmd);
      up.record(cmd, low, gbuffer, timer);
    });
    if (normals_out) *normals_out = normals;
    return up.output().read_floats();
  }
};

// On one plane every geometric weight is 1 (up to float rounding of the G-buffer positions),
// so the upsample is plain bilinear interpolation between the pixels the low samples stand
// for, which reproduces a linear function exactly; the blur's symmetric binomial kernel keeps
// a linear function too. Away from the borders (where samples are clamped) the error is float
// rounding: values are below 200, so 1e-3 is ~10^3 ulps of headroom for the sums.
TEST_F(UpsampleTest, ReproducesALinearSignalOnAPlane) {
  const scenes::Scene plane = test::lambert_plane(0.5f, 100.0f, 1.0f);  // fills the view
  const uint32_t size = 64;
  auto linear = [](uint32_t x, uint32_t y, glm::vec3) {
    return glm::vec3(1.5f * float(x) + 0.25f * float(y) + 3.0f, 2.0f * float(y), 7.0f);
  };
  for (uint32_t k : {1u, 2u, 3u, 4u})
    for (bool blur : {false, true}) {
      const std::vector<float> out = run(plane, size, k, blur, linear);
      // Between the first and the last low sample (the last one clamped to the border), and
      // with the blur 4 pixels further in, where its kernel is whole.
      const uint32_t last = std::min(k * ((size + k - 1) / k - 1) + k / 2, size - 1);
      const uint32_t lo = k / 2 + (blur ? 4 : 0), hi = last - (blur ? 4 : 0);
      for (uint32_t y = lo; y <= std::min(hi, size - 1); ++y)
        for (uint32_t x = lo; x <= std::min(hi, size - 1); ++x) {
          const glm::vec3 want = linear(x, y, {});
          const float* got = &out[4 * (size_t(y) * size + x)];
          ASSERT_NEAR(got[0], want.x, 1e-3f) << "k " << k << " blur " << blur << " at " << x << "," << y;
          ASSERT_NEAR(got[1], want.y, 1e-3f) << "k " << k << " blur " << blur << " at " << x << "," << y;
          ASSERT_NEAR(got[2], want.z, 1e-3f);
        }
    }
}

// Every surface of the test Cornell box meets every other one at a right angle or is parallel
// to it. Encode each low sample's normal as its value: an output pixel that shows any other
// normal than its own has mixed light across a crease. The normal weight is exactly 0 at a
// right angle, so every pixel that has a sample of its own surface among the 4x4 low samples
// around it must show its own normal exactly. Pixels without one (slivers thinner than k
// pixels that no low pixel sees) cannot be recovered by any upsampler and are excluded, and
// with the blur so is every pixel whose 9x9 window reaches one. (Bilinear upsampling without
// the weights would mix along every crease.)
TEST_F(UpsampleTest, NeverMixesSurfacesAcrossACrease) {
  const scenes::Scene box = test::cornell_box();
  const int size = 96;
  for (int k : {2, 3, 4})
    for (bool blur : {false, true}) {
      std::vector<float> normals;
      const std::vector<float> out =
          run(box, size, k, blur, [](uint32_t, uint32_t, glm::vec3 n) { return n; }, &normals);
      auto normal = [&](int x, int y) {
        const float* n = &normals[4 * (size_t(y) * size + x)];
        return glm::vec3(n[0], n[1], n[2]);
      };
      const int low = (size + k - 1) / k;
      auto full = [&](int q) { return std::min(q * k + k / 2, size - 1); };
      std::vector<char> uncovered(size_t(size) * size, 0);
      for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
          const int bx = int(std::floor(float(x - k / 2) / float(k))), by = int(std::floor(float(y - k / 2) / float(k)));
          bool found = false;
          for (int j = -1; j <= 2 && !found; ++j)
            for (int i = -1; i <= 2 && !found; ++i) {
              const int qx = std::clamp(bx + i, 0, low - 1), qy = std::clamp(by + j, 0, low - 1);
              found = normal(full(qx), full(qy)) == normal(x, y);
            }
          uncovered[size_t(y) * size + x] = !found;
        }
      int checked = 0, mixed = 0;
      for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
          const int reach = blur ? 4 : 0;
          bool excluded = false;
          for (int j = -reach; j <= reach; ++j)
            for (int i = -reach; i <= reach; ++i) {
              const int xx = x + i, yy = y + j;
              if (xx >= 0 && yy >= 0 && xx < size && yy < size && uncovered[size_t(yy) * size + xx]) excluded = true;
            }
          if (excluded) continue;
          ++checked;
          const float* o = &out[4 * (size_t(y) * size + x)];
          if (glm::length(glm::vec3(o[0], o[1], o[2]) - normal(x, y)) > 1e-5f) ++mixed;
        }
      EXPECT_EQ(mixed, 0) << "k " << k << " blur " << blur;
      EXPECT_GT(checked, size * size * 8 / 10) << "k " << k << " blur " << blur;  // the test still tests
    }
}

TEST_F(UpsampleTest, WithoutDownsamplingOrBlurItIsACopy) {
  const scenes::Scene box = test::cornell_box();
  const uint32_t size = 32;
  auto value = [](uint32_t x, uint32_t y, glm::vec3 n) { return n * float(x + 1) + glm::vec3(float(y) * 1e-3f); };
  const std::vector<float> out = run(box, size, 1, false, value);
  std::vector<float> normals;
  run(box, size, 1, false, value, &normals);
  for (uint32_t y = 0; y < size; ++y)
    for (uint32_t x = 0; x < size; ++x) {
      const size_t i = 4 * (size_t(y) * size + x);
      const glm::vec3 want = value(x, y, glm::vec3(normals[i], normals[i + 1], normals[i + 2]));
      ASSERT_EQ(out[i], want.x);
      ASSERT_EQ(out[i + 1], want.y);
      ASSERT_EQ(out[i + 2], want.z);
    }
}

}  // namespace
}  // namespace giq::realtime
