// coatcontact._core.kinetics: rate-dependent adhesion (THEORY.md section 14) for Python. Built
// on the C++ library directly (the crack-kinetics run has no C API yet); the Python layer
// (coatcontact/kinetics.py) adds keyword arguments and the protocol's spelling.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "coatcontact/crack_kinetics.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/kinetics_fit.hpp"
#include "coatcontact/reduced.hpp"
#include "module_errors.hpp"

namespace py = pybind11;

namespace {

using Segment = std::tuple<std::string, double, double, double, bool>;  // kind, speed, duration, force, has

py::array_t<double> array_of(const std::vector<double>& v) {
  py::array_t<double> a(static_cast<py::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

py::dict event(const coatcontact::KineticsEventSI& e) {
  py::dict d;
  d["F"] = e.force;
  d["t"] = e.time;
  d["a"] = e.radius;
  return d;
}

using coatcontact_python::without_gil;

std::vector<coatcontact::KineticsSegmentSI> segments_of(const std::vector<Segment>& protocol) {
  using coatcontact::DriveSegment;
  std::vector<coatcontact::KineticsSegmentSI> out;
  for (const auto& [kind, speed, duration, force, has] : protocol) {
    coatcontact::KineticsSegmentSI s;
    if (kind == "approach") s.kind = DriveSegment::Kind::kApproach;
    else if (kind == "dwell") s.kind = DriveSegment::Kind::kDwell;
    else if (kind == "retract") s.kind = DriveSegment::Kind::kRetract;
    else throw py::value_error("protocol: unknown segment '" + kind + "' (approach, dwell or retract)");
    s.speed = speed;
    s.duration = duration;
    s.target_force = force;
    s.has_target = has;
    out.push_back(s);
  }
  return out;
}

coatcontact::Stack film_stack(double film_e, double film_nu, bool rigid, double sub_e, double sub_nu) {
  coatcontact::Material film{film_e, film_nu};
  coatcontact::Substrate substrate;
  substrate.rigid = rigid;
  substrate.material = coatcontact::Material{sub_e, sub_nu};
  return coatcontact::Stack::film_on(film, substrate);
}

// One measured curve: protocol, spring k, t, F, sigma_F (empty: unweighted).
using Curve = std::tuple<std::vector<Segment>, double, std::vector<double>, std::vector<double>, std::vector<double>>;

py::dict kinetics_fit(py::object numerical_error, double film_e, double film_nu, bool rigid, double sub_e,
                      double sub_nu, double radius, double thickness, double work, double v_star, double n,
                      double v_star_adv, double n_adv, const std::vector<Curve>& curves,
                      const std::vector<bool>& free, double tol) {
  using namespace coatcontact;
  if (free.size() != static_cast<std::size_t>(fit::kKineticsParameterCount)) throw py::value_error("free: five flags");
  fit::KineticsFitProblem problem;
  problem.radius = radius;
  problem.thickness = thickness;
  problem.work = work;
  problem.v_star = v_star;
  problem.n = n;
  problem.v_star_adv = v_star_adv;
  problem.n_adv = n_adv;
  problem.solver_tolerance = tol;
  for (int j = 0; j < fit::kKineticsParameterCount; ++j) problem.free[static_cast<std::size_t>(j)] = free[j];
  std::vector<fit::KineticsCurve> data;
  for (const auto& [protocol, spring, t, f, sigma] : curves) {
    fit::KineticsCurve c;
    c.protocol = segments_of(protocol);
    c.spring = spring;
    c.time = t;
    c.force = f;
    c.sigma_force = sigma;
    data.push_back(std::move(c));
  }
  fit::Result r;
  without_gil(numerical_error,
              [&] { r = fit::fit_kinetics(film_stack(film_e, film_nu, rigid, sub_e, sub_nu), data, problem); });
  py::dict out;
  std::vector<std::string> names;
  for (const auto& info : r.parameters) names.push_back(info.name);
  out["names"] = names;
  out["values"] = array_of(r.value);
  out["errors"] = array_of(r.standard_error);
  out["free"] = r.free;
  out["correlation"] = r.correlation;
  out["F_model"] = array_of(r.model_force);
  out["residual"] = array_of(r.residual);
  out["r_squared"] = r.r_squared;
  if (r.weighted) {
    out["chi2_per_dof"] = r.chi2_per_dof;
  } else {
    out["chi2_per_dof"] = py::none();
  }
  out["residual_sigma"] = r.residual_sigma;
  out["iterations"] = r.iterations;
  out["simulations"] = r.solver_calls;
  out["seconds"] = r.seconds;
  return out;
}

py::dict kinetics(py::object numerical_error, double film_e, double film_nu, bool rigid, double sub_e, double sub_nu,
                  double radius, double half_angle, double thickness, double work, double v_star, double n,
                  double v_star_adv, double n_adv, double spring, const std::vector<Segment>& protocol,
                  const std::vector<double>& retract_speeds, double tol) {
  using namespace coatcontact;
  KineticsSetupSI setup;
  setup.radius = radius;
  if (half_angle != 0.0) {  // a cone (section 14, "The cone")
    setup.tip = KineticsTip::kCone;
    setup.half_angle = half_angle;
  }
  setup.thickness = thickness;
  setup.work = work;
  setup.v_star = v_star;
  setup.n = n;
  setup.v_star_adv = v_star_adv;
  setup.n_adv = n_adv;
  setup.spring = spring;
  setup.protocol = segments_of(protocol);
  std::vector<KineticsResultSI> runs;
  KineticsScales scales;
  without_gil(numerical_error, [&] {
    const ReducedSolver solver(film_stack(film_e, film_nu, rigid, sub_e, sub_nu));
    const AdhesiveModel model(solver, tol);
    scales = kinetics_scales(model, setup);
    runs = simulate_kinetics_si(model, setup, retract_speeds, retract_speeds.empty());
  });
  py::dict out;
  py::dict sc;
  sc["l"] = scales.length;
  sc["delta_scale"] = scales.penetration;
  sc["F_scale"] = scales.force;
  sc["t_scale"] = scales.time;
  sc["eta"] = scales.eta;
  sc["k_bar"] = scales.k_bar;
  sc["drive_rate"] = scales.drive_rate;
  out["scales"] = sc;
  if (retract_speeds.empty()) {
    const KineticsResultSI& r = runs.front();
    out["t"] = array_of(r.t);
    out["z"] = array_of(r.z);
    out["delta"] = array_of(r.delta);
    out["a"] = array_of(r.a);
    out["F"] = array_of(r.force);
    out["G"] = array_of(r.g);
    out["pulloff"] = event(r.pulloff);
    out["loss"] = event(r.loss);
    out["work"] = r.reduced.work;
    out["dissipation"] = r.reduced.dissipation;
    out["steps"] = r.reduced.steps;
  } else {
    std::vector<double> v, f, t, a, fl, tl, p;
    for (const KineticsResultSI& r : runs) {
      v.push_back(r.retract_speed);
      f.push_back(r.pulloff.force);
      t.push_back(r.pulloff.time);
      a.push_back(r.pulloff.radius);
      fl.push_back(r.loss.force);
      tl.push_back(r.loss.time);
      p.push_back(r.reduced.pulloff.load);
    }
    py::dict s;
    s["V"] = array_of(v);
    s["F"] = array_of(f);
    s["t"] = array_of(t);
    s["a"] = array_of(a);
    s["F_loss"] = array_of(fl);
    s["t_loss"] = array_of(tl);
    s["P"] = array_of(p);
    out["sweep"] = s;
  }
  return out;
}

}  // namespace

void register_kinetics(py::module_& m) {
  m.def("kinetics_fit", [m](double film_e, double film_nu, bool rigid, double sub_e, double sub_nu, double radius,
                            double thickness, double work, double v_star, double n, double v_star_adv, double n_adv,
                            const std::vector<Curve>& curves, const std::vector<bool>& free, double tol) {
    return kinetics_fit(m.attr("NumericalError"), film_e, film_nu, rigid, sub_e, sub_nu, radius, thickness, work,
                        v_star, n, v_star_adv, n_adv, curves, free, tol);
  });
  m.def("kinetics", [m](double film_e, double film_nu, bool rigid, double sub_e, double sub_nu, double radius,
                        double half_angle, double thickness, double work, double v_star, double n,
                        double v_star_adv, double n_adv, double spring, const std::vector<Segment>& protocol,
                        const std::vector<double>& retract_speeds, double tol) {
    return kinetics(m.attr("NumericalError"), film_e, film_nu, rigid, sub_e, sub_nu, radius, half_angle, thickness,
                    work, v_star, n, v_star_adv, n_adv, spring, protocol, retract_speeds, tol);
  });
}
