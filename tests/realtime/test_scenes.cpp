#include "test_scenes.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace giq::test {

std::string layer(const std::string& name, int c) { return name.empty() ? kRgb[c] : name + "." + kRgb[c]; }

double mean(const image::Image& img, const std::string& channel) {
  double sum = 0.0;
  const float* v = img.channel(channel);
  for (size_t i = 0; i < img.pixel_count(); ++i) sum += v[i];
  return sum / double(img.pixel_count());
}

scenes::Scene builtin(const std::string& name) {
  return scenes::load(std::filesystem::path(GIQ_SCENES_DIR) / (name + ".gltf"));
}

scenes::Scene cornell_with_every_light_off() {
  scenes::Scene scene = builtin("cornell");
  for (auto& m : scene.materials) m.emissive = glm::vec3(0.0f);
  scenes::Light l;
  l.type = scenes::LightType::Point;
  l.position = {0.0f, 0.0f, 0.0f};
  l.intensity = 0.0f;
  scene.lights.push_back(l);
  scene.derive();
  return scene;
}

void VulkanTest::SetUp() {
  realtime::ContextOptions o;
  o.validation = true;
  ctx = std::make_unique<realtime::Context>(o);
  compiler = std::make_unique<realtime::ShaderCompiler>(GIQ_TEST_SHADER_CACHE);
}

void VulkanTest::TearDown() {
  if (!ctx) return;
  for (const auto& m : ctx->validation_messages()) ADD_FAILURE() << "validation: " << m;
}

image::Image VulkanTest::render_last(const scenes::Scene& s, const realtime::RenderOptions& o) {
  image::Image out;
  realtime::render_sequence(*ctx, *compiler, s, o, [&](realtime::RenderedFrame& f) { out = std::move(f.image); });
  return out;
}

image::Image VulkanTest::render(const scenes::Scene& s, const std::string& technique, uint32_t size,
                                std::vector<std::string> params) {
  realtime::RenderOptions o;
  o.technique = technique;
  o.view = "0";
  o.width = o.height = size;
  o.parameters = std::move(params);
  return render_last(s, o);
}

void VulkanTest::expect_persistent_matches_fresh(const scenes::Scene& animated, realtime::RenderOptions o,
                                                 const std::string& channel) {
  ASSERT_TRUE(animated.features.animation);
  std::vector<image::Image> sequence;
  realtime::render_sequence(*ctx, *compiler, animated, o, [&](realtime::RenderedFrame& f) {
    // Frames this technique instance has rendered, this one included: it was never recreated.
    EXPECT_EQ(f.image.metadata.at("giq.technique_frame"), std::to_string(f.frame + 1));
    sequence.push_back(std::move(f.image));
  });
  ASSERT_EQ(sequence.size(), size_t(o.frames));
  for (int f = 1; f < o.frames; ++f) {
    scenes::Scene posed = animated.at_frame(f);
    posed.features.animation = false;
    realtime::RenderOptions one = o;
    one.frames = 1;
    const image::Image alone = render_last(posed, one);
    const float *a = sequence[size_t(f)].channel(channel), *b = alone.channel(channel);
    const float* prev = sequence[size_t(f) - 1].channel(channel);
    double diff = 0.0, change = 0.0;
    for (size_t i = 0; i < alone.pixel_count(); ++i) {
      diff = std::max(diff, double(std::abs(a[i] - b[i])));
      change = std::max(change, double(std::abs(a[i] - prev[i])));
    }
    EXPECT_EQ(diff, 0.0) << o.technique << " frame " << f;
    EXPECT_GT(change, 0.0) << o.technique << " frame " << f;
  }
}

}  // namespace giq::test
