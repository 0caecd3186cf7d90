// Piecewise Chebyshev interpolation of the reduced variables (THEORY.md section 5) in
// u = ln(a/t), of ln X for each variable X (all six are positive; a power law such as the
// Winkler limit E_eq ~ a/t of a rigid substrate becomes a straight line).
//
// Why interpolate rather than solve at every a_bar (measured with the ReducedSolver at its
// default tolerance 1e-8, nu = 0.25, a/t in [1e-3, 1e2], 200 random off-node points against
// direct solves; tests/adhesive/test_table_solver.cpp repeats this check):
//   order per decade       8       12      16      20      24      32
//   E1*/E0* = 0.1        8.5e-6  5.6e-8  1.2e-9  3.8e-11 8.0e-13 1.6e-14   (max relative error)
//   E1*/E0* = 10         4.7e-5  3.3e-6  1.4e-7  3.7e-9  9.7e-11 5.7e-14
//   rigid substrate      9.1e-6  6.0e-8  1.4e-9  4.3e-11 1.1e-12 1.7e-13
// The tail |c_n| + |c_(n-1)| overestimates these errors by ~10x, so the halving test is safe.
// Order 24 (25 solves per decade, ~0.08 s for five decades at ~0.6 ms per solve) is 1e3-1e5
// times below the solver tolerance; a 400-point curve solved directly costs 400 solves per
// eta (~0.2 s), the table serves every eta and every a_bar in the same decades for ~1 us a
// point. Deciding factor: the interpolant has analytic derivatives (d ln X/d ln(a/t) to
// ~1e-10, e.g. the identity Gamma^2 = E_eq (1 + d ln E_eq/d ln(a/t)) holds to <1e-9 above),
// which locate the pull-off by a root of dP/da_bar; direct solves would need finite
// differences of 1e-8-accurate values (derivative error ~1e-5 at best).
#include <gsl/gsl_chebyshev.h>
#include <gsl/gsl_errno.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "coatcontact/detail/constants.hpp"
#include "coatcontact/reduced_table.hpp"
#include "coatcontact/detail/format.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/detail/gsl_handler_off.hpp"

