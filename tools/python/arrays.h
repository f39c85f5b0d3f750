#pragma once
// numpy arrays in and out of giq's planar float images. Every check a file reader makes has
// its counterpart here, with the same kind of message: the array's name stands for the file.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>

#include "giq/image/image.h"

namespace giq::python {

namespace py = pybind11;

// How non-finite values in an input are treated: as giq score treats them (left out of every
// mean and counted), or refused with the first such pixel named.
enum class NanPolicy { Omit, Raise };
NanPolicy parse_nan_policy(const std::string& policy);

// A float array (float16, float32 or float64; any strides, C or Fortran order) of shape
// (H, W, 3), or (H, W) for a grey image, into the channels `layer` names in `image` (created
// at the array's size when empty). Throws InputError(name, field, ...) for any other shape or
// dtype, or a size that differs from the image's.
void add_rgb(image::Image& image, const std::string& layer, const py::handle& array, const std::string& name,
             const std::string& field, NanPolicy nans = NanPolicy::Omit);
// A (H, W) float array into one channel.
void add_plane(image::Image& image, const std::string& channel, const py::handle& array, const std::string& name,
               const std::string& field);

// An input as the metrics take it: an array (the beauty) or a dict of layers as read_exr
// returns it ("beauty", "indirect", "variance", single channels such as "objectId").
image::Image image_from(const py::handle& input, const std::string& name, NanPolicy nans = NanPolicy::Omit);

// A dict of layers: "beauty" and "<layer>" as (H, W, 3) float32 arrays (4 channels where a
// layer has alpha), other channels as (H, W).
py::dict layers_of(const image::Image& image);

// The same as a giq.Layers (the package's dict with .metadata and .channels).
py::object layers_object(const image::Image& image);

// One plane of width x height floats as a (H, W) float32 array (copied).
py::array_t<float> plane_array(const float* values, int width, int height);

}  // namespace giq::python
