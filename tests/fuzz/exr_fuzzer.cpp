// The image reader (image::read_image) on arbitrary bytes: OpenEXR files, and the rejection of
// anything else. OpenEXR itself is Debian's library, not instrumented: libFuzzer sees no
// coverage inside it, but a crash there is still caught.

#include "fuzz_input.h"
#include "giq/image/io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = giq::fuzz::input_file(data, size, "input.exr");
  giq::fuzz::expect_success_or_input_error([&] { (void)giq::image::read_image(path); });
  return 0;
}
