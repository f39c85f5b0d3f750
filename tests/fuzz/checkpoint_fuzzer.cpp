// The checkpoint reader (reference::read_checkpoint). A checkpoint ends with a checksum of
// everything before it, so almost every mutation is refused at that check. An input that
// starts with the byte 0x01 (a checkpoint starts with 'g') is a checkpoint without its
// checksum: the harness drops that byte and appends the right checksum, so the mutations also
// reach the fields behind it (identity, film size, pixel data). The seeds come in both forms.

#include <string>

#include "fuzz_input.h"
#include "giq/base/hash.h"
#include "giq/reference/checkpoint.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string bytes(reinterpret_cast<const char*>(data), size);
  if (!bytes.empty() && bytes[0] == '\x01') {
    bytes.erase(0, 1);
    const uint64_t hash = giq::Hasher().add(bytes).value();
    bytes.append(reinterpret_cast<const char*>(&hash), sizeof hash);
  }
  const auto path = giq::fuzz::input_file(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size(), "input.ckpt");
  giq::fuzz::expect_success_or_input_error(
      [&] { (void)giq::reference::read_checkpoint(path, giq::fuzz::kCheckpointIdentity); });
  return 0;
}
