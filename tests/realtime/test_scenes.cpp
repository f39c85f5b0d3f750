#include "test_scenes.h"

namespace giq::test {

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

}  // namespace giq::test
