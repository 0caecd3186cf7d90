// The Maugis-Dugdale AFM retract fit (THEORY.md section 15, "Maugis-Dugdale through the
// cantilever"): the cohesive-zone table's curve (MaugisDugdaleModel, section 13) in SI units on
// the branch the cantilever holds, searched by the adhesive fit it shares with JKR
// (internal::afm_fit_adhesive). See coatcontact/afm_fit.hpp.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "afm_internal.hpp"
#include "coatcontact/afm_fit.hpp"
#include "coatcontact/detail/constants.hpp"
#include "coatcontact/detail/format.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/limits.hpp"
#include "coatcontact/maugis_dugdale.hpp"

namespace coatcontact::fit::internal {

namespace {

using coatcontact::detail::kPi;
using coatcontact::detail::short_text;

// Scan of Z = delta + F/k over a_bar = a/L in [kScanLow, kScanHigh] (the library's MD pull-off
// scan starts at 1e-3 too), kScanPerDecade per decade; kBranchNodes radii on the branch.
constexpr double kScanLow = 1e-3, kScanHigh = 30.0;
constexpr int kScanPerDecade = 12;
constexpr int kBranchNodes = 128;
// The table's a/t range (MaugisDugdaleOptions' default), kept inside by the scan and by eta.
constexpr double kTableAOverT[2] = {1e-4, 1e2};
constexpr double kForceLimit = 1e3;

// The Maugis-Dugdale models (each with its cohesive-zone table) shared by every fit of the
// process: the curves of a map share the sample's stack (and E1's node grid), so a tile built
// for one curve serves the next. A tile's values are a pure function of the stack and its grid
// index (md_table.hpp), so a fit's result does not depend on what other fits built before.
using ModelKey = std::tuple<double, double, bool, double, double>;
constexpr std::size_t kSharedModels = 96;
std::mutex shared_models_mutex;

std::shared_ptr<const MaugisDugdaleModel> shared_model(Material film, Substrate substrate) {
  static std::map<ModelKey, std::shared_ptr<const MaugisDugdaleModel>> models;
  // On a rigid base or a half-space the table, in units of t and E1*, does not depend on E1
  // (THEORY.md section 15, "Its cost"): one model per nu1, whatever modulus the caller holds (the
  // fit its start value, afm_md_model_force the estimate).
  const bool half_space = !substrate.rigid && substrate.material.youngs_modulus == film.youngs_modulus &&
                          substrate.material.poisson_ratio == film.poisson_ratio;
  if (substrate.rigid || half_space) {
    film.youngs_modulus = 1.0;
    if (half_space) substrate.material = film;
  }
  const ModelKey key{film.youngs_modulus, film.poisson_ratio, substrate.rigid,
                     substrate.rigid ? 0.0 : substrate.material.youngs_modulus,
                     substrate.rigid ? 0.0 : substrate.material.poisson_ratio};
  const std::lock_guard<std::mutex> lock(shared_models_mutex);
  auto it = models.find(key);
  if (it != models.end()) return it->second;
  if (models.size() >= kSharedModels) models.clear();  // the fits holding one keep it
  MaugisDugdaleOptions options;
  options.use_table = true;
  options.table_a_over_t_min = kTableAOverT[0];
  options.table_a_over_t_max = kTableAOverT[1];
  options.table_errors = false;  // the fit's trials use values only
  auto made = std::make_shared<const MaugisDugdaleModel>(Stack::film_on(film, substrate), options);
  return models.emplace(key, std::move(made)).first->second;
}

// The Maugis-Dugdale curves of one fit: one stack's model (half-space; a coating with E1 fixed)
// or one per node E1_j = E0 10^(j/kModulusNodesPerDecade) on an elastic base with E1 free (nodes
// on the substrate's scale, not the start value's: every fit of the sample, and the model force at
// the estimates, interpolate between the same tables), each with its
// cohesive-zone table built tile by tile as the trials need it.
class MdCurves {
 public:
  explicit MdCurves(const AfmFitProblem& problem)
      : problem_(problem),
        coated_(problem.coating.has_value()),
        poisson_(coated_ ? problem.coating->film.poisson_ratio : problem.poisson),
        hint_(coated_ ? problem.coating->film.youngs_modulus : problem.modulus),
        anchor_(coated_ && !problem.coating->substrate.rigid ? problem.coating->substrate.material.youngs_modulus : hint_),
        h0_(kDugdaleRangeOverZ0 * problem.surface_force_range) {}

