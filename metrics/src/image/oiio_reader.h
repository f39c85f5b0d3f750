#pragma once
// Internal: non-EXR formats through OpenImageIO (only in builds with GIQ_WITH_OIIO).
// OpenImageIO lives in a module of its own (giq-image-oiio.so, oiio_reader.cpp) that giq loads
// on first use (oiio_module.cpp), so starting giq does not load its shared libraries.

#include <filesystem>
#include <string>

#include "giq/image/image.h"

namespace giq::image {

#ifdef GIQ_WITH_OIIO
// Reads through the module; throws InputError as the module reports it, or when the module
// cannot be loaded.
Image read_with_oiio(const std::filesystem::path& path);
#endif

// The module's one entry point (C linkage, so dlsym finds it by this name): fills *out and
// returns 0, or returns 1 with an input error's file, field and message, or 2 with another
// error's message. Exceptions do not cross the module boundary.
extern "C" int giq_image_oiio_read(const char* path, Image* out, std::string* file, std::string* field,
                                   std::string* message);

}  // namespace giq::image
