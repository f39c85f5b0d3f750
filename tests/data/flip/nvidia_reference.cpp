// Reference values from NVIDIA's FLIP implementation (github.com/NVlabs/flip, C++ version) for
// giq's FLIP agreement tests. Not part of the giq build: make_reference compiles it against a
// FLIP checkout given on its command line. It calls FLIP's public API exactly as NVIDIA's
// command-line tool does (default parameters, ACES for HDR) and prints one JSON object; with a
// third path it also writes the error map as a single-channel float EXR ("Y").
//
//   nvidia_reference ldr|hdr REF.exr TEST.exr [MAP.exr]
//
// EXR input is linear; PNG input is decoded from sRGB to linear, as NVIDIA's tool does for LDR.

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>

#include <cstdio>
#include <string>

#include "FLIP.h"
#include "tool/imagehelpers.h"
#include "tool/pooling.h"

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: nvidia_reference ldr|hdr REF.exr TEST.exr [MAP.exr]\n");
    return 2;
  }
  const bool hdr = std::string(argv[1]) == "hdr";
  FLIP::image<FLIP::color3> reference, test;
  if (!ImageHelpers::load(reference, argv[2]) || !ImageHelpers::load(test, argv[3])) {
    std::fprintf(stderr, "cannot read %s or %s\n", argv[2], argv[3]);
    return 2;
  }
  const std::string ref_path = argv[2];
  if (ref_path.size() > 4 && ref_path.compare(ref_path.size() - 4, 4, ".png") == 0) {
    reference.sRGBToLinearRGB();
    test.sRGBToLinearRGB();
  }
  const int w = reference.getWidth(), h = reference.getHeight();
  FLIP::Parameters parameters;
  FLIP::image<float> map(w, h, 0.0f);
  FLIP::evaluate(reference, test, hdr, parameters, map);

  FLIPPooling::pooling<float> pooled(100);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) pooled.update(uint32_t(x), uint32_t(y), map.get(x, y));
  std::printf(
      "{\"mean\": %.9g, \"weighted_median\": %.9g, \"weighted_q1\": %.9g, \"weighted_q3\": %.9g, "
      "\"max\": %.9g, \"pixels_per_degree\": %.9g",
      double(pooled.getMean()), double(pooled.getPercentile(0.5f, true)), double(pooled.getPercentile(0.25f, true)),
      double(pooled.getPercentile(0.75f, true)), double(pooled.getMaxValue()), double(parameters.PPD));
  if (hdr)
    std::printf(", \"start_exposure\": %.9g, \"stop_exposure\": %.9g, \"exposures\": %d",
                double(parameters.startExposure), double(parameters.stopExposure), parameters.numExposures);
  std::printf("}\n");

  if (argc > 4) {
    std::vector<float> pixels(size_t(w) * size_t(h));
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) pixels[size_t(y) * size_t(w) + size_t(x)] = map.get(x, y);
    Imf::Header header(w, h);
    header.compression() = Imf::ZIP_COMPRESSION;
    header.channels().insert("Y", Imf::Channel(Imf::FLOAT));
    Imf::FrameBuffer fb;
    fb.insert("Y", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(pixels.data()), sizeof(float),
                              sizeof(float) * size_t(w)));
    Imf::OutputFile file(argv[4], header);
    file.setFrameBuffer(fb);
    file.writePixels(h);
  }
  return 0;
}
