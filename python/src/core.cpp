// coatcontact._core: the C API (coatcontact/coatcontact.h) for Python. One class per handle,
// NumPy arrays in and out, the GIL released around every C call that solves. The Python
// layer (coatcontact/__init__.py) adds keyword arguments, dicts of arrays and docstrings.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <algorithm>
#include <chrono>
#include <exception>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include "coatcontact/coatcontact.h"
#include "module_errors.hpp"

namespace py = pybind11;

void register_kinetics(py::module_& m);  // kinetics.cpp
void register_indent(py::module_& m);    // indent.cpp
void register_indent_analysis(py::module_& m);  // indent_analysis.cpp
void register_afm(py::module_& m);      // afm.cpp (submodule _afm)

namespace {

using coatcontact_python::call_held;
using coatcontact_python::call_released;
using coatcontact_python::check;
using coatcontact_python::NumericalError;  // registered as coatcontact.NumericalError at import

// Ctrl-C and progress during a long C call (cc_set_progress_hook): the library calls the hook
// on this thread between units of work (radii, pull-offs); it takes the GIL, runs Python's
// signal handlers (KeyboardInterrupt) and the progress callback. A Python exception there
// stops the call (CC_INTERRUPTED) and is raised when the call returns.
struct Monitor {
  py::object progress;        // None or callable(done, total)
  bool report_sweeps = true;  // pass the library's sweeps' own progress to `progress`
  std::exception_ptr error;

