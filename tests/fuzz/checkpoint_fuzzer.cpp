// The checkpoint reader (reference::read_checkpoint). A checkpoint ends with a checksum, so the
// harness follows fuzz_input.h's checksum rule (checksummed_input_file) and the mutations reach
// the fields behind it (identity, film size, pixel data). The seeds come in both forms.

#include "fuzz_input.h"
#include "giq/reference/checkpoint.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = giq::fuzz::checksummed_input_file(data, size, "input.ckpt");
  giq::fuzz::expect_success_or_input_error([&] { (void)giq::reference::read_checkpoint(path, giq::fuzz::kCheckpointIdentity); });
  return 0;
}
