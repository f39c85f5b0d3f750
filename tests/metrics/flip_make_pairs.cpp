// Writes FLIP's test pairs as float EXR (R, G, B):
//   flip_make_pairs stored DIR              the pairs of tests/data/flip (DIR/<name>.{ref,test}.exr)
//   flip_make_pairs procedural W H SEED REF.exr TEST.exr   the procedural HDR scene at any size
// tests/data/flip/make_reference runs it and then NVIDIA's implementation on every pair.

#include <cstdio>
#include <cstdlib>
#include <string>

#include "flip_exr.h"
#include "flip_pairs.h"

int main(int argc, char** argv) {
  using namespace giq::flip_pairs;
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "stored" && argc == 3) {
    const std::string dir = argv[2];
    for (const Pair& p : stored_pairs()) {
      write_rgb(dir + "/" + p.name + ".ref.exr", p.reference);
      write_rgb(dir + "/" + p.name + ".test.exr", p.test);
      std::printf("%s %s %dx%d\n", p.name.c_str(), p.hdr ? "hdr" : "ldr", p.reference.width, p.reference.height);
    }
    return 0;
  }
  if (mode == "procedural" && argc == 7) {
    const Pair p = procedural_hdr_pair(std::atoi(argv[2]), std::atoi(argv[3]), uint32_t(std::atoi(argv[4])));
    write_rgb(argv[5], p.reference);
    write_rgb(argv[6], p.test);
    return 0;
  }
  std::fprintf(stderr,
               "usage: flip_make_pairs stored DIR\n"
               "       flip_make_pairs procedural W H SEED REF.exr TEST.exr\n");
  return 2;
}
