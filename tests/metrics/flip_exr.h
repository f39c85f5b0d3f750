#pragma once
// Float EXR reading and writing for FLIP's test data, generator and benchmark, with OpenEXR
// directly: RGB pairs and single-channel ("Y") error maps.

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <Imath/ImathBox.h>
#include <Imath/half.h>

#include <string>
#include <vector>

#include "flip_pairs.h"

namespace giq::flip_pairs {

// `type` is the channels' type in the file; the planes are always float. OpenEXR converts types
// only when reading, so HALF planes are rounded here (to nearest, Imath's conversion).
inline void write_exr(const std::string& path, int w, int h, const std::vector<std::string>& names,
                      const std::vector<const float*>& planes, Imf::PixelType type = Imf::FLOAT) {
  Imf::Header header(w, h);
  header.compression() = Imf::ZIP_COMPRESSION;
  Imf::FrameBuffer fb;
  std::vector<std::vector<Imath::half>> halves(names.size());
  for (size_t c = 0; c < names.size(); ++c) {
    header.channels().insert(names[c], Imf::Channel(type));
    if (type == Imf::HALF) {
      halves[c].assign(planes[c], planes[c] + size_t(w) * size_t(h));
      fb.insert(names[c], Imf::Slice(Imf::HALF, reinterpret_cast<char*>(halves[c].data()), sizeof(Imath::half),
                                     sizeof(Imath::half) * size_t(w)));
    } else {
      fb.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(const_cast<float*>(planes[c])),
                                     sizeof(float), sizeof(float) * size_t(w)));
    }
  }
  Imf::OutputFile file(path.c_str(), header);
  file.setFrameBuffer(fb);
  file.writePixels(h);
}

inline void write_rgb(const std::string& path, const Rgb& img) {
  write_exr(path, img.width, img.height, {"R", "G", "B"}, {img.r.data(), img.g.data(), img.b.data()});
}

// Reads the named float channels (absent ones read as 0).
inline std::vector<std::vector<float>> read_exr(const std::string& path, const std::vector<std::string>& names, int& w,
                                                int& h) {
  Imf::InputFile file(path.c_str());
  const Imath::Box2i dw = file.header().dataWindow();
  w = dw.max.x - dw.min.x + 1;
  h = dw.max.y - dw.min.y + 1;
  std::vector<std::vector<float>> planes(names.size(), std::vector<float>(size_t(w) * size_t(h)));
  Imf::FrameBuffer fb;
  for (size_t c = 0; c < names.size(); ++c) {
    char* base = reinterpret_cast<char*>(planes[c].data()) -
                 (ptrdiff_t(dw.min.x) + ptrdiff_t(dw.min.y) * ptrdiff_t(w)) * ptrdiff_t(sizeof(float));
    fb.insert(names[c], Imf::Slice(Imf::FLOAT, base, sizeof(float), sizeof(float) * size_t(w)));
  }
  file.setFrameBuffer(fb);
  file.readPixels(dw.min.y, dw.max.y);
  return planes;
}

inline Rgb read_rgb(const std::string& path) {
  int w = 0, h = 0;
  auto planes = read_exr(path, {"R", "G", "B"}, w, h);
  Rgb img;
  img.width = w, img.height = h;
  img.r = std::move(planes[0]), img.g = std::move(planes[1]), img.b = std::move(planes[2]);
  return img;
}

}  // namespace giq::flip_pairs
