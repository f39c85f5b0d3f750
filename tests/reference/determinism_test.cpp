// Determinism: the same settings give the same bits for any thread count, for any split into
// passes, and after an interruption at any moment followed by a resume from a checkpoint.

#include <gtest/gtest.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <thread>
#include <unistd.h>

#include "giq/base/error.h"
#include "giq/reference/checkpoint.h"
#include "giq/reference/progressive_render.h"
#include "giq/reference/renderer.h"
#include "scene_builder.h"

namespace giq::reference {
namespace {

bool same_bits(const Film& a, const Film& b) {
  return a.width == b.width && a.height == b.height &&
         std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(PixelAccumulator)) == 0 &&
         std::memcmp(a.aux.data(), b.aux.data(), a.aux.size() * sizeof(PixelAux)) == 0;
}

Film render(const scenes::Scene& s, int threads, std::initializer_list<uint32_t> passes) {
  RenderSettings rs;
  rs.width = 40;  // not a multiple of the tile size
  rs.height = 20;
  rs.threads = threads;
  rs.seed = 77;
  Renderer r(s, s.views[0].camera, rs);
  Film f = r.make_film();
  r.render_aux(f);
  for (uint32_t spp : passes) r.render(f, spp);
  return f;
}

TEST(Determinism, BitIdenticalForAnyThreadCountAndPassSplit) {
  const scenes::Scene s = test::cornell();
  const Film one = render(s, 1, {8});
  EXPECT_TRUE(same_bits(one, render(s, 2, {8})));
  EXPECT_TRUE(same_bits(one, render(s, 3, {1, 2, 5, 8})));
  EXPECT_TRUE(same_bits(one, render(s, 0, {3, 8})));
  // A different seed gives a different image.
  RenderSettings rs;
  rs.width = 40, rs.height = 20, rs.seed = 78;
  Renderer r(s, s.views[0].camera, rs);
  Film other = r.make_film();
  r.render_aux(other);
  r.render(other, 8);
  EXPECT_FALSE(same_bits(one, other));
}

TEST(Determinism, SpecialisedIntegratorGivesTheGenericOnesBits) {
  // The variant compiled for the scene's features (here diffuse + emissive triangles) and
  // the one with every feature compiled in must agree to the bit: specialisation removes
  // code that cannot contribute, nothing else.
  const scenes::Scene s = test::cornell();
  RenderSettings rs;
  rs.width = 32, rs.height = 16, rs.seed = 3;
  Renderer specialised(s, s.views[0].camera, rs);
  rs.all_features = true;
  Renderer generic(s, s.views[0].camera, rs);
  EXPECT_EQ(specialised.feature_mask(), 8u);
  EXPECT_EQ(generic.feature_mask(), 31u);
  Film a = specialised.make_film(), b = generic.make_film();
  RenderStats sa, sb;
  specialised.render_aux(a);
  generic.render_aux(b);
  specialised.render(a, 8, nullptr, &sa);
  generic.render(b, 8, nullptr, &sb);
  EXPECT_TRUE(same_bits(a, b));
  EXPECT_EQ(sa.rays, sb.rays);
  EXPECT_EQ(sa.samples, 32u * 16u * 8u);
  EXPECT_GT(sa.rays, 2 * sa.samples);  // camera rays plus shadow and bounce rays
}

TEST(Determinism, ResumeAfterInterruptionAtAnyMomentIsBitIdentical) {
  const scenes::Scene s = test::cornell();
  RenderSettings rs;
  rs.width = 48, rs.height = 32, rs.seed = 5, rs.threads = 2;
  Renderer r(s, s.views[0].camera, rs);
  const std::filesystem::path ckpt =
      std::filesystem::temp_directory_path() / ("giq_ref_resume_" + std::to_string(::getpid()) + ".ckpt");
  std::filesystem::remove(ckpt);

  ProgressiveOptions o;
  o.stop.spp = 24;
  o.identity = "cornell test";
  const RenderOutcome whole = render_progressive(r, o);
  ASSERT_TRUE(whole.completed);

  // Interrupt after various delays (some land mid-pass, leaving pixels with different counts),
  // then resume to completion.
  for (int delay_ms : {0, 3, 17, 40}) {
    std::filesystem::remove(ckpt);
    std::atomic<bool> cancel{false};
    ProgressiveOptions io = o;
    io.checkpoint = ckpt;
    io.checkpoint_interval_seconds = 0.01;
    io.cancel = &cancel;
    std::thread killer([&] {
      std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
      cancel = true;
    });
    const RenderOutcome first = render_progressive(r, io);
    killer.join();
    ProgressiveOptions ro = o;
    ro.checkpoint = ckpt;
    ro.resume = true;
    const RenderOutcome resumed = render_progressive(r, ro);
    ASSERT_TRUE(resumed.completed);
    EXPECT_EQ(resumed.spp, 24u);
    EXPECT_TRUE(same_bits(whole.film, resumed.film)) << "interrupted after " << delay_ms << " ms"
                                                    << (first.completed ? " (had finished)" : "");
  }

  // A checkpoint of another render is refused, not silently resumed.
  ProgressiveOptions wrong = o;
  wrong.checkpoint = ckpt;
  wrong.resume = true;
  wrong.identity = "another scene";
  write_checkpoint(ckpt, whole.film, o.identity, 1.0);
  EXPECT_THROW(render_progressive(r, wrong), InputError);
  std::filesystem::remove(ckpt);
}

// With the Sobol sampler, renders that stop on an error or a time end on whole blocks: every
// pixel's variance then comes from complete blocks only, and at least two of them.
TEST(Determinism, SobolRendersStoppingOnErrorOrTimeEndOnWholeBlocks) {
  const scenes::Scene s = test::cornell();
  RenderSettings rs;
  rs.width = rs.height = 16;
  ASSERT_EQ(rs.sampler, Sampler::Sobol);
  const Renderer r(s, s.views[0].camera, rs);
  for (int stop = 0; stop < 2; ++stop) {
    ProgressiveOptions o;
    if (stop == 0) o.stop.rel_error = 10.0;  // met as soon as it may be checked
    else o.stop.seconds = 0.2;
    o.identity = "blocks test";
    const RenderOutcome out = render_progressive(r, o);
    ASSERT_TRUE(out.completed);
    EXPECT_EQ(out.spp % rs.sobol_block, 0u) << "stop " << stop << ": " << out.spp << " spp";
    if (stop == 0) EXPECT_GE(out.spp, 2 * rs.sobol_block);
    for (const PixelAccumulator& p : out.film.pixels) ASSERT_EQ(p.blocks * rs.sobol_block, p.samples);
  }
}

}  // namespace
}  // namespace giq::reference
