// The fit model at the data points: THEORY.md section 5 through the adhesion floor. The JKR
// law gives P, D and their a_bar derivatives in Maugis units; Contact's scales turn them
// into SI. The w and t derivatives follow from the same law (see ContactModel::to_si).
#include "fit_model.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

#include "coatcontact/detail/format.hpp"
#include "coatcontact/detail/gsl_handler_off.hpp"
#include "coatcontact/errors.hpp"

namespace coatcontact::fit::internal {
namespace {

using coatcontact::detail::short_text;

// Range of a/t the fit may ask for (kAOverTRange, fit.hpp): far beyond both limits of
// THEORY.md section 6 (the reduced variables have reached their asymptotes), so leaving it
// means a parameter ran away.
constexpr double kMinAOverT = kAOverTRange[0];
constexpr double kMaxAOverT = kAOverTRange[1];
// Relative step of the central difference in ln E1: truncation ~h^2/6 ~ 2e-7, noise of the
// interpolated values ~tolerance/h ~ 1e-5 relative.
constexpr double kStep = 1e-3;
// Grid ratio above the pull-off radius on which a measured delta is bracketed (delta(a)
// rises monotonically there; 32 points per decade as AdhesiveModel's pull-off scan).
const double kBracketRatio = std::pow(10.0, 1.0 / 32.0);
constexpr std::size_t kMaxBracketSteps = 32 * 6;  // six decades above a_c
// Top of the pull-off scan in units of max(1, r), r = (E1*/E0*)^(1/3) (ModelEntry).
constexpr double kPulloffScanTop = 2.0;
// Data points checked against direct solves after the fit: a direct solve at a/t ~ 20 costs
// as much as a whole fit's worth of interpolation, and the interpolant's error varies smoothly,
// so a spread-out sample finds its maximum.
constexpr std::size_t kCheckedPoints = 16;

// Brent root of f on [lo, hi] (f(lo) < 0 <= f(hi)).
double find_root(const std::function<double(double)>& f, double lo, double hi) {
  if (f(hi) == 0.0) return hi;
  gsl_function gf;
  gf.function = [](double x, void* params) {
    return (*static_cast<const std::function<double(double)>*>(params))(x);
  };
  gf.params = const_cast<std::function<double(double)>*>(&f);
  std::unique_ptr<gsl_root_fsolver, void (*)(gsl_root_fsolver*)> solver(
      gsl_root_fsolver_alloc(gsl_root_fsolver_brent), gsl_root_fsolver_free);
  if (!solver || gsl_root_fsolver_set(solver.get(), &gf, lo, hi) != GSL_SUCCESS) {
    throw NumericalError("could not bracket a measured penetration on the model curve");
  }
  for (int iteration = 0; iteration < 200; ++iteration) {
    if (gsl_root_fsolver_iterate(solver.get()) != GSL_SUCCESS) break;
    if (gsl_root_test_interval(gsl_root_fsolver_x_lower(solver.get()),
                               gsl_root_fsolver_x_upper(solver.get()), 0.0, 1e-13) == GSL_SUCCESS) {
      return gsl_root_fsolver_root(solver.get());
    }
  }
  throw NumericalError("root finder on the model curve did not converge");
}

ReducedPoint values_only(const ReducedVariables& v) {
  ReducedPoint r;
  r.a_over_t = v.a_over_t;
  r.pi_s = v.pi_s;
  r.delta_s = v.delta_s;
  r.pi_c = v.pi_c;
  r.delta_c = v.delta_c;
  r.e_eq = v.e_eq;
  r.gamma1 = v.gamma1;
  return r;
}

// The same point with d ln X/d ln(a/t) = 0: the law's a_bar derivative is then the explicit
// one, at fixed a/t.
ReducedPoint frozen(ReducedPoint r) {
  r.dlog_pi_s = r.dlog_delta_s = r.dlog_pi_c = r.dlog_delta_c = r.dlog_e_eq = r.dlog_gamma1 = 0.0;
  return r;
}

}  // namespace

// ---- parameters -----------------------------------------------------------------------------

Parameters Parameters::branch(bool unloading) const {
  Parameters out(std::vector<double>(values.begin(), values.begin() + static_cast<long>(1 + 2 * layers)), layers);
  out.values[kWork] = unloading ? unload_work() : work();
  if (spring) {
    out.values.push_back(stiffness());
    out.spring = true;
  }
  if (md) {
    out.values.push_back(lambda());
    out.md = true;
  }
  return out;
}

double Parameters::total_thickness() const {
  double total = 0.0;
  for (std::size_t i = 0; i < layers; ++i) total += thickness(i);
  return total;
}

std::vector<Layer> problem_layers(const Problem& problem) {
  if (!problem.layers.empty()) return problem.layers;
  return {Layer{problem.thickness, problem.film}};
}

Parameters problem_parameters(const Problem& problem) {
  const std::vector<Layer> layers = problem_layers(problem);
  const std::size_t n = layers.size();
  std::vector<double> v(1 + 2 * n + (problem.hysteresis ? 1 : 0));
  v[kWork] = problem.work;
  for (std::size_t i = 0; i < n; ++i) {
    v[thickness_index(i)] = layers[i].thickness;
    v[modulus_index(i, n)] = layers[i].material.youngs_modulus;
  }
  if (problem.hysteresis) v[unload_work_index(n)] = problem.unload_work;
  if (problem.base_displacement) v.push_back(problem.spring_stiffness);
  if (problem.maugis_dugdale) v.push_back(problem.lambda);
  Parameters p(std::move(v), n, problem.hysteresis, problem.base_displacement);
  p.md = problem.maugis_dugdale;
  return p;
}

std::vector<int> free_indices(const Problem& problem) {
  std::vector<int> out;
  if (problem.layers.empty() && !problem.hysteresis && !problem.base_displacement && !problem.maugis_dugdale) {
    for (int which = 0; which < kParameterCount; ++which) {
      if (problem.free[which]) out.push_back(which);
    }
    return out;
  }
  for (std::size_t which : problem.free_parameters) out.push_back(static_cast<int>(which));
  if (out.empty() && problem.free[kWork]) out.push_back(kWork);
  std::sort(out.begin(), out.end());
  return out;
}

StackKey StackKey::of(const Parameters& p) {
  StackKey key;
  const double total = p.total_thickness();
  for (std::size_t i = 0; i < p.layers; ++i) {
    // One film: exactly 1 (the film is the unit length, as Stack::film_on has it).
    key.relative_thickness.push_back(p.layers == 1 ? 1.0 : p.thickness(i) / total);
    key.modulus.push_back(p.modulus(i));
  }
  return key;
}

// ---- entries and cache ------------------------------------------------------------------

ModelEntry::ModelEntry(const Problem& problem, const StackKey& key) : key_(key) {
  std::vector<Layer> layers = problem_layers(problem);
  for (std::size_t i = 0; i < layers.size(); ++i) {
    layers[i].thickness = key.relative_thickness[i];
    layers[i].material.youngs_modulus = key.modulus[i];
  }
  if (problem.maugis_dugdale) {
    md_model_ = std::make_unique<MaugisDugdaleModel>(Stack(layers, problem.substrate, problem.indenter));
    return;
  }
  if (problem.shape) {
    // A shape: direct solves on the shape floor's factorization, no reduced table.
    shape_solver_ = std::make_unique<ShapeSolver>(Stack(layers, problem.substrate, problem.indenter));
    return;
  }
  solver_ = std::make_unique<ReducedSolver>(Stack(layers, problem.substrate, problem.indenter));
  // The minimum of D lies at a_bar = 1/2 (top layer) and r/2 (base) in the JKR limits
  // (THEORY.md section 6): scanning up to 2 max(1, r), not the default 10 max(1, r), finds it
  // and spares the costly solves at large a/t (~25 ms each above a/t = 10).
  PulloffOptions pulloff;
  pulloff.a_bar_max = kPulloffScanTop * std::max(1.0, solver_->stack().substrate_length_ratio());
  model_ = std::make_unique<AdhesiveModel>(*solver_, problem.solver_tolerance, TableOptions{}, pulloff);
}

ModelEntry& ModelCache::get(const Parameters& p) {
  const StackKey key = StackKey::of(p);
  for (auto it = entries_.begin(); it != entries_.end(); ++it) {
    if ((*it)->key() == key) {
      std::rotate(entries_.begin(), it, it + 1);
      return *entries_.front();
    }
  }
  if (entries_.size() >= capacity_) {
    if (entries_.back()->has_model()) {
      retired_calls_ += static_cast<long>(entries_.back()->model().table().source_evaluations());
    }
    entries_.pop_back();
  }
  entries_.insert(entries_.begin(), std::make_unique<ModelEntry>(problem_, key));
  return *entries_.front();
}

long ModelCache::solver_calls() const {
  long calls = retired_calls_;
  for (const auto& e : entries_) {
    if (e->has_model()) calls += static_cast<long>(e->model().table().source_evaluations());
  }
  return calls;
}

// ---- one parameter set --------------------------------------------------------------------

ContactModel::ContactModel(const AdhesiveModel& model, double sphere_radius, const Parameters& p)
    : model_(model), total_thickness_(p.total_thickness()), contact_(model, sphere_radius, total_thickness_, p.work()) {}

void ContactModel::prepare(double radius_min, double radius_max) const {
  model_.table().prepare(radius_min / total_thickness_, radius_max / total_thickness_);
}

void ContactModel::prepare_pulloff() const {
  // The pull-off scan would build its decades one source call each; one batched call is
  // faster (the solver's sweep runs in parallel). A failure is left to the scan, which stops
  // below the failing decade and says so.
  const PulloffOptions& options = model_.pulloff_options();
  const double r = model_.stack().substrate_length_ratio();
  const double lo = options.a_bar_min > 0.0 ? options.a_bar_min : 1e-3 * std::min(1.0, r);
  const double hi = options.a_bar_max > 0.0 ? options.a_bar_max : 10.0 * std::max(1.0, r);
  try {
    model_.table().prepare(lo / contact_.eta(), hi / contact_.eta());
  } catch (const NumericalError&) {
  }
}

// In Maugis units (THEORY.md section 5) F = pi w R P(a_bar, x) and delta = (l^2/R) D(a_bar, x)
// with a_bar = a/l, l = (pi w R^2/E1*)^(1/3) ~ w^(1/3) and x = ln(a/t); the JKR law depends on
// w only through these scales. With P' = dP/da_bar along the curve and P'_x the same at fixed x:
//   dF/da       = pi w R P'/l
//   dF/d ln t   = -pi w R a_bar (P' - P'_x)          (at fixed a: only x moves)
//   dF/d ln w   = F - pi w R a_bar P'_x / 3          (at fixed a: a_bar ~ w^(-1/3))
//   d delta/d ln w = (2/3) delta - (l^2/R) a_bar D'_x / 3
SiPoint ContactModel::to_si(const coatcontact::CurvePoint& full,
                             const coatcontact::CurvePoint& fixed_x) const {
  const double l = contact_.length_scale();
  const double fs = contact_.force_scale();
  const double ds = contact_.penetration_scale();
  const double a_bar = full.a_bar;
  SiPoint s;
  s.radius = a_bar * l;
  s.force = fs * full.load;
  s.penetration = ds * full.penetration;
  s.force_a = fs * full.dload / l;
  s.penetration_a = ds * full.dpenetration / l;
  s.force_lnt = -fs * a_bar * (full.dload - fixed_x.dload);
  s.penetration_lnt = -ds * a_bar * (full.dpenetration - fixed_x.dpenetration);
  s.force_lnw = s.force - fs * a_bar * fixed_x.dload / 3.0;
  s.penetration_lnw = 2.0 * s.penetration / 3.0 - ds * a_bar * fixed_x.dpenetration / 3.0;
  return s;
}

SiPoint ContactModel::at(double radius) const {
  const double eta = contact_.eta();
  const double a_bar = radius / contact_.length_scale();
  const ReducedPoint r = model_.table().at(a_bar / eta);
  SiPoint s = to_si(model_.law().point(r, eta, a_bar), model_.law().point(frozen(r), eta, a_bar));
  s.radius = radius;
  return s;
}

SiPoint ContactModel::exact(const ReducedVariables& v, double radius) const {
  const double eta = contact_.eta();
  const double a_bar = radius / contact_.length_scale();
  const coatcontact::CurvePoint p = model_.law().point(values_only(v), eta, a_bar);
  SiPoint s = to_si(p, p);  // values only: no derivatives without the interpolant
  s.radius = radius;
  return s;
}

// ---- the model at the data ------------------------------------------------------------------

namespace {
// The stack and its two neighbours in each free parameter that changes the table, and one
// spare (the legacy minimum of four for one film).
std::size_t cache_capacity(const Problem& problem) {
  const Parameters p = problem_parameters(problem);
  const std::vector<ParameterInfo> names = parameter_list(p.layers, p.hysteresis, p.spring);
  std::size_t changing = 0;
  for (int which : free_indices(problem)) {
    if (names[which].kind != ParameterKind::kWork && names[which].kind != ParameterKind::kSpring &&
        names[which].kind != ParameterKind::kLambda &&
        !(which == kThickness && p.layers == 1)) {
      ++changing;
    }
  }
  return std::max<std::size_t>(4, 2 + 2 * changing);
}
}  // namespace

Model::Model(const Problem& problem, const Measurements& data)
    : problem_(problem), data_(&data), cache_(problem, cache_capacity(problem)),
      names_(parameter_list(problem_layers(problem).size(), problem.hysteresis, problem.base_displacement,
                            problem.maugis_dugdale)) {}

void Model::check_range(const Parameters& p) const {
  for (std::size_t which = 0; which < p.values.size(); ++which) {
    const double v = p.values[which];
    const ParameterInfo& info = names_[which];
    if (info.kind == ParameterKind::kWork && !(v >= kWorkRange[0] && v <= kWorkRange[1])) {
      throw NumericalError(info.name + " ran to " + short_text(v) + " J/m2, outside [" + short_text(kWorkRange[0]) +
                           ", " + short_text(kWorkRange[1]) + "]: the data do not determine " + info.name);
    }
    if (info.kind == ParameterKind::kModulus && !(v >= kModulusRange[0] && v <= kModulusRange[1])) {
      throw NumericalError(info.name + " ran to " + short_text(v) + " Pa, outside [" + short_text(kModulusRange[0]) +
                           ", " + short_text(kModulusRange[1]) + "]: the data do not determine " + info.name);
    }
  }
  for (std::size_t which = 0; which < p.values.size(); ++which) {
    const double v = p.values[which];
    const ParameterInfo& info = names_[which];
    if (info.kind == ParameterKind::kLambda && !(v >= kLambdaRange[0] && v <= kLambdaRange[1])) {
      throw NumericalError("lambda ran to " + short_text(v) + ", outside [" + short_text(kLambdaRange[0]) + ", " +
                           short_text(kLambdaRange[1]) + "]: the data do not determine lambda");
    }
    if (info.kind == ParameterKind::kSpring && (!(v > 0.0) || !std::isfinite(v))) {
      throw NumericalError("k ran to " + short_text(v) + " N/m: the data do not determine the spring stiffness k");
    }
    if (info.kind == ParameterKind::kThickness && (!(v > 0.0) || !std::isfinite(v))) {
      throw NumericalError(info.name + " ran to " + short_text(v) + " m: the data do not determine " + info.name);
    }
  }
}

std::string Model::describe(const Parameters& p) const {
  std::string text;
  for (std::size_t which = 0; which < p.values.size(); ++which) {
    text += (text.empty() ? "" : ", ") + names_[which].name + " = " + short_text(p.values[which]) + " " +
            names_[which].unit;
  }
  return text;
}

void Model::rethrow_at(const Parameters& p) const {
  std::string what;
  try {
    throw;
  } catch (const std::exception& error) {
    what = error.what();
  }
  throw NumericalError("model evaluation failed at " + describe(p) + " (" + what +
                       "); if the fit wandered there, try start values closer to the solution");
}

ModelAtData Model::at_data(const Parameters& p, bool with_pulloff) {
  check_range(p);
  coatcontact::detail::GslHandlerOff handler_off;
  try {
    return evaluate(p, with_pulloff);
  } catch (const std::exception&) {
    rethrow_at(p);
  }
}

// Two adhesion energies: each branch's points with their own w (the unloading branch's
// pull-offs are the ones reported), merged back into the data's order.
ModelAtData Model::evaluate(const Parameters& p, bool with_pulloff) {
  if (!p.hysteresis) return evaluate_single(p, *data_, with_pulloff);
  const Measurements& data = *data_;
  const std::size_t n = data.size();
  ModelAtData out;
  out.radius.resize(n);
  out.penetration.resize(n);
  out.force.resize(n);
  out.force_lnw.resize(n);
  out.force_lnt.resize(n);
  out.slope.resize(n);
  out.force_x.resize(n);
  out.clamped.resize(n);
  for (const bool unloading : {false, true}) {
    Measurements part;
    part.kind = data.kind;
    std::vector<std::size_t> index;
    for (std::size_t i = 0; i < n; ++i) {
      if (data.unloading[i] != unloading) continue;
      index.push_back(i);
      part.abscissa.push_back(data.abscissa[i]);
      part.force.push_back(data.force[i]);
    }
    if (index.empty()) continue;
    const ModelAtData m = evaluate_single(p.branch(unloading), part, unloading && with_pulloff);
    for (std::size_t k = 0; k < index.size(); ++k) {
      const std::size_t i = index[k];
      out.radius[i] = m.radius[k];
      out.penetration[i] = m.penetration[k];
      out.force[i] = m.force[k];
      out.force_lnw[i] = m.force_lnw[k];
      out.force_lnt[i] = m.force_lnt[k];
      out.slope[i] = m.slope[k];
      out.force_x[i] = m.force_x[k];
      out.clamped[i] = m.clamped[k];
    }
    if (unloading) {
      out.has_pulloff = m.has_pulloff;
      out.pulloff_radius = m.pulloff_radius;
      out.pulloff_penetration = m.pulloff_penetration;
      out.pulloff_force = m.pulloff_force;
      out.has_load_pulloff = m.has_load_pulloff;
      out.load_pulloff_radius = m.load_pulloff_radius;
      out.load_pulloff_penetration = m.load_pulloff_penetration;
      out.load_pulloff_force = m.load_pulloff_force;
    }
  }
  return out;
}

ModelAtData Model::evaluate_single(const Parameters& p, const Measurements& data_, bool with_pulloff) {
  if (problem_.shape) return evaluate_shape(p, data_, with_pulloff);
  if (problem_.maugis_dugdale) return evaluate_md(p, data_, with_pulloff);
  const ContactModel cm(cache_.get(p).model(), problem_.sphere_radius, p);
  const double total_thickness = p.total_thickness();
  const std::size_t n = data_.size();
  ModelAtData out;
  out.radius.resize(n);
  out.penetration.resize(n);
  out.force.resize(n);
  out.force_lnw.resize(n);
  out.force_lnt.resize(n);
  out.slope.assign(n, 0.0);
  out.force_x.assign(n, 0.0);
  out.clamped.assign(n, false);
  const auto check_a_over_t = [&](double a) {
    const double x = a / total_thickness;
    if (!(x >= kMinAOverT && x <= kMaxAOverT)) {
      throw NumericalError("the model needs a/t = " + short_text(x) + ", outside [" +
                           short_text(kMinAOverT) + ", " + short_text(kMaxAOverT) + "]");
    }
  };

  const bool radius_data = data_.kind == DataKind::kRadiusForce;
  // z,F data (p.spring): the abscissa is z = delta + F/k; a_c is then the spring pull-off.
  const double compliance = p.spring ? 1.0 / p.stiffness() : 0.0;
  double spring_radius = 0.0, spring_force = 0.0, spring_base = 0.0;
  if (!radius_data || with_pulloff) {
    // For delta,F data the displacement-controlled pull-off bounds the stable branch (a failure
    // to find it fails the evaluation); for a,F data the pull-offs are only reported.
    const Pulloff* pulloff = nullptr;
    try {
      cm.prepare_pulloff();
      pulloff = &cm.contact().pulloff();
    } catch (const NumericalError&) {
      if (!radius_data) throw;
    }
    if (pulloff != nullptr) {
      const PulloffPoint& c = pulloff->displacement_control;
      const double a_c = c.a_bar * cm.contact().length_scale();
      const PulloffPoint& f = pulloff->load_control;
      if (f.interior) {
        out.has_load_pulloff = true;
        out.load_pulloff_radius = f.a_bar * cm.contact().length_scale();
        out.load_pulloff_penetration = f.penetration * cm.contact().penetration_scale();
        out.load_pulloff_force = f.load * cm.contact().force_scale();
      }
      if (c.interior) {
        out.has_pulloff = true;
        out.pulloff_radius = a_c;
        out.pulloff_penetration = c.penetration * cm.contact().penetration_scale();
        out.pulloff_force = c.load * cm.contact().force_scale();
      }
      if (p.spring) {
        // z = delta + F/k data: the branch stable under spring control starts at its pull-off.
        const double k_bar = p.stiffness() * cm.contact().penetration_scale() / cm.contact().force_scale();
        const SpringPulloff s = cm.contact().model().pulloff_spring(cm.contact().eta(), k_bar);
        if (!s.point.interior) {
          throw NumericalError("delta + F/k has no minimum in the scanned range at k = " + short_text(p.stiffness()) +
                               " N/m (no spring-controlled pull-off)");
        }
        spring_radius = s.point.a_bar * cm.contact().length_scale();
        spring_force = s.point.load * cm.contact().force_scale();
        spring_base = s.point.penetration * cm.contact().penetration_scale() + spring_force / p.stiffness();
      } else if (!c.interior && !radius_data) {
        throw NumericalError("delta(a) has no minimum for a_bar in [" + short_text(pulloff->a_bar_scan_min) +
                             ", " + short_text(pulloff->a_bar_scan_max) +
                             "] (no displacement-controlled pull-off)");
      }
    }
  }

  if (radius_data) {
    const auto [lo, hi] = std::minmax_element(data_.abscissa.begin(), data_.abscissa.end());
    check_a_over_t(*lo);
    check_a_over_t(*hi);
    cm.prepare(*lo, *hi);
    for (std::size_t i = 0; i < n; ++i) {
      const SiPoint s = cm.at(data_.abscissa[i]);
      out.radius[i] = s.radius;
      out.penetration[i] = s.penetration;
      out.force[i] = s.force;
      out.force_lnw[i] = s.force_lnw;
      out.force_lnt[i] = s.force_lnt;
      out.force_x[i] = s.force_a;
    }
    return out;
  }

  // delta,F data: each measured delta at a* >= a_c on the stable branch (fit.hpp); z,F data
  // the same with delta + F/k in place of delta.
  const double a_c = p.spring ? spring_radius : out.pulloff_radius;
  const double x_c = p.spring ? spring_base : out.pulloff_penetration;
  const auto abscissa = [&](const SiPoint& s) { return s.penetration + compliance * s.force; };
  const double delta_max = *std::max_element(data_.abscissa.begin(), data_.abscissa.end());
  // Grid upwards from a_c until delta exceeds the largest measured one.
  std::vector<double> grid{a_c};
  std::vector<double> grid_delta{x_c};
  while (grid_delta.back() < delta_max) {
    if (grid.size() > kMaxBracketSteps) {
      throw NumericalError("the model's delta(a) stays below the largest measured delta up to a = " +
                           short_text(grid.back()) + " m");
    }
    const double a = grid.back() * kBracketRatio;
    check_a_over_t(a);
    grid.push_back(a);
    grid_delta.push_back(abscissa(cm.at(a)));
  }
  for (std::size_t i = 0; i < n; ++i) {
    const double delta = data_.abscissa[i];
    double a = a_c;
    if (delta <= x_c) {
      out.clamped[i] = true;
    } else {
      // The first crossing above a_c (the branch reached continuously from the pull-off).
      std::size_t k = 1;
      while (grid_delta[k] < delta) ++k;
      a = find_root([&](double r) { return abscissa(cm.at(r)) - delta; }, grid[k - 1], grid[k]);
    }
    const SiPoint s = cm.at(a);
    out.radius[i] = a;
    out.penetration[i] = s.penetration;
    out.force[i] = s.force;
    if (out.clamped[i]) {
      // Jacobian approximation: the motion of a_c with the parameters is ignored (for every
      // parameter alike; the pull-off at E1 e^(+-h) would cost two more pull-off scans).
      out.force_lnw[i] = s.force_lnw;
      out.force_lnt[i] = s.force_lnt;
    } else {
      // a*(p) from delta(a*, p) = delta_i: d a*/dp = -delta_p / delta_a.
      out.slope[i] = s.force_a / (s.penetration_a + compliance * s.force_a);
      out.force_x[i] = out.slope[i];
      out.force_lnw[i] = s.force_lnw - out.slope[i] * (s.penetration_lnw + compliance * s.force_lnw);
      out.force_lnt[i] = s.force_lnt - out.slope[i] * (s.penetration_lnt + compliance * s.force_lnt);
    }
  }
  return out;
}

// Problem::maugis_dugdale: F = pi w R P, delta = (l^2/R) D at a_bar = a/l, l = (pi w R^2/E*)^(1/3),
// eta = T/l (THEORY.md section 13), from MaugisDugdaleModel::curve at the measured radii.
ModelAtData Model::evaluate_md(const Parameters& p, const Measurements& data, bool with_pulloff) {
  constexpr double kPi = 3.14159265358979323846;
  const MaugisDugdaleModel& md = cache_.get(p).md_model();
  const double radius = problem_.sphere_radius;
  const double work = p.work();
  const double l = std::cbrt(kPi * work * radius * radius / md.stack().reference_modulus());
  const double force_scale = kPi * work * radius, penetration_scale = l * l / radius;
  const double eta = p.total_thickness() / l;
  const double lambda = p.lambda();
  const std::size_t n = data.size();
  ModelAtData out;
  out.radius = data.abscissa;
  out.penetration.resize(n);
  out.force.resize(n);
  out.force_lnw.assign(n, 0.0);  // not used: every derivative is differenced in force_derivatives
  out.force_lnt.assign(n, 0.0);
  out.slope.assign(n, 0.0);
  out.force_x.assign(n, 0.0);
  out.clamped.assign(n, false);
  std::vector<double> a_bar(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double x = data.abscissa[i] / p.total_thickness();
    if (!(x >= kMinAOverT && x <= kMaxAOverT)) {
      throw NumericalError("the model needs a/t = " + short_text(x) + ", outside [" + short_text(kMinAOverT) + ", " +
                           short_text(kMaxAOverT) + "]");
    }
    a_bar[i] = data.abscissa[i] / l;
  }
  const std::vector<MaugisDugdalePoint> points = md.curve(eta, lambda, a_bar);
  shape_calls_ += static_cast<long>(n);
  for (std::size_t i = 0; i < n; ++i) {
    out.force[i] = force_scale * points[i].load;
    out.penetration[i] = penetration_scale * points[i].penetration;
  }
  if (!data.sigma_abscissa.empty()) {
    // dF/da along the curve for the effective variance (relative step kStep in a).
    std::vector<double> up(n), down(n);
    for (std::size_t i = 0; i < n; ++i) {
      up[i] = a_bar[i] * std::exp(kStep);
      down[i] = a_bar[i] * std::exp(-kStep);
    }
    const auto pu = md.curve(eta, lambda, up), pd = md.curve(eta, lambda, down);
    shape_calls_ += static_cast<long>(2 * n);
    for (std::size_t i = 0; i < n; ++i) {
      out.force_x[i] = force_scale * (pu[i].load - pd[i].load) / (l * (up[i] - down[i]));
    }
  }
  if (with_pulloff) {
    try {
      const MaugisDugdalePulloff pulloff = md.pulloff(eta, lambda);
      const MaugisDugdalePulloffPoint& f = pulloff.load_control;
      if (f.interior) {
        out.has_load_pulloff = true;
        out.load_pulloff_radius = f.point.a_bar * l;
        out.load_pulloff_penetration = f.point.penetration * penetration_scale;
        out.load_pulloff_force = f.point.load * force_scale;
      }
      const MaugisDugdalePulloffPoint& c = pulloff.displacement_control;
      if (c.interior) {
        out.has_pulloff = true;
        out.pulloff_radius = c.point.a_bar * l;
        out.pulloff_penetration = c.point.penetration * penetration_scale;
        out.pulloff_force = c.point.load * force_scale;
      }
    } catch (const NumericalError&) {
      // Reported as absent; the fit itself stands.
    }
  }
  return out;
}

ShapeContact Model::shape_contact(const Parameters& branch) {
  return ShapeContact(cache_.get(branch).shape_solver(), problem_.shape, branch.total_thickness(), branch.work(),
                      problem_.solver_tolerance);
}

// Problem::shape: F and delta from ShapeContact at each radius (THEORY.md sections 5, 11). At
// fixed a, F = F_H + S delta_fp and delta = delta_H + delta_fp with delta_fp ~ sqrt(w), so
// dF/d ln w = (F - F_H)/2 and d delta/d ln w = (delta - delta_H)/2 exactly; d/da along the
// curve is a central difference in ln a. delta,F data: a* >= a_c on the stable branch as for
// the sphere, a_c the displacement-controlled pull-off of ShapeContact::pulloff.
ModelAtData Model::evaluate_shape(const Parameters& p, const Measurements& data, bool with_pulloff) {
  const ShapeContact contact = shape_contact(p);
  const double total_thickness = p.total_thickness();
  const std::size_t n = data.size();
  ModelAtData out;
  out.radius.resize(n);
  out.penetration.resize(n);
  out.force.resize(n);
  out.force_lnw.resize(n);
  out.force_lnt.assign(n, 0.0);  // not used: t is differenced in force_derivatives
  out.slope.assign(n, 0.0);
  out.force_x.assign(n, 0.0);
  out.clamped.assign(n, false);
  const auto check_radius = [&](double a) {
    const double x = a / total_thickness;
    if (!(x >= kMinAOverT && x <= kMaxAOverT)) {
      throw NumericalError("the model needs a/t = " + short_text(x) + ", outside [" + short_text(kMinAOverT) + ", " +
                           short_text(kMaxAOverT) + "]");
    }
    if (a > problem_.shape->max_contact_radius()) {
      throw NumericalError("the model needs a contact radius " + short_text(a) + " m beyond the shape's largest, " +
                           short_text(problem_.shape->max_contact_radius()) + " m");
    }
  };
  const auto at = [&](double a) {
    ++shape_calls_;
    return contact.at(a);
  };
  // dF/da and d delta/da along the curve (relative step kStep in a).
  const auto along = [&](double a) {
    const ShapePoint up = at(a * std::exp(kStep)), down = at(a * std::exp(-kStep));
    const double da = a * (std::exp(kStep) - std::exp(-kStep));
    return std::array<double, 2>{(up.force - down.force) / da, (up.penetration - down.penetration) / da};
  };
  const bool radius_data = data.kind == DataKind::kRadiusForce;
  const bool need_slope = !data.sigma_abscissa.empty();
  if (!radius_data || with_pulloff) {
    ShapePulloff pulloff;
    bool found = false;
    try {
      pulloff = contact.pulloff(0.0);
      found = true;
    } catch (const NumericalError&) {
      if (!radius_data) throw;
    }
    if (found) {
      if (pulloff.load.interior) {
        out.has_load_pulloff = true;
        out.load_pulloff_radius = pulloff.load.radius;
        out.load_pulloff_penetration = pulloff.load.penetration;
        out.load_pulloff_force = pulloff.load.force;
      }
      if (pulloff.displacement.interior) {
        out.has_pulloff = true;
        out.pulloff_radius = pulloff.displacement.radius;
        out.pulloff_penetration = pulloff.displacement.penetration;
        out.pulloff_force = pulloff.displacement.force;
      } else if (!radius_data) {
        throw NumericalError("delta(a) of the shape has no minimum for a in [" + short_text(pulloff.scan_min) + ", " +
                             short_text(pulloff.scan_max) + "] m (no displacement-controlled pull-off)");
      }
    }
  }
  if (radius_data) {
    for (std::size_t i = 0; i < n; ++i) check_radius(data.abscissa[i]);
    const std::vector<ShapePoint> points = contact.curve(data.abscissa);
    shape_calls_ += static_cast<long>(n);
    for (std::size_t i = 0; i < n; ++i) {
      out.radius[i] = points[i].radius;
      out.penetration[i] = points[i].penetration;
      out.force[i] = points[i].force;
      out.force_lnw[i] = (points[i].force - points[i].force_h) / 2.0;
      if (need_slope) out.force_x[i] = along(points[i].radius)[0];
    }
    return out;
  }
  const double a_c = out.pulloff_radius;
  const double delta_max = *std::max_element(data.abscissa.begin(), data.abscissa.end());
  std::vector<double> grid{a_c};
  std::vector<double> grid_delta{out.pulloff_penetration};
  while (grid_delta.back() < delta_max) {
    if (grid.size() > kMaxBracketSteps) {
      throw NumericalError("the model's delta(a) stays below the largest measured delta up to a = " +
                           short_text(grid.back()) + " m");
    }
    const double a = std::min(grid.back() * kBracketRatio, problem_.shape->max_contact_radius());
    if (!(a > grid.back())) throw NumericalError("the largest measured delta is beyond the shape's largest radius");
    check_radius(a);
    grid.push_back(a);
    grid_delta.push_back(at(a).penetration);
  }
  for (std::size_t i = 0; i < n; ++i) {
    const double delta = data.abscissa[i];
    double a = a_c;
    if (delta <= out.pulloff_penetration) {
      out.clamped[i] = true;
    } else {
      std::size_t k = 1;
      while (grid_delta[k] < delta) ++k;
      a = find_root([&](double r) { return at(r).penetration - delta; }, grid[k - 1], grid[k]);
    }
    const ShapePoint s = at(a);
    out.radius[i] = a;
    out.penetration[i] = s.penetration;
    out.force[i] = s.force;
    const double force_lnw = (s.force - s.force_h) / 2.0;
    const double penetration_lnw = (s.penetration - s.penetration_h) / 2.0;
    if (out.clamped[i]) {
      out.force_lnw[i] = force_lnw;
    } else {
      const auto d = along(a);
      out.slope[i] = d[0] / d[1];
      out.force_x[i] = out.slope[i];
      out.force_lnw[i] = force_lnw - out.slope[i] * penetration_lnw;
    }
  }
  return out;
}

std::vector<std::vector<double>> Model::force_derivatives(const Parameters& p, const ModelAtData& m,
                                                          const std::vector<int>& which) {
  const std::size_t n = m.radius.size();
  std::vector<std::vector<double>> columns;
  for (int parameter : which) {
    const auto shifted = [&](double sign) {
      Parameters q = p;
      q.values[static_cast<std::size_t>(parameter)] *= std::exp(sign * kStep);
      return q;
    };
    std::vector<double> column(n, 0.0);
    if (problem_.maugis_dugdale) {
      // Every parameter by a central difference in ln p at the measured a (a,F data only).
      for (double sign : {1.0, -1.0}) {
        const Parameters q = shifted(sign);
        check_range(q);
        coatcontact::detail::GslHandlerOff handler_off;
        try {
          const ModelAtData mq = evaluate_md(q, *data_, false);
          for (std::size_t i = 0; i < n; ++i) column[i] += sign * mq.force[i] / (2.0 * kStep);
        } catch (const std::exception&) {
          rethrow_at(q);
        }
      }
      columns.push_back(std::move(column));
      continue;
    }
    const bool is_unload_work = p.hysteresis && static_cast<std::size_t>(parameter) == unload_work_index(p.layers);
    if (parameter == kWork || is_unload_work) {
      // With two adhesion energies each moves only the points of its own branch.
      column = m.force_lnw;
      if (p.hysteresis) {
        const Measurements& data = *data_;
        for (std::size_t i = 0; i < n; ++i) {
          if (data.unloading[i] != is_unload_work) column[i] = 0.0;
        }
      }
    } else if (p.spring && static_cast<std::size_t>(parameter) + 1 == p.values.size()) {
      // k: at fixed a, z moves by d(F/k)/d ln k = -F/k; at fixed measured z the residual moves by
      // -slope times that (0 at clamped points, where a = a_c).
      for (std::size_t i = 0; i < n; ++i) {
        column[i] = m.clamped[i] ? 0.0 : m.slope[i] * m.force[i] / p.stiffness();
      }
    } else if (parameter == kThickness && p.layers == 1 && !problem_.shape) {
      column = m.force_lnt;
    } else if (problem_.shape) {
      // Direct solves at the model radii for p e^(+-h); at fixed measured delta the residual
      // moves by dF - slope d delta (as below).
      for (double sign : {1.0, -1.0}) {
        const Parameters q = shifted(sign);
        check_range(q);
        coatcontact::detail::GslHandlerOff handler_off;
        try {
          const ShapeContact load = shape_contact(q.branch(false));
          const ShapeContact unload = shape_contact(q.branch(true));
          for (std::size_t i = 0; i < n; ++i) {
            const bool unloading = q.hysteresis && data_->unloading[i];
            const ShapePoint s = (unloading ? unload : load).at(m.radius[i]);
            ++shape_calls_;
            column[i] += sign * (s.force - m.slope[i] * s.penetration) / (2.0 * kStep);
          }
        } catch (const std::exception&) {
          rethrow_at(q);
        }
      }
    } else {
      // F and delta at the model radii for p e^(+-h) (a new table: C(q) changes); at fixed
      // measured delta the residual moves by dF - slope d delta.
      const auto [lo, hi] = std::minmax_element(m.radius.begin(), m.radius.end());
      for (double sign : {1.0, -1.0}) {
        const Parameters q = shifted(sign);
        check_range(q);
        coatcontact::detail::GslHandlerOff handler_off;
        try {
          // One contact per adhesion energy (the same table: w does not enter C(q)).
          const ContactModel cm(cache_.get(q).model(), problem_.sphere_radius, q.branch(false));
          const ContactModel cm_unload(cache_.get(q).model(), problem_.sphere_radius, q.branch(true));
          cm.prepare(*lo, *hi);
          for (std::size_t i = 0; i < n; ++i) {
            const bool unloading = q.hysteresis && data_->unloading[i];
            const SiPoint s = (unloading ? cm_unload : cm).at(m.radius[i]);
            const double x = s.penetration + (q.spring ? s.force / q.stiffness() : 0.0);
            column[i] += sign * (s.force - m.slope[i] * x) / (2.0 * kStep);
          }
        } catch (const std::exception&) {
          rethrow_at(q);
        }
      }
    }
    columns.push_back(std::move(column));
  }
  return columns;
}

std::optional<std::array<double, 3>> Model::spring_pulloff(const Parameters& p, double k) {
  coatcontact::detail::GslHandlerOff handler_off;
  if (problem_.maugis_dugdale) return std::nullopt;  // not implemented for the cohesive zone
  if (problem_.shape) {
    const ShapeJump s = shape_contact(p.branch(true)).pulloff(k).spring;
    if (!s.interior) return std::nullopt;
    return std::array<double, 3>{s.radius, s.penetration, s.force};
  }
  const ContactModel cm(cache_.get(p).model(), problem_.sphere_radius, p.branch(true));
  cm.prepare_pulloff();
  // k_bar = k (l^2/R) / (pi w R): the stiffness in the Maugis units of force and penetration.
  const double k_bar = k * cm.contact().penetration_scale() / cm.contact().force_scale();
  const SpringPulloff s = cm.contact().model().pulloff_spring(cm.contact().eta(), k_bar);
  if (!s.point.interior) return std::nullopt;
  return std::array<double, 3>{s.point.a_bar * cm.contact().length_scale(),
                               s.point.penetration * cm.contact().penetration_scale(),
                               s.point.load * cm.contact().force_scale()};
}

double Model::interpolation_error(const Parameters& p, const ModelAtData& m) {
  // Every model value of a shape or Maugis-Dugdale fit is a direct solve.
  if (problem_.shape || problem_.maugis_dugdale) return 0.0;
  coatcontact::detail::GslHandlerOff handler_off;
  const ModelEntry& entry = cache_.get(p);
  const ContactModel cm(entry.model(), problem_.sphere_radius, p.branch(false));
  const ContactModel cm_unload(entry.model(), problem_.sphere_radius, p.branch(true));
  const std::size_t n = m.radius.size();
  const std::size_t stride = std::max<std::size_t>(1, (n + kCheckedPoints - 1) / kCheckedPoints);
  std::vector<std::size_t> index;
  std::vector<double> a_over_t;
  for (std::size_t i = 0; i < n; i += stride) {
    index.push_back(i);
    a_over_t.push_back(m.radius[i] / p.total_thickness());
  }
  const SolverSource source(entry.solver(), problem_.solver_tolerance);
  const std::vector<ReducedVariables> solved = source.evaluate(a_over_t);
  check_calls_ += static_cast<long>(solved.size());
  double error = 0.0;
  for (std::size_t k = 0; k < index.size(); ++k) {
    const std::size_t i = index[k];
    const SiPoint exact = (p.hysteresis && data_->unloading[i] ? cm_unload : cm).exact(solved[k], m.radius[i]);
    // At fixed measured delta, moving to the exact curve changes F by -slope * (delta mismatch).
    const double compliance = p.spring ? 1.0 / p.stiffness() : 0.0;
    const double difference = exact.force - m.force[i] -
                              m.slope[i] * (exact.penetration - m.penetration[i] + compliance * (exact.force - m.force[i]));
    error = std::max(error, std::fabs(difference));
  }
  return error;
}

}  // namespace coatcontact::fit::internal
