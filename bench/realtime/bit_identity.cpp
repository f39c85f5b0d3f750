// giq-bit-identity A B: compares two folders of EXR images pixel for pixel, bit for bit (a
// refactoring of the real-time module must not change any technique's image: see
// bench/realtime/bit-identity). Every *.exr under A must exist under B with the same relative
// path, the same size and the same channels, and every float's bits must be equal (so -0 and
// +0, or two NaN payloads, differ). B may hold more images than A. Prints one line per differing file and a summary; exit 0
// when everything is identical, 1 otherwise, 2 for missing files or unreadable input.
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <set>
#include <string>

#include "giq/image/io.h"

namespace fs = std::filesystem;

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: giq-bit-identity DIR_A DIR_B\n");
    return 2;
  }
  const fs::path a(argv[1]), b(argv[2]);
  std::set<fs::path> files;
  try {
    for (const auto& e : fs::recursive_directory_iterator(a))
      if (e.is_regular_file() && e.path().extension() == ".exr") files.insert(fs::relative(e.path(), a));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "giq-bit-identity: %s\n", e.what());
    return 2;
  }
  if (files.empty()) {
    std::fprintf(stderr, "giq-bit-identity: no .exr under %s\n", a.c_str());
    return 2;
  }
  int differing = 0;
  for (const auto& rel : files) {
    try {
      const giq::image::Image x = giq::image::read_image(a / rel), y = giq::image::read_image(b / rel);
      std::string why;
      if (x.width() != y.width() || x.height() != y.height()) why = "size differs";
      else if (x.channel_names() != y.channel_names()) why = "channels differ";
      for (const auto& c : x.channel_names()) {
        if (!why.empty()) break;
        size_t n = 0;
        for (size_t i = 0; i < x.pixel_count(); ++i)
          if (std::memcmp(x.channel(c) + i, y.channel(c) + i, sizeof(float)) != 0) ++n;
        if (n > 0) why = "channel " + c + ": " + std::to_string(n) + " of " + std::to_string(x.pixel_count()) + " pixels";
      }
      if (!why.empty()) {
        std::printf("DIFFERS  %s  (%s)\n", rel.c_str(), why.c_str());
        ++differing;
      }
    } catch (const std::exception& e) {
      std::fprintf(stderr, "giq-bit-identity: %s: %s\n", rel.c_str(), e.what());
      return 2;
    }
  }
  std::printf("%zu images compared, %d differ\n", files.size(), differing);
  return differing == 0 ? 0 : 1;
}
