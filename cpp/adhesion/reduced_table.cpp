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
#include <sstream>

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
  Segment() = default;
  Segment(const Segment&) = delete;
  Segment& operator=(const Segment&) = delete;
  ~Segment() {
    for (auto* s : value) gsl_cheb_free(s);
    for (auto* s : deriv) gsl_cheb_free(s);
  }
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

void ReducedTable::build_decades(const std::vector<long>& decades) const {
  struct Pending {
    double u_lo, u_hi;
    int halvings;
  };
  std::vector<Pending> pending;
  for (long k : decades) {
    pending.push_back({static_cast<double>(k) * kLn10, static_cast<double>(k + 1) * kLn10, 0});
  }
  const std::size_t n_nodes = options_.order + 1;
  detail::GslHandlerOff gsl_guard;

  while (!pending.empty()) {
    // One batched source call for all nodes of all pending intervals.
    std::vector<std::vector<double>> nodes(pending.size());
    std::vector<double> a_over_t;
    a_over_t.reserve(pending.size() * n_nodes);
    for (std::size_t p = 0; p < pending.size(); ++p) {
      nodes[p] = cheb_nodes(options_.order, pending[p].u_lo, pending[p].u_hi);
      for (double u : nodes[p]) a_over_t.push_back(std::exp(u));
    }
    const std::vector<ReducedVariables> solved = source_.evaluate(a_over_t);
    if (solved.size() != a_over_t.size()) {
      throw NumericalError("reduced-variable source returned " + std::to_string(solved.size()) +
                           " values for " + std::to_string(a_over_t.size()) + " radii");
    }
    evaluations_ += solved.size();

    std::vector<Pending> next;
    for (std::size_t p = 0; p < pending.size(); ++p) {
      auto segment = std::make_unique<Segment>();
      segment->u_lo = pending[p].u_lo;
      segment->u_hi = pending[p].u_hi;
      double noise = 0.0;
      std::array<std::vector<double>, kVariables> logs;
      for (std::size_t k = 0; k < n_nodes; ++k) {
        const ReducedVariables& v = solved[p * n_nodes + k];
        noise = std::max(noise, v.error_estimate);
        const auto vals = values_of(v);
        for (int j = 0; j < kVariables; ++j) {
          if (!(std::isfinite(vals[j]) && vals[j] > 0.0)) {
            throw NumericalError(std::string("reduced variable ") + kNames[j] + " = " +
                                 format_g(vals[j]) + " at a/t = " + format_g(a_over_t[p * n_nodes + k]) +
                                 " (expected finite and > 0)");
          }
          logs[j].push_back(std::log(vals[j]));
        }
      }
      for (int j = 0; j < kVariables; ++j) {
        segment->value[j] = gsl_cheb_alloc(options_.order);
        segment->deriv[j] = gsl_cheb_alloc(options_.order);
        if (segment->value[j] == nullptr || segment->deriv[j] == nullptr) {
          throw NumericalError("cannot allocate a Chebyshev series");
        }
        CachedValues cache{&nodes[p], &logs[j]};
        gsl_function f{&cached_value, &cache};
        const int status = gsl_cheb_init(segment->value[j], &f, segment->u_lo, segment->u_hi);
        if (status != GSL_SUCCESS || cache.mismatch || cache.next != n_nodes) {
          throw NumericalError("Chebyshev interpolation setup failed (node mismatch)");
        }
        gsl_cheb_calc_deriv(segment->deriv[j], segment->value[j]);
        const double* c = gsl_cheb_coeffs(segment->value[j]);
        segment->tail = std::max(segment->tail, std::abs(c[options_.order]) + std::abs(c[options_.order - 1]));
      }
      const double allowed = options_.tail_tolerance + options_.tail_noise_factor * noise;
      if (segment->tail > allowed) {
        if (pending[p].halvings >= options_.max_halvings) {
          throw NumericalError("reduced variables not resolved by order-" +
                               std::to_string(options_.order) + " Chebyshev series on a/t in [" +
                               format_g(std::exp(pending[p].u_lo)) + ", " +
                               format_g(std::exp(pending[p].u_hi)) + "]: tail " +
                               format_g(segment->tail) + " > " + format_g(allowed));
        }
        const double mid = 0.5 * (pending[p].u_lo + pending[p].u_hi);
        next.push_back({pending[p].u_lo, mid, pending[p].halvings + 1});
        next.push_back({mid, pending[p].u_hi, pending[p].halvings + 1});
        continue;
      }
      interpolation_error_ = std::max(interpolation_error_, segment->tail);
      source_error_ = std::max(source_error_, noise);
      segments_[segment->u_lo] = std::move(segment);
    }
    pending = std::move(next);
  }
  for (long k : decades) built_decades_[k] = true;
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
  if (!missing.empty()) build_decades(missing);
}

const ReducedTable::Segment& ReducedTable::segment_for(double u) const {
  const long k = static_cast<long>(std::floor(u / kLn10));
  if (built_decades_.count(k) == 0) build_decades({k});
  // Decade k covers [k ln10, (k+1) ln10] without gaps; allow rounding at its ends.
  const double slack = 1e-12 * (1.0 + std::abs(u));
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

}  // namespace coatcontact
