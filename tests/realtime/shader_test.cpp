#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>

#include "giq/realtime/shader.h"
#include "giq/scenes/features.h"

namespace giq::realtime {
namespace {

TEST(ShaderCompiler, ReportsFileLineAndMessage) {
  ShaderCompiler c("");
  const std::string src = "#version 460\nlayout(local_size_x = 1) in;\nvoid main() {\n  float x = undefined_name;\n}\n";
  try {
    c.compile_source("tests/broken.comp", src);
    FAIL() << "expected a ShaderError";
  } catch (const ShaderError& e) {
    EXPECT_EQ(e.file(), "tests/broken.comp");
    EXPECT_EQ(e.line(), 4);
    EXPECT_NE(e.message().find("undefined_name"), std::string::npos) << e.message();
    EXPECT_NE(std::string(e.what()).find("tests/broken.comp:4:"), std::string::npos);
  }
}

TEST(ShaderCompiler, ReportsErrorsInsideIncludesWithTheIncludedFile) {
  ShaderCompiler c("");
  // A missing include is reported at the line of the directive in the including file.
  const std::string src =
      "#version 460\n#extension GL_GOOGLE_include_directive : require\n#include \"shaders/no_such_file.glsl\"\n"
      "layout(local_size_x = 1) in;\nvoid main() {}\n";
  try {
    c.compile_source("techniques/x/x.comp", src);
    FAIL() << "expected a ShaderError";
  } catch (const ShaderError& e) {
    EXPECT_EQ(e.file(), "techniques/x/x.comp");
    EXPECT_EQ(e.line(), 3);
  }
}

TEST(ShaderCompiler, DefinesFromTheFeatureSetSelectCode) {
  ShaderCompiler c("");
  // Compiles only when GIQ_POINT_LIGHTS is defined.
  const std::string src =
      "#version 460\nlayout(local_size_x = 1) in;\n#ifndef GIQ_POINT_LIGHTS\n#error point lights expected\n#endif\n"
      "void main() {}\n";
  scenes::FeatureSet f;
  EXPECT_THROW(c.compile_source("t.comp", src, feature_defines(f)), ShaderError);
  f.point_lights = true;
  const auto spirv = c.compile_source("t.comp", src, feature_defines(f));
  ASSERT_GT(spirv.size(), 5u);
  EXPECT_EQ(spirv[0], 0x07230203u);
}

TEST(ShaderCompiler, CachesByContentHash) {
  const auto dir = std::filesystem::temp_directory_path() / ("giq-spirv-test-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  const std::string a = "#version 460\nlayout(local_size_x = 1) in;\nvoid main() {}\n";
  const std::string b = "#version 460\nlayout(local_size_x = 2) in;\nvoid main() {}\n";
  {
    ShaderCompiler c(dir);
    const auto s1 = c.compile_source("a.comp", a);
    EXPECT_EQ(c.compilations(), 1);
    EXPECT_EQ(c.cache_hits(), 0);
    ShaderCompiler c2(dir);
    EXPECT_EQ(c2.compile_source("a.comp", a), s1);
    EXPECT_EQ(c2.cache_hits(), 1);
    c2.compile_source("b.comp", b);  // different text: compiled, not a stale hit
    EXPECT_EQ(c2.compilations(), 1);
    // Defines are part of the key.
    c2.compile_source("a.comp", a, {{"GIQ_SOMETHING", "1"}});
    EXPECT_EQ(c2.compilations(), 2);
  }
  std::filesystem::remove_all(dir);
}

TEST(ShaderCompiler, EveryEmbeddedEntryPointCompiles) {
  ShaderCompiler c("");
  for (const char* path : {"shaders/ray_query.comp"}) EXPECT_NO_THROW(c.compile(path)) << path;
}

}  // namespace
}  // namespace giq::realtime
