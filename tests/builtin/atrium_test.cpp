// The atrium (giq-scenegen --atrium, the large-scene benchmark's scene), written at its small
// detail: what the generator promises, read back through the scene library, and the sealed
// sacristy black in the reference while the nave is lit.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "giq/reference/renderer.h"
#include "giq/scenes/scene.h"

namespace fs = std::filesystem;

namespace {

class Atrium : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    path_ = fs::temp_directory_path() / ("giq-atrium-" + std::to_string(::getpid()) + ".glb");
    const std::string command = std::string("\"") + GIQ_SCENEGEN + "\" --atrium \"" + path_.string() + "\" --small";
    ASSERT_EQ(std::system(command.c_str()), 0) << command;
    scene_ = new giq::scenes::Scene(giq::scenes::load(path_));
  }
  static void TearDownTestSuite() {
    delete scene_;
    fs::remove(path_);
  }
  static fs::path path_;
  static giq::scenes::Scene* scene_;
};
fs::path Atrium::path_;
giq::scenes::Scene* Atrium::scene_ = nullptr;

TEST_F(Atrium, HasWhatTheGeneratorPromises) {
  const giq::scenes::Scene& s = *scene_;
  // AtriumDetail::small(): 4 materials of 3 textures each, 16² texels.
  ASSERT_EQ(s.materials.size(), 4u);
  ASSERT_EQ(s.textures.size(), 12u);
  for (const auto& t : s.textures) EXPECT_TRUE(t.valid() && t.width == 16 && t.height == 16);
  for (const auto& m : s.materials) EXPECT_TRUE(m.base_color_texture >= 0 && m.metallic_roughness_texture >= 0 && m.normal_texture >= 0);
  EXPECT_TRUE(s.materials.back().double_sided);  // the curtains' fabric
  // Triangles: floor and walls 5 x 2 x 2^2, ceiling 4 x 2, sacristy 6 x 2 x 1^2, 12 columns of
  // 12 x 2 quads, 10 arches of 4 grids of 8 x 2 quads, 3 curtains of 2 sheets of 12 x 4 quads;
  // two triangles a quad.
  const size_t quads = 5 * 4 + 4 + 6 * 1 + 12 * 24 + 10 * 4 * 16 + 3 * 2 * 48;
  EXPECT_EQ(s.stats.triangles, 2 * quads);
  EXPECT_TRUE(s.features.textures && s.features.normal_maps && s.features.directional_lights && s.features.double_sided);
  ASSERT_EQ(s.views.size(), 4u);
  EXPECT_EQ(s.leak_regions.size(), 6u);
}

// The sacristy is sealed: no path reaches it from the sun, so its view is exactly black,
// while the nave's is not.
TEST_F(Atrium, SacristyIsBlackAndTheNaveIsLit) {
  const giq::scenes::Scene& s = *scene_;
  auto mean = [&](const std::string& view) {
    const giq::scenes::View* v = nullptr;
    for (const auto& x : s.views)
      if (x.name == view) v = &x;
    EXPECT_NE(v, nullptr) << view;
    if (!v) return -1.0;
    giq::reference::RenderSettings rs;
    rs.width = rs.height = 24;
    const giq::reference::Renderer r(s, v->camera, rs);
    giq::reference::Film f = r.make_film();
    r.render(f, 16);
    const auto image = f.to_image();
    double sum = 0.0;
    for (const char* c : {"R", "G", "B"})
      for (size_t i = 0; i < image.pixel_count(); ++i) sum += image.channel(c)[i];
    return sum;
  };
  EXPECT_EQ(mean("sacristy"), 0.0);
  EXPECT_GT(mean("nave"), 0.0);
}

}  // namespace
