// The Maugis-Dugdale cohesive zone (THEORY.md section 13, MaugisDugdaleModel of the adhesion
// floor): F = pi w R P(a_bar; eta, lambda), lambda = 2 sigma0 (R/(pi w K^2))^(1/3), K = 4E1*/3,
// the last parameter ("lambda"). a,F data of a rigid sphere; the points from the stack's reduced
// table of the cohesive zone (or one direct solve per point and trial), every derivative a
// central difference in ln p (w included: F is not linear in sqrt(w) at fixed a), no spring
// pull-off.
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "coatcontact/detail/format.hpp"
#include "coatcontact/detail/constants.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/maugis_dugdale.hpp"
#include "force_model.hpp"
#include "stack_cache.hpp"

namespace coatcontact::fit::internal {
namespace {

using coatcontact::detail::short_text;

constexpr double kMinAOverT = kAOverTRange[0];
constexpr double kMaxAOverT = kAOverTRange[1];

// The model of one stack: its reduced table of the cohesive zone serves every w, t and lambda
// (Problem::maugis_dugdale_direct: the direct solve instead).
class MaugisDugdaleEntry {
 public:
  MaugisDugdaleEntry(const Problem& problem, const StackKey& key)
      : key_(key), solver_(std::make_unique<MaugisDugdaleModel>(stack_of(problem, key), options_of(problem))) {}
  const MaugisDugdaleModel& solver() const { return *solver_; }
  const StackKey& key() const { return key_; }
  long source_evaluations() const { return solver_->table_nodes(); }

 private:
  static MaugisDugdaleOptions options_of(const Problem& problem) {
    MaugisDugdaleOptions o;
    o.use_table = !problem.maugis_dugdale_direct;
    return o;
  }
  StackKey key_;
  std::unique_ptr<MaugisDugdaleModel> solver_;
};

class MaugisDugdaleFit : public ForceModel {
 public:
  explicit MaugisDugdaleFit(const Problem& problem) : problem_(problem), cache_(problem, cache_capacity(problem)) {}
  ModelAtData evaluate(const Parameters& p, const Measurements& data, bool with_pulloff) override;
  std::optional<std::vector<double>> analytic_column(const Parameters&, const ModelAtData&, const Measurements&,
                                                     std::size_t) const override {
    return std::nullopt;
  }
  // F at the measured a (a,F data: slope 0, the model radius is the measured one).
  std::vector<double> shifted_force(const Parameters& q, const ModelAtData&, const Measurements& data) override {
    return evaluate(q, data, false).force;
  }
  // Direct cohesive-zone solves: the tables' nodes, or one per point and trial.
  long solver_calls() const override { return problem_.maugis_dugdale_direct ? solves_ : cache_.solver_calls(); }
  double adhesionless_radius(double penetration) const override {
    return std::sqrt(problem_.sphere_radius * penetration);
  }
  bool work_separates() const override { return false; }
  double work_estimate(const Measurements& data) const override {
    const double f_min = *std::min_element(data.force.begin(), data.force.end());
    return f_min < 0.0 ? jkr_work_estimate(data, problem_.sphere_radius) : 0.0;
  }
  // lambda within kSearchLambdaFactor of its hint, inside [kMinimumLambda, kMaximumLambda].
  void add_search_axes(const Parameters& hint, const std::vector<int>& free_index,
                       std::vector<SearchAxis>& axes) const override {
    const int last = static_cast<int>(hint.values.size() - 1);
    if (std::find(free_index.begin(), free_index.end(), last) == free_index.end()) return;
    const double lambda = hint.lambda();
    axes.push_back({hint.values.size() - 1,
                    log_axis(std::max(kMinimumLambda, lambda / kSearchLambdaFactor),
                             std::min(kMaximumLambda, lambda * kSearchLambdaFactor), kCoarsePointsPerDecade)});
  }

 private:
  const Problem& problem_;
  StackCache<MaugisDugdaleEntry> cache_;
  long solves_ = 0;  // cohesive-zone solves (one per point and trial)
};

}  // namespace

// F = pi w R P, delta = (l^2/R) D at a_bar = a/l, l = (pi w R^2/E*)^(1/3), eta = T/l (THEORY.md
// section 13), from MaugisDugdaleModel::curve at the measured radii.
ModelAtData MaugisDugdaleFit::evaluate(const Parameters& p, const Measurements& data, bool with_pulloff) {
  using detail::kPi;
  const MaugisDugdaleModel& md = cache_.get(p).solver();
  const double radius = problem_.sphere_radius;
  const double work = p.work();
  const double l = std::cbrt(kPi * work * radius * radius / md.stack().reference_modulus());
  const double force_scale = kPi * work * radius, penetration_scale = l * l / radius;
  const double eta = p.total_thickness() / l;
  const double lambda = p.lambda();
  const std::size_t n = data.size();
  // force_lnw and force_lnt stay 0: every derivative is differenced.
  ModelAtData out = ModelAtData::zeros(n);
  out.radius = data.abscissa;
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
  solves_ += static_cast<long>(n);
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
    solves_ += static_cast<long>(2 * n);
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

std::unique_ptr<ForceModel> make_maugis_dugdale_model(const Problem& problem) {
  return std::make_unique<MaugisDugdaleFit>(problem);
}

}  // namespace coatcontact::fit::internal
