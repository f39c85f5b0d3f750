#pragma once
// Internal: what every image reader checks about the size a file declares before it allocates
// a pixel (giq/image/io.h, kMaxImageBytes).

#include <cstdint>
#include <filesystem>
#include <string>

namespace giq::image {

// Throws InputError naming the size unless `width` x `height` pixels of `channels` float planes
// fit in kMaxImageBytes.
void check_decoded_size(const std::filesystem::path& path, const std::string& field, int64_t width, int64_t height,
                        int64_t channels);

// Throws InputError unless the file is at least `least_bytes` long: the fewest bytes in which
// its codec could have stored the pixel data it declares (`what`, for the message).
void check_file_can_hold(const std::filesystem::path& path, const std::string& field, double least_bytes,
                         const std::string& what);

}  // namespace giq::image
