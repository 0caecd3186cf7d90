// The adhesive AFM retract fit (THEORY.md section 15, "Adhesive retract"): JKR of a sphere on
// the half-space or a coating, on the branch stable under the cantilever's spring k, with the
// contact point, a baseline and its slope. See coatcontact/afm_fit.hpp.
#include <gsl/gsl_interp.h>
#include <gsl/gsl_multifit.h>
#include <gsl/gsl_multimin.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <numeric>
#include <string>
#include <tuple>
#include <utility>

#include "afm_internal.hpp"
#include "coatcontact/afm_fit.hpp"
#include "coatcontact/detail/brent.hpp"
#include "coatcontact/detail/format.hpp"
#include "coatcontact/detail/gsl_handler_off.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/limits.hpp"
#include "coatcontact/reduced.hpp"

namespace coatcontact::fit {

namespace {

using coatcontact::detail::short_text;
constexpr double kPi = 3.14159265358979323846;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Nodes of one branch table (contact radii from a_s to the deepest indentation).
constexpr int kBranchNodes = 256;
// Scan of delta + F/k for its minimum a_s: a/L_a in [kScanLow, kScanHigh], per decade.
constexpr double kScanLow = 0.01, kScanHigh = 30.0;
constexpr int kScanPerDecade = 24;
// Bounded searches: Nelder-Mead iterations (binned data), Gauss-Newton steps (all points).
constexpr int kSimplexIterations = 300;
constexpr int kPolishSteps = 8;
// A short contact (THEORY.md section 15, "Search and errors"): the points up to the data's jump
// would fill fewer than kContactBins search bins; the contact-point grid then holds at least
// kContactGridPoints points where a contact point can hold data in contact.
constexpr std::size_t kContactBins = 12;
constexpr int kContactGridPoints = 12;
// The coarse stage of a free E1 on a coating sweeps its nodes up to this a/t: below ~1 the
// solver needs no kernel table (~0.02 ms a radius; the first radius past it builds one, ~10 ms,
// for a soft film of nu1 = 0.5 on a stiffer base; measured at E1/E0 0.005-2.5).
constexpr double kCoarseAOverT = 1.0;
// The coarse stage's simplex stops at this size in the ln-parameters: the whole reach's simplex
// starts from it.
constexpr double kCoarseSimplexSize = 1e-3;
// Stages 1b and 1c: each node probed (E1 on the node, its table alone) has its other axes
// searched by a simplex to this size (it only picks stage 2's start: on the four real curves
// 1e-3 cost 1.6-1.9 times the probes' profile evaluations, for answers within 0.005 SE).
constexpr double kProbeSimplexSize = 1e-2;
// Stage 1c, the walk over the model's nodes: its step at most this many nodes (half a decade: a
// step of a decade took igor U3_3 past the every-node search's minimum at 135 kPa to a basin at
// 26 MPa), at most kWalkReach nodes (4 decades) from where it starts.
constexpr long kWalkStep = 4;
constexpr long kWalkReach = 32;
// Stage 2's first simplex step in ln E1 (after the walk): a quarter node (the other axes 0.15),
// so that its first trials stay on the four nodes around its start (0.15, half a node, had them
// read a fifth node's table on pr14 and spot3).
constexpr double kModelFirstStep = 0.25 * 2.302585092994046 / kModulusNodesPerDecade;  // (ln 10)
// The anchored model of a free E1 on a coating: re-anchored while the polish moves E1 by more
// than this in ln E1 (the fitted E1 then misses the anchor-exact one by ~6e-3 of the move: ~2e-6; THEORY.md section 15), at most
// kAnchorMoves times.
constexpr double kAnchorTolerance = 3e-4;
// ... or by more than this fraction of the standard error of ln E1, when larger (a miss of
// ~6e-3 of the move is then ~0.003 of a standard error).
constexpr double kAnchorTolerancePerError = 0.5;
constexpr int kAnchorMoves = 4;

// The four reduced variables at a/t: constant on a half-space, splines of a reduced-solver
// sweep (per film modulus) on a coating.
using Reduced = internal::ReducedAt;

class CoatingSweep {
 public:
  CoatingSweep(const std::vector<ReducedVariables>& sweep) {
    std::vector<double> x, pi, delta, eeq, gamma;
    for (const ReducedVariables& v : sweep) {
      x.push_back(std::log(v.a_over_t));
      pi.push_back(v.pi_s);
      delta.push_back(v.delta_s);
      eeq.push_back(v.e_eq);
      gamma.push_back(v.gamma1);
    }
    for (auto* y : {&pi, &delta, &eeq, &gamma}) {
      splines_.emplace_back(x, *y);
      splines_.back().declare_uniform();  // the lattice is uniform in ln(a/t)
    }
  }

  // Outside the sweep: its end values (the film's own limit below; trials only above, the
  // final fit is checked against max_a_over_t()).
  Reduced at(double a_over_t) const {
    const std::vector<double>& x = splines_.front().x();
    const double v = std::clamp(std::log(a_over_t), x.front(), x.back());
    const std::size_t k = splines_.front().interval(v);
    return {splines_[0].value(v, k), splines_[1].value(v, k), splines_[2].value(v, k), splines_[3].value(v, k)};
  }
  // Past the sweep's end the natural spline's line in ln(a/t) (the coarse stage's trials,
  // THEORY.md section 15, "The JKR search on a coating"); inside, at().
  Reduced extrapolated(double a_over_t) const {
    const std::vector<double>& x = splines_.front().x();
    const double v = std::log(a_over_t);
    if (v <= x.back()) return at(a_over_t);
    const std::size_t k = x.size() - 2;
    const double end = x.back();
    double out[4];
    for (int j = 0; j < 4; ++j) out[j] = splines_[j].value(end, k) + (v - end) * splines_[j].slope(end, k);
    return {out[0], out[1], out[2], out[3]};
  }
  double max_a_over_t() const { return std::exp(splines_.front().x().back()); }