  int step(long done, long total, bool report) {
    py::gil_scoped_acquire gil;
    try {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      if (report && !progress.is_none()) progress(done, total);
    } catch (...) {
      error = std::current_exception();
      return 1;
    }
    return 0;
  }
  static int hook(void* user, long done, long total) {
    auto* self = static_cast<Monitor*>(user);
    return self->step(done, total, self->report_sweeps);
  }
};

// call_released with the monitor's hook installed for the call.
template <typename Call>
void call_monitored(Monitor& monitor, Call&& call) {
  int status;
  std::string message;
  {
    py::gil_scoped_release release;
    cc_set_progress_hook(&Monitor::hook, &monitor);
    status = call();
    cc_set_progress_hook(nullptr, nullptr);
    if (status != CC_OK) message = cc_last_error_message();
  }
  if (monitor.error) std::rethrow_exception(monitor.error);
  check(status, message);
}


using InArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

int count_of(const InArray& a) {
  if (a.ndim() != 1) throw py::value_error("expected a one-dimensional array");
  if (a.shape(0) > 0x7fffffff) throw py::value_error("array too long for the C interface (n > 2^31-1)");
  return static_cast<int>(a.shape(0));
}

py::array_t<double> rows(int n, int columns) {
  return py::array_t<double>({static_cast<py::ssize_t>(n), static_cast<py::ssize_t>(columns)});
}

// The per-point statuses of an _each call (coatcontact.h, "arrays point by point") and the
// reasons, one line per point (read in the calling thread, right after the call).
struct PointOutcome {
  py::array_t<int> status;
  std::string reasons;
  explicit PointOutcome(int n) : status(static_cast<py::ssize_t>(n)) {}
  // After a successful call: the reasons as a list of str, one per point ("" if delivered).
  py::tuple with(py::array_t<double> table) const {
    py::list list;
    std::size_t start = 0;
    const int n = static_cast<int>(status.shape(0));
    for (int i = 0; i < n; ++i) {
      const std::size_t end = reasons.find('\n', start);
      list.append(reasons.substr(start, end == std::string::npos ? std::string::npos : end - start));
      start = end == std::string::npos ? reasons.size() : end + 1;
    }
    return py::make_tuple(table, status, list);
  }
};

struct Stack {
  std::shared_ptr<cc_stack> handle;
  Stack() {
    cc_stack* s = nullptr;
    call_held([&] { return cc_stack_create(&s); });
    handle.reset(s, cc_stack_destroy);
  }
};

struct Solver {
  std::shared_ptr<cc_reduced_solver> handle;
  explicit Solver(const Stack& stack) {
    cc_reduced_solver* s = nullptr;
    call_released([&] { return cc_reduced_solver_create(stack.handle.get(), &s); });
    handle.reset(s, cc_reduced_solver_destroy);
  }
  py::array_t<double> sweep(const InArray& a_over_t, double tolerance, py::object progress) const {
    const int n = count_of(a_over_t);
    auto out = rows(n, CC_REDUCED_COLUMNS);
    const double* in = a_over_t.data();
    double* o = out.mutable_data();
    Monitor monitor{std::move(progress), true, nullptr};
    // One radius: solve() spares the parallel region's start-up (identical numbers).
    call_monitored(monitor, [&] {
      return n == 1 ? cc_reduced_solver_solve(handle.get(), in[0], tolerance, o)
                    : cc_reduced_solver_sweep(handle.get(), n, in, tolerance, o);
    });
    return out;
  }
  // Every radius that can be solved: (table, status, reasons).
  py::tuple sweep_each(const InArray& a_over_t, double tolerance, py::object progress) const {
    const int n = count_of(a_over_t);
    auto out = rows(n, CC_REDUCED_COLUMNS);
    PointOutcome outcome(n);
    const double* in = a_over_t.data();
    double* o = out.mutable_data();
    int* st = outcome.status.mutable_data();
    Monitor monitor{std::move(progress), true, nullptr};
    call_monitored(monitor, [&] {
      const int status = cc_reduced_solver_sweep_each(handle.get(), n, in, tolerance, o, st);
      if (status == CC_OK) outcome.reasons = cc_point_reasons();
      return status;
    });
    return outcome.with(out);
  }
  // Seconds per C call (median of `repeats`), timed here so that the Python bench can set
  // the interpreter's overhead against the library's own cost on the same machine.
  double time_c_call(const InArray& a_over_t, double tolerance, int repeats) const {
    const int n = count_of(a_over_t);
    std::vector<double> out(static_cast<std::size_t>(n) * CC_REDUCED_COLUMNS);
    std::vector<double> times;
    const double* in = a_over_t.data();
    call_released([&] {
      for (int r = 0; r < repeats; ++r) {
        const auto start = std::chrono::steady_clock::now();
        const int status = n == 1 ? cc_reduced_solver_solve(handle.get(), in[0], tolerance, out.data())
                                  : cc_reduced_solver_sweep(handle.get(), n, in, tolerance, out.data());
        if (status != CC_OK) return status;
        times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      }
      return static_cast<int>(CC_OK);
    });
    if (times.empty()) return 0.0;
    std::sort(times.begin(), times.end());
    return times[times.size() / 2];
  }
};

// A model and its contacts fill one lazy cache: the mutex keeps Python threads (the GIL is
// released during solves) from using it at once, as the C API requires.
struct Model {
  std::shared_ptr<cc_adhesive_model> handle;
  std::shared_ptr<std::mutex> lock = std::make_shared<std::mutex>();
  Model(const Solver& solver, double tolerance) {
    cc_adhesive_model* m = nullptr;
    call_released([&] { return cc_adhesive_model_create(solver.handle.get(), tolerance, &m); });
    handle.reset(m, cc_adhesive_model_destroy);
  }
  py::tuple default_range() const {
    double range[2];
    call_held([&] { return cc_adhesive_default_range(handle.get(), range); });
    return py::make_tuple(range[0], range[1]);
  }
  py::array_t<double> curve(double eta, const InArray& a_bar) const {
    const int n = count_of(a_bar);
    auto out = rows(n, CC_CURVE_COLUMNS);
    const double* in = a_bar.data();
    double* o = out.mutable_data();
    call_released([&] {
      std::lock_guard<std::mutex> guard(*lock);
      return n == 0 ? static_cast<int>(CC_OK) : cc_adhesive_curve(handle.get(), eta, n, in, o);
    });
    return out;
  }
  py::tuple curve_each(double eta, const InArray& a_bar) const {
    const int n = count_of(a_bar);
    auto out = rows(n, CC_CURVE_COLUMNS);
    PointOutcome outcome(n);
    const double* in = a_bar.data();
    double* o = out.mutable_data();
    int* st = outcome.status.mutable_data();
    call_released([&] {
      std::lock_guard<std::mutex> guard(*lock);
      if (n == 0) return static_cast<int>(CC_OK);
      const int status = cc_adhesive_curve_each(handle.get(), eta, n, in, o, st);
      if (status == CC_OK) outcome.reasons = cc_point_reasons();
      return status;
    });
    return outcome.with(out);
  }
  // One row per eta: the six pull-off columns and the warning flags.
  // Progress is reported per eta (the sweeps inside a pull-off only check for signals).
  py::tuple pulloff(const InArray& eta, py::object progress) const {
    const int n = count_of(eta);
    auto out = rows(n, CC_PULLOFF_COLUMNS);
    py::array_t<int> flags(static_cast<py::ssize_t>(n));
    const double* in = eta.data();
    double* o = out.mutable_data();
    int* f = flags.mutable_data();
    Monitor monitor{std::move(progress), false, nullptr};
    call_monitored(monitor, [&] {
      std::lock_guard<std::mutex> guard(*lock);
      const int prepared = cc_pulloff_prepare(handle.get(), n, in);  // one table for the etas, as the CLI
      if (prepared != CC_OK) return prepared;
      for (int i = 0; i < n; ++i) {
        const int status = cc_pulloff(handle.get(), in[i], o + CC_PULLOFF_COLUMNS * i, f + i);
        if (status != CC_OK) return status;
        if (monitor.step(i + 1, n, true) != 0) return static_cast<int>(CC_INTERRUPTED);
      }
      return static_cast<int>(CC_OK);
    });
    return py::make_tuple(out, flags);
  }
};

struct Contact {
  std::shared_ptr<cc_contact> handle;
  std::shared_ptr<std::mutex> lock;
  Contact(const Model& model, double radius, double thickness, double work) : lock(model.lock) {
    cc_contact* c = nullptr;
    call_released([&] {
      std::lock_guard<std::mutex> guard(*lock);
      return cc_contact_create(model.handle.get(), radius, thickness, work, &c);
    });
    handle.reset(c, cc_contact_destroy);
  }
  py::tuple scales() const {
    double s[4];
    call_held([&] { return cc_contact_scales(handle.get(), s); });
    return py::make_tuple(s[0], s[1], s[2], s[3]);
  }
  py::array_t<double> curve(int n) const {
    if (n < 1) throw py::value_error("contact curve: points = " + std::to_string(n) + "; at least one point is needed");
    auto out = rows(n, CC_CONTACT_COLUMNS);
    double* o = out.mutable_data();
    call_released([&] {
      std::lock_guard<std::mutex> guard(*lock);
      return cc_contact_curve(handle.get(), n, o);
    });
    return out;
  }
  py::array_t<double> at(const InArray& a) const {
    const int n = count_of(a);
    auto out = rows(n, CC_CONTACT_COLUMNS);
    const double* in = a.data();
    double* o = out.mutable_data();
    call_released([&] {
      std::lock_guard<std::mutex> guard(*lock);
      return cc_contact_at(handle.get(), n, in, o);
    });
    return out;
  }
  py::tuple at_each(const InArray& a) const {
    const int n = count_of(a);
    auto out = rows(n, CC_CONTACT_COLUMNS);
    PointOutcome outcome(n);
    const double* in = a.data();
    double* o = out.mutable_data();
    int* st = outcome.status.mutable_data();
    call_released([&] {
      std::lock_guard<std::mutex> guard(*lock);
      const int status = cc_contact_at_each(handle.get(), n, in, o, st);
      if (status == CC_OK) outcome.reasons = cc_point_reasons();
      return status;
    });
    return outcome.with(out);
  }
  py::tuple pulloff() const {
    auto out = py::array_t<double>(CC_PULLOFF_COLUMNS);
    double* o = out.mutable_data();
    int flags = 0;
    call_released([&] {
      std::lock_guard<std::mutex> guard(*lock);
      return cc_contact_pulloff(handle.get(), o, &flags);
    });
    return py::make_tuple(out, flags);
  }
  // The library's validity warnings (coatcontact/limits.hpp) of rows a, delta, F: one per line.
  std::string validity(const InArray& rows) const {
    if (rows.ndim() != 2 || rows.shape(1) != CC_CONTACT_COLUMNS) {
      throw py::value_error("contact validity: expected rows of a, delta, F");
    }
    if (rows.shape(0) > 0x7fffffff) throw py::value_error("array too long for the C interface (n > 2^31-1)");
    const int n = static_cast<int>(rows.shape(0));
    const char* text = nullptr;
    call_held([&] { return cc_contact_validity(handle.get(), n, rows.data(), &text); });
    return text ? std::string(text) : std::string();
  }
};

py::dict fit(const Stack& stack, int kind, const InArray& x, const InArray& force, double radius,
             double thickness_start, double work_start, unsigned free_mask) {
  const int n = count_of(x);
  if (count_of(force) != n) {
    throw py::value_error("fit: x has " + std::to_string(n) + " points, force " +
                          std::to_string(force.shape(0)));
  }
  cc_fit_result r{};
  const double* px = x.data();
  const double* pf = force.data();
  call_released([&] {
    return cc_fit(stack.handle.get(), kind, n, px, pf, radius, thickness_start, work_start, free_mask, &r);
  });
  py::array_t<double> value(3), error(3), correlation({3, 3}), pulloff(3);
  for (int i = 0; i < 3; ++i) {
    value.mutable_at(i) = r.value[i];
    error.mutable_at(i) = r.standard_error[i];
    pulloff.mutable_at(i) = r.displacement_pulloff[i];
    for (int j = 0; j < 3; ++j) correlation.mutable_at(i, j) = r.correlation[3 * i + j];
  }
  py::dict d;
  d["value"] = value;
  d["standard_error"] = error;
  d["correlation"] = correlation;
  d["free_mask"] = r.free_mask;
  d["points"] = r.points;
  d["residual_norm"] = r.residual_norm;
  d["residual_sigma"] = r.residual_sigma;
  d["r_squared"] = r.r_squared;
  d["iterations"] = r.iterations;
  d["converged"] = r.converged != 0;
  d["displacement_pulloff"] = pulloff;
  return d;
}

// Fit of any parameters of a stack (cc_fit_stack): the parameter vector is w, h1..hN, E1..EN
// (N layers, top first). The C API gives estimates, standard errors and sigma only; the
// correlation of a stack fit does not cross it.
py::dict fit_stack(const Stack& stack, int kind, const InArray& x, const InArray& force, double radius,
                   double work_start, const std::string& free_names, int parameter_count) {
  const int n = count_of(x);
  if (count_of(force) != n) {
    throw py::value_error("fit_stack: x has " + std::to_string(n) + " points, F " +
                          std::to_string(force.shape(0)));
  }
  if (parameter_count < 3) throw py::value_error("fit_stack: parameter_count < 3");
  py::array_t<double> value(parameter_count), error(parameter_count);
  double sigma = 0.0;
  const double* px = x.data();
  const double* pf = force.data();
  double* pv = value.mutable_data();
  double* pe = error.mutable_data();
  call_released([&] {
    return cc_fit_stack(stack.handle.get(), kind, n, px, pf, radius, work_start, free_names.c_str(),
                        parameter_count, pv, pe, &sigma);
  });
  py::dict d;
  d["value"] = value;
  d["standard_error"] = error;
  d["residual_sigma"] = sigma;
  return d;
}

// Spring control on a Model (THEORY.md section 10): one row (P, a_bar, D) per k_bar.
py::array_t<double> pulloff_spring(const Model& model, double eta, const InArray& k_bar) {
  const int n = count_of(k_bar);
  auto out = rows(n, 3);
  const double* in = k_bar.data();
  double* o = out.mutable_data();
  call_released([&] {
    std::lock_guard<std::mutex> guard(*model.lock);
    for (int i = 0; i < n; ++i) {
      const int status = cc_pulloff_spring(model.handle.get(), eta, in[i], o + 3 * i, nullptr);
      if (status != CC_OK) return status;
    }
    return static_cast<int>(CC_OK);
  });
  return out;
}

// Maugis-Dugdale (THEORY.md section 13): the model's table is thread-safe, so no lock.
struct MaugisDugdale {
  std::shared_ptr<cc_md_model> handle;
  // direct_solve: the per-radius solve (the reference) instead of the reduced table.
  MaugisDugdale(const Stack& stack, bool direct_solve) {
    cc_md_model* m = nullptr;
    call_released([&] {
      return direct_solve ? cc_md_model_create_direct(stack.handle.get(), &m) : cc_md_model_create(stack.handle.get(), &m);
    });
    handle.reset(m, cc_md_model_destroy);
  }
  py::array_t<double> curve(double eta, double lambda, const InArray& a_bar) const {
    const int n = count_of(a_bar);
    auto out = rows(n, CC_MD_CURVE_COLUMNS);
    const double* in = a_bar.data();
    double* o = out.mutable_data();
    call_released([&] { return n == 0 ? static_cast<int>(CC_OK) : cc_md_curve(handle.get(), eta, lambda, n, in, o); });
    return out;
  }
  // (values, the error estimate of each, flags)
  py::tuple pulloff(double eta, double lambda) const {
    auto out = py::array_t<double>(CC_MD_PULLOFF_COLUMNS);
    auto errors = py::array_t<double>(CC_MD_PULLOFF_ALL_ERROR_COLUMNS);
    double* o = out.mutable_data();
    double* e = errors.mutable_data();
    int flags = 0;
    call_released([&] { return cc_md_pulloff_all_errors(handle.get(), eta, lambda, o, e, &flags); });
    return py::make_tuple(out, errors, flags);
  }
};

// Indenter shapes and their SI contact (THEORY.md section 11).
struct Shape {
  std::shared_ptr<cc_shape> handle;
};

Shape make_shape(const std::string& kind, double p1, double p2) {
  cc_shape* s = nullptr;
  call_held([&] {
    if (kind == "sphere") return cc_shape_paraboloid(p1, &s);
    if (kind == "cone") return cc_shape_cone(p1, &s);
    if (kind == "pyramid") return cc_shape_pyramid(p1, &s);
    if (kind == "punch") return cc_shape_flat_punch(p1, &s);
    if (kind == "power") return cc_shape_power_law(p1, p2, &s);
    if (kind == "blunted-cone") return cc_shape_blunted_cone(p1, p2, &s);
    throw py::value_error("shape: '" + kind + "' is not one of sphere, cone, pyramid, punch, power, blunted-cone, profile");
  });
  return Shape{std::shared_ptr<cc_shape>(s, cc_shape_destroy)};
}

Shape make_profile(const InArray& r, const InArray& z) {
  const int n = count_of(r);
  if (count_of(z) != n) throw py::value_error("profile: r and z differ in length");
  cc_shape* s = nullptr;
  call_held([&] { return cc_shape_profile(n, r.data(), z.data(), &s); });
  return Shape{std::shared_ptr<cc_shape>(s, cc_shape_destroy)};
}

// The fit with every model of the CLI (cc_fit_run). Empty arrays stand for "not given"; the
// Python layer maps its keyword arguments to these positional ones.
py::dict fit_run(const Stack& stack, int kind, const InArray& x, const InArray& force, const InArray& sigma_x,
                 const InArray& sigma_force, const InArray& unloading, double radius, const Shape* shape,
                 const std::string& free_names, double work, double unload_work, double spring, int model,
                 double lambda, int bootstrap, unsigned long seed) {
  const int n = count_of(x);
  if (count_of(force) != n) throw py::value_error("F: " + std::to_string(force.shape(0)) + " forces for " + std::to_string(n) + " x values");
  for (const auto* a : {&sigma_x, &sigma_force, &unloading}) {
    if (count_of(*a) != 0 && count_of(*a) != n) throw py::value_error("fit: a per-point array differs in length from x");
  }
  std::vector<int> branch;
  for (py::ssize_t i = 0; i < unloading.shape(0); ++i) branch.push_back(unloading.at(i) != 0.0 ? 1 : 0);
  cc_fit_request request{};
  request.kind = kind;
  request.n = n;
  request.x = x.data();
  request.force = force.data();
  request.sigma_x = sigma_x.shape(0) > 0 ? sigma_x.data() : nullptr;
  request.sigma_force = sigma_force.shape(0) > 0 ? sigma_force.data() : nullptr;
  request.unloading = branch.empty() ? nullptr : branch.data();
  request.sphere_radius = radius;
  request.shape = shape != nullptr ? shape->handle.get() : nullptr;
  request.free_names = free_names.c_str();
  request.work = work;
  request.unload_work = unload_work;
  request.spring_stiffness = spring;
  request.model = model;
  request.lambda = lambda;
  request.bootstrap = bootstrap;
  request.seed = seed;
  std::vector<char> names(65536);
  int p = 0;
  call_held([&] { return cc_fit_parameter_names(stack.handle.get(), &request, names.data(), static_cast<int>(names.size()), &p); });
  py::array_t<double> value(p), error(p), start(p), correlation({p, p}), i68({p, 2}), i95({p, 2}), f_model(n), a_model(n);
  cc_fit_summary summary{};
  double* pv = value.mutable_data();
  double* pe = error.mutable_data();
  double* ps = start.mutable_data();
  double* pc = correlation.mutable_data();
  double* p68 = i68.mutable_data();
  double* p95 = i95.mutable_data();
  double* pf = f_model.mutable_data();
  double* pa = a_model.mutable_data();
  call_released([&] { return cc_fit_run(stack.handle.get(), &request, p, pv, pe, ps, pc, p68, p95, pf, pa, &summary); });
  const auto triple = [](const double* v) { return py::make_tuple(v[0], v[1], v[2]); };
  py::dict d;
  d["names"] = std::string(names.data());
  d["value"] = value;
  d["standard_error"] = error;
  d["start"] = start;
  d["correlation"] = correlation;
  d["interval68"] = i68;
  d["interval95"] = i95;
  d["F_model"] = f_model;
  d["a_model"] = a_model;
  d["points"] = summary.points;
  d["iterations"] = summary.iterations;
  d["weighted"] = summary.weighted != 0;
  d["residual_norm"] = summary.residual_norm;
  d["residual_sigma"] = summary.residual_sigma;
  d["r_squared"] = summary.r_squared;
  d["chi2_per_dof"] = summary.chi2_per_dof;
  d["load_pulloff"] = summary.has_load_pulloff ? py::object(triple(summary.load_pulloff)) : py::object(py::none());
  d["displacement_pulloff"] =
      summary.has_displacement_pulloff ? py::object(triple(summary.displacement_pulloff)) : py::object(py::none());
  d["spring_pulloff"] = summary.has_spring_pulloff ? py::object(triple(summary.spring_pulloff)) : py::object(py::none());
  d["bootstrap_samples"] = summary.bootstrap_samples;
  return d;
}

struct ShapeContact {
  std::shared_ptr<cc_shape_contact> handle;
  ShapeContact(const Stack& stack, const Shape& shape, double thickness, double work, double tolerance) {
    cc_shape_contact* c = nullptr;
    call_released([&] {
      return cc_shape_contact_create(stack.handle.get(), shape.handle.get(), thickness, work, tolerance, &c);
    });
    handle.reset(c, cc_shape_contact_destroy);
  }
  py::tuple default_range() const {
    double range[2];
    call_held([&] { return cc_shape_contact_default_range(handle.get(), range); });
    return py::make_tuple(range[0], range[1]);
  }
  py::array_t<double> curve(const InArray& a) const {
    const int n = count_of(a);
    auto out = rows(n, CC_SHAPE_CURVE_COLUMNS);
    const double* in = a.data();
    double* o = out.mutable_data();
    call_released([&] { return n == 0 ? static_cast<int>(CC_OK) : cc_shape_contact_curve(handle.get(), n, in, o); });
    return out;
  }
  py::tuple curve_each(const InArray& a) const {
    const int n = count_of(a);
    auto out = rows(n, CC_SHAPE_CURVE_COLUMNS);
    PointOutcome outcome(n);
    const double* in = a.data();
    double* o = out.mutable_data();
    int* st = outcome.status.mutable_data();
    call_released([&] {
      if (n == 0) return static_cast<int>(CC_OK);
      const int status = cc_shape_contact_curve_each(handle.get(), n, in, o, st);
      if (status == CC_OK) outcome.reasons = cc_point_reasons();
      return status;
    });
    return outcome.with(out);
  }
  py::array_t<double> pulloff(double spring_stiffness) const {
    auto out = py::array_t<double>(CC_SHAPE_PULLOFF_COLUMNS);
    double* o = out.mutable_data();
    call_released([&] { return cc_shape_contact_pulloff(handle.get(), spring_stiffness, o); });
    return out;
  }
  // The library's validity warnings of curve rows (a, delta, F, delta_H, F_H): one per line.
  std::string validity(const InArray& rows) const {
    if (rows.ndim() != 2 || rows.shape(1) != CC_SHAPE_CURVE_COLUMNS) {
      throw py::value_error("shape contact validity: expected rows of a, delta, F, delta_H, F_H");
    }
    if (rows.shape(0) > 0x7fffffff) throw py::value_error("array too long for the C interface (n > 2^31-1)");
    const char* text = nullptr;
    call_held([&] {
      return cc_shape_contact_validity(handle.get(), static_cast<int>(rows.shape(0)), rows.data(), &text);
    });
    return text ? std::string(text) : std::string();
  }
};

// A measured force curve read by the library (cc_curve_read: the CLI's reader and unit table):
// (kind, units text, {column: array}) with the columns the file has, x as "x".
py::tuple read_curve(const std::string& path, const std::string& columns) {
  cc_curve* raw = nullptr;
  call_released([&] { return cc_curve_read(path.c_str(), columns.c_str(), &raw); });
  const std::unique_ptr<cc_curve, void (*)(cc_curve*)> curve(raw, cc_curve_destroy);
  int n = 0, kind = 0;
  call_held([&] { return cc_curve_size(curve.get(), &n, &kind); });
  py::dict values;
  const std::pair<const char*, int> names[] = {{"x", CC_CURVE_X}, {"F", CC_CURVE_F}, {"sigma_x", CC_CURVE_SIGMA_X},
                                               {"sigma_F", CC_CURVE_SIGMA_F}, {"branch", CC_CURVE_BRANCH},
                                               {"line", CC_CURVE_LINE}};
  for (const auto& [name, column] : names) {
    py::array_t<double> a(n);
    if (cc_curve_column(curve.get(), column, a.mutable_data()) == CC_OK) values[name] = a;
  }
  char units[4096];
  call_held([&] { return cc_curve_units(curve.get(), units, static_cast<int>(sizeof units)); });
  return py::make_tuple(kind, std::string(units), values);
}

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "Compiled bindings of the coatcontact C API; use the coatcontact package.";
  py::register_exception<NumericalError>(m, "NumericalError", PyExc_RuntimeError);

