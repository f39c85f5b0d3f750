// The glTF loader (scenes::load) on arbitrary bytes: JSON glTF, or binary glTF when the input
// starts with the "glTF" magic.

#include <cstring>

#include "fuzz_input.h"
#include "giq/scenes/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
  const auto path = giq::fuzz::input_file(data, size, binary ? "input.glb" : "input.gltf");
  giq::fuzz::expect_success_or_input_error([&] { (void)giq::scenes::load(path); });
  return 0;
}