 private:
  std::vector<internal::SplinePieces> splines_;
};

// Reduced-solver sweeps of the E1 nodes, shared by every fit of the process: the curves of a
// map share the coating and E1's start, hence their nodes (THEORY.md section 15). A node's sweep
// is a prefix of the a/t lattice, extended on demand; a fit uses the prefix of its own reach
// only, so its result does not depend on what other fits computed before (the values at one a/t
// do not depend on the other radii solved, coatcontact/reduced.hpp).
struct SharedNode {
  std::mutex mutex;
  std::unique_ptr<ReducedSolver> solver;
  std::vector<ReducedVariables> values;
};
using NodeKey = std::tuple<double, double, bool, double, double, double, std::size_t, std::vector<double>>;
constexpr std::size_t kSharedNodes = 96;
std::mutex shared_nodes_mutex;
std::map<NodeKey, std::shared_ptr<SharedNode>>& shared_nodes() {
  static std::map<NodeKey, std::shared_ptr<SharedNode>> nodes;
  return nodes;
}

// The first `count` values of the lattice's sweep of the coating's stack with the free layer's
// modulus `modulus` (the lattice is identified by its size: kCoatingAOverT at kCoatingPerDecade;
// a/T on a stack, THEORY.md section 15, "JKR and DMT on a stack").
std::vector<ReducedVariables> shared_sweep(const AfmCoating& coating, double modulus, const std::vector<double>& lattice,
                                           std::size_t count) {
  const Substrate& substrate = coating.substrate;
  const double tolerance = coating.solver_tolerance;
  std::shared_ptr<SharedNode> node;
  {
    const std::lock_guard<std::mutex> lock(shared_nodes_mutex);
    auto& nodes = shared_nodes();
    const NodeKey key{modulus, coating.film.poisson_ratio, substrate.rigid, substrate.rigid ? 0.0 : substrate.material.youngs_modulus,
                      substrate.rigid ? 0.0 : substrate.material.poisson_ratio, tolerance, lattice.size(),
                      internal::afm_stack_shape(coating)};
    auto it = nodes.find(key);
    if (it == nodes.end()) {
      if (nodes.size() >= kSharedNodes) nodes.clear();  // the fits holding one keep it
      it = nodes.emplace(key, std::make_shared<SharedNode>()).first;
    }
    node = it->second;
  }
  const std::lock_guard<std::mutex> lock(node->mutex);
  if (!node->solver) node->solver = std::make_unique<ReducedSolver>(coating.stack_with(modulus, coating.thickness));
  if (node->values.size() < count) {
    // One radius at a time: a node's few tens of radii cost ~1 ms beside its kernel table, and a
    // parallel sweep's idle threads spin between them (twice the CPU of a first curve).
    for (std::size_t k = node->values.size(); k < count; ++k) node->values.push_back(node->solver->solve(lattice[k], tolerance));
  }
  return {node->values.begin(), node->values.begin() + static_cast<long>(count)};
}

using Trial = internal::AdhesiveTrial;
using Branch = internal::SpringBranch;

// The branch F(delta) of a law under spring control for one trial (internal::SpringBranch): the
// scan of delta + F/k over a/L_a in [kScanLow, kScanHigh], kBranchNodes radii from a_s.
std::unique_ptr<Branch> law_branch(const AfmFitProblem& problem, std::shared_ptr<const CoatingSweep> sweep,
                                   const Trial& trial, double max_indentation, const internal::ReducedLaw& law,
                                   bool extrapolate = false) {
  // On a stack: a/T and the top layer's E* (THEORY.md section 15, "JKR and DMT on a stack").
  const bool stack = sweep && problem.coating && problem.coating->multilayer();
  const double reduced = stack ? problem.coating->reference_modulus(trial.modulus)
                               : trial.modulus / (1.0 - problem.poisson * problem.poisson);
  const double length_unit = stack ? problem.coating->total_thickness(trial.thickness) : trial.thickness;
  if (!(reduced > 0.0) || !std::isfinite(reduced) || !(trial.work > 0.0) || !std::isfinite(trial.work) ||
      (sweep && !(trial.thickness > 0.0 && std::isfinite(trial.thickness)))) {
    throw NumericalError("afm fit: a " + law.name + " trial left the finite positive parameters");
  }
  const double radius = problem.tip.radius;
  const double length = std::cbrt(kPi * trial.work * radius * radius / reduced);
  const auto point = [&](double a) -> std::pair<double, double> {
    Reduced v;
    if (sweep) v = extrapolate ? sweep->extrapolated(a / length_unit) : sweep->at(a / length_unit);
    return law.point(a, v, reduced, trial.work, radius);
  };
  return std::make_unique<Branch>(point, length, kScanLow, kScanHigh, kScanPerDecade, problem.spring_constant,
                                  max_indentation, std::sqrt(radius * std::max(max_indentation, 0.0)), kBranchNodes,
                                  law.end ? law.end(reduced, trial.work, radius) : std::nullopt, reduced);
}

// Weighted points sorted by tip position (bins of a dense curve carry their counts).
struct Points {
  std::vector<double> z, f, weight;
};

Points sorted_points(const std::vector<double>& z, const std::vector<double>& f) {
  std::vector<std::size_t> order(z.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return z[a] < z[b]; });
  Points p;
  for (std::size_t i : order) {
    p.z.push_back(z[i]);
    p.f.push_back(f[i]);
    p.weight.push_back(1.0);
  }
  return p;
}

// The deepest points up to the data's deepest force (the jump-off): every point a fit near the
// data's jump holds in contact lies there. Their count (sorted points from the front).
std::size_t points_to_jump(const Points& p) {
  return static_cast<std::size_t>(std::min_element(p.f.begin(), p.f.end()) - p.f.begin()) + 1;
}

std::size_t points_per_bin(std::size_t n) { return (n + kAdhesiveSearchPoints - 1) / kAdhesiveSearchPoints; }

// A contact too short for the search's bins (THEORY.md section 15, "Search and errors"): the
// points up to the jump would fill fewer than kContactBins bins.
bool short_contact(const Points& all) { return points_to_jump(all) < kContactBins * points_per_bin(all.z.size()); }

// The top of the contact points at which data can be in contact near the data's jump: the
// deepest point plus twice the depth of the jump (-inf unless the contact is short).
double contact_top(const Points& all) {
  return short_contact(all) ? 2.0 * all.z[points_to_jump(all) - 1] - all.z.front() : -kInfinity;
}

// Equal-count bins (means of z and F, weight = count) of at most kAdhesiveSearchPoints bins; a
// bin closes early at a gap in z wider than 5 median spacings (the jump-off leaves one on the
// tip axis), so that no bin straddles the jump. A short contact's points below its contact top
// stay single (a few more bins).
Points binned(const Points& all) {
  const std::size_t n = all.z.size();
  if (n <= kAdhesiveSearchPoints) return all;
  std::vector<double> gaps(n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i) gaps[i] = all.z[i + 1] - all.z[i];
  std::nth_element(gaps.begin(), gaps.begin() + static_cast<long>(gaps.size() / 2), gaps.end());
  const double wide = 5.0 * gaps[gaps.size() / 2];
  const std::size_t per_bin = points_per_bin(n);
  // Points kept single: those below the contact top.
  const auto single = static_cast<std::size_t>(std::lower_bound(all.z.begin(), all.z.end(), contact_top(all)) - all.z.begin());
  Points out;
  double sz = 0.0, sf = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < n; ++i) {
    sz += all.z[i];
    sf += all.f[i];
    ++count;
    const bool gap = i + 1 < n && all.z[i + 1] - all.z[i] > wide;
    if (count == per_bin || i < single || gap || i + 1 == n) {
      out.z.push_back(sz / count);
      out.f.push_back(sf / count);
      out.weight.push_back(static_cast<double>(count));
      sz = sf = 0.0;
      count = 0;
    }
  }
  return out;
}

struct Linear {
  double baseline = 0.0, tilt = 0.0, rss = kInfinity;
  std::size_t in_contact = 0;  // points (bins) the model holds in contact
};

// At one contact point: F_i = b + m (z_i - z_c) + g(z_c - z_i), (b, m) free or fixed in closed
// form (weighted normal equations), and the weighted residual sum.
class Objective {
 public:
  Objective(const Points& p, const AfmFitProblem& problem, double contact_top) : p_(p), problem_(problem), contact_top_(contact_top) {
    for (std::size_t i = 0; i < p.z.size(); ++i) {
      const double w = p.weight[i], z = p.z[i] - origin(), f = p.f[i];
      sw_ += w, sz_ += w * z, szz_ += w * z * z, sf_ += w * f, szf_ += w * z * f, sff_ += w * f * f;
    }
  }
  // z is shifted by the mean of the data for conditioning.
  double origin() const { return p_.z.empty() ? 0.0 : 0.5 * (p_.z.front() + p_.z.back()); }

  Linear at(const Branch& branch, double contact) const {
    ++evaluations_;
    double sg = 0.0, szg = 0.0, sfg = 0.0, sgg = 0.0;
    const double limit = contact - branch.jump_delta();  // in contact: z < limit
    const std::size_t count = static_cast<std::size_t>(std::lower_bound(p_.z.begin(), p_.z.end(), limit) - p_.z.begin());
    // No point in contact costs +inf: the model is the bare line, its w (and E, t) undetermined,
    // and the final fit would refuse it (THEORY.md section 15, "Search and errors").
    if (count == 0) return Linear{};
    ++contact_evaluations_;
    thread_local std::vector<double> g;
    g.resize(count);
    branch.values(contact, p_.z.data(), count, g.data());
    for (std::size_t i = 0; i < count; ++i) {
      const double w = p_.weight[i];
      sg += w * g[i], szg += w * (p_.z[i] - origin()) * g[i], sfg += w * p_.f[i] * g[i], sgg += w * g[i] * g[i];
    }
    // y = F - g; u = z - z_c = (z - origin) - c.
    const double c = contact - origin();
    const double sy = sf_ - sg, szy = szf_ - szg, syy = sff_ - 2.0 * sfg + sgg;
    const double su = sz_ - c * sw_, suu = szz_ - 2.0 * c * sz_ + c * c * sw_, suy = szy - c * sy;
    Linear out;
    double b = problem_.baseline, m = problem_.tilt;
    if (problem_.free.baseline && problem_.free.tilt) {
      const double det = sw_ * suu - su * su;
      if (!(det > 0.0)) return out;
      b = (suu * sy - su * suy) / det;
      m = (sw_ * suy - su * sy) / det;
    } else if (problem_.free.baseline) {
      b = (sy - m * su) / sw_;
    } else if (problem_.free.tilt) {
      if (!(suu > 0.0)) return out;
      m = (suy - b * su) / suu;
    }
    // sum w (y - b - m u)^2
    const double rss = syy + b * b * sw_ + m * m * suu - 2.0 * b * sy - 2.0 * m * suy + 2.0 * b * m * su;
    out.baseline = b;
    out.tilt = m;
    out.rss = std::isfinite(rss) ? std::max(0.0, rss) : kInfinity;  // (a NaN would read as a perfect fit)
    out.in_contact = count;
    return out;
  }
  int evaluations() const { return evaluations_; }
  // contact_top(all points) (the profile's grid is refined below it).
  double contact_top() const { return contact_top_; }
  // Evaluations that held at least one point in contact.
  int contact_evaluations() const { return contact_evaluations_; }