namespace coatcontact {

namespace {

constexpr int kVariables = 6;
const char* const kNames[kVariables] = {"Pi_s", "Delta_s", "Pi_c", "Delta_c", "E_eq", "Gamma(1)"};
const double kLn10 = std::log(10.0);

std::array<double, kVariables> values_of(const ReducedVariables& v) {
  return {v.pi_s, v.delta_s, v.pi_c, v.delta_c, v.e_eq, v.gamma1};
}

// Chebyshev nodes exactly as gsl_cheb_init computes them (gsl 2.x, cheb/init.c), so that
// values solved beforehand in one batch can be handed to gsl_cheb_init.
std::vector<double> cheb_nodes(std::size_t order, double a, double b) {
  std::vector<double> nodes(order + 1);
  const double bma = 0.5 * (b - a);
  const double bpa = 0.5 * (b + a);
  for (std::size_t k = 0; k <= order; ++k) {
    const double y = std::cos(detail::kPi * (static_cast<double>(k) + 0.5) / static_cast<double>(order + 1));
    nodes[k] = y * bma + bpa;
  }
  return nodes;
}

// gsl_function returning precomputed values in node order; flags any mismatch of abscissae.
struct CachedValues {
  const std::vector<double>* nodes;
  const std::vector<double>* values;
  std::size_t next = 0;
  bool mismatch = false;
};

double cached_value(double x, void* params) {
  auto* c = static_cast<CachedValues*>(params);
  if (c->next >= c->values->size() ||
      std::abs(x - (*c->nodes)[c->next]) > 1e-13 * (1.0 + std::abs(x))) {
    c->mismatch = true;
    return 0.0;
  }
  return (*c->values)[c->next++];
}

std::string format_g(double v) { return detail::full_precision(v); }

}  // namespace

struct ReducedTable::Segment {
  double u_lo = 0.0, u_hi = 0.0;
  std::array<gsl_cheb_series*, kVariables> value{};
  std::array<gsl_cheb_series*, kVariables> deriv{};
  double tail = 0.0;
  double check = 0.0;  // largest relative difference from the direct solves at the ends (verify)
  double noise = 0.0;  // largest error estimate of the source at the nodes and ends
  Segment() = default;
  Segment(const Segment&) = delete;
  Segment& operator=(const Segment&) = delete;
  ~Segment() {
    for (auto* s : value) gsl_cheb_free(s);
    for (auto* s : deriv) gsl_cheb_free(s);
  }
  // Verified: the measured end difference, or a tenth of the tail where that is larger (the
  // tail overestimates the error ~10x, table above); else the tail alone.
  bool verified = false;
  double interpolation_error() const { return verified ? std::max(check, 0.1 * tail) : tail; }
};

struct ReducedTable::Pending {
  double u_lo, u_hi;
  int halvings;
};

ReducedTable::ReducedTable(const ReducedSource& source, TableOptions options)
    : source_(source), options_(options) {
  if (options_.order < 4 || options_.order > 200) {
    throw InputError("table order " + std::to_string(options_.order) + " not allowed (4..200)");
  }
  if (!(options_.tail_tolerance > 0.0) || !(options_.tail_noise_factor >= 0.0) ||
      options_.max_halvings < 0) {
    throw InputError("table tolerances must be > 0 and max_halvings >= 0");
  }
  if (!(options_.decades_per_segment > 0.0 && options_.decades_per_segment <= 20.0)) {
    throw InputError("table decades_per_segment " + format_g(options_.decades_per_segment) +
                     " not allowed (0 < width <= 20)");
  }
}

ReducedTable::~ReducedTable() = default;

ReducedPoint reduced_point_of(const ReducedVariables& v) {
  ReducedPoint r;
  static_cast<ReducedValues&>(r) = v;
  return r;
}

std::size_t ReducedTable::segments() const { return segments_.size(); }
double ReducedTable::interpolation_error_estimate() const { return interpolation_error_; }
double ReducedTable::source_error_estimate() const { return source_error_; }

namespace {

// ln X of the six variables at the nodes of one segment (NumericalError unless finite, > 0).
std::array<std::vector<double>, kVariables> logs_at(const std::vector<ReducedVariables>& solved, std::size_t first,
                                                    std::size_t count) {
  std::array<std::vector<double>, kVariables> logs;
  for (std::size_t k = first; k < first + count; ++k) {
    const auto vals = values_of(solved[k]);
    for (int j = 0; j < kVariables; ++j) {
      if (!(std::isfinite(vals[j]) && vals[j] > 0.0)) {
        throw NumericalError(std::string("reduced variable ") + kNames[j] + " = " + format_g(vals[j]) +
                             " at a/t = " + format_g(solved[k].a_over_t) + " (expected finite and > 0)");
      }
      logs[j].push_back(std::log(vals[j]));
    }
  }
  return logs;
}

// Fills one series per variable (and its derivative) from the node values; returns the tail
// |c_n| + |c_(n-1)| of the worst variable.
double fill_series(std::array<gsl_cheb_series*, kVariables>& value, std::array<gsl_cheb_series*, kVariables>& deriv,
                   std::size_t order, double u_lo, double u_hi, const std::vector<double>& nodes,
                   const std::array<std::vector<double>, kVariables>& logs) {
  double tail = 0.0;
  for (int j = 0; j < kVariables; ++j) {
    value[j] = gsl_cheb_alloc(order);
    deriv[j] = gsl_cheb_alloc(order);
    if (value[j] == nullptr || deriv[j] == nullptr) throw NumericalError("cannot allocate a Chebyshev series");
    CachedValues cache{&nodes, &logs[j]};
    gsl_function f{&cached_value, &cache};
    const int status = gsl_cheb_init(value[j], &f, u_lo, u_hi);
    if (status != GSL_SUCCESS || cache.mismatch || cache.next != nodes.size()) {
      throw NumericalError("Chebyshev interpolation setup failed (node mismatch)");
    }
    gsl_cheb_calc_deriv(deriv[j], value[j]);
    const double* c = gsl_cheb_coeffs(value[j]);
    tail = std::max(tail, std::abs(c[order]) + std::abs(c[order - 1]));
  }
  return tail;
}

// Largest relative difference of the interpolated values at u from the solved ones.
double difference_at(const std::array<gsl_cheb_series*, kVariables>& value, double u, const ReducedVariables& solved) {
  const auto direct = values_of(solved);
  double worst = 0.0;
  for (int j = 0; j < kVariables; ++j) {
    const double interpolated = std::exp(gsl_cheb_eval(value[j], u));
    worst = std::max(worst, std::abs(interpolated - direct[j]) / std::abs(direct[j]));
  }
  return worst;
}

}  // namespace

namespace {

// The initial segments [u_lo, u_hi] of prepare_range: ends on the breaks, else on multiples of
// the width (in decades), clipped to the range: the same grid whatever the range, so two
// sweeps share their inner segments' nodes.
std::vector<std::pair<double, double>> initial_segments(const TableOptions& options, double u_lo, double u_hi) {
  const double width = options.decades_per_segment * kLn10;
  const std::vector<double>& breaks = options.breaks_decades;
  const auto next_end = [&](double left) {
    if (!breaks.empty() && left >= breaks.front() * kLn10 - 1e-9 * width) {
      for (double b : breaks) {
        if (b * kLn10 > left + 1e-9 * width) return b * kLn10;
      }
    }
    double end = (std::floor(left / width + 1e-9) + 1.0) * width;
    if (!breaks.empty() && left < breaks.front() * kLn10) end = std::min(end, breaks.front() * kLn10);
    return end;
  };
  std::vector<std::pair<double, double>> segments;
  for (double left = u_lo; left < u_hi;) {
    const double right = std::min(u_hi, next_end(left));
    if (right - left > 1e-9 * width || segments.empty()) {
      segments.emplace_back(left, right);
    } else {
      segments.back().second = right;  // a sliver of rounding: merged into the segment before
    }
    left = right;
  }
  return segments;
}

}  // namespace

void ReducedTable::build_decades(const std::vector<long>& decades) const {
  std::vector<Pending> pending;
  for (long k : decades) {
    pending.push_back({static_cast<double>(k) * kLn10, static_cast<double>(k + 1) * kLn10, 0});
  }
  build_segments(std::move(pending));
  for (long k : decades) built_decades_[k] = true;
}

void ReducedTable::build_segments(std::vector<Pending> pending) const {
  const std::size_t n_nodes = options_.order + 1;
  detail::GslHandlerOff gsl_guard;
  std::map<double, ReducedVariables> ends;  // verified ends, shared by neighbouring segments

  while (!pending.empty()) {
    // One batched source call for all nodes (and new ends) of all pending intervals.
    std::vector<std::vector<double>> nodes(pending.size());
    std::vector<double> a_over_t, end_u;
    a_over_t.reserve(pending.size() * (n_nodes + 2));
    for (std::size_t p = 0; p < pending.size(); ++p) {
      nodes[p] = cheb_nodes(options_.order, pending[p].u_lo, pending[p].u_hi);
      for (double u : nodes[p]) a_over_t.push_back(std::exp(u));
    }
    if (options_.verify) {
      for (const Pending& p : pending) {
        for (double u : {p.u_lo, p.u_hi}) {
          if (ends.count(u) == 0 && std::find(end_u.begin(), end_u.end(), u) == end_u.end()) end_u.push_back(u);
        }
      }
      for (double u : end_u) a_over_t.push_back(std::exp(u));
    }
    const std::vector<ReducedVariables> solved = source_.evaluate(a_over_t);
    if (solved.size() != a_over_t.size()) {
      throw NumericalError("reduced-variable source returned " + std::to_string(solved.size()) +
                           " values for " + std::to_string(a_over_t.size()) + " radii");
    }
    evaluations_ += solved.size();
    for (std::size_t e = 0; e < end_u.size(); ++e) ends[end_u[e]] = solved[pending.size() * n_nodes + e];
    logs_at(solved, pending.size() * n_nodes, end_u.size());  // the ends' values are checked too

    std::vector<Pending> next;
    for (std::size_t p = 0; p < pending.size(); ++p) {
      auto segment = std::make_unique<Segment>();
      segment->u_lo = pending[p].u_lo;
      segment->u_hi = pending[p].u_hi;
      for (std::size_t k = 0; k < n_nodes; ++k) {
        segment->noise = std::max(segment->noise, solved[p * n_nodes + k].error_estimate);
      }
      segment->tail = fill_series(segment->value, segment->deriv, options_.order, segment->u_lo, segment->u_hi,
                                  nodes[p], logs_at(solved, p * n_nodes, n_nodes));
      if (options_.verify) {
        segment->verified = true;
        for (double u : {segment->u_lo, segment->u_hi}) {
          const ReducedVariables& end = ends.at(u);
          segment->noise = std::max(segment->noise, end.error_estimate);
          segment->check = std::max(segment->check, difference_at(segment->value, u, end));
        }
      }
      const double allowed = options_.tail_tolerance + options_.tail_noise_factor * segment->noise;
      if (segment->interpolation_error() > allowed) {
        if (pending[p].halvings < options_.max_halvings) {
          const double mid = 0.5 * (pending[p].u_lo + pending[p].u_hi);
          next.push_back({pending[p].u_lo, mid, pending[p].halvings + 1});
          next.push_back({mid, pending[p].u_hi, pending[p].halvings + 1});
          continue;
        }
        if (!options_.verify) {  // verified segments keep their (large) estimate instead
          throw NumericalError("reduced variables not resolved by order-" + std::to_string(options_.order) +
                               " Chebyshev series on a/t in [" + format_g(std::exp(pending[p].u_lo)) + ", " +
                               format_g(std::exp(pending[p].u_hi)) + "]: tail " + format_g(segment->tail) +
                               " > " + format_g(allowed));
        }
      }
      interpolation_error_ = std::max(interpolation_error_, segment->interpolation_error());
      source_error_ = std::max(source_error_, segment->noise);
      segments_[segment->u_lo] = std::move(segment);
    }
    pending = std::move(next);
  }
}

void ReducedTable::prepare(double a_over_t_min, double a_over_t_max) const {
  if (!(a_over_t_min > 0.0 && std::isfinite(a_over_t_min) && a_over_t_max >= a_over_t_min &&
        std::isfinite(a_over_t_max))) {
    throw InputError("a/t range [" + format_g(a_over_t_min) + ", " + format_g(a_over_t_max) +
                     "] not allowed (need 0 < min <= max, finite)");
  }
  const long k_lo = static_cast<long>(std::floor(std::log(a_over_t_min) / kLn10));
  const long k_hi = static_cast<long>(std::floor(std::log(a_over_t_max) / kLn10));
  std::vector<long> missing;
  for (long k = k_lo; k <= k_hi; ++k) {
    if (built_decades_.count(k) == 0) missing.push_back(k);
  }
  if (ranged_) throw std::logic_error("ReducedTable::prepare on a table of prepare_range");
  if (!missing.empty()) build_decades(missing);
}

void ReducedTable::prepare_range(double a_over_t_min, double a_over_t_max) const {
  if (!(a_over_t_min > 0.0 && std::isfinite(a_over_t_min) && a_over_t_max > a_over_t_min &&
        std::isfinite(a_over_t_max))) {
    throw InputError("a/t range [" + format_g(a_over_t_min) + ", " + format_g(a_over_t_max) +
                     "] not allowed (need 0 < min < max, finite)");
  }
  if (!segments_.empty()) throw std::logic_error("ReducedTable::prepare_range on a table already built");
  const double u_lo = std::log(a_over_t_min), u_hi = std::log(a_over_t_max);
  std::vector<Pending> pending;
  for (const auto& [left, right] : initial_segments(options_, u_lo, u_hi)) pending.push_back({left, right, 0});
  ranged_ = true;
  range_lo_ = u_lo;
  range_hi_ = u_hi;
  build_segments(std::move(pending));
}

double ReducedTable::range_min() const { return std::exp(range_lo_); }
double ReducedTable::range_max() const { return std::exp(range_hi_); }

double ReducedTable::error_estimate_at(double a_over_t) const {
  if (!(a_over_t > 0.0 && std::isfinite(a_over_t))) {
    throw InputError("a/t = " + format_g(a_over_t) + " not allowed (need finite and > 0)");
  }
  const Segment& s = segment_for(std::log(a_over_t));
  return s.interpolation_error() + s.noise;
}

double ReducedTable::derivative_error_at(double a_over_t) const {
  error_estimate_at(a_over_t);  // the input check
  const double u = std::log(a_over_t);
  const Segment& s = segment_for(u);
  // The interpolation error taken as e T_(n+1)(x) (its leading term; THEORY.md section 5,
  // "Pull-off sweeps"): d/du = e (2/h) (n+1) U_n(x), |U_n(x)| <= min(n+1, 1/sqrt(1 - x^2)).
  const double h = s.u_hi - s.u_lo;
  const double x = std::min(1.0, std::abs(2.0 * (u - s.u_lo) / h - 1.0));
  const double k = static_cast<double>(options_.order + 1);
  const double envelope = x < 1.0 ? std::min(k, 1.0 / std::sqrt(1.0 - x * x)) : k;
  return s.interpolation_error() * (2.0 / h) * k * envelope;
}

double ReducedTable::interpolation_error_at(double a_over_t) const {
  const double total = error_estimate_at(a_over_t);  // the input check and the segment
  return std::min(total, segment_for(std::log(a_over_t)).interpolation_error());
}

const ReducedTable::Segment& ReducedTable::segment_for(double u) const {
  const double slack = 1e-12 * (1.0 + std::abs(u));
  if (ranged_) {
    if (!(u >= range_lo_ - slack && u <= range_hi_ + slack)) {
      throw InputError("a/t = " + format_g(std::exp(u)) + " outside the table's range [" + format_g(std::exp(range_lo_)) +
                       ", " + format_g(std::exp(range_hi_)) + "]");
    }
  } else {
    const long k = static_cast<long>(std::floor(u / kLn10));
    if (built_decades_.count(k) == 0) build_decades({k});
  }
  // Segments cover the decades (or the range) without gaps; allow rounding at their ends.
  auto it = segments_.upper_bound(u);
  if (it != segments_.begin()) {
    const Segment& s = *std::prev(it)->second;
    if (u <= s.u_hi + slack) return s;
  }
  if (it != segments_.end() && it->second->u_lo - u <= slack) return *it->second;
  throw NumericalError("internal: no interpolation segment for ln(a/t) = " + format_g(u));
}

ReducedPoint ReducedTable::at(double a_over_t, Variables which) const {
  if (!(a_over_t > 0.0 && std::isfinite(a_over_t))) {
    throw InputError("a/t = " + format_g(a_over_t) + " not allowed (need finite and > 0)");
  }
  const double u = std::log(a_over_t);
  const Segment& s = segment_for(u);
  // Clamp rounding excursions at segment ends (u from exp/log of a decade boundary).
  const double uc = std::min(std::max(u, s.u_lo), s.u_hi);
  std::array<double, kVariables> v{}, d{};
  for (int j = 0; j < kVariables; ++j) {
    const bool cone_variable = j == 2 || j == 3, sphere_variable = j == 0 || j == 1;
    if ((which == Variables::kSphere && cone_variable) || (which == Variables::kCone && sphere_variable)) continue;
    v[j] = std::exp(gsl_cheb_eval(s.value[j], uc));
    d[j] = gsl_cheb_eval(s.deriv[j], uc);
  }
  ReducedPoint p;
  p.a_over_t = a_over_t;
  p.pi_s = v[0];
  p.delta_s = v[1];
  p.pi_c = v[2];
  p.delta_c = v[3];
  p.e_eq = v[4];
  p.gamma1 = v[5];
  p.dlog_pi_s = d[0];
  p.dlog_delta_s = d[1];
  p.dlog_pi_c = d[2];
  p.dlog_delta_c = d[3];
  p.dlog_e_eq = d[4];
  p.dlog_gamma1 = d[5];
  return p;
}

TableOptions sweep_table_options(double tolerance) {
  TableOptions options;
  // Measured on a/t in [1e-3, 1e4] (E1*/E0* = 10 and 0.1, nu = 0.25; docs/solver.md, Sweeps):
  // order 14 on two-decade segments needs ~130 solves where order 24 on decades needs ~180.
  options.order = 14;
  options.decades_per_segment = 2.0;
  options.tail_tolerance = 0.4 * tolerance;
  options.tail_noise_factor = 1.0;
  options.max_halvings = 5;
  options.verify = true;
  return options;
}

TableOptions radii_sweep_table_options(double tolerance) {
  TableOptions options = sweep_table_options(tolerance);
  options.breaks_decades = {-1.0, -0.5, 0.0, 0.5, 1.0, 2.0, 4.0, 6.0, 8.0};
  return options;
}

TableOptions pulloff_sweep_table_options(double tolerance) {
  // The sweep's table with room for the nodes' own error: solved at kPulloffNodeShare x tol,
  // interpolation held below the rest, so that interpolation + node estimate <= tol.
  TableOptions options = radii_sweep_table_options(tolerance);
  options.tail_tolerance = (1.0 - kPulloffNodeShare) * tolerance;
  options.tail_noise_factor = 0.0;
  return options;
}

namespace {

// Rows `which` solved directly into `out` (tolerant when status is given).
void solve_rows(const ReducedSolver& solver, const std::vector<double>& a_over_t, const std::vector<std::size_t>& which,
                double tolerance, std::vector<ReducedVariables>& out, std::vector<PointStatus>* status) {
  if (which.empty()) return;
  std::vector<double> radii;
  for (std::size_t i : which) radii.push_back(a_over_t[i]);
  std::vector<PointStatus> part;
  const std::vector<ReducedVariables> solved =
      status == nullptr ? solver.sweep(radii, tolerance) : solver.sweep(radii, tolerance, part);
  for (std::size_t k = 0; k < which.size(); ++k) {
    out[which[k]] = solved[k];
    if (status != nullptr) (*status)[which[k]] = part[k];
  }
}

}  // namespace

InterpolatedSweep interpolated_sweep(const ReducedSolver& solver, const std::vector<double>& a_over_t,
                                     double tolerance, std::vector<PointStatus>* status) {
  check_tolerance(tolerance);
  for (double a : a_over_t) {
    if (!(std::isfinite(a) && a > 0.0 && a <= kMaximumAOverT)) {
      throw InputError("a/t " + format_g(a) + " is not allowed; it must be > 0 and <= " + format_g(kMaximumAOverT));
    }
  }
  InterpolatedSweep result;
  result.rows.resize(a_over_t.size());
  result.interpolation_error.assign(a_over_t.size(), 0.0);
  if (status != nullptr) status->assign(a_over_t.size(), PointStatus{});
  std::vector<std::size_t> direct;
  const TableOptions options = radii_sweep_table_options(tolerance);
  double lo = a_over_t.empty() ? 1.0 : *std::min_element(a_over_t.begin(), a_over_t.end());
  double hi = a_over_t.empty() ? 1.0 : *std::max_element(a_over_t.begin(), a_over_t.end());
  // A lower bound of the table's solves: two-decade segments, none halved (the graded layout
  // needs 1.6 times this on a/t 1e-3..1e4: 129 solves in one round).
  const double expected_solves =
      (std::ceil(std::log10(hi / lo) / 2.0) + 1.0) * static_cast<double>(options.order + 2);
  if (hi > lo && static_cast<double>(a_over_t.size()) >= 1.5 * expected_solves) {
    const SolverSource source(solver, tolerance);
    ReducedTable table(source, options);
    try {
      table.prepare_range(lo, hi);
      for (std::size_t i = 0; i < a_over_t.size(); ++i) {
        const double estimate = table.error_estimate_at(a_over_t[i]);
        if (!(estimate <= tolerance)) {
          direct.push_back(i);
          continue;
        }
        ReducedVariables& row = result.rows[i];
        static_cast<ReducedValues&>(row) = table.at(a_over_t[i]);
        row.a_over_t = a_over_t[i];
        row.error_estimate = estimate;
        row.unknowns = 0;
        result.interpolation_error[i] = table.interpolation_error_at(a_over_t[i]);
        ++result.interpolated;
      }
      result.segments = table.segments();
    } catch (const NumericalError& e) {  // a node the solver cannot deliver: every row on its own
      result.direct_reason = e.what();
      result.interpolated = 0;
      result.interpolation_error.assign(a_over_t.size(), 0.0);
      direct.clear();
    }
    result.source_solves = table.source_evaluations();
  } else {
    result.direct_reason = "too few radii for the table to pay";
  }
  if (!result.direct_reason.empty()) {
    direct.resize(a_over_t.size());
    for (std::size_t i = 0; i < direct.size(); ++i) direct[i] = i;
  }
  solve_rows(solver, a_over_t, direct, tolerance, result.rows, status);
  return result;
}

}  // namespace coatcontact
