#include "declared_size.h"

#include <cmath>
#include <system_error>

#include "giq/base/error.h"
#include "giq/image/io.h"

namespace giq::image {

namespace {

std::string gib(double bytes) {
  char s[32];
  std::snprintf(s, sizeof s, "%.3g GiB", bytes / double(uint64_t(1) << 30));
  return s;
}

}  // namespace

void check_decoded_size(const std::filesystem::path& path, const std::string& field, int64_t width, int64_t height,
                        int64_t channels) {
  const double bytes = double(width) * double(height) * double(channels) * sizeof(float);
  if (bytes > double(kMaxImageBytes))
    throw InputError(path.string(), field,
                     std::to_string(width) + "x" + std::to_string(height) + " pixels of " + std::to_string(channels) +
                         " channels decode to " + gib(bytes) + "; expected at most " + gib(double(kMaxImageBytes)));
}

void check_file_can_hold(const std::filesystem::path& path, const std::string& field, double least_bytes,
                         const std::string& what) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) return;  // not a regular file: the decoder reports what it finds
  if (double(size) < least_bytes)
    throw InputError(path.string(), field,
                     what + " cannot be stored in " + std::to_string(size) + " bytes (at least " +
                         std::to_string(int64_t(std::ceil(least_bytes))) + "); the file is truncated or its size is wrong");
}

}  // namespace giq::image