 private:
  const Points& p_;
  const AfmFitProblem& problem_;
  const double contact_top_;
  double sw_ = 0.0, sz_ = 0.0, szz_ = 0.0, sf_ = 0.0, szf_ = 0.0, sff_ = 0.0;
  mutable int evaluations_ = 0, contact_evaluations_ = 0;
};

struct ContactFit {
  double contact = 0.0;
  Linear linear;
};

// The profile's grid: `count` points on [lo, hi], and kContactGridPoints more on its part below
// the objective's contact top when fewer than that lie there (a contact shorter than the step).
std::vector<double> contact_grid(const Objective& objective, double lo, double hi, int count) {
  std::vector<double> grid(count);
  for (int k = 0; k < count; ++k) grid[k] = lo + (hi - lo) * k / (count - 1.0);
  const double top = std::min(hi, objective.contact_top());
  if (!(top > lo) || std::upper_bound(grid.begin(), grid.end(), top) - grid.begin() >= kContactGridPoints) return grid;
  for (int k = 1; k <= kContactGridPoints; ++k) grid.push_back(lo + (top - lo) * k / (kContactGridPoints + 1.0));
  std::sort(grid.begin(), grid.end());
  grid.erase(std::unique(grid.begin(), grid.end()), grid.end());
  return grid;
}

// The contact point on [lo, hi]: a grid (contact_grid), then Brent on the brackets of the
// three lowest grid minima (the profile has kinks where points enter contact, and a jump
// where the jump-off passes a point); fixed: the problem's value.
ContactFit search_contact(const Objective& objective, const Branch& branch, const AfmFitProblem& problem, double lo,
                          double hi, int grid_points) {
  if (!problem.free.contact_point) return {problem.contact_point, objective.at(branch, problem.contact_point)};
  const std::vector<double> grid = contact_grid(objective, lo, hi, grid_points);
  const int count = static_cast<int>(grid.size());
  std::vector<double> cost(count);
  for (int k = 0; k < count; ++k) cost[k] = objective.at(branch, grid[k]).rss;
  std::vector<int> minima;
  for (int k = 0; k < count; ++k) {
    if ((k == 0 || cost[k] <= cost[k - 1]) && (k + 1 == count || cost[k] <= cost[k + 1])) minima.push_back(k);
  }
  std::sort(minima.begin(), minima.end(), [&](int a, int b) { return cost[a] < cost[b]; });
  if (minima.size() > 3) minima.resize(3);
  ContactFit best{grid[minima.front()], objective.at(branch, grid[minima.front()])};
  const auto rss = [&](double c) { return objective.at(branch, c).rss; };
  for (int k : minima) {
    if (k == 0 || k + 1 == count) continue;
    const auto found = coatcontact::detail::brent_minimum(rss, grid[k - 1], cost[k - 1], grid[k], cost[k], grid[k + 1],
                                                          cost[k + 1], {(hi - lo) * 1e-10, 0.0, 100});
    if (!found) continue;
    const Linear value = objective.at(branch, found->x);
    if (value.rss < best.linear.rss) best = {found->x, value};
  }
  return best;
}

// Minimum of f over ln-parameters by GSL's Nelder-Mead simplex (bounded iterations).
std::vector<double> simplex(const std::function<double(const std::vector<double>&)>& f, std::vector<double> start,
                            double step, double size, int* iterations, double first_step = 0.0) {
  coatcontact::detail::GslHandlerOff handler_off;
  const std::size_t dim = start.size();
  struct Params {
    const std::function<double(const std::vector<double>&)>* f;
    std::size_t dim;
  } params{&f, dim};
  gsl_multimin_function fn;
  fn.n = dim;
  fn.params = &params;
  fn.f = [](const gsl_vector* x, void* raw) {
    const auto* p = static_cast<Params*>(raw);
    std::vector<double> v(p->dim);
    for (std::size_t k = 0; k < p->dim; ++k) v[k] = gsl_vector_get(x, k);
    const double value = (*p->f)(v);
    return std::isfinite(value) ? value : std::numeric_limits<double>::max();
  };
  std::unique_ptr<gsl_vector, void (*)(gsl_vector*)> x(gsl_vector_alloc(dim), gsl_vector_free),
      steps(gsl_vector_alloc(dim), gsl_vector_free);
  for (std::size_t k = 0; k < dim; ++k) gsl_vector_set(x.get(), k, start[k]);
  gsl_vector_set_all(steps.get(), step);
  if (first_step > 0.0) gsl_vector_set(steps.get(), 0, first_step);  // (the first axis's own, if given)
  std::unique_ptr<gsl_multimin_fminimizer, void (*)(gsl_multimin_fminimizer*)> minimizer(
      gsl_multimin_fminimizer_alloc(gsl_multimin_fminimizer_nmsimplex2, dim), gsl_multimin_fminimizer_free);
  gsl_multimin_fminimizer_set(minimizer.get(), &fn, x.get(), steps.get());
  int k = 0;
  for (; k < kSimplexIterations; ++k) {
    if (gsl_multimin_fminimizer_iterate(minimizer.get()) != 0) break;
    if (gsl_multimin_test_size(gsl_multimin_fminimizer_size(minimizer.get()), size) == GSL_SUCCESS) break;
  }
  *iterations = k;
  for (std::size_t j = 0; j < dim; ++j) start[j] = gsl_vector_get(minimizer->x, j);
  return start;
}

}  // namespace

void afm_clear_shared_sweeps() {
  {
    const std::lock_guard<std::mutex> lock(shared_nodes_mutex);
    shared_nodes().clear();
  }
  internal::afm_clear_coated_tables();
}