  // lambda of a trial's w and reduced modulus: 2 (w/h0) (R/(pi w K^2))^(1/3), K = 4E*/3.
  double lambda(double work, double reduced) const {
    const double k = 4.0 * reduced / 3.0;
    return 2.0 * (work / h0_) * std::cbrt(problem_.tip.radius / (kPi * work * k * k));
  }

  std::unique_ptr<SpringBranch> branch(const AdhesiveTrial& trial, double max_indentation) {
    const double reduced = trial.modulus / (1.0 - poisson_ * poisson_);
    if (!(reduced > 0.0) || !std::isfinite(reduced) || !(trial.work > 0.0) || !std::isfinite(trial.work) ||
        (coated_ && !(trial.thickness > 0.0 && std::isfinite(trial.thickness)))) {
      throw NumericalError("afm fit: a Maugis-Dugdale trial left the finite positive parameters");
    }
    const double radius = problem_.tip.radius;
    const double length = std::cbrt(kPi * trial.work * radius * radius / reduced);
    const double a_top = std::sqrt(radius * std::max(max_indentation, 0.0));
    // The table's length unit t: the coating's; on a half-space any, chosen so that the radii
    // the branch needs (up to a few times the Hertz radius a_top) lie in the table:
    // eta = t/L >= 1.
    const double t = coated_ ? trial.thickness : length * std::max(4.0 * a_top / (kTableAOverT[1] * length), 1.0);
    // The nodes and weights of the trial's modulus (one node unless E1 is free on a coating).
    std::vector<std::pair<const MaugisDugdaleModel*, double>> mix;
    std::vector<double> node_reduced;
    // On a rigid base the modulus is a pure scale (the table's units are t and E1*): one table
    // serves every E1, and the trial's own E1 sets L and lambda.
    if (coated_ && problem_.free.modulus && !problem_.coating->substrate.rigid) {
      const double x = std::log10(trial.modulus / anchor_) * kModulusNodesPerDecade;
      const double nearest = std::round(x);
      if (coarse_) {
        // The coarse stage: linear in ln E1 between the nodes kCoarseNodeStep apart, each node's
        // table at the trial's own L and lambda (only the shape E1/E0 interpolated; THEORY.md
        // section 15, "One table per shape", "The coarse nodes").
        const double xc = x / static_cast<double>(kCoarseNodeStep);
        const long j0 = static_cast<long>(std::floor(xc));
        const double s = xc - static_cast<double>(j0);
        add_node(j0 * kCoarseNodeStep, 1.0 - s, mix, node_reduced);
        if (s > 1e-9) add_node((j0 + 1) * kCoarseNodeStep, s, mix, node_reduced);
        std::fill(node_reduced.begin(), node_reduced.end(), reduced);
      } else if (std::abs(x - nearest) < 1e-9) {
        add_node(static_cast<long>(nearest), 1.0, mix, node_reduced);
      } else {
        const long j0 = static_cast<long>(std::floor(x)) - 1;
        double weight[4];
        lagrange_weights(x, j0, weight);
        for (int a = 0; a < 4; ++a) add_node(j0 + a, weight[a], mix, node_reduced);
      }
    } else {
      // A half-space or a rigid base: the given modulus's table serves every E (shared by the
      // curves of a map); an elastic base with E1 fixed: trial.modulus is E1.
      const bool scale_free = !coated_ || problem_.coating->substrate.rigid;
      mix.push_back({&model(scale_free ? hint_ : trial.modulus, 0), 1.0});
      node_reduced.push_back(reduced);
    }
    // Each node's L and lambda at the trial's w (a radius's reads need nothing else of the trial).
    std::vector<double> node_length(mix.size()), node_lambda(mix.size());
    for (std::size_t k = 0; k < mix.size(); ++k) {
      node_length[k] = std::cbrt(kPi * trial.work * radius * radius / node_reduced[k]);
      node_lambda[k] = std::clamp(lambda(trial.work, node_reduced[k]), kMinimumLambda, kMaximumLambda);
    }
    // (delta, F) at radius a (a = 0: the curve's end): the weighted nodes' SI values, a pure
    // function of the trial and a. The branch asks some radii twice (its jump-off a_s, its top,
    // the scan's first point as the first node), and the search asks some trials again (~12 % of
    // an elastic-base fit's: a simplex's repeated vertices, the estimate's reports): each point
    // is computed once per fit.
    std::map<double, std::pair<double, double>>& computed = trial_points(trial);
    const auto point = [&](double a) -> std::pair<double, double> {
      if (const auto it = computed.find(a); it != computed.end()) return it->second;
      if (a > 0.0 && !(a / t >= kTableAOverT[0] && a / t <= kTableAOverT[1])) {
        // (the direct solve would take ~0.03 s a point)
        throw NumericalError("afm fit: the Maugis-Dugdale branch needs a contact radius " + short_text(a) +
                             " m, outside the cohesive-zone table's [" + short_text(kTableAOverT[0] * t) + ", " +
                             short_text(kTableAOverT[1] * t) + "] m at t = " + short_text(t) + " m (a/t = " +
                             short_text(a / t) + ")");
      }
      double delta = 0.0, force = 0.0;
      for (std::size_t k = 0; k < mix.size(); ++k) {
        const double l = node_length[k], lam = node_lambda[k];
        MaugisDugdalePoint p;
        try {
          p = mix[k].first->point(t / l, lam, a / l);
        } catch (const InputError& e) {
          throw NumericalError(std::string("afm fit: a Maugis-Dugdale trial: ") + e.what());
        }
        delta += mix[k].second * p.penetration * l * l / radius;
        force += mix[k].second * p.load * kPi * trial.work * radius;
      }
      computed.emplace(a, std::pair{delta, force});
      return {delta, force};
    };
    // The scan inside the table's a/t (eta = t/L: a/t = a_bar/eta). A weak adhesion (L small
    // against the table's smallest radius) scans from there over half a decade: its minimum of
    // Z is the curve's end (DMT's limit), found as the scan's first point.
    const double eta = t / length;
    const double lo = std::max(kScanLow, 1.0001 * kTableAOverT[0] * eta);
    const double hi = std::min(std::max(kScanHigh, 3.0 * lo), 0.9999 * kTableAOverT[1] * eta);
    if (!(lo < hi)) {
      throw NumericalError("afm fit: the Maugis-Dugdale branch's contact radii leave the cohesive-zone table's [" +
                           short_text(kTableAOverT[0] * t) + ", " + short_text(kTableAOverT[1] * t) + "] m at t = " +
                           short_text(t) + " m");
    }
    auto made = std::make_unique<SpringBranch>(point, length, lo, hi, kScanPerDecade, problem_.spring_constant,
                                               max_indentation, a_top, kBranchNodes, point(0.0), reduced);
    if (force_limit_ > 0.0 && !(std::abs(made->jump_force()) <= force_limit_)) {
      throw NumericalError("afm fit: a Maugis-Dugdale trial's jump-off force " + short_text(made->jump_force()) +
                           " N exceeds kForceLimit times the data's force range");
    }
    return made;
  }

