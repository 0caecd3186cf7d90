// The sphere through the reduced interpolant (sphere_model.hpp): THEORY.md section 5 through
// the adhesion floor. The JKR law gives P, D and their a_bar derivatives in Maugis units;
// Contact's scales turn them into SI. The w and t derivatives follow from the same law (see
// ContactModel::to_si).
#include "sphere_model.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "coatcontact/detail/format.hpp"
#include "coatcontact/detail/gsl_handler_off.hpp"
#include "coatcontact/errors.hpp"

namespace coatcontact::fit::internal {
namespace {

using coatcontact::detail::short_text;

// Top of the pull-off scan in units of max(1, r), r = (E1*/E0*)^(1/3) (SphereEntry).
constexpr double kPulloffScanTop = 2.0;
// Data points checked against direct solves after the fit: a direct solve at a/t ~ 20 costs
// as much as a whole fit's worth of interpolation, and the interpolant's error varies smoothly,
// so a spread-out sample finds its maximum.
constexpr std::size_t kCheckedPoints = 16;

// The same point with d ln X/d ln(a/t) = 0: the law's a_bar derivative is then the explicit
// one, at fixed a/t.
ReducedPoint frozen(ReducedPoint r) {
  r.dlog_pi_s = r.dlog_delta_s = r.dlog_pi_c = r.dlog_delta_c = r.dlog_e_eq = r.dlog_gamma1 = 0.0;
  return r;
}

}  // namespace

SphereEntry::SphereEntry(const Problem& problem, const StackKey& key)
    : key_(key), solver_(std::make_unique<ReducedSolver>(stack_of(problem, key))) {
  // The minimum of D lies at a_bar = 1/2 (top layer) and r/2 (base) in the JKR limits
  // (THEORY.md section 6): scanning up to 2 max(1, r), not the default 10 max(1, r), finds it
  // and spares the costly solves at large a/t (~25 ms each above a/t = 10).
  PulloffOptions pulloff;
  pulloff.a_bar_max = kPulloffScanTop * std::max(1.0, solver_->stack().substrate_length_ratio());
  model_ = std::make_unique<AdhesiveModel>(*solver_, problem.solver_tolerance, TableOptions{}, pulloff);
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
  const coatcontact::CurvePoint p = model_.law().point(reduced_point_of(v), eta, a_bar);
  SiPoint s = to_si(p, p);  // values only: no derivatives without the interpolant
  s.radius = radius;
  return s;
}

// ---- the model at the data ------------------------------------------------------------------

SphereModel::SphereModel(const Problem& problem) : problem_(problem), cache_(problem, cache_capacity(problem)) {}

double SphereModel::compliance(const Parameters&) const { return 0.0; }

double SphereModel::shifted_abscissa(const SiPoint& s, const Parameters&) const { return s.penetration + 0.0; }

std::array<double, 2> SphereModel::branch_start(const ContactModel&, const Parameters&, const Pulloff& pulloff,
                                                const ModelAtData& out) const {
  if (!pulloff.displacement_control.interior) {
    throw NumericalError("delta(a) has no minimum for a_bar in [" + short_text(pulloff.a_bar_scan_min) + ", " +
                         short_text(pulloff.a_bar_scan_max) + "] (no displacement-controlled pull-off)");
  }
  return {out.pulloff_radius, out.pulloff_penetration};
}

std::array<double, 2> SphereModel::pulloffs(const ContactModel& cm, const Parameters& p, bool radius_data,
                                            ModelAtData& out) const {
  // For delta,F data the displacement-controlled pull-off bounds the stable branch (a failure
  // to find it fails the evaluation); for a,F data the pull-offs are only reported.
  const Pulloff* pulloff = nullptr;
  try {
    cm.prepare_pulloff();
    pulloff = &cm.contact().pulloff();
  } catch (const NumericalError&) {
    if (!radius_data) throw;
  }
  if (pulloff == nullptr) return {0.0, 0.0};
  const PulloffPoint& c = pulloff->displacement_control;
  const PulloffPoint& f = pulloff->load_control;
  if (f.interior) {
    out.has_load_pulloff = true;
    out.load_pulloff_radius = f.a_bar * cm.contact().length_scale();
    out.load_pulloff_penetration = f.penetration * cm.contact().penetration_scale();
    out.load_pulloff_force = f.load * cm.contact().force_scale();
  }
  if (c.interior) {
    out.has_pulloff = true;
    out.pulloff_radius = c.a_bar * cm.contact().length_scale();
    out.pulloff_penetration = c.penetration * cm.contact().penetration_scale();
    out.pulloff_force = c.load * cm.contact().force_scale();
  }
  if (radius_data) return {0.0, 0.0};
  return branch_start(cm, p, *pulloff, out);
}

ModelAtData SphereModel::evaluate(const Parameters& p, const Measurements& data, bool with_pulloff) {
  const ContactModel cm(cache_.get(p).model(), problem_.sphere_radius, p);
  const std::size_t n = data.size();
  ModelAtData out = ModelAtData::zeros(n);
  const bool radius_data = data.kind == DataKind::kRadiusForce;
  std::array<double, 2> start{0.0, 0.0};
  if (!radius_data || with_pulloff) start = pulloffs(cm, p, radius_data, out);
  if (!radius_data) {
    invert(cm, p, data, start, out);
    return out;
  }
  const auto [lo, hi] = std::minmax_element(data.abscissa.begin(), data.abscissa.end());
  check_a_over_t(*lo, p.total_thickness());
  check_a_over_t(*hi, p.total_thickness());
  cm.prepare(*lo, *hi);
  for (std::size_t i = 0; i < n; ++i) {
    const SiPoint s = cm.at(data.abscissa[i]);
    out.radius[i] = s.radius;
    out.penetration[i] = s.penetration;
    out.force[i] = s.force;
    out.force_lnw[i] = s.force_lnw;
    out.force_lnt[i] = s.force_lnt;
    out.force_x[i] = s.force_a;
  }
  return out;
}

// delta,F data: each measured delta at a* >= a_c on the stable branch (fit.hpp); z,F data the
// same with delta + F/k in place of delta.
void SphereModel::invert(const ContactModel& cm, const Parameters& p, const Measurements& data,
                         std::array<double, 2> start, ModelAtData& out) const {
  const double compliance = this->compliance(p);
  const double a_c = start[0];
  const double x_c = start[1];
  const auto abscissa = [&](const SiPoint& s) { return s.penetration + compliance * s.force; };
  const double delta_max = *std::max_element(data.abscissa.begin(), data.abscissa.end());
  // Grid upwards from a_c until delta exceeds the largest measured one.
  std::vector<double> grid{a_c};
  std::vector<double> grid_delta{x_c};
  while (grid_delta.back() < delta_max) {
    if (grid.size() > kMaxBracketSteps) {
      throw NumericalError("the model's delta(a) stays below the largest measured delta up to a = " +
                           short_text(grid.back()) + " m");
    }
    const double a = grid.back() * kBracketRatio;
    check_a_over_t(a, p.total_thickness());
    grid.push_back(a);
    grid_delta.push_back(abscissa(cm.at(a)));
  }
  for (std::size_t i = 0; i < data.size(); ++i) {
    const double delta = data.abscissa[i];
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
}

std::optional<std::vector<double>> SphereModel::analytic_column(const Parameters& p, const ModelAtData& m,
                                                                const Measurements& data, std::size_t parameter) const {
  if (parameter == static_cast<std::size_t>(kThickness) && p.layers == 1) return m.force_lnt;
  return ForceModel::analytic_column(p, m, data, parameter);
}

// F and delta at the model radii for q (a new table: C(q) changes); at fixed measured delta the
// residual moves by dF - slope d delta.
std::vector<double> SphereModel::shifted_force(const Parameters& q, const ModelAtData& m, const Measurements& data) {
  const std::size_t n = m.radius.size();
  const auto [lo, hi] = std::minmax_element(m.radius.begin(), m.radius.end());
  // One contact per adhesion energy (the same table: w does not enter C(q)).
  const ContactModel cm(cache_.get(q).model(), problem_.sphere_radius, q.branch(false));
  const ContactModel cm_unload(cache_.get(q).model(), problem_.sphere_radius, q.branch(true));
  cm.prepare(*lo, *hi);
  std::vector<double> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    const bool unloading = q.hysteresis && data.unloading[i];
    const SiPoint s = (unloading ? cm_unload : cm).at(m.radius[i]);
    out[i] = s.force - m.slope[i] * shifted_abscissa(s, q);
  }
  return out;
}

std::optional<std::array<double, 3>> SphereModel::spring_pulloff(const Parameters& p, double k) {
  coatcontact::detail::GslHandlerOff handler_off;
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

double SphereModel::interpolation_error(const Parameters& p, const ModelAtData& m, const Measurements& data) {
  coatcontact::detail::GslHandlerOff handler_off;
  const SphereEntry& entry = cache_.get(p);
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
    const SiPoint exact = (p.hysteresis && data.unloading[i] ? cm_unload : cm).exact(solved[k], m.radius[i]);
    // At fixed measured delta, moving to the exact curve changes F by -slope * (delta mismatch).
    const double compliance = this->compliance(p);
    const double difference = exact.force - m.force[i] -
                              m.slope[i] * (exact.penetration - m.penetration[i] + compliance * (exact.force - m.force[i]));
    error = std::max(error, std::fabs(difference));
  }
  return error;
}

double SphereModel::adhesionless_radius(double penetration) const {
  return std::sqrt(problem_.sphere_radius * penetration);
}

double SphereModel::work_estimate(const Measurements& data) const {
  // Around the load-controlled JKR estimate when the data are tensile somewhere.
  const double f_min = *std::min_element(data.force.begin(), data.force.end());
  return f_min < 0.0 ? jkr_work_estimate(data, problem_.sphere_radius) : 0.0;
}

std::unique_ptr<ForceModel> make_sphere_model(const Problem& problem) { return std::make_unique<SphereModel>(problem); }

}  // namespace coatcontact::fit::internal
