// Loads the OpenImageIO module (oiio_reader.h) once, on the first image giq reads that is not
// OpenEXR.

#include <dlfcn.h>

#include <filesystem>
#include <mutex>
#include <stdexcept>

#include "giq/base/error.h"
#include "oiio_reader.h"

namespace giq::image {
namespace {

using ReadFunction = decltype(&giq_image_oiio_read);

struct Module {
  ReadFunction read = nullptr;
  std::string error;
};

// The module built beside this library (its absolute path in the build tree), else by file
// name through the executable's RUNPATH and LD_LIBRARY_PATH (a relocated build).
const Module& module() {
  static const Module m = [] {
    Module r;
    void* handle = nullptr;
    std::error_code ec;
    if (std::filesystem::exists(GIQ_OIIO_MODULE, ec)) handle = dlopen(GIQ_OIIO_MODULE, RTLD_NOW | RTLD_LOCAL);
    if (!handle) handle = dlopen(std::filesystem::path(GIQ_OIIO_MODULE).filename().c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      const char* e = dlerror();
      r.error = e ? e : "unknown reason";
      return r;
    }
    r.read = reinterpret_cast<ReadFunction>(dlsym(handle, "giq_image_oiio_read"));
    if (!r.read) r.error = std::string(GIQ_OIIO_MODULE) + " has no giq_image_oiio_read";
    return r;
  }();
  return m;
}

}  // namespace

Image read_with_oiio(const std::filesystem::path& path) {
  const Module& m = module();
  if (!m.read)
    throw InputError(path.string(), "", "not an OpenEXR file, and giq's reader for other formats (OpenImageIO) could not be loaded: " + m.error);
  Image image;
  std::string file, field, message;
  const int r = m.read(path.c_str(), &image, &file, &field, &message);
  if (r == 1) throw InputError(file, field, message);
  if (r != 0) throw std::runtime_error(message);
  return image;
}

}  // namespace giq::image
