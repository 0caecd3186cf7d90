// coatcontact._core's Oliver–Pharr and film analysis on the C API (coatcontact_indent_analysis.h):
// NumPy arrays and plain numbers in, {"columns": {name: array}, "scalars": {name: float}} out;
// coatcontact/indent_analysis.py names the options and the keys.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "coatcontact/coatcontact.h"
#include "module_errors.hpp"

namespace py = pybind11;

namespace {

using coatcontact_python::call_held;
using coatcontact_python::call_released;
using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

struct Result {
  cc_indent_result* r = nullptr;
  ~Result() { cc_indent_result_destroy(r); }
};

// The test's arrays, kept alive while the C call reads them.
struct Data {
  Array depth, load;
  std::optional<Array> stiffness, hardness;
  std::vector<double> area;
  cc_indent_data c{};
  Data(Array d, Array l, std::optional<Array> s, std::optional<Array> h, std::vector<double> a, double poisson,
       double range_min, double range_max)
      : depth(std::move(d)), load(std::move(l)), stiffness(std::move(s)), hardness(std::move(h)), area(std::move(a)) {
    if (depth.size() != load.size()) throw py::value_error("depth and load differ in length");
    for (const auto* o : {&stiffness, &hardness})
      if (*o && (*o)->size() != depth.size()) throw py::value_error("stiffness and hardness must have the depth's length");
    c.depth = depth.data();
    c.load = load.data();
    c.stiffness = stiffness ? stiffness->data() : nullptr;
    c.hardness = hardness ? hardness->data() : nullptr;
    c.points = static_cast<long>(depth.size());
    c.area_coefficients = area.data();
    c.area_count = static_cast<long>(area.size());
    c.poisson = poisson;
    c.range_min = range_min;
    c.range_max = range_max;
  }
};

py::dict table(const cc_indent_result* r) {
  long rows = 0, columns = 0, scalars = 0;
  call_held([&] { return cc_indent_result_rows(r, &rows); });
  call_held([&] { return cc_indent_result_column_count(r, &columns); });
  call_held([&] { return cc_indent_result_scalar_count(r, &scalars); });
  py::dict cols, sc;
  for (long c = 0; c < columns; ++c) {
    const char* name = nullptr;
    call_held([&] { return cc_indent_result_column_name(r, c, &name); });
    py::array_t<double> v(rows);
    long length = 0;
    call_held([&] { return cc_indent_result_column(r, name, v.mutable_data(), rows, &length); });
    cols[py::str(name)] = v;
  }
  for (long s = 0; s < scalars; ++s) {
    const char* name = nullptr;
    double value = 0;
    call_held([&] { return cc_indent_result_scalar(r, s, &name, &value); });
    sc[py::str(name)] = value;
  }
  py::dict out;
  out["columns"] = cols;
  out["scalars"] = sc;
  return out;
}

cc_indent_options options_of(const py::dict& o) {
  cc_indent_options c;
  cc_indent_options_default(&c);
  c.area_from_hardness = o["area_from_hardness"].cast<bool>();
  c.rigid_indenter = o["rigid_indenter"].cast<bool>();
  c.indenter_modulus = o["indenter_modulus"].cast<double>();
  c.indenter_poisson = o["indenter_poisson"].cast<double>();
  c.poisson = o["poisson"].cast<double>();
  c.beta = o["beta"].cast<double>();
  c.epsilon = o["epsilon"].cast<double>();
  c.frame_stiffness = o["frame_stiffness"].cast<double>();
  c.depth_min = o["depth_min"].cast<double>();
  c.depth_max = o["depth_max"].cast<double>();
  c.stiffness = o["stiffness"].cast<int>();
  return c;
}

py::dict analyse(Data& data, const std::vector<double>& area, const py::dict& options) {
  cc_indent_options c = options_of(options);
  c.area_coefficients = area.data();
  c.area_count = static_cast<long>(area.size());
  Result r;
  call_released([&] { return cc_indent_analyse(&data.c, &c, &r.r); });
  return table(r.r);
}

py::dict film(Data& data, const std::vector<double>& area, const py::dict& options, const std::vector<double>& layers,
              const py::dict& f) {
  cc_indent_options c = options_of(options);
  c.area_coefficients = area.data();
  c.area_count = static_cast<long>(area.size());
  cc_indent_film_options fo;
  cc_indent_film_options_default(&fo);
  fo.layers = layers.data();
  fo.layer_count = static_cast<long>(layers.size() / 3);
  fo.substrate_rigid = f["substrate_rigid"].cast<bool>();
  fo.substrate_modulus = f["substrate_modulus"].cast<double>();
  fo.substrate_poisson = f["substrate_poisson"].cast<double>();
  fo.solve_thickness = f["solve_thickness"].cast<bool>();
  const std::string model = f["model"].cast<std::string>();
  fo.model = model.c_str();
  fo.alpha = f["alpha"].cast<double>();
  fo.coated_contact_depth = f["coated_contact_depth"].cast<bool>();
  fo.max_points = f["max_points"].cast<long>();
  Result r;
  call_released([&] { return cc_indent_film(&data.c, &c, &fo, &r.r); });
  return table(r.r);
}

}  // namespace

void register_indent_analysis(py::module_& m) {
  py::class_<Data>(m, "IndentData")
      .def(py::init<Array, Array, std::optional<Array>, std::optional<Array>, std::vector<double>, double, double, double>(),
           py::arg("depth"), py::arg("load"), py::arg("stiffness"), py::arg("hardness"), py::arg("area"),
           py::arg("poisson"), py::arg("range_min"), py::arg("range_max"));
  m.def("indent_analyse", &analyse, py::arg("data"), py::arg("area"), py::arg("options"));
  m.def("indent_film", &film, py::arg("data"), py::arg("area"), py::arg("options"), py::arg("layers"), py::arg("film"));
}