namespace internal {

std::vector<double> afm_least_squares_step(const std::vector<std::vector<double>>& columns, const std::vector<double>& residual) {
  const std::size_t p = columns.size(), n = residual.size();
  coatcontact::detail::GslHandlerOff handler_off;
  std::unique_ptr<gsl_matrix, void (*)(gsl_matrix*)> a(gsl_matrix_alloc(n, p), gsl_matrix_free);
  std::unique_ptr<gsl_vector, void (*)(gsl_vector*)> y(gsl_vector_alloc(n), gsl_vector_free), x(gsl_vector_alloc(p), gsl_vector_free);
  std::unique_ptr<gsl_matrix, void (*)(gsl_matrix*)> cov(gsl_matrix_alloc(p, p), gsl_matrix_free);
  std::unique_ptr<gsl_multifit_linear_workspace, void (*)(gsl_multifit_linear_workspace*)> work(
      gsl_multifit_linear_alloc(n, p), gsl_multifit_linear_free);
  for (std::size_t i = 0; i < n; ++i) {
    gsl_vector_set(y.get(), i, residual[i]);
    for (std::size_t k = 0; k < p; ++k) gsl_matrix_set(a.get(), i, k, columns[k][i]);
  }
  std::size_t rank = 0;
  double chisq = 0.0;
  std::vector<double> out(p, 0.0);
  if (gsl_multifit_linear_tsvd(a.get(), y.get(), 1e-12, x.get(), cov.get(), &chisq, &rank, work.get()) != 0) return out;
  for (std::size_t k = 0; k < p; ++k) out[k] = std::isfinite(gsl_vector_get(x.get(), k)) ? gsl_vector_get(x.get(), k) : 0.0;
  return out;
}

void afm_tabor_maugis(const AfmFitProblem& problem, AfmFitResult& r) {
  const double z0 = problem.surface_force_range, reduced = r.reduced_modulus, w = r.work, radius = problem.tip.radius;
  r.tabor_mu = std::cbrt(radius * w * w / (reduced * reduced * z0 * z0 * z0));
  // Maugis's lambda with the Dugdale stress of the Lennard-Jones law of range z0: h0 = w/sigma0
  // = 0.97 z0 (Johnson & Greenwood 1997); the scales' thickness does not enter lambda.
  const double length = std::cbrt(kPi * w * radius * radius / reduced);
  const MaugisScales scales = maugis_scales(radius, length, w, reduced);
  r.maugis_lambda = maugis_lambda(scales, w / (kDugdaleRangeOverZ0 * z0));
}

std::vector<double> afm_reduced_model_force(const AfmFitProblem& problem, const std::vector<double>& z,
                                            const ReducedLaw& law) {
  if (problem.tip.kind != AfmTip::Kind::kParaboloid) throw InputError("afm fit: the " + law.name + " model takes a sphere tip (radius R)");
  if (!(problem.spring_constant > 0.0) || !std::isfinite(problem.spring_constant)) {
    throw InputError("afm fit: the " + law.name + " model needs the cantilever's spring constant k > 0");
  }
  double max_delta = 0.0;
  for (double v : z) max_delta = std::max(max_delta, problem.contact_point - v);
  std::shared_ptr<const CoatingSweep> sweep;
  Trial trial{problem.modulus, problem.work, 0.0};
  AfmFitProblem p = problem;
  if (problem.coating) {
    const AfmCoating& c = *problem.coating;
    trial = {c.film.youngs_modulus, problem.work, c.thickness};
    p.poisson = c.film.poisson_ratio;
    const ReducedSolver solver(c.stack());
    std::vector<double> grid;
    const double decades = std::log10(kCoatingAOverT[1] / kCoatingAOverT[0]);
    const int count = static_cast<int>(std::lround(decades * kCoatingPerDecade)) + 1;
    for (int k = 0; k < count; ++k) grid.push_back(kCoatingAOverT[0] * std::pow(10.0, decades * k / (count - 1)));
    sweep = std::make_shared<const CoatingSweep>(solver.sweep(grid, c.solver_tolerance));
  }
  const auto branch = law_branch(p, sweep, trial, std::max(max_delta, 1e-12), law);
  std::vector<double> f(z.size());
  for (std::size_t i = 0; i < z.size(); ++i) {
    f[i] = problem.baseline + problem.tilt * (z[i] - problem.contact_point) + branch->at(problem.contact_point - z[i]).first;
  }
  return f;
}

namespace {

// The adhesive fit's input: a sphere, the spring, z0, a fixed w > 0 and a half-space E > 0.
void check_adhesive_input(const AfmFitProblem& problem, const std::string& name) {
  if (problem.tip.kind != AfmTip::Kind::kParaboloid) {
    throw InputError("afm fit: the " + name + " model takes a sphere tip (radius R); got " + problem.tip.description);
  }
  if (!(problem.spring_constant > 0.0) || !std::isfinite(problem.spring_constant)) {
    throw InputError("afm fit: the " + name + " model needs the cantilever's spring constant k > 0 (got " +
                     short_text(problem.spring_constant) + " N/m)");
  }
  if (!(problem.surface_force_range > 0.0) || !std::isfinite(problem.surface_force_range)) {
    throw InputError("afm fit: the surface-force range z0 must be > 0 (got " + short_text(problem.surface_force_range) + " m)");
  }
  if (!problem.free.work && !(problem.work > 0.0 && std::isfinite(problem.work))) {
    throw InputError("afm fit: a fixed w must be > 0 (got " + short_text(problem.work) + " J/m2)");
  }
  if (!problem.coating && !(problem.modulus > 0.0 && std::isfinite(problem.modulus))) {
    throw InputError("afm fit: E must be > 0 (the value if fixed, the centre of its search if free; got " +
                     short_text(problem.modulus) + ")");
  }
}

// The start values: E (the adhesionless fit of the same points for a free half-space modulus:
// the given value may be anything > 0, as in the Hertz fit) and w (the law's soft-lever
// pull-off below the median force), unless given.
std::pair<double, double> adhesive_hints(const std::vector<double>& z_data, const std::vector<double>& f_data,
                                         const AfmFitProblem& problem, const Points& all, const ReducedLaw& law) {
  const bool coated = problem.coating.has_value();
  const std::size_t n = all.f.size();
  double e_hint = coated ? problem.coating->film.youngs_modulus : problem.modulus;
  if (!coated && problem.free.modulus) {
    AfmFitProblem hertz = problem;
    hertz.model = AfmModel::kHertz;
    hertz.free = {true, true, true, false, false, false};
    hertz.noise_sigma = 0.0;
    try {
      const double e = afm_fit(z_data, f_data, hertz).modulus;
      if (e > 0.0 && std::isfinite(e)) e_hint = e;
    } catch (const NumericalError&) {
    }
  }
  double w_hint = problem.work;
  if (!(w_hint > 0.0)) {
    // The law's pull-off through a soft lever (JKR: -(3/2) pi w R) below the median force.
    std::vector<double> sorted(all.f);
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(n / 2), sorted.end());
    const double drop = sorted[n / 2] - *std::min_element(all.f.begin(), all.f.end());
    w_hint = std::max(drop / (law.soft_pulloff * kPi * problem.tip.radius), 1e-9);
  }
  return {e_hint, w_hint};
}

// Lagrange weights at x of the three points at[0..2].
void quadratic_weights(double x, const double at[3], double weight[3]) {
  for (int a = 0; a < 3; ++a) {
    weight[a] = 1.0;
    for (int b = 0; b < 3; ++b) {
      if (b != a) weight[a] *= (x - at[b]) / (at[a] - at[b]);
    }
  }
}

// Coating: reduced-solver sweeps at film moduli E1_j = E1_hint 10^(j/kModulusNodesPerDecade)
// (kept); a trial E1 between nodes takes the cubic Lagrange interpolant in ln E1 of the four
// reduced variables at each a/t from its four nearest nodes (THEORY.md section 15). The
// sweeps cover a prefix of the a/t lattice of kCoatingAOverT, extended (on every node, by the
// missing radii only) when a trial's branch reaches past it: the solves at large a/t cost
// most, and a curve's indentations rarely reach them.
class CoatingNodes {
 public:
  CoatingNodes(const AfmFitProblem& problem, double e_hint) : problem_(problem), e_hint_(e_hint) {
    if (!problem.coating) return;
    const double decades = std::log10(kCoatingAOverT[1] / kCoatingAOverT[0]);
    const int count = static_cast<int>(std::lround(decades * kCoatingPerDecade)) + 1;
    for (int k = 0; k < count; ++k) lattice_.push_back(kCoatingAOverT[0] * std::pow(10.0, decades * k / (count - 1)));
  }
  // Sweeps up to the first radius >= a_over_t (at least 8 radii past 1/2 of the lattice's
  // start, at most the whole lattice); the trials' interpolated sweeps are rebuilt.
  void reach(double a_over_t) {
    std::size_t k = 0;
    while (k < lattice_.size() && lattice_[k] < a_over_t) ++k;
    swept_ = std::min(lattice_.size(), std::max<std::size_t>(k + 1, 8));
    sweeps_.clear();
  }
  // Sweeps the radii up to a_over_t only (the coarse stage).
  void reach_below(double a_over_t) {
    std::size_t k = 0;
    while (k < lattice_.size() && lattice_[k] <= a_over_t * (1.0 + 1e-9)) ++k;
    swept_ = std::max<std::size_t>(k, 8);
    sweeps_.clear();
  }
  // From here on every E1 is read from the sweep at `film_modulus` itself and the quadratic
  // through it and its two neighbouring nodes.
  void anchor(double film_modulus) {
    anchor_ = film_modulus;
    anchor_solver_.reset();
    anchor_sweep_.clear();
    sweeps_.clear();
  }
  double anchored() const { return anchor_; }
  // Until anchored, every E1 is read from the quadratic through the node nearest `film_modulus`
  // and its two neighbours.
  void centre(double film_modulus) {
    centred_ = true;
    centre_ = std::lround(std::log10(film_modulus / e_hint_) * kModulusNodesPerDecade);
    sweeps_.clear();
  }
  bool covers(double a_over_t) const { return swept_ == lattice_.size() || a_over_t <= lattice_[swept_ - 1]; }
  // (the solves the fit's model rests on, whether this fit or an earlier one made them)
  long solver_calls() const { return solver_calls_; }

