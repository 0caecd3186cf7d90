// coatcontact._core's nanoindentation part on the C API (coatcontact_indent.h): the tests of a
// vendor file as plain dicts of NumPy arrays, strings and numbers; coatcontact/indent.py makes
// them Test objects with the documented metadata keys.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cmath>
#include <memory>
#include <string>

#include "coatcontact/coatcontact.h"
#include "module_errors.hpp"

namespace py = pybind11;

namespace {

using coatcontact_python::call_held;
using coatcontact_python::call_released;

struct Handle {
  cc_indent_tests* tests = nullptr;
  ~Handle() { cc_indent_tests_destroy(tests); }
};

py::object number_or_none(double value) { return std::isnan(value) ? py::none() : py::object(py::float_(value)); }

py::dict channels(const cc_indent_tests* tests, long index) {
  long points = 0, count = 0;
  call_held([&] { return cc_indent_points(tests, index, &points); });
  call_held([&] { return cc_indent_channel_count(tests, index, &count); });
  py::dict out;
  for (long c = 0; c < count; ++c) {
    const char* name = nullptr;
    call_held([&] { return cc_indent_channel_name(tests, index, c, &name); });
    py::array_t<double> values(points);
    long length = 0;
    call_held([&] { return cc_indent_channel(tests, index, name, values.mutable_data(), points, &length); });
    if (std::string(name) == "segment") out[name] = values.attr("astype")("int64");
    else out[name] = values;
  }
  return out;
}

py::dict calibration(const cc_indent_tests* tests, long index) {
  cc_indent_calibration c{};
  call_held([&] { return cc_indent_calibration_get(tests, index, &c); });
  py::dict out;
  if (c.area_count > 0) {
    py::array_t<double> area(c.area_count);
    for (long k = 0; k < c.area_count; ++k) area.mutable_at(k) = c.area_coefficients[k];
    out["area coefficients"] = area;
  } else {
    out["area coefficients"] = py::none();
  }
  out["frame stiffness"] = number_or_none(c.frame_stiffness);
  out["poisson"] = number_or_none(c.poisson);
  out["tip"] = c.tip[0] != '\0' ? py::object(py::str(c.tip)) : py::none();
  out["beta"] = number_or_none(c.beta);
  out["epsilon"] = number_or_none(c.eps);
  out["range"] = std::isnan(c.range_min) || std::isnan(c.range_max) ? py::object(py::none())
                                                                     : py::object(py::make_tuple(c.range_min, c.range_max));
  out["calibration source"] = c.source[0] != '\0' ? py::object(py::str(c.source)) : py::none();
  return out;
}

py::list indent_read(const std::string& path) {
  Handle handle;
  call_released([&] { return cc_indent_read(path.c_str(), &handle.tests); });
  long count = 0;
  call_held([&] { return cc_indent_count(handle.tests, &count); });
  py::list tests;
  for (long i = 0; i < count; ++i) {
    py::dict test;
    const char* name = nullptr;
    call_held([&] { return cc_indent_name(handle.tests, i, &name); });
    test["name"] = py::str(name);
    test["channels"] = channels(handle.tests, i);
    test["calibration"] = calibration(handle.tests, i);
    long entries = 0;
    call_held([&] { return cc_indent_metadata_count(handle.tests, i, &entries); });
    py::dict metadata;
    for (long e = 0; e < entries; ++e) {
      const char *key = nullptr, *value = nullptr;
      call_held([&] { return cc_indent_metadata_entry(handle.tests, i, e, &key, &value); });
      metadata[py::str(key)] = py::str(value);
    }
    test["file metadata"] = metadata;
    call_held([&] { return cc_indent_result_count(handle.tests, i, &entries); });
    py::dict results;
    for (long e = 0; e < entries; ++e) {
      const char* key = nullptr;
      double value = 0.0;
      call_held([&] { return cc_indent_result_entry(handle.tests, i, e, &key, &value); });
      results[py::str(key)] = value;
    }
    test["vendor results"] = results;
    tests.append(test);
  }
  return tests;
}

}  // namespace

void register_indent(py::module_& m) { m.def("indent_read", &indent_read, py::arg("path")); }
