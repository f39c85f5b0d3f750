// The reader of a sharded render's part files (reference::read_part). A part ends with a
// checksum, so the harness follows fuzz_input.h's checksum rule (checksummed_input_file) and
// the mutations reach the fields behind it (settings, frames, tiles, pixel data). The seeds
// come in both forms. Each input is read as a shard's part and as a checkpoint of a render
// across ranks, which allows pixels with fewer samples.

#include "fuzz_input.h"
#include "giq/reference/part.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = giq::fuzz::checksummed_input_file(data, size, "input.part");
  for (const auto use : {giq::reference::PartUse::Shard, giq::reference::PartUse::Checkpoint})
    giq::fuzz::expect_success_or_input_error([&] { (void)giq::reference::read_part(path, use); });
  return 0;
}
