#include "module.h"

#include "giq/base/error.h"
#include "giq/base/version.h"

namespace giq::python {

py::object to_python(const nlohmann::json& j) {
  switch (j.type()) {
    case nlohmann::json::value_t::object: {
      py::dict d;
      for (const auto& [k, v] : j.items()) d[py::str(k)] = to_python(v);
      return d;
    }
    case nlohmann::json::value_t::array: {
      py::list l;
      for (const auto& v : j) l.append(to_python(v));
      return l;
    }
    case nlohmann::json::value_t::string: return py::str(j.get<std::string>());
    case nlohmann::json::value_t::boolean: return py::bool_(j.get<bool>());
    case nlohmann::json::value_t::number_integer: return py::int_(j.get<int64_t>());
    case nlohmann::json::value_t::number_unsigned: return py::int_(j.get<uint64_t>());
    case nlohmann::json::value_t::number_float: return py::float_(j.get<double>());
    default: return py::none();
  }
}

bool is_path(const py::handle& h) { return py::isinstance<py::str>(h) || py::hasattr(h, "__fspath__"); }
std::string path_of(const py::handle& h) { return py::str(py::module_::import("os").attr("fspath")(h)); }

}  // namespace giq::python

PYBIND11_MODULE(_giq, m) {
  namespace gp = giq::python;
  m.doc() = "giq: how far real-time global illumination is from the path-traced truth (docs/python.md)";
  m.attr("__version__") = giq::version();
  // Bad input a user can fix: ValueError with the command line's one-line message.
  pybind11::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const giq::InputError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });
  gp::register_images(m);
  gp::register_metrics(m);
  gp::register_rendering(m);
}
