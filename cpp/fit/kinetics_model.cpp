// Fit of the crack-kinetics law to force-time curves (kinetics_fit.hpp, THEORY.md section 14, fitting):
// each curve is simulated through its own protocol by the adhesion floor (simulate_kinetics_si),
// its force interpolated at the measured times; GSL's trust region minimises over ln p; the
// statistics are the fit floor's (fill_statistics).
#include "coatcontact/kinetics_fit.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_interp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "coatcontact/adhesion.hpp"
#include "coatcontact/detail/format.hpp"
#include "coatcontact/detail/gsl_handler_off.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/reduced.hpp"
#include "force_model.hpp"
#include "statistics.hpp"
#include "trust_region.hpp"

namespace coatcontact::fit {
namespace {

using coatcontact::detail::short_text;
using internal::kLogOffset;
using internal::TrustRegion;

// The stack with the top layer's Young modulus set to e1.
Stack with_film_modulus(const Stack& stack, double e1) {
  std::vector<Layer> layers = stack.layers();
  layers.front().material.youngs_modulus = e1;
  return Stack(std::move(layers), stack.substrate(), stack.indenter());
}

// JKR models of the stack at the values of E1 a fit visits: the value at the parameters and its
// Jacobian neighbours e^(+-h), most recent first (each builds its own table, THEORY.md section 14,
// fitting). The value of the given model's own stack is served by that model.
class FilmModulusModels {
 public:
  FilmModulusModels(const AdhesiveModel& base, double tolerance) : base_(base), tolerance_(tolerance) {}
  const AdhesiveModel& at(double e1) {
    if (e1 == base_.stack().top().youngs_modulus) return base_;
    for (auto it = entries_.begin(); it != entries_.end(); ++it) {
      if ((*it)->e1 == e1) {
        std::rotate(entries_.begin(), it, it + 1);
        return *entries_.front()->model;
      }
    }
    if (entries_.size() >= kCapacity) entries_.pop_back();
    auto entry = std::make_unique<Entry>();
    entry->e1 = e1;
    entry->solver = std::make_unique<ReducedSolver>(with_film_modulus(base_.stack(), e1));
    entry->model = std::make_unique<AdhesiveModel>(*entry->solver, tolerance_);
    entries_.insert(entries_.begin(), std::move(entry));
    ++built_;
    return *entries_.front()->model;
  }
  long built() const { return built_; }

 private:
  struct Entry {
    double e1 = 0.0;
    std::unique_ptr<ReducedSolver> solver;
    std::unique_ptr<AdhesiveModel> model;  // refers to *solver: declared after it
  };
  static constexpr std::size_t kCapacity = 4;
  const AdhesiveModel& base_;
  double tolerance_;
  std::vector<std::unique_ptr<Entry>> entries_;
  long built_ = 0;
};

struct KineticsContext {
  const AdhesiveModel* model = nullptr;
  FilmModulusModels* models = nullptr;
  const std::vector<KineticsCurve>* curves = nullptr;
  const KineticsFitProblem* problem = nullptr;
  std::vector<int> free_index;
  std::array<double, kKineticsParameterCount> start{};
  std::vector<double> scale;  // per point: 1/sigma, or 1/max|F|
  long simulations = 0;
  long evaluations_done = 0;  // residual evaluations that ran
  long failed_steps = 0;      // trial steps the simulation could not run (kFailedStepResidual)