  std::shared_ptr<const CoatingSweep> sweep_of(double film_modulus) {
    if (!problem_.coating) return nullptr;
    auto it = sweeps_.find(film_modulus);
    if (it != sweeps_.end()) return it->second;
    const double x = std::log10(film_modulus / e_hint_) * kModulusNodesPerDecade;
    const double nearest = std::round(x);
    std::shared_ptr<const CoatingSweep> sweep;
    if (problem_.coating->direct) {
      // The direct path: a sweep at this very E1 (AfmCoating::direct; the check of the nodes).
      solver_calls_ += static_cast<long>(swept_);
      sweep = std::make_shared<const CoatingSweep>(shared_sweep(*problem_.coating, film_modulus, lattice_, swept_));
    } else if (centred_ && anchor_ == 0.0) {
      // Before the anchor: the quadratic through the node nearest the coarse estimate and its
      // two neighbours.
      const double at[3] = {static_cast<double>(centre_ - 1), static_cast<double>(centre_), static_cast<double>(centre_ + 1)};
      double weight[3];
      quadratic_weights(x, at, weight);
      sweep = std::make_shared<const CoatingSweep>(mixed({&node(centre_ - 1), &node(centre_), &node(centre_ + 1)}, weight));
    } else if (anchor_ > 0.0) {
      // Anchored: the quadratic in log E1 through the anchor's own sweep and the nodes either
      // side of it, each at least a quarter spacing away (THEORY.md section 15, "The JKR search
      // on a coating").
      const double xa = std::log10(anchor_ / e_hint_) * kModulusNodesPerDecade;
      const long lo = static_cast<long>(std::floor(xa - 0.25)), hi = static_cast<long>(std::ceil(xa + 0.25));
      const double at[3] = {xa, static_cast<double>(lo), static_cast<double>(hi)};
      double weight[3];
      quadratic_weights(x, at, weight);
      sweep = std::make_shared<const CoatingSweep>(mixed({&anchor_values(), &node(lo), &node(hi)}, weight));
    } else if (std::abs(x - nearest) < 1e-9) {
      sweep = std::make_shared<const CoatingSweep>(node(static_cast<long>(nearest)));
    } else {
      const long j0 = static_cast<long>(std::floor(x)) - 1;
      double weight[4];
      lagrange_weights(x, j0, weight);
      sweep = std::make_shared<const CoatingSweep>(mixed({&node(j0), &node(j0 + 1), &node(j0 + 2), &node(j0 + 3)}, weight));
    }
    if (sweeps_.size() > 64) sweeps_.clear();
    sweeps_.emplace(film_modulus, sweep);
    return sweep;
  }

 private:
  const std::vector<ReducedVariables>& node(long j) {
    std::vector<ReducedVariables>& v = nodes_[j];
    if (v.size() < swept_) {
      const double modulus = e_hint_ * std::pow(10.0, static_cast<double>(j) / kModulusNodesPerDecade);
      solver_calls_ += static_cast<long>(swept_ - v.size());
      v = shared_sweep(*problem_.coating, modulus, lattice_, swept_);
    }
    return v;
  }

  // The sweep at the anchor: this fit's own solver (an anchor is the fit's estimate, so no
  // other fit asks for it; kept among the shared nodes, a map's anchors would crowd them out).
  const std::vector<ReducedVariables>& anchor_values() {
    if (!anchor_solver_) anchor_solver_ = std::make_unique<ReducedSolver>(problem_.coating->stack_with(anchor_, problem_.coating->thickness));
    for (std::size_t k = anchor_sweep_.size(); k < swept_; ++k) {
      anchor_sweep_.push_back(anchor_solver_->solve(lattice_[k], problem_.coating->solver_tolerance));
      ++solver_calls_;
    }
    return anchor_sweep_;
  }
  // sum_a weight[a] v_a of the swept prefix.
  std::vector<ReducedVariables> mixed(const std::vector<const std::vector<ReducedVariables>*>& values, const double* weight) const {
    std::vector<ReducedVariables> out(swept_);
    for (std::size_t a = 0; a < values.size(); ++a) {
      const std::vector<ReducedVariables>& v = *values[a];
      for (std::size_t k = 0; k < out.size(); ++k) {
        out[k].a_over_t = lattice_[k];
        out[k].pi_s += weight[a] * v[k].pi_s;
        out[k].delta_s += weight[a] * v[k].delta_s;
        out[k].e_eq += weight[a] * v[k].e_eq;
        out[k].gamma1 += weight[a] * v[k].gamma1;
      }
    }
    return out;
  }

