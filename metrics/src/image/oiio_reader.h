#pragma once
// Internal: non-EXR formats through OpenImageIO (only in builds with GIQ_WITH_OIIO).

#include <filesystem>

#include "giq/image/image.h"

namespace giq::image {

#ifdef GIQ_WITH_OIIO
Image read_with_oiio(const std::filesystem::path& path);
#endif

}  // namespace giq::image