  m.attr("REDUCED_COLUMNS") = CC_REDUCED_COLUMNS;
  m.attr("PULLOFF_LOAD_SEVERAL_MINIMA") = CC_PULLOFF_LOAD_SEVERAL_MINIMA;
  m.attr("PULLOFF_LOAD_NO_MINIMUM") = CC_PULLOFF_LOAD_NO_MINIMUM;
  m.attr("PULLOFF_DISP_SEVERAL_MINIMA") = CC_PULLOFF_DISP_SEVERAL_MINIMA;
  m.attr("PULLOFF_DISP_NO_MINIMUM") = CC_PULLOFF_DISP_NO_MINIMUM;
  m.attr("PULLOFF_SCAN_TRUNCATED") = CC_PULLOFF_SCAN_TRUNCATED;
  m.attr("FIT_RADIUS_FORCE") = static_cast<int>(CC_FIT_RADIUS_FORCE);
  m.attr("FIT_PENETRATION_FORCE") = static_cast<int>(CC_FIT_PENETRATION_FORCE);

  py::class_<Stack>(m, "Stack")
      .def(py::init<>())
      .def("add_layer", [](Stack& s, double t, double e, double nu, bool slip) {
        call_held([&] { return cc_stack_add_layer(s.handle.get(), t, e, nu, slip ? 1 : 0); });
      })
      .def("set_substrate", [](Stack& s, double e, double nu) {
        call_held([&] { return cc_stack_set_substrate(s.handle.get(), e, nu); });
      })
      .def("set_rigid_substrate", [](Stack& s) {
        call_held([&] { return cc_stack_set_rigid_substrate(s.handle.get()); });
      })
      .def("set_indenter", [](Stack& s, double e, double nu) {
        call_held([&] { return cc_stack_set_indenter(s.handle.get(), e, nu); });
      })
      .def("set_rigid_indenter", [](Stack& s) {
        call_held([&] { return cc_stack_set_rigid_indenter(s.handle.get()); });
      })
      .def("reference_modulus", [](const Stack& s) {
        double e = 0.0;
        call_held([&] { return cc_stack_reference_modulus(s.handle.get(), &e); });
        return e;
      });

