#pragma once
// The test fixture that gives every test a
// Vulkan context with the validation layer on and fails it on any validation message.

#include <gtest/gtest.h>

#include <memory>

#include "giq/realtime/context.h"
#include "giq/realtime/shader.h"
#include "giq/scenes/scene.h"
#include "scene_builders.h"

namespace giq::test {

class VulkanTest : public ::testing::Test {
 protected:
  void SetUp() override;
  void TearDown() override;
  std::unique_ptr<realtime::Context> ctx;
  std::unique_ptr<realtime::ShaderCompiler> compiler;
};

}  // namespace giq::test
