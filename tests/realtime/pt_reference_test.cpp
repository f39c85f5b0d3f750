// `pt` against the CPU reference (`giq_reference`) on every built-in scene: the same camera,
// units, BRDF and light transport must give the same image up to noise. Per pixel, the
// z-score (pt - reference) / sqrt(var_pt + var_reference) uses both renders' variance of the
// pixel mean; with both estimators unbiased it is close to standard normal, so beyond 4 sigma
// there should be almost no pixels (6e-5 of a normal population; the requirement allows
// 0.5%), the mean z-score must be consistent with zero and the image means must agree within
// 4 standard errors (reference_agreement.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <vector>

#include "giq/realtime/renderer.h"
#include "giq/reference/renderer.h"
#include "giq/scenes/scene.h"
#include "reference_agreement.h"
#include "test_scenes.h"

namespace giq::realtime {
namespace {

// `pt` and the reference at `spp` paths per pixel through view `view` of `loaded` at sequence
// frame `frame` (`pt` renders the frames before it as warm-up, restarting its sums each time
// the scene moves), compared per pixel.
void expect_pt_agrees(Context& ctx, ShaderCompiler& compiler, const scenes::Scene& loaded, const std::string& view,
                      int size, uint32_t spp, const std::string& what, int frame = 0, bool check_mean_z = true) {
  RenderOptions o;
  o.technique = "pt";
  o.view = view;
  o.width = o.height = size;
  o.warmup = frame;
  o.parameters = {"samples_per_frame=" + std::to_string(spp), "seed=7"};
  image::Image gpu;
  render_sequence(ctx, compiler, loaded, o, [&](RenderedFrame& f) { gpu = std::move(f.image); });

  const scenes::Scene scene = loaded.features.animation ? loaded.at_frame(frame) : loaded;
  reference::RenderSettings rs;
  rs.width = rs.height = size;
  rs.seed = 3;
  // Per-pixel z-scores need the same i.i.d. sampling as pt's and a per-pixel variance with
  // many degrees of freedom: the reference's independent sampler (its Sobol sampler agrees
  // with it, tests/reference/sobol_test.cpp).
  rs.sampler = reference::Sampler::Independent;
  reference::Renderer ref(scene, scene.view(view).camera, rs);
  reference::Film film = ref.make_film();
  ref.render(film, spp);
  const image::Image cpu = film.to_image();

  // Each built-in scene has emissive meshes only or one punctual light only, which `pt` and
  // the reference sample alike, so the mean z-score is gated too (reference_agreement.h).
  test::expect_agreement(gpu, cpu, what, "", check_mean_z);
}

// The light of the deforming files, which bring none of their own: a sun from above and in
// front, and a constant sky.
void add_sun_and_sky(scenes::Scene& scene) {
  scenes::Light sun;
  sun.type = scenes::LightType::Directional;
  sun.direction = glm::normalize(glm::vec3(-0.3f, -1.0f, -0.5f));
  sun.intensity = 3.0f;
  scene.add_light(sun, "sun");
  scene.set_environment(glm::vec3(0.3f), "sky");
}

class PtReferenceTest : public test::VulkanTest, public ::testing::WithParamInterface<std::string> {};
class PtReferenceCases : public test::VulkanTest {};

TEST_P(PtReferenceTest, AgreesWithinNoise) {
  const scenes::Scene loaded = scenes::load(std::filesystem::path(GIQ_SCENES_DIR) / (GetParam() + ".gltf"));
  // 128 x 128 (the resolution the requirement names) at 32 paths per pixel on both sides:
  // about 7 s per scene on lavapipe with 2 cores. The z-score carries both renders' variance,
  // so fewer paths widen it without biasing it; 32 paths still estimate each variance well
  // enough that a normal population's 4-sigma tail stays far below the 0.5% allowed.
  expect_pt_agrees(*ctx, *compiler, loaded, "0", 128, 32, GetParam());
}

// An orthographic view of the Cornell box: both sides start every ray on the camera's plane.
TEST_F(PtReferenceCases, OrthographicCameraAgreesWithinNoise) {
  scenes::Scene scene = scenes::load(std::filesystem::path(GIQ_SCENES_DIR) / "cornell.gltf");
  scenes::View view = scene.view("0");
  view.name = "ortho";
  view.camera.ymag = 0.3f;  // the box's opening is 0.56 m on a side
  scene.add_view(view);
  expect_pt_agrees(*ctx, *compiler, scene, "ortho", 64, 32, "cornell, orthographic");
}

// A BLEND card in the Cornell box: both sides pass it with probability 1 - alpha (stochastic
// transparency, each deciding per ray by its own hash), so they agree within noise.
TEST_F(PtReferenceCases, BlendCardAgreesWithinNoise) {
  scenes::Scene scene = test::cornell_box();
  const int card = test::add_material(scene, glm::vec3(0.2f, 0.5f, 0.9f));
  scene.materials[size_t(card)].alpha_mode = scenes::AlphaMode::Blend;
  scene.materials[size_t(card)].base_color.a = 0.45f;
  scene.materials[size_t(card)].double_sided = true;
  test::add_quad(scene, {-0.5f, -0.6f, 0.2f}, {0.3f, -0.6f, 0.2f}, {0.3f, 0.4f, 0.2f}, {-0.5f, 0.4f, 0.2f}, card);
  scene.derive();
  ASSERT_TRUE(scene.features.alpha_mask);
  expect_pt_agrees(*ctx, *compiler, scene, "0", 64, 64, "cornell, BLEND card");
}

// The Cornell box's contents on an open plane under an equirectangular map (a bright upper
// hemisphere whose colour runs round the horizon): both sides read the same texels (nearest,
// scenes/environment.h); the reference importance-samples the map, `pt` finds it by BRDF
// sampling only, so the per-pixel z-scores are gated and their mean is not.
TEST_F(PtReferenceCases, EnvironmentMapAgreesWithinNoise) {
  scenes::Scene scene = test::lambert_plane(0.7f, 4.0f, 3.0f);
  const int white = test::add_material(scene, glm::vec3(0.8f));
  test::add_quad(scene, {-0.5f, 0.0f, 0.5f}, {0.5f, 0.0f, 0.5f}, {0.5f, 1.0f, 0.5f}, {-0.5f, 1.0f, 0.5f}, white);
  test::add_quad(scene, {0.5f, 0.0f, -0.5f}, {-0.5f, 0.0f, -0.5f}, {-0.5f, 1.0f, -0.5f}, {0.5f, 1.0f, -0.5f}, white);
  scene.views.push_back({"angle", scenes::Camera::look_at({2.5f, 2.0f, 3.0f}, {0.0f, 0.3f, 0.0f}, {0, 1, 0}, 1.0f), -1});
  scene.derive();
  const int w = 32, h = 16;
  std::vector<glm::vec3> map(size_t(w) * size_t(h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float az = float(x) / float(w);
      map[size_t(y) * size_t(w) + size_t(x)] = (y < h / 2 ? 1.5f : 0.1f) * glm::vec3(0.3f + 0.7f * az, 0.6f, 1.0f - 0.6f * az);
    }
  scene.set_environment_map(w, h, map, "test map");
  ASSERT_TRUE(scene.features.environment_map);
  RenderOptions o;
  o.technique = "pt";
  o.view = "angle";
  o.width = o.height = 64;
  o.parameters = {"samples_per_frame=64", "seed=7"};
  image::Image gpu;
  render_sequence(*ctx, *compiler, scene, o, [&](RenderedFrame& f) { gpu = std::move(f.image); });
  reference::RenderSettings rs;
  rs.width = rs.height = 64;
  rs.seed = 3;
  rs.sampler = reference::Sampler::Independent;
  reference::Renderer ref(scene, scene.view("angle").camera, rs);
  reference::Film film = ref.make_film();
  ref.render(film, 64);
  test::expect_agreement(gpu, film.to_image(), "plane and walls under an environment map");
}

// A skinned, morphing figure exported by Blender (tests/data/scenes/blender_figure.py) at frame
// 15 of its walk, under a sun and a constant sky: both sides render the triangles the scene
// library deformed for that frame, `pt` after re-uploading them for each of the frames before.
// The sky is found by BRDF sampling in `pt` and sampled as a light by the reference, so the
// mean z-score is not gated (reference_agreement.h).
TEST_F(PtReferenceCases, SkinnedFrameAgreesWithinNoise) {
  scenes::Scene scene = scenes::load(std::filesystem::path(GIQ_TEST_DATA) / "scenes" / "blender_figure.glb");
  ASSERT_TRUE(scene.features.skinning && scene.features.morph_targets);
  add_sun_and_sky(scene);
  const glm::vec3 eye = glm::vec3(glm::dvec3(2.2, 1.2, 2.2) - scene.origin), target = glm::vec3(glm::dvec3(0.0, 0.9, -0.3) - scene.origin);
  scene.add_view({"side", scenes::Camera::look_at(eye, target, {0, 1, 0}, 0.7f), -1});
  expect_pt_agrees(*ctx, *compiler, scene, "side", 64, 32, "blender_figure, frame 15", 15, false);
}

// Particles of the generated fountain (tests/data/scenes/generate.py) at frame 20, lit by
// nothing but themselves: both sides render the octahedra the scene library places for that
// frame, and the floor under them takes their light (emissive triangles sampled by power).
TEST_F(PtReferenceCases, ParticlesAgreeWithinNoise) {
  const scenes::Scene scene = scenes::load(std::filesystem::path(GIQ_TEST_DATA) / "scenes" / "fountain.gltf");
  ASSERT_TRUE(scene.features.particles);
  expect_pt_agrees(*ctx, *compiler, scene, "side", 64, 32, "fountain, frame 20", 20);
}

// Skinned and morphing glTF files that nobody here wrote (the Khronos sample models, say), from
// the folder GIQ_SAMPLE_ASSETS names, searched recursively; skipped without it, since the suite
// carries no third-party assets. Each file with a skin or morph targets is rendered at frame
// min(45, last) under the sun and sky of add_sun_and_sky, from the front of its posed
// bounds (as `--camera auto` frames a scene): `pt` must agree with the reference within noise
// and `direct` must give finite light. docs/realtime.md lists the files run and what they gave.
TEST_F(PtReferenceCases, SampleAssetsAgreeWithinNoise) {
  const char* dir = std::getenv("GIQ_SAMPLE_ASSETS");
  if (dir == nullptr) GTEST_SKIP() << "set GIQ_SAMPLE_ASSETS to a folder of skinned or morphing glTF files";
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir))
    if (e.is_regular_file() && (e.path().extension() == ".gltf" || e.path().extension() == ".glb"))
      files.push_back(e.path());
  std::sort(files.begin(), files.end());
  int deforming = 0;
  for (const std::filesystem::path& file : files) {
    scenes::Scene scene = scenes::load(file);
    if (!scene.features.skinning && !scene.features.morph_targets) continue;
    ++deforming;
    const int frame = std::min(45, scene.sequence.frames - 1);
    add_sun_and_sky(scene);
    const float fov = 0.7f;
    const scenes::Framing view = scenes::frame_bounds(scene.at_frame(frame).bounds, fov);
    scene.add_view({"front", scenes::Camera::look_at(glm::vec3(view.eye), glm::vec3(view.target), {0, 1, 0}, fov), -1});
    const std::string what = file.filename().string() + ", frame " + std::to_string(frame);
    expect_pt_agrees(*ctx, *compiler, scene, "front", 64, 32, what, frame, false);

    RenderOptions o;
    o.technique = "direct";
    o.view = "front";
    o.width = o.height = 64;
    o.warmup = frame;
    const image::Image lit = render_last(scene, o);
    double sum = 0.0;
    for (const char* c : test::kRgb)
      for (size_t i = 0; i < lit.pixel_count(); ++i) {
        ASSERT_TRUE(std::isfinite(lit.channel(c)[i])) << what << ": direct, pixel " << i;
        sum += lit.channel(c)[i];
      }
    EXPECT_GT(sum, 0.0) << what << ": direct is black";
  }
  EXPECT_GT(deforming, 0) << dir << " holds no glTF file with a skin or morph targets";
}

INSTANTIATE_TEST_SUITE_P(BuiltinScenes, PtReferenceTest,
                         ::testing::Values("cornell", "leak", "movinglight", "sunroom", "atrium"));

}  // namespace
}  // namespace giq::realtime
