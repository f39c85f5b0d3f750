// The public FLIP entry points (giq/metrics/flip.h) on giq::image::Image: layers, options and the
// errors a user can get.

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "flip/evaluator.h"
#include "flip_pairs.h"
#include "giq/base/error.h"
#include "giq/image/io.h"
#include "giq/metrics/flip.h"

namespace giq::metrics {
namespace {

// An Image holding `rgb` as the RGB layer `layer` ("" = beauty).
image::Image to_image(const flip_pairs::Rgb& rgb, const std::string& layer) {
  image::Image img(rgb.width, rgb.height);
  const std::string prefix = layer.empty() ? "" : layer + ".";
  const std::vector<float>* planes[3] = {&rgb.r, &rgb.g, &rgb.b};
  const char* names[3] = {"R", "G", "B"};
  for (int c = 0; c < 3; ++c) {
    float* dst = img.add_channel(prefix + names[c]);
    std::copy(planes[c]->begin(), planes[c]->end(), dst);
  }
  return img;
}

flip::ImagePair view(const flip_pairs::Pair& p) {
  flip::ImagePair v;
  v.width = p.reference.width, v.height = p.reference.height;
  v.reference = {p.reference.r.data(), p.reference.g.data(), p.reference.b.data()};
  v.test = {p.test.r.data(), p.test.g.data(), p.test.b.data()};
  return v;
}

TEST(FlipApi, LayersReachTheSameComputation) {
  const flip_pairs::Pair pair = flip_pairs::procedural_hdr_pair(50, 30, 2);
  const FlipResult direct_hdr = flip::evaluate(view(pair), true, {});
  const FlipResult direct_ldr = flip::evaluate(view(pair), false, {});
  for (const std::string layer : {"", "indirect"}) {
    const image::Image ref = to_image(pair.reference, layer), test = to_image(pair.test, layer);
    const FlipResult hdr = hdr_flip(ref, test, layer);
    const FlipResult ldr = ldr_flip(ref, test, layer);
    EXPECT_EQ(hdr.map, direct_hdr.map) << layer;
    EXPECT_EQ(ldr.map, direct_ldr.map) << layer;
    EXPECT_EQ(hdr.mean, direct_hdr.mean);
    EXPECT_EQ(hdr.width, 50);
    EXPECT_EQ(hdr.height, 30);
    EXPECT_GT(hdr.exposures, 1);
    EXPECT_EQ(ldr.exposures, 0);
  }
}

// The stored pairs again, this time as giq reads files: EXR or 8-bit PNG (decoded from sRGB) ->
// image::read_image -> hdr_flip / ldr_flip, against NVIDIA's maps (tolerances as in
// flip_test.cpp).
TEST(FlipApi, AgreesWithNvidiaThroughImageFiles) {
  const std::string data = std::string(GIQ_TEST_DATA) + "/flip/";
  std::ifstream in(data + "reference.json");
  ASSERT_TRUE(in.good());
  const nlohmann::json ref = nlohmann::json::parse(in);
  for (const auto& nv : ref["pairs"]) {
    const std::string name = nv["name"], ext = nv["format"];
    // Render pairs (half-float EXR) share reference files and name them.
    const image::Image a = image::read_image(data + "pairs/" + nv.value("reference", name + ".ref." + ext));
    const image::Image b = image::read_image(data + "pairs/" + nv.value("test", name + ".test." + ext));
    const FlipResult r = nv["mode"] == "hdr" ? hdr_flip(a, b, "") : ldr_flip(a, b, "");
    EXPECT_NEAR(r.mean, nv["mean"].get<double>(), 1e-3) << name;
    const image::Image map = image::read_image(data + nv["map"].get<std::string>());
    ASSERT_EQ(map.pixel_count(), r.map.size()) << name;
    const float* expected = map.channel("Y");
    for (size_t i = 0; i < r.map.size(); ++i) ASSERT_NEAR(r.map[i], expected[i], 1e-2) << name << " pixel " << i;
  }
}

TEST(FlipApi, ExplicitExposureRange) {
  const flip_pairs::Pair pair = flip_pairs::procedural_hdr_pair(20, 20, 4);
  FlipOptions o;
  o.start_exposure = -2.0f;
  o.stop_exposure = 1.0f;
  const FlipResult r = hdr_flip(to_image(pair.reference, ""), to_image(pair.test, ""), "", o);
  EXPECT_EQ(r.start_exposure, -2.0f);
  EXPECT_EQ(r.stop_exposure, 1.0f);
  EXPECT_EQ(r.exposures, 3);  // max(2, ceil(1 - (-2)))
  // One exposure at c = 0 is LDR-FLIP of the ACES-tone-mapped pair; more exposures can only
  // raise each pixel (a per-pixel maximum).
  o.start_exposure = 0.0f;
  o.stop_exposure = 0.0f;
  o.exposures = 1;
  const FlipResult one = hdr_flip(to_image(pair.reference, ""), to_image(pair.test, ""), "", o);
  o.stop_exposure = 3.0f;
  o.exposures = 4;
  const FlipResult four = hdr_flip(to_image(pair.reference, ""), to_image(pair.test, ""), "", o);
  for (size_t i = 0; i < one.map.size(); ++i) ASSERT_GE(four.map[i], one.map[i]);
}

TEST(FlipApi, BadInputIsAnInputError) {
  const flip_pairs::Pair a = flip_pairs::procedural_hdr_pair(8, 8, 1);
  const flip_pairs::Pair b = flip_pairs::procedural_hdr_pair(8, 9, 1);
  EXPECT_THROW(hdr_flip(to_image(a.reference, ""), to_image(b.test, ""), ""), InputError);
  EXPECT_THROW(ldr_flip(to_image(a.reference, ""), to_image(a.test, ""), "indirect"), InputError);
  FlipOptions o;
  o.start_exposure = 3.0f;
  o.stop_exposure = 1.0f;
  EXPECT_THROW(hdr_flip(to_image(a.reference, ""), to_image(a.test, ""), "", o), InputError);
}

}  // namespace
}  // namespace giq::metrics
