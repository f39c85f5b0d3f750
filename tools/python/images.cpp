// giq.read_exr and giq.write_exr: multi-layer OpenEXR through the same reader and atomic
// writer as the command line.

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "arrays.h"
#include "giq/base/error.h"
#include "giq/image/io.h"
#include "module.h"

namespace giq::python {
namespace {

py::object read_exr(const std::filesystem::path& path) {
  image::Image image;
  {
    py::gil_scoped_release release;
    if (!image::is_exr_file(path)) {
      // read_image names a missing or unreadable file; an image of another format is refused.
      if (!std::filesystem::is_regular_file(path)) image::read_image(path);
      throw InputError(path.string(), "", "not an OpenEXR file; expected a .exr image (giq.score reads other formats by path)");
    }
    image = image::read_image(path);
  }
  return layers_object(image);
}

void write_exr(const std::filesystem::path& path, const py::dict& layers, const std::map<std::string, std::string>& metadata) {
  image::Image image;
  image::ExrOptions options;
  // A Layers object names each layer's channels (N.X, N.Y, N.Z); a plain dict gets R, G, B.
  py::dict channels;
  if (py::hasattr(layers, "channels")) channels = layers.attr("channels");
  if (layers.empty()) throw InputError(path.string(), "layers", "none given; expected at least one array");
  for (const auto& [key, value] : layers) {
    if (!py::isinstance<py::str>(key)) throw InputError(path.string(), "layers", "a key that is not a string; expected layer names");
    const std::string layer = py::str(key);
    const py::array a = py::isinstance<py::array>(value) ? py::reinterpret_borrow<py::array>(value) : py::array();
    if (a && a.ndim() == 3) {
      const std::string prefix = layer == "beauty" ? "" : layer + ".";
      std::array<std::string, 3> names{prefix + "R", prefix + "G", prefix + "B"};
      if (channels.contains(key)) {
        const auto given = channels[key].cast<std::vector<std::string>>();
        if (given.size() == 3) std::copy(given.begin(), given.end(), names.begin());
      }
      // Three planes under the given names: add them as R, G, B of a scratch layer, then rename.
      image::Image one;
      if (image.width() > 0) one = image::Image(image.width(), image.height());
      add_rgb(one, "", value, path.string(), layer);
      if (image.channel_names().empty()) image = image::Image(one.width(), one.height());
      if (one.width() != image.width() || one.height() != image.height())
        throw InputError(path.string(), layer, "differs in size from the other layers");
      const char* rgb[3] = {"R", "G", "B"};
      for (int k = 0; k < 3; ++k) {
        if (image.has_channel(names[size_t(k)])) throw InputError(path.string(), layer, "channel " + names[size_t(k)] + " given twice");
        float* dst = image.add_channel(names[size_t(k)]);
        std::copy_n(one.channel(rgb[k]), image.pixel_count(), dst);
        if (a.dtype().itemsize() == 2) options.half_channels.insert(names[size_t(k)]);
      }
    } else {
      if (image.has_channel(layer)) throw InputError(path.string(), layer, "channel given twice");
      add_plane(image, layer, value, path.string(), layer);
      if (a && a.dtype().itemsize() == 2) options.half_channels.insert(layer);
    }
  }
  image.metadata = metadata;
  py::gil_scoped_release release;
  image::write_exr(image, path, options);
}

}  // namespace

void register_images(py::module_& m) {
  m.def("read_exr", &read_exr, py::arg("path"),
        "Every layer of an OpenEXR file as float32 arrays: 'beauty' and each '<layer>' as (H, W, 3), other channels\n"
        "(objectId, Z, spp...) as (H, W). Returns a giq.Layers (a dict with .metadata, the header's strings, and\n"
        ".channels, each layer's channel names).");
  m.def("write_exr", &write_exr, py::arg("path"), py::arg("layers"), py::arg("metadata") = std::map<std::string, std::string>{},
        "Writes arrays as one multi-layer OpenEXR file, atomically (a crash never leaves half a file under the name):\n"
        "'beauty' as R, G, B, each '<layer>' of shape (H, W, 3) as <layer>.R/G/B (or the names a giq.Layers gives),\n"
        "(H, W) arrays as single channels. float16 arrays are stored as half, others as float32; metadata: header strings.");
}

}  // namespace giq::python
