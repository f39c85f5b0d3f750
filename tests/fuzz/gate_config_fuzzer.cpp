// The gate config reader (gate::parse_config): JSON text, every field checked.

#include <string>

#include "fuzz_input.h"
#include "giq/gate/config.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  giq::fuzz::expect_success_or_input_error([&] { (void)giq::gate::parse_config(text, "gate.json"); });
  return 0;
}
