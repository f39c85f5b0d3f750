// Writes FLIP's test pairs as float EXR (R, G, B), and one as 8-bit sRGB PNG (the LDR input path
// of `giq score`):
//   flip_make_pairs stored DIR              the pairs of tests/data/flip (DIR/<name>.{ref,test}.<ext>)
//   flip_make_pairs procedural W H SEED REF.exr TEST.exr   the procedural HDR scene at any size
//   flip_make_pairs extract IN.exr LAYER OUT.exr   one RGB layer of a giq render (`beauty` is R,G,B;
//                                                  otherwise LAYER.R/G/B) as a plain R,G,B half EXR
// tests/data/flip/make_reference runs it and then NVIDIA's implementation on every pair;
// tests/data/flip/make_render_pairs runs `extract` on giq's own renders.

#include <cstdio>
#include <cstdlib>
#include <string>

#include <algorithm>
#include <vector>

#include "flip_exr.h"
#include "flip_pairs.h"
#include "giq/image/io.h"
#include "giq/image/srgb.h"

namespace {

// 8-bit sRGB encoding of a linear image, rounded to nearest.
void write_png8(const std::string& path, const giq::flip_pairs::Rgb& img) {
  std::vector<unsigned char> px(size_t(img.width) * size_t(img.height) * 3);
  for (size_t i = 0; i < size_t(img.width) * size_t(img.height); ++i) {
    const float c[3] = {img.r[i], img.g[i], img.b[i]};
    for (int k = 0; k < 3; ++k) px[3 * i + size_t(k)] = (unsigned char)(giq::image::srgb_encode(c[k]) * 255.0f + 0.5f);
  }
  giq::image::write_png_rgb8(path, img.width, img.height, 3, px.data());
}

}  // namespace

int main(int argc, char** argv) {
  using namespace giq::flip_pairs;
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "stored" && argc == 3) {
    const std::string dir = argv[2];
    for (const Pair& p : stored_pairs()) {
      write_rgb(dir + "/" + p.name + ".ref.exr", p.reference);
      write_rgb(dir + "/" + p.name + ".test.exr", p.test);
      std::printf("%s %s %dx%d exr\n", p.name.c_str(), p.hdr ? "hdr" : "ldr", p.reference.width, p.reference.height);
    }
    // LDR-FLIP of 8-bit files: the procedural scene's display values, sRGB-encoded.
    const Pair scene = procedural_hdr_pair(80, 56, 43);
    write_png8(dir + "/ldr_png_scene.ref.png", scene.reference);
    write_png8(dir + "/ldr_png_scene.test.png", scene.test);
    std::printf("ldr_png_scene ldr 80x56 png\n");
    return 0;
  }
  if (mode == "procedural" && argc == 7) {
    const Pair p = procedural_hdr_pair(std::atoi(argv[2]), std::atoi(argv[3]), uint32_t(std::atoi(argv[4])));
    write_rgb(argv[5], p.reference);
    write_rgb(argv[6], p.test);
    return 0;
  }
  if (mode == "extract" && argc == 5) {
    // Plain R,G,B because NVIDIA's EXR loader reads only unprefixed channels. Half precision keeps
    // the stored renders small; both implementations read the same half values back as floats,
    // so the rounding changes the inputs, never the agreement.
    const std::string layer = argv[3];
    const std::string prefix = layer == "beauty" ? "" : layer + ".";
    for (const char* c : {"R", "G", "B"})
      if (Imf::InputFile(argv[2]).header().channels().findChannel(prefix + c) == nullptr) {
        std::fprintf(stderr, "%s has no channel %s%s\n", argv[2], prefix.c_str(), c);
        return 2;
      }
    int w = 0, h = 0;
    const auto planes = read_exr(argv[2], {prefix + "R", prefix + "G", prefix + "B"}, w, h);
    write_exr(argv[4], w, h, {"R", "G", "B"}, {planes[0].data(), planes[1].data(), planes[2].data()}, Imf::HALF);
    return 0;
  }
  std::fprintf(stderr,
               "usage: flip_make_pairs stored DIR\n"
               "       flip_make_pairs procedural W H SEED REF.exr TEST.exr\n"
               "       flip_make_pairs extract IN.exr LAYER OUT.exr\n");
  return 2;
}