  // The coarse stage's reading of E1 (SpringModel::coarse) on or off (off: the model).
  void coarse(bool on) { coarse_ = on; }

  // Trials whose jump-off force exceeds kForceLimit times `range` [N] (the data's) cost +inf:
  // they cannot describe the data, and the least-squares sums of the profile (closed-form
  // normal equations) lose every digit to cancellation for model forces ~1e8 times the data's.
  void limit_force(double range) { force_limit_ = kForceLimit * range; }

  // The direct solves the tables of this fit rest on (tables shared with earlier fits count
  // what those built too).
  long solves() const {
    long n = 0;
    for (const auto& m : models_) n += m.second->table_nodes();
    return n;
  }

 private:
  void add_node(long j, double weight, std::vector<std::pair<const MaugisDugdaleModel*, double>>& mix,
                std::vector<double>& node_reduced) {
    const double e = anchor_ * std::pow(10.0, static_cast<double>(j) / kModulusNodesPerDecade);
    mix.push_back({&model(e, j), weight});
    node_reduced.push_back(e / (1.0 - poisson_ * poisson_));
  }
  // The model of the stack at film modulus e (node j; one model when E1 is not free).
  const MaugisDugdaleModel& model(double e, long j) {
    auto it = models_.find(j);
    if (it != models_.end()) return *it->second;
    Material film{coated_ ? e : hint_, poisson_};
    Substrate substrate;
    substrate.material = film;
    if (coated_) substrate = problem_.coating->substrate;
    return *models_.emplace(j, shared_model(film, substrate)).first->second;
  }

