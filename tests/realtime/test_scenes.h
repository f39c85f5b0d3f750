#pragma once
// The test fixture that gives every test a
// Vulkan context with the validation layer on and fails it on any validation message.

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "giq/image/image.h"
#include "giq/realtime/context.h"
#include "giq/realtime/renderer.h"
#include "giq/realtime/shader.h"
#include "giq/scenes/scene.h"
#include "scene_builders.h"

namespace giq::test {

inline constexpr const char* kRgb[3] = {"R", "G", "B"};
// The channel c of an output layer: layer("", 0) = "R", layer("indirect", 2) = "indirect.B".
std::string layer(const std::string& name, int c);
// The mean of a channel over the image.
double mean(const image::Image& img, const std::string& channel);
// A built-in scene, scenes/<name>.gltf.
scenes::Scene builtin(const std::string& name);
// The built-in Cornell box with every light off: its emitter black, and a point light of zero
// intensity added so that the punctual-light code runs too.
scenes::Scene cornell_with_every_light_off();

class VulkanTest : public ::testing::Test {
 protected:
  void SetUp() override;
  void TearDown() override;
  // The last measured frame of the sequence `o` describes.
  image::Image render_last(const scenes::Scene& s, const realtime::RenderOptions& o);
  // One frame of `technique` on view 0 at size x size.
  image::Image render(const scenes::Scene& s, const std::string& technique, uint32_t size,
                      std::vector<std::string> params = {});
  // One instance of o.technique through frames 0..o.frames-1 of an animated scene gives, at
  // every frame, the bits of an instance created for that frame's pose alone (same commands
  // on the same data), in `channel`; and consecutive frames differ, so something did move.
  void expect_persistent_matches_fresh(const scenes::Scene& animated, realtime::RenderOptions o,
                                       const std::string& channel);
  std::unique_ptr<realtime::Context> ctx;
  std::unique_ptr<realtime::ShaderCompiler> compiler;
};

}  // namespace giq::test