  const AfmFitProblem& problem_;
  double e_hint_;
  double anchor_ = 0.0;  // E1 of the anchored model (0: none)
  bool centred_ = false;
  long centre_ = 0;
  std::unique_ptr<ReducedSolver> anchor_solver_;
  std::vector<ReducedVariables> anchor_sweep_;
  std::map<long, std::vector<ReducedVariables>> nodes_;  // this fit's prefix of each node's sweep
  long solver_calls_ = 0;
  std::vector<double> lattice_;  // the whole a/t lattice
  std::size_t swept_ = 0;        // its prefix the sweeps cover
  std::map<double, std::shared_ptr<const CoatingSweep>> sweeps_;
};

using TrialCost = std::function<ContactFit(const std::vector<double>& u, const double* centre)>;
using BranchAt = std::function<std::unique_ptr<Branch>(const std::vector<double>& u)>;

// 1. Start: a grid around the hints (E 1.5 decades each way, E1 one, w one, t half a decade);
// the best node's ln-parameters, its fit in best_fit.
std::vector<double> start_grid(const std::vector<int>& axes, const std::vector<double>& u0, bool coated,
                               const TrialCost& trial_cost, ContactFit& best_fit) {
  std::vector<double> u_best = u0;
  best_fit = trial_cost(u0, nullptr);
  std::vector<std::vector<double>> offsets(axes.size());
  for (std::size_t k = 0; k < axes.size(); ++k) {
    // (a coating's E1 a decade: each new E1 node costs a sweep of the solver)
    offsets[k] = axes[k] == 0   ? (coated ? std::vector<double>{-1.0, -0.5, 0.0, 0.5, 1.0}
                                          : std::vector<double>{-1.5, -1.0, -0.5, 0.0, 0.5, 1.0, 1.5})
                 : axes[k] == 1 ? std::vector<double>{-1.0, -0.5, 0.0, 0.5, 1.0}
                                : std::vector<double>{-0.5, 0.0, 0.5};
  }
  std::vector<std::size_t> index(axes.size(), 0);
  while (!axes.empty()) {
    std::vector<double> u(axes.size());
    for (std::size_t k = 0; k < axes.size(); ++k) u[k] = u0[k] + std::log(10.0) * offsets[k][index[k]];
    const ContactFit c = trial_cost(u, nullptr);
    if (c.linear.rss < best_fit.linear.rss) best_fit = c, u_best = u;
    std::size_t k = 0;
    while (k < axes.size() && ++index[k] == offsets[k].size()) index[k++] = 0;
    if (k == axes.size()) break;
  }
  return u_best;
}

struct State {
  std::vector<double> u;
  ContactFit c;
  double first_error = 0.0;  // standard error of u[0] at the polish's last Jacobian (0: none)
};

// 3. Every point: damped Gauss-Newton steps on all free parameters from `state` (bounded; a
// step is kept only if it lowers the sum).
State polish(State state, const std::vector<int>& axes, const AfmFitProblem& problem, const Points& all,
             const Objective& fine, const BranchAt& branch_at) {
  const std::size_t n = all.z.size();
  const auto model_all = [&](const Branch& b, const ContactFit& c, std::vector<double>* slope) {
    std::vector<double> m(n);
    for (std::size_t i = 0; i < n; ++i) {
      const auto [g, dg] = b.at(c.contact - all.z[i]);
      m[i] = c.linear.baseline + c.linear.tilt * (all.z[i] - c.contact) + g;
      if (slope) (*slope)[i] = dg;
    }
    return m;
  };
  int polish = 0;
  for (; polish < kPolishSteps && !axes.empty(); ++polish) {
    // Columns: each ln-parameter by central differences, then z_c, b, m (linear ones exact).
    const auto centre_branch = branch_at(state.u);
    std::vector<double> dg(n);
    const std::vector<double> m0 = model_all(*centre_branch, state.c, &dg);
    std::vector<std::vector<double>> cols;
    for (std::size_t k = 0; k < axes.size(); ++k) {
      constexpr double h = 1e-4;
      std::vector<double> up = state.u, down = state.u;
      up[k] += h, down[k] -= h;
      const auto bu = branch_at(up), bd = branch_at(down);
      const std::vector<double> mu = model_all(*bu, state.c, nullptr), md = model_all(*bd, state.c, nullptr);
      std::vector<double> col(n);
      for (std::size_t i = 0; i < n; ++i) col[i] = (mu[i] - md[i]) / (2 * h);
      cols.push_back(std::move(col));
    }
    if (problem.free.contact_point) {
      std::vector<double> col(n);
      for (std::size_t i = 0; i < n; ++i) col[i] = dg[i] - state.c.linear.tilt;
      cols.push_back(std::move(col));
    }
    if (problem.free.baseline) cols.push_back(std::vector<double>(n, 1.0));
    if (problem.free.tilt) {
      std::vector<double> col(n);
      for (std::size_t i = 0; i < n; ++i) col[i] = all.z[i] - state.c.contact;
      cols.push_back(std::move(col));
    }
    std::vector<double> residual(n);
    for (std::size_t i = 0; i < n; ++i) residual[i] = all.f[i] - m0[i];
    std::vector<double> step = internal::afm_least_squares_step(cols, residual);
    double sum = 0.0;
    for (double v : residual) sum += v * v;
    try {
      state.first_error = internal::afm_standard_errors(cols, std::sqrt(sum / static_cast<double>(n - cols.size()))).front();
    } catch (const NumericalError&) {
      state.first_error = 0.0;
    }
    // A parameter that hardly changes the model (w of a curve without adhesion) gets a huge
    // step: at most a decade of any ln-parameter a step.
    double largest = 0.0;
    for (std::size_t k = 0; k < axes.size(); ++k) largest = std::max(largest, std::abs(step[k]));
    if (largest > std::log(10.0)) {
      for (double& v : step) v *= std::log(10.0) / largest;
    }
    bool improved = false;
    for (double scale = 1.0; scale > 1.0 / 64.0; scale /= 4.0) {
      State next = state;
      for (std::size_t k = 0; k < axes.size(); ++k) next.u[k] += scale * step[k];
      if (problem.free.contact_point) next.c.contact += scale * step[axes.size()];
      std::unique_ptr<Branch> b;
      try {
        b = branch_at(next.u);
      } catch (const NumericalError&) {
        continue;
      }
      next.c.linear = fine.at(*b, next.c.contact);
      if (next.c.linear.in_contact == 0) continue;  // (the bare line: refused, as by the search)
      // The sums' closed form loses the residual to cancellation when a wild trial's force
      // dwarfs the data: the candidate's sum point by point.
      const std::vector<double> model = model_all(*b, next.c, nullptr);
      double rss = 0.0;
      for (std::size_t i = 0; i < n; ++i) rss += all.weight[i] * (all.f[i] - model[i]) * (all.f[i] - model[i]);
      next.c.linear.rss = std::isfinite(rss) ? rss : kInfinity;
      if (next.c.linear.rss < state.c.linear.rss) {
        const double gain = (state.c.linear.rss - next.c.linear.rss) / state.c.linear.rss;
        state = next;
        improved = gain > 1e-10;
        break;
      }
    }
    if (!improved) break;
  }
  return state;
}

// The per-point model and the standard errors at the estimates (central differences in ln p
// for E, w, t; exact columns for z_c, b, m), with the residual statistics.
void fill_errors(AfmFitResult& r, const std::vector<double>& z_data, const std::vector<double>& f_data, const Branch& branch,
                 const State& state, const std::vector<int>& axes, const BranchAt& branch_at, const AfmFitProblem& problem,
                 int free_count, const std::string& name) {
  const std::size_t n = z_data.size();
  // Per point, in the caller's order.
  std::vector<double> slope(n);
  r.model_force.resize(n);
  r.indentation.resize(n);
  std::vector<double> col_c(n), col_m(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double delta = r.contact_point - z_data[i];
    const auto [g, dg] = branch.at(delta);
    r.model_force[i] = r.baseline + r.tilt * (z_data[i] - r.contact_point) + g;
    col_c[i] = dg - r.tilt;
    col_m[i] = z_data[i] - r.contact_point;
    r.indentation[i] = delta;
  }
  std::vector<std::vector<double>> columns;
  std::vector<double*> slots;
  for (std::size_t k = 0; k < axes.size(); ++k) {
    constexpr double h = 1e-4;
    std::vector<double> up = state.u, down = state.u;
    up[k] += h, down[k] -= h;
    const auto bu = branch_at(up), bd = branch_at(down);
    std::vector<double> col(n);
    const double value = std::exp(state.u[k]);
    for (std::size_t i = 0; i < n; ++i) {
      const double delta = r.contact_point - z_data[i];
      col[i] = (bu->at(delta).first - bd->at(delta).first) / (2 * h * value);  // per unit of the parameter
    }
    columns.push_back(std::move(col));
    slots.push_back(axes[k] == 0 ? &r.modulus_error : axes[k] == 1 ? &r.work_error : &r.thickness_error);
  }
  if (problem.free.contact_point) columns.push_back(col_c), slots.push_back(&r.contact_point_error);
  if (problem.free.baseline) columns.push_back(std::vector<double>(n, 1.0)), slots.push_back(&r.baseline_error);
  if (problem.free.tilt) columns.push_back(col_m), slots.push_back(&r.tilt_error);

  afm_residual_statistics(r, f_data, problem.noise_sigma, free_count, r.jump_off_indentation,
                          "the " + name + " fit leaves no point in contact; check the segment (retract) and the range");
  const std::vector<double> errors = afm_standard_errors(columns, r.residual_sigma);
  for (std::size_t a = 0; a < errors.size(); ++a) *slots[a] = errors[a];
  for (double v : {r.modulus, r.work, r.contact_point, r.baseline, r.tilt, r.rss, r.jump_off_force}) {
    if (!std::isfinite(v)) throw NumericalError("afm fit: the " + name + " fit did not converge (a non-finite estimate)");
  }
  for (double v : errors) {
    if (!std::isfinite(v)) throw NumericalError("afm fit: the " + name + " fit's standard errors are not finite (parameters not identifiable)");
  }
}

// A trial's cost: the contact point on the whole range (centre null: global) or within a
// window around `centre` (the simplex's trials; widened to the whole range at its edge).
ContactFit trial_contact(const Objective& objective, const Branch& branch, const AfmFitProblem& problem, double z_lo,
                         double c_hi, double span, int grid_points, const double* centre) {
  const double lo = z_lo + std::min(0.0, branch.jump_delta());
  if (centre == nullptr) return search_contact(objective, branch, problem, lo, c_hi, grid_points);
  const double half = 0.1 * span;
  const double a = std::max(lo, *centre - half), b = std::min(c_hi, *centre + half);
  ContactFit local = search_contact(objective, branch, problem, a, b, 13);
  const double edge = 0.02 * (b - a);
  if (problem.free.contact_point && (local.contact - a < edge || b - local.contact < edge)) {
    const ContactFit wide = search_contact(objective, branch, problem, lo, c_hi, grid_points);
    if (wide.linear.rss < local.linear.rss) local = wide;
  }
  return local;
}

// NumericalError when the final branch's deepest fitted indentation needs radii past the tabulated a/t.
void check_tabulated_reach(const Branch& check, double length_unit, double deepest) {
  if (check.max_radius() / length_unit > kCoatingAOverT[1]) {
    throw NumericalError("afm fit: the indentations reach " + short_text(deepest) + " m, where the contact radius " +
                         short_text(check.max_radius()) + " m exceeds " + short_text(kCoatingAOverT[1]) +
                         " film thicknesses (t = " + short_text(length_unit) +
                         " m), as far as the coating model is tabulated; a thicker film or a shallower --indentation-range");
  }
}

// The estimates of a fit and its branch's jump-off.
AfmFitResult estimates_of(const Trial& estimate, const State& state, const Branch& branch, bool coated, std::size_t n,
                          int free_count) {
  AfmFitResult r;
  r.points = n;
  r.free_count = free_count;
  r.modulus = estimate.modulus;
  r.work = estimate.work;
  r.thickness = coated ? estimate.thickness : 0.0;
  r.reduced_modulus = branch.reduced_modulus();
  r.contact_point = state.c.contact;
  r.baseline = state.c.linear.baseline;
  r.tilt = state.c.linear.tilt;
  r.tilt_origin = r.contact_point;
  r.jump_off_indentation = branch.jump_delta();
  r.jump_off_force = branch.jump_force();
  return r;
}

// A warning for each ln-parameter that ended more than 2.5 decades from its start.
void warn_far_from_start(AfmFitResult& r, const std::vector<int>& axes, const std::vector<double>& u, const std::vector<double>& u0,
                         const std::string& modulus_name) {
  for (std::size_t k = 0; k < axes.size(); ++k) {
    if (std::abs(u[k] - u0[k]) > std::log(10.0) * 2.5) {
      r.warnings.push_back((axes[k] == 0 ? modulus_name : axes[k] == 1 ? "w" : "t") +
                           " ended more than 2.5 decades from its start (" + short_text(std::exp(u0[k])) +
                           "); check the given value");
    }
  }
}

// The adhesive search's axes: 0 (ln E or ln E1), 1 (ln w), 2 (ln t), those free, in that order.
std::vector<int> adhesive_search_axes(const AfmFitProblem& problem) {
  std::vector<int> axes;
  if (problem.free.modulus) axes.push_back(0);
  if (problem.free.work) axes.push_back(1);
  if (problem.coating && problem.free.thickness) axes.push_back(2);
  return axes;
}

// The trial at the search point u: `base` with the free parameters exp(u) on their axes.
Trial trial_at(const std::vector<int>& axes, Trial base, const std::vector<double>& u) {
  for (std::size_t k = 0; k < axes.size(); ++k) {
    const double v = std::exp(u[k]);
    if (axes[k] == 0) base.modulus = v;
    else if (axes[k] == 1) base.work = v;
    else base.thickness = v;
  }
  return base;
}

using Cost = std::function<double(const std::vector<double>&)>;

// A probe of the model at E1 = exp(ln_e) on a node (the model reads that node's table alone
// there): the other axes searched from `rest`; its residual sum and point.
std::pair<double, std::vector<double>> probe_node(double ln_e, std::vector<double> rest, const Cost& cost) {
  const auto at = [&](const std::vector<double>& r) {
    std::vector<double> p{ln_e};
    p.insert(p.end(), r.begin(), r.end());
    return p;
  };
  int iterations = 0;
  if (!rest.empty()) rest = simplex([&](const std::vector<double>& r) { return cost(at(r)); }, rest, 0.15, kProbeSimplexSize, &iterations);
  return {cost(at(rest)), at(rest)};
}

// Stage 1c (THEORY.md section 15, "The coarse nodes"): the walk over the model's nodes
// E0 10^(j/8) from u, each node probed. A pattern search on j: one node first (toward the lower
// neighbour, both probed), the step doubled after each gain (at most kWalkStep), halved after a
// loss and tried ahead, then behind, until both neighbours of the best node lose; then the
// vertex of the parabola through the three (within half a node), the other axes interpolated
// toward the better neighbour.
std::vector<double> node_walk(const std::vector<double>& u, double e0, const Cost& cost) {
  const double spacing = std::log(10.0) / kModulusNodesPerDecade;
  const long first = std::lround((u[0] - std::log(e0)) / spacing);
  std::map<long, std::pair<double, std::vector<double>>> seen;
  long best = first;
  const auto profile = [&](long j) {
    auto it = seen.find(j);
    if (it == seen.end()) {
      const std::vector<double>& from = seen.empty() ? u : seen.at(best).second;  // the best node's other axes
      it = seen.emplace(j, probe_node(std::log(e0) + static_cast<double>(j) * spacing, {from.begin() + 1, from.end()}, cost)).first;
    }
    return it->second.first;
  };
  double value = profile(best);
  const double up1 = profile(best + 1), down1 = profile(best - 1);
  long dir = std::min(up1, down1) < value ? (up1 <= down1 ? 1 : -1) : 0;
  for (long step = 1; dir != 0 && std::abs(best + dir * step - first) <= kWalkReach;) {
    // (a node seen before lost to a best at least as high as today's: it never wins again)
    if (const long next = best + dir * step; profile(next) < value) {
      best = next, value = profile(next), step = std::min(2 * step, kWalkStep);
      continue;
    }
    if (step == 1) break;
    step /= 2;
    if (const double ahead = profile(best + dir * step); ahead < value) best += dir * step, value = ahead;
    else if (const double behind = profile(best - dir * step); behind < value) best -= dir * step, value = behind, dir = -dir;
    else if (step == 1) break;
  }
  const double up = profile(best + 1), down = profile(best - 1), curvature = up - 2.0 * value + down;
  std::vector<double> out = seen.at(best).second;
  if (std::isfinite(curvature) && curvature > 0.0) {
    const double offset = std::clamp(0.5 * (down - up) / curvature, -0.5, 0.5);
    const std::vector<double>& side = seen.at(offset > 0.0 ? best + 1 : best - 1).second;
    for (std::size_t k = 1; k < out.size(); ++k) out[k] += std::abs(offset) * (side[k] - out[k]);
    out[0] += offset * spacing;
  }
  return out;
}

// Where the model's simplex starts after the coarse stage on one table a decade (THEORY.md
// section 15, "The coarse nodes", stages 1b and 1c): the model at the two decade nodes E0 10^k
// bracketing the coarse estimate u (its coarse residual sum `rss`), probed; from the better of
// them if it beats u, else from u, the walk over the nodes, whose vertex is kept if the model
// there beats the model at that start.
std::vector<double> model_start(const std::vector<double>& u, double rss, double e0, const Cost& cost) {
  const double k0 = std::floor((u[0] - std::log(e0)) / std::log(10.0));
  std::vector<double> start = u;
  double best = rss;
  for (double k : {k0, k0 + 1}) {
    const auto [r, at] = probe_node(std::log(e0) + k * std::log(10.0), {u.begin() + 1, u.end()}, cost);
    if (r < best) best = r, start = at;
  }
  // On precise data the probes at nodes a fraction of a node from the answer can end in another
  // basin of the other axes (w -> 0 on a synthetic curve): the vertex's E1 with the start's other
  // axes is a candidate too, and the start itself.
  const std::vector<double> vertex = node_walk(start, e0, cost);
  std::vector<double> mixed = start;
  mixed[0] = vertex[0];
  const double at_vertex = cost(vertex), at_mixed = cost(mixed);
  if (!(std::min(at_vertex, at_mixed) < cost(start))) return start;
  return at_vertex <= at_mixed ? vertex : mixed;
}

}  // namespace

