// The one place OpenImageIO is used, built as a module of its own (oiio_reader.h): reading
// formats other than OpenEXR. Integer formats
// (8/16-bit PNG, JPEG, TIFF...) are display-referred sRGB unless the file says it is linear;
// they are decoded to linear float so every metric sees radiance-like values.

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <memory>

#include "declared_size.h"
#include "giq/base/error.h"
#include "giq/image/srgb.h"
#include "oiio_reader.h"

namespace giq::image {
namespace {

Image read(const std::filesystem::path& path) {
  auto in = OIIO::ImageInput::open(path.string());
  if (!in) throw InputError(path.string(), "", "cannot read image: " + OIIO::geterror());
  const OIIO::ImageSpec spec = in->spec();
  const int w = spec.width, h = spec.height, nc = spec.nchannels;
  if (w <= 0 || h <= 0 || nc <= 0 || w > (1 << 20) || h > (1 << 20))
    throw InputError(path.string(), "", "image size " + std::to_string(w) + "x" + std::to_string(h) + "x" +
                                            std::to_string(nc) + " out of range");
  // Read as interleaved floats, then copied to planes: twice the decoded size at the peak.
  check_decoded_size(path, "size", w, h, 2 * int64_t(nc));
  // PNG's pixel rows are deflated: at most 1032:1 (giq/image/io.h).
  if (std::string(in->format_name()) == "png")
    check_file_can_hold(path, "IHDR",
                        double(h) * (1.0 + double(w) * nc * double(spec.format.size())) / 1032.0,
                        "the " + std::to_string(w) + "x" + std::to_string(h) + " pixels it declares");
  std::vector<float> pixels(size_t(w) * size_t(h) * size_t(nc));
  if (!in->read_image(0, 0, 0, nc, OIIO::TypeDesc::FLOAT, pixels.data()))
    throw InputError(path.string(), "", "cannot decode image: " + in->geterror());
  in->close();

  const bool integer = spec.format.basetype != OIIO::TypeDesc::FLOAT &&
                       spec.format.basetype != OIIO::TypeDesc::HALF &&
                       spec.format.basetype != OIIO::TypeDesc::DOUBLE;
  const std::string colour_space = spec.get_string_attribute("oiio:ColorSpace");
  const bool decode_srgb = integer && colour_space != "Linear" && colour_space != "linear";

  // Grey (+alpha) files become R,G,B (+A) so every RGB metric applies to them.
  std::vector<std::string> names;
  std::vector<int> source;
  if (nc <= 2) {
    names = {"R", "G", "B"};
    source = {0, 0, 0};
    if (nc == 2) names.push_back("A"), source.push_back(1);
  } else {
    for (int c = 0; c < nc; ++c) names.push_back(spec.channelnames[size_t(c)]), source.push_back(c);
  }
  Image image(w, h);
  for (size_t k = 0; k < names.size(); ++k) {
    float* plane = image.add_channel(names[k]);
    const int c = source[k];
    const bool alpha = c == spec.alpha_channel || names[k] == "A";
    const size_t n = image.pixel_count();
    for (size_t i = 0; i < n; ++i) {
      float v = pixels[i * size_t(nc) + size_t(c)];
      plane[i] = (decode_srgb && !alpha) ? srgb_decode(v) : v;
    }
  }
  for (const auto& a : spec.extra_attribs)
    if (a.type() == OIIO::TypeDesc::STRING) image.metadata[a.name().string()] = a.get_string();
  return image;
}

}  // namespace

extern "C" int giq_image_oiio_read(const char* path, Image* out, std::string* file, std::string* field, std::string* message) {
  try {
    *out = read(path);
    return 0;
  } catch (const InputError& e) {
    *file = e.file(), *field = e.field(), *message = e.message();
    return 1;
  } catch (const std::exception& e) {
    *message = e.what();
    return 2;
  }
}

}  // namespace giq::image
