// read_image(): dispatch on the file's content (the OpenEXR magic number), not its extension,
// so a mis-named file is still read correctly or rejected with a clear message.

#include <fstream>

#include "exr.h"
#include "giq/base/error.h"
#include "giq/image/io.h"
#include "oiio_reader.h"

namespace giq::image {
namespace fs = std::filesystem;

namespace {

// OpenEXR files start with 0x76 0x2f 0x31 0x01 (OpenEXR file layout, "Magic Number").
bool exr_magic(const unsigned char m[4]) { return m[0] == 0x76 && m[1] == 0x2f && m[2] == 0x31 && m[3] == 0x01; }

}  // namespace

bool is_exr_file(const fs::path& path) {
  unsigned char magic[4] = {0, 0, 0, 0};
  std::ifstream in(path, std::ios::binary);
  in.read(reinterpret_cast<char*>(magic), 4);
  return in.gcount() == 4 && exr_magic(magic);
}

Image read_image(const fs::path& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InputError(path.string(), "", "no such file");
  if (fs::is_directory(path, ec)) throw InputError(path.string(), "", "is a directory, expected an image file");
  unsigned char magic[4] = {0, 0, 0, 0};
  {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path.string(), "", "cannot open for reading");
    in.read(reinterpret_cast<char*>(magic), 4);
    if (in.gcount() < 4) throw InputError(path.string(), "", "file too short to be an image");
  }
  if (exr_magic(magic)) return read_exr(path);
#ifdef GIQ_WITH_OIIO
  return read_with_oiio(path);
#else
  throw InputError(path.string(), "",
                   "not an OpenEXR file; this build reads other formats only with OpenImageIO (GIQ_WITH_OIIO=ON)");
#endif
}

}  // namespace giq::image