AfmFitResult afm_fit_adhesive(const std::vector<double>& z_data, const std::vector<double>& f_data,
                              const AfmFitProblem& problem, int free_count, const SpringModel* model,
                              const ReducedLaw* law_given) {
  const ReducedLaw& law = law_given ? *law_given : jkr_law();
  const std::string name = model ? model->name : law.name;
  const auto start = std::chrono::steady_clock::now();
  check_adhesive_input(problem, name);
  const bool coated = problem.coating.has_value();
  AfmFitProblem p = problem;
  if (coated) p.poisson = problem.coating->film.poisson_ratio;
  const std::size_t n = z_data.size();
  const Points all = sorted_points(z_data, f_data);
  const Points search = binned(all);
  const double z_lo = all.z.front(), z_hi = all.z.back(), span = z_hi - z_lo;
  if (problem.free.contact_point && !(span > 0.0)) throw InputError("afm fit: the fitted points have one tip position only");
  const double c_hi = problem.free.contact_point ? z_hi + kContactBeyond * span : problem.contact_point;
  const double max_delta = std::max(c_hi - z_lo, 1e-12);

  // The search's parameters: ln E (or ln E1), ln w, ln t, those free, in that order.
  const auto [e_hint, w_hint] = adhesive_hints(z_data, f_data, problem, all, law);
  const double t_hint = coated ? problem.coating->thickness : 0.0;
  const std::vector<int> axes = adhesive_search_axes(problem);
  const Trial base{e_hint, problem.free.work ? w_hint : problem.work, t_hint};
  const auto trial_of = [&](const std::vector<double>& u) { return trial_at(axes, base, u); };
  std::vector<double> u0;
  for (int a : axes) u0.push_back(std::log(a == 0 ? e_hint : a == 1 ? w_hint : t_hint));

  CoatingNodes nodes(problem, e_hint);
  // A free E1 is searched first on nodes swept to kCoarseAOverT only (THEORY.md section 15,
  // "The JKR search on a coating"), then polished on the whole reach.
  // Radii in units of T, the stack's total thickness (t on one film).
  const auto length_of = [&](const Trial& t) { return coated ? problem.coating->total_thickness(t.thickness) : t.thickness; };
  const double full_reach = coated ? 2.0 * std::sqrt(problem.tip.radius * max_delta) / problem.coating->total_thickness(t_hint) : 0.0;
  const bool staged = coated && !model && problem.free.modulus;
  const bool anchoring = staged && !problem.coating->direct;  // (the direct path reads every E1 exactly)
  // (not on a stack: its layers' features lie inside a/T < 1, at h_i/T, so the coarse sweep's
  // line past kCoarseAOverT misleads the search; THEORY.md section 15, "JKR and DMT on a stack")
  bool coarse_stage = staged && full_reach > kCoarseAOverT && !problem.coating->multilayer();
  if (coarse_stage) nodes.reach_below(kCoarseAOverT);
  else if (coated) nodes.reach(full_reach);
  int tables = 0;
  const auto branch_of = [&](const Trial& t) {
    for (;;) {
      ++tables;
      auto branch = model ? model->branch(t, max_delta) : law_branch(p, nodes.sweep_of(t.modulus), t, max_delta, law, coarse_stage);
      // The branch's radii past the swept a/t would take the sweep's end values: widen it.
      if (model || !coated || coarse_stage || nodes.covers(branch->top_radius() / length_of(t))) return branch;
      nodes.reach(branch->top_radius() / length_of(t));
    }
  };
  const BranchAt branch_at = [&](const std::vector<double>& u) { return branch_of(trial_of(u)); };

  const Objective coarse(search, problem, contact_top(all));
  // A trial's cost: the contact point on the whole range (global) or within a window around
  // `centre` (the simplex's trials; the window is widened to the whole range at its edge).
  const int grid_points = static_cast<int>(std::clamp<std::size_t>(problem.profile_points / 4, 24, 200));
  const auto trial_cost = [&](const Trial& t, const double* centre) -> ContactFit {
    std::unique_ptr<Branch> branch;
    try {
      branch = branch_of(t);
    } catch (const NumericalError&) {
      return {0.0, Linear{}};
    }
    return trial_contact(coarse, *branch, problem, z_lo, c_hi, span, grid_points, centre);
  };

  // A model with a table per E1 node (SpringModel::coarse) searches first on one node a decade.
  const bool coarse_nodes = model && model->coarse && !axes.empty() && axes[0] == 0;
  if (coarse_nodes) model->coarse(true);
  ContactFit best_fit;
  std::vector<double> u_best =
      start_grid(axes, u0, coated, [&](const std::vector<double>& u, const double* c) { return trial_cost(trial_of(u), c); }, best_fit);
  if (!std::isfinite(best_fit.linear.rss)) {
    // Profiled trials, none holding a point in contact (a trial whose branch failed is not profiled).
    const bool no_contact = coarse.evaluations() > 0 && coarse.contact_evaluations() == 0;
    throw NumericalError(no_contact ? "afm fit: the " + name + " fit leaves no point in contact; check the segment (retract) and the range"
                                    : "afm fit: no " + name + " trial near the given E/E1 and w fits the data (check the tip radius, "
                                      "the spring constant and the segment)");
  }
  // 2. Nelder-Mead in the ln-parameters on the binned points, z_c near `centre`.
  int iterations = 0;
  const auto run_simplex = [&](double centre, double size, double first_step = 0.0) {
    int k = 0;
    u_best = simplex([&](const std::vector<double>& u) { return trial_cost(trial_of(u), &centre).linear.rss; }, u_best, 0.15, size, &k, first_step);
    iterations = std::max(iterations, k);
  };
  if (!axes.empty()) run_simplex(best_fit.contact, coarse_stage || coarse_nodes ? kCoarseSimplexSize : 1e-6);
  Trial estimate = trial_of(u_best);
  if (coarse_nodes) {
    // The model at the decade nodes around the coarse estimate and a walk over its nodes, then every node.
    const ContactFit at_coarse = trial_cost(estimate, nullptr);
    model->coarse(false);
    u_best = model_start(u_best, at_coarse.linear.rss, problem.coating->substrate.material.youngs_modulus,
                         [&](const std::vector<double>& u) { return trial_cost(trial_of(u), &at_coarse.contact).linear.rss; });
    run_simplex(trial_cost(trial_of(u_best), nullptr).contact, 1e-6, kModelFirstStep);
    estimate = trial_of(u_best);
  } else if (coarse_stage) {
    // Again on the whole reach (on the three nodes around the coarse E1): the coarse model,
    // short of the deepest points, can hold a basin of its own.
    coarse_stage = false;
    nodes.reach(full_reach);
    nodes.centre(estimate.modulus);
    run_simplex(trial_cost(estimate, nullptr).contact, 1e-6);
    estimate = trial_of(u_best);
  } else if (staged) {
    nodes.centre(estimate.modulus);
  }
  const ContactFit fit = trial_cost(estimate, nullptr);
  if (!std::isfinite(fit.linear.rss)) throw NumericalError("afm fit: the " + name + " search ended on a trial without a jump-off");

  // 3. Every point: the contact point re-profiled in a window, then polished.
  const Objective fine(all, problem, contact_top(all));
  State state{u_best, {}};
  {
    const auto branch = branch_of(estimate);
    const double half = 0.1 * span, lo = z_lo + std::min(0.0, branch->jump_delta());
    state.c = search_contact(fine, *branch, problem, std::max(lo, fit.contact - half), std::min(c_hi, fit.contact + half), 25);
  }
  state = polish(state, axes, problem, all, fine, branch_at);
  estimate = trial_of(state.u);
  // The anchor follows E1 until the polish leaves it where it was (THEORY.md section 15).
  for (int k = 0; anchoring && k < kAnchorMoves &&
                  !(std::abs(std::log(estimate.modulus / nodes.anchored())) <= std::max(kAnchorTolerance, kAnchorTolerancePerError * state.first_error));
       ++k) {
    nodes.anchor(estimate.modulus);
    state.c.linear = fine.at(*branch_of(estimate), state.c.contact);
    state = polish(state, axes, problem, all, fine, branch_at);
    estimate = trial_of(state.u);
  }
  const auto branch = branch_of(estimate);

  AfmFitResult r = estimates_of(estimate, state, *branch, coated, n, free_count);
  r.solver_calls = nodes.solver_calls();
  r.profile_evaluations = coarse.evaluations() + fine.evaluations();
  r.model_evaluations = tables;
  if (coated && branch->max_radius() / length_of(estimate) > kCoatingAOverT[1] && r.contact_point - z_lo > 0.0) {
    // Only the radii the data reach matter: the deepest fitted indentation's.
    const double deepest = r.contact_point - z_lo;
    const auto check = model ? model->branch(estimate, deepest) : law_branch(p, nodes.sweep_of(estimate.modulus), estimate, deepest, law);
    check_tabulated_reach(*check, length_of(estimate), deepest);
  }
  fill_errors(r, z_data, f_data, *branch, state, axes, branch_at, problem, free_count, name);
  if (model) model->report(estimate, r);
  else law.report(p, r);
  warn_far_from_start(r, axes, state.u, u0, coated ? problem.coating->free_modulus_name() : "E");
  if (iterations >= kSimplexIterations) r.warnings.push_back("the simplex search stopped at its iteration bound");
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace internal

}  // namespace coatcontact::fit
