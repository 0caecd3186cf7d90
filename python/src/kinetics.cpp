// coatcontact._core.kinetics: rate-dependent adhesion (THEORY.md section 14) for Python, on the
// C API's crack-kinetics runs and fit (coatcontact.h, cc_kinetics_*); the Python layer
// (coatcontact/kinetics.py) adds keyword arguments and the protocol's spelling.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "coatcontact/coatcontact.h"
#include "module_errors.hpp"

namespace py = pybind11;

namespace {

using coatcontact_python::call_held;
using coatcontact_python::call_released;

using Segment = std::tuple<std::string, double, double, double, bool>;  // kind, speed, duration, force, has

py::array_t<double> array_of(const std::vector<double>& v) {
  py::array_t<double> a(static_cast<py::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

// Column `column` of `rows` rows of `columns` values each.
py::array_t<double> column_of(const std::vector<double>& table, int columns, int column) {
  const std::size_t rows = table.size() / static_cast<std::size_t>(columns);
  py::array_t<double> a(static_cast<py::ssize_t>(rows));
  for (std::size_t i = 0; i < rows; ++i) a.mutable_data()[i] = table[i * columns + column];
  return a;
}

py::dict event(const double* force_time_radius) {
  py::dict d;
  d["F"] = force_time_radius[0];
  d["t"] = force_time_radius[1];
  d["a"] = force_time_radius[2];
  return d;
}

std::vector<cc_kinetics_segment> segments_of(const std::vector<Segment>& protocol) {
  std::vector<cc_kinetics_segment> out;
  for (const auto& [kind, speed, duration, force, has] : protocol) {
    cc_kinetics_segment s{};
    if (kind == "approach") s.kind = CC_KINETICS_APPROACH;
    else if (kind == "dwell") s.kind = CC_KINETICS_DWELL;
    else if (kind == "retract") s.kind = CC_KINETICS_RETRACT;
    else throw py::value_error("protocol: unknown segment '" + kind + "' (approach, dwell or retract)");
    s.speed = speed;
    s.duration = duration;
    s.target_force = force;
    s.has_target = has ? 1 : 0;
    out.push_back(s);
  }
  return out;
}

// A film of the given thickness on an elastic or rigid substrate: the coating of section 14.
std::shared_ptr<cc_stack> film_stack(double film_e, double film_nu, double thickness, bool rigid, double sub_e,
                                     double sub_nu) {
  cc_stack* raw = nullptr;
  call_held([&] { return cc_stack_create(&raw); });
  std::shared_ptr<cc_stack> stack(raw, cc_stack_destroy);
  call_held([&] { return cc_stack_add_layer(raw, thickness, film_e, film_nu, 0); });
  call_held([&] { return rigid ? cc_stack_set_rigid_substrate(raw) : cc_stack_set_substrate(raw, sub_e, sub_nu); });
  return stack;
}

// One measured curve: protocol, spring k, t, F, sigma_F (empty: unweighted).
using Curve = std::tuple<std::vector<Segment>, double, std::vector<double>, std::vector<double>, std::vector<double>>;

py::dict kinetics_fit(double film_e, double film_nu, bool rigid, double sub_e, double sub_nu, double radius,
                      double thickness, double work, double v_star, double n, double v_star_adv, double n_adv,
                      const std::vector<Curve>& curves, const std::vector<bool>& free, double tol) {
  constexpr int kCount = CC_KINETICS_FIT_PARAMETERS;
  if (free.size() != static_cast<std::size_t>(kCount)) throw py::value_error("free: five flags");
  cc_kinetics_fit_request request{};
  request.radius = radius;
  request.work = work;
  request.v_star = v_star;
  request.n = n;
  request.v_star_adv = v_star_adv;
  request.n_adv = n_adv;
  request.tolerance = tol;
  for (int j = 0; j < kCount; ++j) request.free[j] = free[j] ? 1 : 0;
  std::vector<std::vector<cc_kinetics_segment>> protocols;
  std::vector<cc_kinetics_curve> data;
  std::size_t points = 0;
  for (const auto& [protocol, spring, t, f, sigma] : curves) {
    protocols.push_back(segments_of(protocol));
    if (f.size() != t.size() || (!sigma.empty() && sigma.size() != t.size())) {
      throw py::value_error("curves[" + std::to_string(data.size()) + "]: t, F and sigma_F need the same length");
    }
    cc_kinetics_curve c{};
    c.segment_count = static_cast<int>(protocols.back().size());
    c.segments = protocols.back().data();
    c.spring = spring;
    c.n = static_cast<int>(t.size());
    c.time = t.data();
    c.force = f.data();
    c.sigma_force = sigma.empty() ? nullptr : sigma.data();
    data.push_back(c);
    points += t.size();
  }
  const auto stack = film_stack(film_e, film_nu, thickness, rigid, sub_e, sub_nu);
  request.curve_count = static_cast<int>(data.size());
  request.curves = data.data();
  std::vector<double> values(kCount), errors(kCount), correlation(kCount * kCount), model(points), residual(points);
  cc_kinetics_fit_summary summary{};
  call_released([&] {
    return cc_kinetics_fit(stack.get(), &request, values.data(), errors.data(), correlation.data(), model.data(),
                           residual.data(), &summary);
  });
  py::dict out;
  out["names"] = std::vector<std::string>{"w", "v_star", "n", "t", "E1"};  // coatcontact.h's order
  out["values"] = array_of(values);
  out["errors"] = array_of(errors);
  out["free"] = free;
  std::vector<std::vector<double>> rows;
  for (int j = 0; j < kCount; ++j) rows.emplace_back(correlation.begin() + j * kCount, correlation.begin() + (j + 1) * kCount);
  out["correlation"] = rows;
  out["F_model"] = array_of(model);
  out["residual"] = array_of(residual);
  out["r_squared"] = summary.r_squared;
  if (summary.weighted != 0) {
    out["chi2_per_dof"] = summary.chi2_per_dof;
  } else {
    out["chi2_per_dof"] = py::none();
  }
  out["residual_sigma"] = summary.residual_sigma;
  out["iterations"] = summary.iterations;
  out["simulations"] = summary.simulations;
  out["seconds"] = summary.seconds;
  return out;
}

py::dict kinetics(double film_e, double film_nu, bool rigid, double sub_e, double sub_nu, double radius,
                  double half_angle, double thickness, double work, double v_star, double n, double v_star_adv,
                  double n_adv, double spring, const std::vector<Segment>& protocol,
                  const std::vector<double>& retract_speeds, double tol) {
  const std::vector<cc_kinetics_segment> segments = segments_of(protocol);
  const auto stack = film_stack(film_e, film_nu, thickness, rigid, sub_e, sub_nu);
  cc_kinetics_setup setup{};
  setup.tip = half_angle != 0.0 ? CC_KINETICS_CONE : CC_KINETICS_SPHERE;  // the cone: section 14, "The cone"
  setup.radius = radius;
  setup.half_angle = half_angle;
  setup.work = work;
  setup.v_star = v_star;
  setup.n = n;
  setup.v_star_adv = v_star_adv;
  setup.n_adv = n_adv;
  setup.spring = spring;
  setup.segment_count = static_cast<int>(segments.size());
  setup.segments = segments.data();
  setup.tolerance = tol;
  double scales[CC_KINETICS_SCALE_COLUMNS];
  call_released([&] { return cc_kinetics_scales(stack.get(), &setup, scales); });
  py::dict out;
  py::dict sc;
  sc["l"] = scales[0];
  sc["delta_scale"] = scales[1];
  sc["F_scale"] = scales[2];
  sc["t_scale"] = scales[3];
  sc["eta"] = scales[4];
  sc["k_bar"] = scales[5];
  sc["drive_rate"] = scales[6];
  out["scales"] = sc;
  if (retract_speeds.empty()) {
    cc_kinetics* raw = nullptr;
    call_released([&] { return cc_kinetics_run(stack.get(), &setup, &raw); });
    const std::unique_ptr<cc_kinetics, void (*)(cc_kinetics*)> run(raw, cc_kinetics_destroy);
    int rows = 0;
    call_held([&] { return cc_kinetics_size(run.get(), &rows); });
    std::vector<double> states(static_cast<std::size_t>(rows) * CC_KINETICS_COLUMNS);
    double events[CC_KINETICS_EVENT_COLUMNS], energy[CC_KINETICS_ENERGY_COLUMNS];
    call_held([&] { return cc_kinetics_states(run.get(), rows, states.data()); });
    call_held([&] { return cc_kinetics_events(run.get(), events); });
    call_held([&] { return cc_kinetics_energy(run.get(), energy); });
    const char* const names[CC_KINETICS_COLUMNS] = {"t", "z", "delta", "a", "F", "G"};
    for (int k = 0; k < CC_KINETICS_COLUMNS; ++k) out[names[k]] = column_of(states, CC_KINETICS_COLUMNS, k);
    out["pulloff"] = event(events);
    out["loss"] = event(events + 3);
    out["work"] = energy[0];
    out["dissipation"] = energy[1];
    out["steps"] = static_cast<std::size_t>(energy[2]);
  } else {
    std::vector<double> table(retract_speeds.size() * CC_KINETICS_SWEEP_COLUMNS);
    call_released([&] {
      return cc_kinetics_sweep(stack.get(), &setup, static_cast<int>(retract_speeds.size()), retract_speeds.data(),
                               table.data());
    });
    py::dict s;
    const char* const names[CC_KINETICS_SWEEP_COLUMNS] = {"V", "F", "t", "a", "F_loss", "t_loss", nullptr, "P"};
    for (int k = 0; k < CC_KINETICS_SWEEP_COLUMNS; ++k) {
      if (names[k] != nullptr) s[names[k]] = column_of(table, CC_KINETICS_SWEEP_COLUMNS, k);
    }
    out["sweep"] = s;
  }
  return out;
}

}  // namespace

void register_kinetics(py::module_& m) {
  m.def("kinetics_fit", &kinetics_fit);
  m.def("kinetics", &kinetics);
}