  // The points computed for a trial (modulus, w, t and the stage's reading of E1) this fit;
  // the oldest trial's forgotten past kRememberedTrials (a fit reads ~250 trials of ~200 points).
  using TrialKey = std::tuple<double, double, double, bool>;
  static constexpr std::size_t kRememberedTrials = 512;
  std::map<double, std::pair<double, double>>& trial_points(const AdhesiveTrial& trial) {
    const TrialKey key{trial.modulus, trial.work, trial.thickness, coarse_};
    if (const auto it = trial_points_.find(key); it != trial_points_.end()) return it->second;
    if (trial_order_.size() >= kRememberedTrials) {
      trial_points_.erase(trial_order_.front());
      trial_order_.erase(trial_order_.begin());
    }
    trial_order_.push_back(key);
    return trial_points_[key];
  }

  const AfmFitProblem& problem_;
  std::map<TrialKey, std::map<double, std::pair<double, double>>> trial_points_;
  std::vector<TrialKey> trial_order_;
  bool coated_, coarse_ = false;
  double poisson_, hint_, anchor_, h0_, force_limit_ = 0.0;
  std::map<long, std::shared_ptr<const MaugisDugdaleModel>> models_;
};

void check_md_problem(const AfmFitProblem& problem) {
  if (problem.tip.kind != AfmTip::Kind::kParaboloid) {
    throw InputError("afm fit: the Maugis-Dugdale model takes a sphere tip (radius R); got " + problem.tip.description);
  }
  if (!(problem.spring_constant > 0.0) || !std::isfinite(problem.spring_constant)) {
    throw InputError("afm fit: the Maugis-Dugdale model needs the cantilever's spring constant k > 0 (got " +
                     short_text(problem.spring_constant) + " N/m)");
  }
  if (!(problem.surface_force_range > 0.0) || !std::isfinite(problem.surface_force_range)) {
    throw InputError("afm fit: the surface-force range z0 must be > 0 (got " + short_text(problem.surface_force_range) + " m)");
  }
  const double e = problem.coating ? problem.coating->film.youngs_modulus : problem.modulus;
  if (!(e > 0.0 && std::isfinite(e))) {
    throw InputError("afm fit: E must be > 0 (the value if fixed, the centre of its search if free; got " + short_text(e) + ")");
  }
}

}  // namespace

AfmFitResult afm_fit_md(const std::vector<double>& z, const std::vector<double>& force, const AfmFitProblem& problem,
                        int free_count) {
  return afm_fit_md(z, force, problem, free_count, MdE1Search::kCoarseNodes);
}

AfmFitResult afm_fit_md(const std::vector<double>& z, const std::vector<double>& force, const AfmFitProblem& problem,
                        int free_count, MdE1Search search) {
  check_md_problem(problem);
  MdCurves curves(problem);
  if (!force.empty()) {
    const auto [lo, hi] = std::minmax_element(force.begin(), force.end());
    curves.limit_force(*hi - *lo);
  }
  SpringModel model;
  model.name = "Maugis-Dugdale";
  model.branch = [&](const AdhesiveTrial& t, double max_indentation) { return curves.branch(t, max_indentation); };
  if (search == MdE1Search::kCoarseNodes && problem.coating && problem.free.modulus && !problem.coating->substrate.rigid) {
    model.coarse = [&](bool on) { curves.coarse(on); };
  }
  model.report = [&](const AdhesiveTrial& estimate, AfmFitResult& r) {
    afm_tabor_maugis(problem, r);
    const double z0 = problem.surface_force_range;
    const std::string where = "Maugis's lambda = " + short_text(r.maugis_lambda) + " (Dugdale range h0 = " +
                              short_text(kDugdaleRangeOverZ0 * z0) + " m from --range z0 = " + short_text(z0) + " m)";
    if (r.maugis_lambda > kMaximumLambda) {
      r.warnings.push_back(where + " is above " + short_text(kMaximumLambda) +
                           ": the curve is JKR's (computed at lambda = " + short_text(kMaximumLambda) +
                           "); the JKR fit (--model jkr) is the same fit at a fraction of the cost");
    } else if (r.maugis_lambda < kMinimumLambda) {
      r.warnings.push_back(where + " is below " + short_text(kMinimumLambda) +
                           ": outside the cohesive-zone table; computed at lambda = " + short_text(kMinimumLambda) +
                           " (DMT's curve to ~3e-4)");
    }
    const auto branch = curves.branch(estimate, std::max(r.max_indentation, 1e-12));
    if (branch->jump_at_end()) {
      r.warnings.push_back(where + ", k = " + short_text(problem.spring_constant) +
                           " N/m: the spring holds the tip down to the curve's end (contact radius 0); the "
                           "separated-surfaces branch beyond it is not in the model, which jumps off there "
                           "(outside the Maugis-Dugdale model's range through the cantilever)");
    }
    r.solver_calls = curves.solves();
  };
  return afm_fit_adhesive(z, force, problem, free_count, &model);
}

std::vector<double> afm_md_model_force(const AfmFitProblem& problem, const std::vector<double>& z) {
  check_md_problem(problem);
  if (!(problem.work > 0.0 && std::isfinite(problem.work))) {
    throw InputError("afm fit: the Maugis-Dugdale model needs w > 0 (got " + short_text(problem.work) + " J/m2)");
  }
  double max_delta = 0.0;
  for (double v : z) max_delta = std::max(max_delta, problem.contact_point - v);
  MdCurves curves(problem);
  AdhesiveTrial trial{problem.coating ? problem.coating->film.youngs_modulus : problem.modulus, problem.work,
                      problem.coating ? problem.coating->thickness : 0.0};
  const auto branch = curves.branch(trial, std::max(max_delta, 1e-12));
  std::vector<double> f(z.size());
  for (std::size_t i = 0; i < z.size(); ++i) {
    f[i] = problem.baseline + problem.tilt * (z[i] - problem.contact_point) + branch->at(problem.contact_point - z[i]).first;
  }
  return f;
}

const AfmModelInfo& afm_model_md() {
  static const AfmModelInfo model{
      "md", {"maugis-dugdale"}, "Maugis-Dugdale", "adhesive Maugis-Dugdale fit through the cantilever", true,
      afm::SegmentKind::kRetract, afm_parameter_table({afm_work_parameter()}, true), afm_fit_md, afm_md_model_force,
      [](const AfmFitProblem& problem, bool batch) -> std::string {
        char h0[32];  // shortest round trip, as the CLI writes numbers
        *std::to_chars(h0, h0 + sizeof h0 - 1, kDugdaleRangeOverZ0 * problem.surface_force_range).ptr = '\0';
        return std::string("F = b + m (z - z_c) + F_MD(z_c - z), F_MD: Maugis-Dugdale (cohesive-zone table, sigma0 = w/h0, h0 = 0.97 z0") +
               (batch ? std::string(" = ") + h0 + " m) of the sphere on the sample on the branch stable under the cantilever's spring k (each curve's), 0 past its jump-off"
                      : ") of the sphere on the sample on the branch stable under the spring k (0 past its jump-off)");
      },
      "the Maugis-Dugdale table holds lambda in [" + short_text(kMinimumLambda) + ", " + short_text(kMaximumLambda) + "]",
      "the same with a Maugis-Dugdale zone of range h0 = 0.97 z0, --range: for lambda below ~5"};
  return model;
}

}  // namespace coatcontact::fit::internal