  std::array<double, kKineticsParameterCount> parameters(const gsl_vector* x) const {
    auto p = start;
    for (std::size_t j = 0; j < free_index.size(); ++j) {
      p[free_index[j]] = start[free_index[j]] * std::exp(gsl_vector_get(x, j) - kLogOffset);
    }
    return p;
  }
};

// F of one simulated run at time t: monotone cubic (Steffen) through the accepted steps and
// events; 0 after the loss of contact (the sphere hangs free on its spring).
std::vector<double> force_at(const KineticsResultSI& run, const std::vector<double>& times) {
  std::vector<double> t, f;
  // States closer than this in time (an event next to a step) count as one: the cubic's slopes
  // divide by the spacing.
  const double merge = 1e-12 * std::max(run.t.back() - run.t.front(), 0.0);
  for (std::size_t i = 0; i < run.t.size(); ++i) {
    if (!t.empty() && !(run.t[i] > t.back() + merge)) {
      f.back() = run.force[i];  // an event at the time of a step: its state is the later one
      continue;
    }
    t.push_back(run.t[i]);
    f.push_back(run.force[i]);
  }
  if (t.size() < 3) throw NumericalError("kinetics fit: a simulated curve has fewer than three states");
  std::unique_ptr<gsl_interp, void (*)(gsl_interp*)> interp(gsl_interp_alloc(gsl_interp_steffen, t.size()),
                                                            gsl_interp_free);
  std::unique_ptr<gsl_interp_accel, void (*)(gsl_interp_accel*)> accel(gsl_interp_accel_alloc(),
                                                                       gsl_interp_accel_free);
  gsl_interp_init(interp.get(), t.data(), f.data(), t.size());
  std::vector<double> out;
  for (double time : times) {
    out.push_back(time > t.back() ? 0.0
                                  : gsl_interp_eval(interp.get(), t.data(), f.data(), std::max(time, t.front()),
                                                    accel.get()));
    if (!std::isfinite(out.back())) throw NumericalError("kinetics fit: the interpolated model force is not finite");
  }
  return out;
}

bool same_segment(const KineticsSegmentSI& a, const KineticsSegmentSI& b) {
  return a.kind == b.kind && a.speed == b.speed && a.duration == b.duration && a.target_force == b.target_force &&
         a.has_target == b.has_target;
}

// Whether every curve has the first one's spring and protocol up to the speed of the last
// retract: then the approach and dwell are simulated once per evaluation (sweep_kinetics).
bool shared_prefix(const std::vector<KineticsCurve>& curves) {
  const KineticsCurve& first = curves.front();
  for (const KineticsCurve& c : curves) {
    if (c.spring != first.spring || c.protocol.size() != first.protocol.size()) return false;
    for (std::size_t k = 0; k < c.protocol.size(); ++k) {
      KineticsSegmentSI segment = c.protocol[k];
      if (k + 1 == c.protocol.size()) segment.speed = first.protocol[k].speed;
      if (!same_segment(segment, first.protocol[k])) return false;
    }
  }
  return true;
}

// The model force at every point of every curve (in order) for parameters p.
std::vector<double> model_forces(KineticsContext& ctx, const std::array<double, kKineticsParameterCount>& p) {
  const KineticsFitProblem& problem = *ctx.problem;
  const std::vector<KineticsCurve>& curves = *ctx.curves;
  const auto setup_of = [&](const KineticsCurve& curve) {
    KineticsSetupSI setup;
    setup.radius = problem.radius;
    setup.work = p[kKinWork];
    setup.v_star = p[kKinSpeed];
    setup.n = p[kKinExponent];
    setup.thickness = p[kKinThickness];
    setup.v_star_adv = problem.v_star_adv;
    setup.n_adv = problem.n_adv;
    setup.spring = curve.spring;
    setup.protocol = curve.protocol;
    return setup;
  };
  const AdhesiveModel& model = ctx.models->at(p[kKinFilmModulus]);
  std::vector<KineticsResultSI> runs;
  if (curves.size() > 1 && shared_prefix(curves)) {
    std::vector<double> speeds;
    for (const KineticsCurve& c : curves) speeds.push_back(c.protocol.back().speed);
    runs = simulate_kinetics_si(model, setup_of(curves.front()), speeds, true, problem.options);
  } else {
    for (const KineticsCurve& curve : curves) {
      runs.push_back(simulate_kinetics_si(model, setup_of(curve), {}, true, problem.options).front());
    }
  }
  ctx.simulations += static_cast<long>(curves.size());
  std::vector<double> out;
  for (std::size_t c = 0; c < curves.size(); ++c) {
    const std::vector<double> f = force_at(runs[c], curves[c].time);
    out.insert(out.end(), f.begin(), f.end());
  }
  return out;
}

// d F_model / d ln p_j by central differences, the fit floor's step kStep (the interpolated runs
// carry relative noise ~ the ODE tolerance, 1e-9, far below kStep^2).
std::vector<std::vector<double>> derivatives(KineticsContext& ctx, const std::array<double, kKineticsParameterCount>& p) {
  std::vector<std::vector<double>> columns;
  for (int which : ctx.free_index) {
    auto up = p, down = p;
    up[which] *= std::exp(internal::kStep);
    down[which] *= std::exp(-internal::kStep);
    const std::vector<double> f_up = model_forces(ctx, up), f_down = model_forces(ctx, down);
    std::vector<double> column(f_up.size());
    for (std::size_t i = 0; i < column.size(); ++i) column[i] = (f_up[i] - f_down[i]) / (2.0 * internal::kStep);
    columns.push_back(std::move(column));
  }
  return columns;
}

std::vector<double> measured_forces(const std::vector<KineticsCurve>& curves) {
  std::vector<double> out;
  for (const KineticsCurve& c : curves) out.insert(out.end(), c.force.begin(), c.force.end());
  return out;
}

// Scaled residual of every point where a trial step leaves the parameters at which the
// simulation can run (e.g. an event it cannot bracket far from the data): a cost far above any
// reachable one, so the trust region rejects the step and shrinks instead of stopping.
constexpr double kFailedStepResidual = 1e6;

void residuals(KineticsContext& ctx, const gsl_vector* x, gsl_vector* f) {
  try {
    const std::vector<double> model = model_forces(ctx, ctx.parameters(x));
    std::size_t i = 0;
    for (const KineticsCurve& c : *ctx.curves) {
      for (double measured : c.force) {
        gsl_vector_set(f, i, (model[i] - measured) * ctx.scale[i]);
        ++i;
      }
    }
    ++ctx.evaluations_done;
  } catch (const std::runtime_error&) {  // InputError, NumericalError of the simulation
    if (ctx.evaluations_done == 0) throw;  // the start itself: nothing to fall back on
    gsl_vector_set_all(f, kFailedStepResidual);
    ++ctx.failed_steps;
  }
}

void jacobian(KineticsContext& ctx, const gsl_vector* x, gsl_matrix* J) {
  try {
    const auto columns = derivatives(ctx, ctx.parameters(x));
    for (std::size_t j = 0; j < columns.size(); ++j) {
      for (std::size_t i = 0; i < columns[j].size(); ++i) gsl_matrix_set(J, i, j, columns[j][i] * ctx.scale[i]);
    }
  } catch (const std::runtime_error& e) {
    // The trust region has reached parameters next to which a curve cannot be simulated (e.g. w
    // and v* both tiny, where w (v/v*)^n mimics the data): not a fault of the input.
    const auto p = ctx.parameters(x);
    throw NumericalError("kinetics fit: the fit reached w = " + short_text(p[kKinWork]) + ", v_star = " +
                         short_text(p[kKinSpeed]) + ", n = " + short_text(p[kKinExponent]) + ", t = " +
                         short_text(p[kKinThickness]) + ", E1 = " + short_text(p[kKinFilmModulus]) +
                         ", where the curves cannot be simulated (" + e.what() + "); start closer or fix a parameter");
  }
}

void validate(const std::vector<KineticsCurve>& curves, const KineticsFitProblem& problem) {
  if (curves.empty()) throw InputError("kinetics fit: no curve");
  const auto positive = [](double v, const std::string& name) {
    if (!(v > 0.0) || !std::isfinite(v)) throw InputError("kinetics fit: " + name + " must be > 0 (got " + short_text(v) + ")");
  };
  positive(problem.radius, "radius");
  positive(problem.thickness, "thickness");
  positive(problem.work, "work");
  positive(problem.v_star, "v_star");
  positive(problem.n, "n");
  if (!(problem.film_modulus <= 0.0 || std::isfinite(problem.film_modulus))) {
    throw InputError("kinetics fit: film_modulus must be finite (got " + short_text(problem.film_modulus) + ")");
  }
  std::size_t points = 0;
  std::set<double> retract_speeds;
  for (std::size_t c = 0; c < curves.size(); ++c) {
    const KineticsCurve& curve = curves[c];
    const std::string where = "kinetics fit: curve " + std::to_string(c + 1);
    if (curve.protocol.empty() || curve.protocol.back().kind != DriveSegment::Kind::kRetract) {
      throw InputError(where + ": the protocol must end with a retract");
    }
    if (curve.time.size() != curve.force.size() || curve.time.empty()) {
      throw InputError(where + ": time and force columns must be non-empty and of equal length");
    }
    if (!curve.sigma_force.empty() && curve.sigma_force.size() != curve.force.size()) {
      throw InputError(where + ": the sigma column differs in length from the force column");
    }
    if (!curve.sigma_force.empty() != !curves.front().sigma_force.empty()) {
      throw InputError(where + ": give force uncertainties for every curve or for none");
    }
    for (std::size_t i = 0; i < curve.time.size(); ++i) {
      if (!std::isfinite(curve.time[i]) || !std::isfinite(curve.force[i]) || curve.time[i] < 0.0 ||
          (i > 0 && !(curve.time[i] > curve.time[i - 1]))) {
        throw InputError(where + ", point " + std::to_string(i + 1) +
                         ": times must be finite, >= 0 (from first contact) and increasing; forces finite");
      }
      if (!curve.sigma_force.empty() && (!(curve.sigma_force[i] > 0.0) || !std::isfinite(curve.sigma_force[i]))) {
        throw InputError(where + ", point " + std::to_string(i + 1) + ": a force uncertainty must be finite and > 0");
      }
    }
    points += curve.time.size();
    retract_speeds.insert(curve.protocol.back().speed);
  }
  const auto free_count = static_cast<std::size_t>(std::count(problem.free.begin(), problem.free.end(), true));
  if (free_count == 0) throw InputError("kinetics fit: no free parameter: name at least one of w, v_star, n, t, E1");
  if (points <= free_count) {
    throw InputError("kinetics fit: " + std::to_string(points) + " points for " + std::to_string(free_count) +
                     " free parameters: a fit needs more points than free parameters");
  }
  if (problem.free[kKinSpeed] && problem.free[kKinExponent] && retract_speeds.size() < 2) {
    throw InputError("kinetics fit: v_star and n are both free but every curve retracts at " +
                     short_text(*retract_speeds.begin()) +
                     ": one speed determines only the rate factor (v/v*)^n at that speed (THEORY.md section 14, fitting); "
                     "give curves at two retract speeds at least, or fix v_star or n");
  }
}

// Each curve up to its measured pull-off (its most tensile force, as an instrument reads it): the
// run-off after it lasts a few percent of the retract, moves with the pull-off's time by many
// sigma per 1e-4 in ln p, and ends in the jump to F = 0 at the loss of contact, so its points
// would make the cost discontinuous in p (THEORY.md section 14, fitting).
std::vector<KineticsCurve> up_to_pulloff(const std::vector<KineticsCurve>& curves) {
  std::vector<KineticsCurve> out = curves;
  for (KineticsCurve& c : out) {
    const auto end = static_cast<std::size_t>(std::min_element(c.force.begin(), c.force.end()) - c.force.begin()) + 1;
    c.time.resize(end);
    c.force.resize(end);
    if (!c.sigma_force.empty()) c.sigma_force.resize(end);
  }
  return out;
}

}  // namespace

const char* kinetics_parameter_name(int parameter) {
  switch (parameter) {
    case kKinWork: return "w";
    case kKinSpeed: return "v_star";
    case kKinExponent: return "n";
    case kKinThickness: return "t";
    case kKinFilmModulus: return "E1";
    default: return "?";
  }
}

Result fit_kinetics(const Stack& stack, const std::vector<KineticsCurve>& curves, const KineticsFitProblem& problem) {
  validate(curves, problem);
  const ReducedSolver solver(stack);
  const AdhesiveModel model(solver, problem.solver_tolerance);
  return fit_kinetics(model, curves, problem);
}

namespace {

// One trust-region fit from the problem's start values.
Result fit_from_start(const AdhesiveModel& model, const std::vector<KineticsCurve>& measured_curves,
                      const KineticsFitProblem& problem) {
  const auto clock_start = std::chrono::steady_clock::now();
  const std::vector<KineticsCurve> curves = up_to_pulloff(measured_curves);
  coatcontact::detail::GslHandlerOff handler_off;

  // Other values of E1 are solved (ReducedSolver) at the tolerance of the given model's solver.
  const auto* solver_source = dynamic_cast<const SolverSource*>(&model.table().source());
  FilmModulusModels models(model, solver_source != nullptr ? solver_source->tolerance() : problem.solver_tolerance);
  KineticsContext ctx;
  ctx.model = &model;
  ctx.models = &models;
  ctx.curves = &curves;
  ctx.problem = &problem;
  const double e1 = problem.film_modulus > 0.0 ? problem.film_modulus : model.stack().top().youngs_modulus;
  ctx.start = {problem.work, problem.v_star, problem.n, problem.thickness, e1};
  for (int j = 0; j < kKineticsParameterCount; ++j) {
    if (problem.free[static_cast<std::size_t>(j)]) ctx.free_index.push_back(j);
  }
  const std::vector<double> measured = measured_forces(curves);
  const std::size_t n = measured.size();
  const std::size_t p_count = ctx.free_index.size();
  if (n <= p_count) {
    throw InputError("kinetics fit: " + std::to_string(n) + " points up to the pull-offs for " + std::to_string(p_count) +
                     " free parameters: a fit needs more points than free parameters");
  }
  const bool weighted = !curves.front().sigma_force.empty();
  double largest = 0.0;
  for (double f : measured) largest = std::max(largest, std::fabs(f));
  if (!(largest > 0.0)) throw InputError("kinetics fit: all measured forces are zero: nothing to fit");
  for (const KineticsCurve& c : curves) {
    for (std::size_t i = 0; i < c.force.size(); ++i) ctx.scale.push_back(weighted ? 1.0 / c.sigma_force[i] : 1.0 / largest);
  }

  TrustRegion region(
      n, p_count, [&ctx](const gsl_vector* x, gsl_vector* f) { residuals(ctx, x, f); },
      [&ctx](const gsl_vector* x, gsl_matrix* J) { jacobian(ctx, x, J); });
  if (!region.start()) throw NumericalError("kinetics fit: could not evaluate the model at the start values");
  // Relative change of each parameter ~ xtol * kLogOffset = 1e-7: far below any standard error
  // the interpolated runs could support.
  int info = 0;
  const int status = region.run(problem.max_iterations, 1e-8, 1e-10, 0.0, &info);
  const auto estimate = ctx.parameters(region.position());
  if (status != GSL_SUCCESS && status != GSL_ENOPROG) {
    throw NumericalError(std::string("kinetics fit did not converge: ") + gsl_strerror(status));
  }

  Result result;
  for (int j = 0; j < kKineticsParameterCount; ++j) {
    static const char* const units[] = {"J/m2", "m/s", "", "m", "Pa"};
    static const ParameterKind kinds[] = {ParameterKind::kWork, ParameterKind::kSpeed, ParameterKind::kExponent,
                                          ParameterKind::kThickness, ParameterKind::kModulus};
    result.parameters.push_back({kinds[j], 0, kinetics_parameter_name(j), units[j]});
    result.free.push_back(problem.free[static_cast<std::size_t>(j)]);
  }
  result.value.assign(estimate.begin(), estimate.end());
  result.points = n;
  result.free_count = static_cast<int>(p_count);
  result.iterations = region.iterations();
  result.converged = true;
  result.stop_reason = status == GSL_ENOPROG ? "no further progress" : (info == 1 ? "small step" : "small gradient");
  result.model_force = model_forces(ctx, estimate);
  Measurements data;  // the statistics' view: all points of all curves, abscissa = time
  data.kind = DataKind::kPenetrationForce;
  data.force = measured;
  for (const KineticsCurve& c : curves) data.abscissa.insert(data.abscissa.end(), c.time.begin(), c.time.end());
  std::vector<double> inv_sigma;
  if (weighted) inv_sigma = ctx.scale;
  internal::fill_statistics(data, result.model_force, derivatives(ctx, estimate), ctx.free_index, inv_sigma, result);
  // Per point of the measured curves, the run-offs included (marked: not in the residual).
  ctx.curves = &measured_curves;
  result.model_force = model_forces(ctx, estimate);
  result.residual.clear();
  result.clamped.clear();
  std::size_t i = 0;
  for (std::size_t c = 0; c < measured_curves.size(); ++c) {
    for (std::size_t k = 0; k < measured_curves[c].force.size(); ++k, ++i) {
      result.residual.push_back(result.model_force[i] - measured_curves[c].force[k]);
      result.clamped.push_back(k >= curves[c].force.size());
    }
  }
  result.solver_calls = ctx.simulations;  // kinetics simulations (one per curve and evaluation)
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
  return result;
}

}  // namespace

Result fit_kinetics(const AdhesiveModel& model, const std::vector<KineticsCurve>& measured_curves,
                    const KineticsFitProblem& problem) {
  validate(measured_curves, problem);
  const bool law_free = problem.free[kKinSpeed] || problem.free[kKinExponent];
  const bool scale_free = problem.free[kKinFilmModulus] || problem.free[kKinWork];
  if (!scale_free || !law_free) return fit_from_start(model, measured_curves, problem);
  // E1 or w free with the law: first those (and t if free) with the law held at its start, then
  // all (THEORY.md section 14, fitting: from a start off in E1, or in w and the law, the first
  // full steps tend to leave into the valley w, v* -> 0 where w (v/v*)^n mimics the data).
  KineticsFitProblem first = problem;
  first.free[kKinSpeed] = first.free[kKinExponent] = false;
  const Result stage = fit_from_start(model, measured_curves, first);
  KineticsFitProblem second = problem;
  second.work = stage.value[kKinWork];
  second.thickness = stage.value[kKinThickness];
  second.film_modulus = stage.value[kKinFilmModulus];
  Result result = fit_from_start(model, measured_curves, second);
  result.iterations += stage.iterations;
  result.solver_calls += stage.solver_calls;
  result.seconds += stage.seconds;
  return result;
}

}  // namespace coatcontact::fit
