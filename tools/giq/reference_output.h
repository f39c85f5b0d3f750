#pragma once
// Where `giq reference` and `giq reference merge` write a render's EXR files, and how.

#include <filesystem>
#include <string>

#include "giq/image/image.h"
#include "giq/image/io.h"

namespace giq::cli {

// The output path of one frame: "#" runs are replaced by the zero-padded frame number;
// otherwise, when several frames are rendered, ".<frame>" goes before the extension.
std::filesystem::path frame_path(const std::string& pattern, int frame, bool several);

// --half: the colour layers as float16 where they fit (the rest float32).
image::ExrOptions exr_options(const image::Image& img, bool half);

}  // namespace giq::cli
