#include "arrays.h"

#include <Imath/half.h>
#include <pybind11/stl.h>

#include <cmath>
#include <cstring>

#include "giq/base/error.h"

namespace giq::python {
namespace {

std::string shape_text(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) s += (i ? ", " : "") + std::to_string(a.shape(i));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

py::array as_array(const py::handle& h, const std::string& name, const std::string& field) {
  if (!py::isinstance<py::array>(h))
    throw InputError(name, field, std::string("a ") + std::string(py::str(py::type::of(h).attr("__name__"))) +
                                      "; expected a numpy array of floats");
  return py::reinterpret_borrow<py::array>(h);
}

// Element (y, x, c) of a float array, as float, whatever its width and strides.
struct Reader {
  const char* data;
  py::ssize_t sy, sx, sc;
  char kind;
  int bytes;
  float operator()(py::ssize_t y, py::ssize_t x, py::ssize_t c) const {
    const char* p = data + y * sy + x * sx + c * sc;
    if (bytes == 4) {
      float v;
      std::memcpy(&v, p, 4);
      return v;
    }
    if (bytes == 8) {
      double v;
      std::memcpy(&v, p, 8);
      return float(v);
    }
    Imath::half v;
    std::memcpy(&v, p, 2);
    return float(v);
  }
};

Reader reader(const py::array& a, const std::string& name, const std::string& field) {
  const py::dtype dt = a.dtype();
  if (dt.kind() != 'f' || (dt.itemsize() != 2 && dt.itemsize() != 4 && dt.itemsize() != 8))
    throw InputError(name, field, "dtype " + py::str(dt.attr("name")).cast<std::string>() + "; expected float16, float32 or float64");
  return {static_cast<const char*>(a.data()), a.strides(0), a.strides(1), a.ndim() == 3 ? a.strides(2) : 0, dt.kind(),
          int(dt.itemsize())};
}

void check_size(image::Image& image, const py::array& a, const std::string& name, const std::string& field) {
  const int h = int(a.shape(0)), w = int(a.shape(1));
  if (a.shape(0) <= 0 || a.shape(1) <= 0 || a.shape(0) > 16384 || a.shape(1) > 16384)
    throw InputError(name, field, "shape " + shape_text(a) + "; expected 1 to 16384 rows and columns");
  if (image.width() == 0 && image.height() == 0 && image.channel_names().empty()) image = image::Image(w, h);
  if (w != image.width() || h != image.height())
    throw InputError(name, field,
                     "shape " + shape_text(a) + " is " + std::to_string(w) + "x" + std::to_string(h) + ", expected " +
                         std::to_string(image.width()) + "x" + std::to_string(image.height()) +
                         " as the other arrays (width x height)");
}

}  // namespace

NanPolicy parse_nan_policy(const std::string& policy) {
  if (policy == "omit") return NanPolicy::Omit;
  if (policy == "raise") return NanPolicy::Raise;
  throw InputError("", "nan_policy", "'" + policy + "'; expected 'omit' (left out of every mean and counted, as giq score does) or 'raise'");
}

void add_rgb(image::Image& image, const std::string& layer, const py::handle& input, const std::string& name,
             const std::string& field, NanPolicy nans) {
  const py::array a = as_array(input, name, field);
  if (!(a.ndim() == 2 || (a.ndim() == 3 && a.shape(2) == 3)))
    throw InputError(name, field, "shape " + shape_text(a) + "; expected (H, W, 3) for RGB or (H, W) for grey");
  const Reader at = reader(a, name, field);
  check_size(image, a, name, field);
  const std::array<std::string, 3> names = image.layer_channels(layer);
  float* c[3];
  for (int k = 0; k < 3; ++k) c[k] = image.add_channel(names[size_t(k)]);
  const int w = image.width(), h = image.height();
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = image.index(x, y);
      for (int k = 0; k < 3; ++k) {
        const float v = at(y, x, a.ndim() == 3 ? k : 0);
        if (nans == NanPolicy::Raise && !std::isfinite(v))
          throw InputError(name, field, "pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") is " +
                                            (std::isnan(v) ? "NaN" : "infinite") +
                                            "; expected finite values (nan_policy='raise')");
        c[k][i] = v;
      }
    }
}

void add_plane(image::Image& image, const std::string& channel, const py::handle& input, const std::string& name,
               const std::string& field) {
  const py::array a = as_array(input, name, field);
  if (a.ndim() != 2) throw InputError(name, field, "shape " + shape_text(a) + "; expected (H, W)");
  const Reader at = reader(a, name, field);
  check_size(image, a, name, field);
  float* c = image.add_channel(channel);
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) c[image.index(x, y)] = at(y, x, 0);
}

image::Image image_from(const py::handle& input, const std::string& name, NanPolicy nans) {
  image::Image image;
  if (!py::isinstance<py::dict>(input)) {
    add_rgb(image, "", input, name, "", nans);
    return image;
  }
  for (const auto& [key, value] : py::reinterpret_borrow<py::dict>(input)) {
    if (!py::isinstance<py::str>(key)) throw InputError(name, "layers", "a key that is not a string; expected layer names");
    const std::string layer = py::str(key);
    const py::array a = as_array(value, name, layer);
    // Only the compared layers follow the NaN policy; a variance or depth may hold Inf.
    if (a.ndim() == 3) add_rgb(image, layer == "beauty" ? "" : layer, value, name, layer, layer == "beauty" ? nans : NanPolicy::Omit);
    else add_plane(image, layer, value, name, layer);
  }
  return image;
}

py::array_t<float> plane_array(const float* values, int width, int height) {
  py::array_t<float> out({py::ssize_t(height), py::ssize_t(width)});
  std::memcpy(out.mutable_data(), values, size_t(width) * size_t(height) * sizeof(float));
  return out;
}

py::dict layers_of(const image::Image& image) {
  py::dict out;
  std::vector<std::string> used;
  const py::ssize_t h = image.height(), w = image.width();
  for (const std::string& layer : image.layers()) {
    const auto names = image.layer_channels(layer);
    py::array_t<float> a({h, w, py::ssize_t(3)});
    float* dst = a.mutable_data();
    for (int k = 0; k < 3; ++k) {
      const float* src = image.channel(names[size_t(k)]);
      for (size_t i = 0; i < image.pixel_count(); ++i) dst[i * 3 + size_t(k)] = src[i];
      used.push_back(names[size_t(k)]);
    }
    out[py::str(layer.empty() ? "beauty" : layer)] = a;
  }
  for (const std::string& c : image.channel_names())
    if (std::find(used.begin(), used.end(), c) == used.end())
      out[py::str(c)] = plane_array(image.channel(c), image.width(), image.height());
  return out;
}

py::object layers_object(const image::Image& img) {
  py::dict channels;
  for (const std::string& layer : img.layers()) {
    py::list names;
    for (const std::string& c : img.layer_channels(layer)) names.append(c);
    channels[py::str(layer.empty() ? "beauty" : layer)] = names;
  }
  return py::module_::import("giq").attr("Layers")(layers_of(img), img.metadata, channels);
}

}  // namespace giq::python
