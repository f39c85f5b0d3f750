#pragma once
// The giq Python module (_giq, re-exported by the giq package): each file registers its part.
// Every function calls the code the command line calls; InputError becomes ValueError with the
// message the command line prints after "giq: error: ".

#include <pybind11/pybind11.h>
// Every file converts std:: containers the same way (pybind11 needs one choice per program).
#include <pybind11/stl.h>

#include <nlohmann/json.hpp>
#include <string>

namespace giq::python {

namespace py = pybind11;

void register_images(py::module_& m);
void register_metrics(py::module_& m);
void register_rendering(py::module_& m);

// JSON as Python objects (dict, list, str, int, float, bool, None).
py::object to_python(const nlohmann::json& j);

// A path argument: a str or an os.PathLike, as os.fspath reads it.
bool is_path(const py::handle& h);
std::string path_of(const py::handle& h);

}  // namespace giq::python