  py::class_<Solver>(m, "Solver")
      .def(py::init<const Stack&>())
      .def("sweep", &Solver::sweep, py::arg("a_over_t"), py::arg("tolerance"), py::arg("progress") = py::none())
      .def("sweep_each", &Solver::sweep_each, py::arg("a_over_t"), py::arg("tolerance"),
           py::arg("progress") = py::none())
      .def("time_c_call", &Solver::time_c_call);

  py::class_<Model>(m, "Model")
      .def(py::init<const Solver&, double>())
      .def("default_range", &Model::default_range)
      .def("curve", &Model::curve)
      .def("curve_each", &Model::curve_each)
      .def("pulloff", &Model::pulloff, py::arg("eta"), py::arg("progress") = py::none());

  py::class_<Contact>(m, "Contact")
      .def(py::init<const Model&, double, double, double>())
      .def("scales", &Contact::scales)
      .def("curve", &Contact::curve)
      .def("at", &Contact::at)
      .def("at_each", &Contact::at_each)
      .def("pulloff", &Contact::pulloff)
      .def("validity", &Contact::validity);

  m.def("fit", &fit);
  m.def("fit_stack", &fit_stack);
  m.attr("FIT_BASE_FORCE") = static_cast<int>(CC_FIT_BASE_FORCE);
  m.attr("FIT_JKR") = static_cast<int>(CC_FIT_JKR);
  m.attr("FIT_MAUGIS_DUGDALE") = static_cast<int>(CC_FIT_MAUGIS_DUGDALE);

  m.def("pulloff_spring", &pulloff_spring);
  m.def("read_curve", &read_curve);
  py::class_<MaugisDugdale>(m, "MaugisDugdale")
      .def(py::init<const Stack&, bool>())
      .def("curve", &MaugisDugdale::curve)
      .def("pulloff", &MaugisDugdale::pulloff);
  py::class_<Shape>(m, "Shape");
  m.def("make_shape", &make_shape);
  m.def("fit_run", &fit_run);
  m.def("make_profile", &make_profile);
  py::class_<ShapeContact>(m, "ShapeContact")
      .def(py::init<const Stack&, const Shape&, double, double, double>())
      .def("default_range", &ShapeContact::default_range)
      .def("curve", &ShapeContact::curve)
      .def("curve_each", &ShapeContact::curve_each)
      .def("pulloff", &ShapeContact::pulloff)
      .def("validity", &ShapeContact::validity);
  register_kinetics(m);
  register_indent(m);
  register_indent_analysis(m);
  register_afm(m);
}
