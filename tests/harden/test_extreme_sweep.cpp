// Extreme-parameter sweep of the reduced-variable solver (issue 7, label physics).
//
// Grid: E1*/E0* in {1e-4, 1e-2, 0.1, 1, 10, 100, 1e4} and a rigid substrate; film nu1 in
// {-0.9, 0, 0.3, 0.49, 0.5}; substrate nu0 in {-0.9, 0.3, 0.5} (rigid: nu0 does not enter);
// a/t in {1e-4, 1e-3, ..., 1e4}; the default tolerance 1e-8 (what the CLI uses).
//
// Every solve must either return finite, positive values with error_estimate <= tol that pass
// the identity check of THEORY.md section 6, item 1 [EqGde1],
//     Gamma(1)^2 = d(a E_eq)/da,
// with the derivative taken by an independent finite difference of the solver's own E_eq, or
// throw NumericalError with a message (the CLI's exit 3). Failures of the second kind are the
// documented limits (docs/limits.md): only the known ones (kKnownFailures) are allowed, so a
// regression that adds one fails the test. The test also fails on a wrong-but-returned value,
// a NaN/inf, a non-positive value, any other exception, a crash or a hang (ctest TIMEOUT).
//
// Reduced workload (sanitizer builds): COATCONTACT_SWEEP_STRIDE=k keeps every k-th material
// pair (k >= 1, default 1 = the whole grid); the log says how many pairs were skipped.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "check.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/reduced.hpp"
#include "coatcontact/stack.hpp"

using namespace coatcontact;

namespace {

// Finite difference in x = ln(a/t) of f(x) = (a/t) E_eq from samples at x +- h, +- 2h, +- 4h:
// fourth-order central differences D4(h) = [8(f(h) - f(-h)) - (f(2h) - f(-2h))] / (12 h) and
// D4(2h), then one Richardson step D6 = (16 D4(h) - D4(2h)) / 15 (sixth order). D6 is the
// derivative used; |D6 - D4(h)| (the error of the lower-order member of the pair) bounds its
// truncation error conservatively. kStep = 0.02 keeps that estimate ~1e-6 relative for the
// steepest case (f ~ (a/t)^4, rigid substrate and incompressible film) while the solver noise
// stays ~1.5 err / h (7.5e-7 at the default tolerance 1e-8, usually far less: the returned
// estimates are mostly ~1e-13).
constexpr double kStep = 0.02;
// The compared quantities carry estimated errors (the solver's error_estimate, an estimate
// from its refinement levels, and the embedded D6/D4 estimate above): a difference beyond
// kSafety times their sum is a wrong value. The slack 3 covers estimates that are a little
// optimistic; observed: every returned point within 0.11 x bound (Release build).
constexpr double kSafety = 3.0;
// A finite-difference neighbour that cannot meet the tolerance of its centre is re-solved at
// kFallbackFactor times it (its own returned estimate then widens the bound accordingly).
constexpr double kFallbackFactor = 100.0;
// Points that fail at the default tolerance are tried again at this looser one (what the
// NumericalError message advises); they must then pass the same identity check or fail again.
constexpr double kLooseTolerance = 1e-6;

const double kRatios[] = {1e-4, 1e-2, 1e-1, 1.0, 1e1, 1e2, 1e4};
const double kFilmNu[] = {-0.9, 0.0, 0.3, 0.49, 0.5};
const double kSubstrateNu[] = {-0.9, 0.3, 0.5};
const double kAOverT[] = {1e-4, 1e-3, 1e-2, 1e-1, 1.0, 1e1, 1e2, 1e3, 1e4};
constexpr int kRadii = sizeof kAOverT / sizeof kAOverT[0];

struct Pair {
  double ratio = 0.0;  // E1*/E0*; 0 = rigid substrate
  double nu1 = 0.0;
  double nu0 = 0.0;
};

// The points that may stop with NumericalError at the default tolerance (2 of 990): an
// incompressible film on a rigid substrate beyond a/t ~ 220-300, where the condition number grows
// like (a/t)^3 (lubrication limit; docs/limits.md).
struct KnownFailure {
  double ratio, nu1, a_over_t;
};
const KnownFailure kKnownFailures[] = {{0.0, 0.5, 1e3}, {0.0, 0.5, 1e4}};
constexpr int kMaxNumericalFailures = sizeof kKnownFailures / sizeof kKnownFailures[0];

bool is_known_failure(const Pair& p, double a_over_t) {
  for (const KnownFailure& k : kKnownFailures) {
    if (p.ratio == k.ratio && p.nu1 == k.nu1 && a_over_t == k.a_over_t) return true;
  }
  return false;
}

enum class Outcome { kOk, kNumericalError, kWrong, kUnchecked };

struct PointResult {
  Outcome outcome = Outcome::kOk;
  std::string message;       // NumericalError text, or what was wrong
  double discrepancy = 0.0;  // |Gamma^2 - d(aE)/da| / bound (ok points)
  double relative = 0.0;     // |Gamma^2 - d(aE)/da| / Gamma^2
};

std::string pair_name(const Pair& p) {
  char buffer[96];
  if (p.ratio == 0.0) {
    std::snprintf(buffer, sizeof buffer, "rigid  nu1=%-5g", p.nu1);
  } else {
    std::snprintf(buffer, sizeof buffer, "%-6g nu1=%-5g nu0=%-4g", p.ratio, p.nu1, p.nu0);
  }
  return buffer;
}

ReducedSolver make_solver(const Pair& p) {
  Material film;
  film.youngs_modulus = 1.0;
  film.poisson_ratio = p.nu1;
  Substrate substrate;
  if (p.ratio == 0.0) {
    substrate.rigid = true;
  } else {
    // E0* = E1* / ratio, E0 = E0* (1 - nu0^2).
    substrate.material.poisson_ratio = p.nu0;
    substrate.material.youngs_modulus =
        film.reduced_modulus() / p.ratio * (1.0 - p.nu0 * p.nu0);
  }
  return ReducedSolver(Stack::film_on(film, substrate));
}

bool all_finite_positive(const ReducedVariables& v) {
  const double values[6] = {v.pi_s, v.delta_s, v.pi_c, v.delta_c, v.e_eq, v.gamma1};
  for (double x : values) {
    if (!std::isfinite(x) || !(x > 0.0)) return false;
  }
  return std::isfinite(v.error_estimate) && v.error_estimate >= 0.0;
}

// One finite-difference neighbour: f = a E_eq and its absolute error estimate.
struct Sample {
  bool ok = false;
  double f = 0.0;
  double error = 0.0;
  std::string problem;
};

Sample sample(const ReducedSolver& solver, double a, double tolerance) {
  Sample s;
  for (double tol : {tolerance, std::min(kFallbackFactor * tolerance, kMaximumTolerance)}) {
    try {
      const ReducedVariables v = solver.solve(a, tol);
      if (!all_finite_positive(v) || v.error_estimate > tol) {
        s.problem = "neighbour a/t=" + std::to_string(a) + " returned a non-finite, non-positive "
                    "or over-tolerance value";
        return s;
      }
      s.ok = true;
      s.f = a * v.e_eq;
      s.error = std::abs(s.f) * v.error_estimate;
      return s;
    } catch (const NumericalError&) {
      continue;  // try the looser tolerance
    }
  }
  s.problem = "neighbour a/t=" + std::to_string(a) + " failed also at " +
              std::to_string(kFallbackFactor) + " x the tolerance";
  return s;
}

PointResult check_point(const ReducedSolver& solver, double a, double tolerance) {
  PointResult r;
  ReducedVariables v;
  try {
    v = solver.solve(a, tolerance);
  } catch (const NumericalError& e) {
    r.outcome = Outcome::kNumericalError;
    r.message = e.what();
    if (r.message.empty()) {
      r.outcome = Outcome::kWrong;
      r.message = "NumericalError without a message";
    }
    return r;
  }
  // Anything else (InputError on valid input, std::bad_alloc, ...) propagates to the caller.
  if (!all_finite_positive(v)) {
    r.outcome = Outcome::kWrong;
    char buffer[256];
    std::snprintf(buffer, sizeof buffer,
                  "non-finite or non-positive value: Pi_s %g Delta_s %g Pi_c %g Delta_c %g "
                  "E_eq %g Gamma1 %g estimate %g",
                  v.pi_s, v.delta_s, v.pi_c, v.delta_c, v.e_eq, v.gamma1, v.error_estimate);
    r.message = buffer;
    return r;
  }
  if (v.error_estimate > tolerance) {
    r.outcome = Outcome::kWrong;
    r.message = "returned error_estimate " + std::to_string(v.error_estimate) + " > tolerance";
    return r;
  }

  // Samples at x + k h, k = -4, -2, -1, 1, 2, 4.
  const int offsets[6] = {-4, -2, -1, 1, 2, 4};
  Sample s[6];
  for (int i = 0; i < 6; ++i) {
    s[i] = sample(solver, a * std::exp(offsets[i] * kStep), tolerance);
    if (!s[i].ok) {
      r.outcome = Outcome::kUnchecked;
      r.message = s[i].problem;
      return r;
    }
  }
  const Sample &m4 = s[0], &m2 = s[1], &m1 = s[2], &p1 = s[3], &p2 = s[4], &p4 = s[5];
  const double h = kStep;
  // df/dx and its noise bound from the samples' own error estimates.
  const double d_h = (8.0 * (p1.f - m1.f) - (p2.f - m2.f)) / (12.0 * h);
  const double d_2h = (8.0 * (p2.f - m2.f) - (p4.f - m4.f)) / (24.0 * h);
  const double noise_h = (8.0 * (p1.error + m1.error) + (p2.error + m2.error)) / (12.0 * h);
  const double noise_2h = (8.0 * (p2.error + m2.error) + (p4.error + m4.error)) / (24.0 * h);
  const double d_6 = (16.0 * d_h - d_2h) / 15.0;
  const double noise_6 = (16.0 * noise_h + noise_2h) / 15.0;
  // |D6 - D4(h)| itself carries the noise of both members.
  const double truncation = std::abs(d_6 - d_h) + noise_6 + noise_h;
  // d(a E_eq)/da = (1/a) df/dx.
  const double derivative = d_6 / a;
  const double gamma_sq = v.gamma1 * v.gamma1;
  const double bound = 2.0 * gamma_sq * v.error_estimate + (noise_6 + truncation) / a;
  const double difference = std::abs(gamma_sq - derivative);
  r.relative = difference / gamma_sq;
  r.discrepancy = difference / bound;
  if (!(difference <= kSafety * bound)) {
    r.outcome = Outcome::kWrong;
    char buffer[320];
    std::snprintf(buffer, sizeof buffer,
                  "identity violated: Gamma1^2 = %.12g, d(a E_eq)/da = %.12g, difference %.3g "
                  "> %g x bound %.3g (estimate %.3g)",
                  gamma_sq, derivative, difference, kSafety, bound, v.error_estimate);
    r.message = buffer;
  }
  return r;
}

}  // namespace

int main() {
  int stride = 1;
  if (const char* text = std::getenv("COATCONTACT_SWEEP_STRIDE")) {
    stride = std::atoi(text);
    if (stride < 1) {
      std::printf("COATCONTACT_SWEEP_STRIDE='%s' is not an integer >= 1\n", text);
      return 1;
    }
  }

  std::vector<Pair> all_pairs;
  for (double ratio : kRatios) {
    for (double nu1 : kFilmNu) {
      for (double nu0 : kSubstrateNu) all_pairs.push_back({ratio, nu1, nu0});
    }
  }
  for (double nu1 : kFilmNu) all_pairs.push_back({0.0, nu1, 0.0});
  std::vector<Pair> pairs;
  for (std::size_t i = 0; i < all_pairs.size(); i += static_cast<std::size_t>(stride)) {
    pairs.push_back(all_pairs[i]);
  }
  std::printf("extreme sweep: %zu of %zu material pairs (COATCONTACT_SWEEP_STRIDE=%d), %d radii, "
              "tol %g, FD step %g in ln(a/t), safety %g\n",
              pairs.size(), all_pairs.size(), stride, kRadii, kDefaultTolerance, kStep, kSafety);
  if (stride > 1) {
    std::printf("NOTE: reduced workload: %zu material pairs skipped by COATCONTACT_SWEEP_STRIDE\n",
                all_pairs.size() - pairs.size());
  }

  // results: at the default tolerance; retried: the NumericalError points again at kLooseTolerance.
  std::vector<std::vector<PointResult>> results(pairs.size(), std::vector<PointResult>(kRadii));
  std::vector<std::vector<PointResult>> retried(pairs.size(), std::vector<PointResult>(kRadii));
  std::vector<std::string> errors(pairs.size());
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    for (std::size_t i = next++; i < pairs.size(); i = next++) {
      try {
        const ReducedSolver solver = make_solver(pairs[i]);
        for (int j = 0; j < kRadii; ++j) {
          results[i][j] = check_point(solver, kAOverT[j], kDefaultTolerance);
          if (results[i][j].outcome == Outcome::kNumericalError) {
            retried[i][j] = check_point(solver, kAOverT[j], kLooseTolerance);
          }
        }
      } catch (const std::exception& e) {
        errors[i] = std::string("unexpected exception: ") + e.what();
      }
    }
  };
  const unsigned threads = std::max(1u, std::min(2u, std::thread::hardware_concurrency()));
  std::vector<std::thread> pool;
  for (unsigned t = 0; t < threads; ++t) pool.emplace_back(worker);
  for (auto& t : pool) t.join();

  struct Tally {
    int ok = 0, numerical = 0, unchecked = 0, wrong = 0, above_bound = 0;
    double worst_discrepancy = 0.0, worst_relative = 0.0;
    std::string worst_where;
    void add(const PointResult& r, const std::string& where) {
      switch (r.outcome) {
        case Outcome::kOk:
          ++ok;
          if (r.discrepancy > worst_discrepancy) {
            worst_discrepancy = r.discrepancy;
            worst_where = where;
          }
          worst_relative = std::max(worst_relative, r.relative);
          if (r.discrepancy > 1.0) ++above_bound;
          break;
        case Outcome::kNumericalError: ++numerical; break;
        case Outcome::kUnchecked: ++unchecked; break;
        case Outcome::kWrong: ++wrong; break;
      }
    }
    void print(const char* label) const {
      std::printf("%s: %d ok, %d NumericalError, %d unchecked, %d WRONG; identity on the ok points: "
                  "worst relative difference %.3g, worst |difference|/bound %.3g (%s), %d above "
                  "1 x bound (allowed %g x)\n",
                  label, ok, numerical, unchecked, wrong, worst_relative, worst_discrepancy,
                  worst_where.empty() ? "-" : worst_where.c_str(), above_bound, kSafety);
    }
  };
  Tally first;
  Tally second;
  int exceptions = 0;
  // cells[table key + "|" + radius index] = {ok, fail}
  std::map<std::string, std::pair<int, int>> by_ratio, by_nu, by_ratio_loose;
  auto radius_key = [](int j) {
    char key[16];
    std::snprintf(key, sizeof key, "%02d", j);
    return std::string(key);
  };

  std::printf("\nper material pair, columns a/t = 1e-4 1e-3 ... 1e4: '.' ok at tol %g; 'f' "
              "NumericalError at %g, ok at %g; 'F' NumericalError at both; 'u' not checkable; "
              "'X' WRONG\n",
              kDefaultTolerance, kDefaultTolerance, kLooseTolerance);
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    if (!errors[i].empty()) {
      std::printf("%-32s ERROR %s\n", pair_name(pairs[i]).c_str(), errors[i].c_str());
      ++exceptions;
      continue;
    }
    char ratio_key[32];
    if (pairs[i].ratio == 0.0) {
      std::snprintf(ratio_key, sizeof ratio_key, "rigid");
    } else {
      std::snprintf(ratio_key, sizeof ratio_key, "%g", pairs[i].ratio);
    }
    char nu_key[32];
    std::snprintf(nu_key, sizeof nu_key, "%g", pairs[i].nu1);
    std::string row;
    for (int j = 0; j < kRadii; ++j) {
      char where_text[64];
      std::snprintf(where_text, sizeof where_text, " a/t=%g", kAOverT[j]);
      const std::string where = pair_name(pairs[i]) + where_text;
      const PointResult& r = results[i][j];
      first.add(r, where);
      const bool fine = r.outcome == Outcome::kOk;
      auto& ratio_cell = by_ratio[std::string(ratio_key) + "|" + radius_key(j)];
      auto& nu_cell = by_nu[std::string(nu_key) + "|" + radius_key(j)];
      (fine ? ratio_cell.first : ratio_cell.second)++;
      (fine ? nu_cell.first : nu_cell.second)++;
      char mark = '.';
      if (r.outcome == Outcome::kNumericalError) {
        check::that(is_known_failure(pairs[i], kAOverT[j]), "NumericalError only at a known limit: " + where);
        const PointResult& again = retried[i][j];
        second.add(again, where);
        auto& loose_cell = by_ratio_loose[std::string(ratio_key) + "|" + radius_key(j)];
        (again.outcome == Outcome::kOk ? loose_cell.first : loose_cell.second)++;
        mark = again.outcome == Outcome::kOk               ? 'f'
               : again.outcome == Outcome::kNumericalError ? 'F'
               : again.outcome == Outcome::kUnchecked      ? 'u'
                                                           : 'X';
      } else if (r.outcome == Outcome::kUnchecked) {
        mark = 'u';
      } else if (r.outcome == Outcome::kWrong) {
        mark = 'X';
      }
      row += mark;
    }
    std::printf("%-32s %s\n", pair_name(pairs[i]).c_str(), row.c_str());
  }

  auto print_table = [&](const std::string& title, const std::map<std::string, std::pair<int, int>>& cells,
                         const std::vector<std::string>& keys) {
    std::printf("\n%s\n%-8s", title.c_str(), "");
    for (double a : kAOverT) std::printf(" %7g", a);
    std::printf("\n");
    for (const std::string& key : keys) {
      std::printf("%-8s", key.c_str());
      for (int j = 0; j < kRadii; ++j) {
        const auto it = cells.find(key + "|" + radius_key(j));
        if (it == cells.end()) {
          std::printf(" %7s", "-");
        } else {
          char cell[16];
          std::snprintf(cell, sizeof cell, "%d/%d", it->second.first, it->second.second);
          std::printf(" %7s", cell);
        }
      }
      std::printf("\n");
    }
  };
  std::vector<std::string> ratio_keys;
  for (double ratio : kRatios) {
    char key[32];
    std::snprintf(key, sizeof key, "%g", ratio);
    ratio_keys.emplace_back(key);
  }
  ratio_keys.emplace_back("rigid");
  std::vector<std::string> nu_keys;
  for (double nu : kFilmNu) {
    char key[32];
    std::snprintf(key, sizeof key, "%g", nu);
    nu_keys.emplace_back(key);
  }
  char title[160];
  std::snprintf(title, sizeof title, "ok/fail at tol %g by E1*/E0* (rows) and a/t (columns):",
                kDefaultTolerance);
  print_table(title, by_ratio, ratio_keys);
  std::snprintf(title, sizeof title, "ok/fail at tol %g by film nu1 (rows) and a/t (columns):",
                kDefaultTolerance);
  print_table(title, by_nu, nu_keys);
  std::snprintf(title, sizeof title,
                "the points that failed at tol %g, again at tol %g: ok/fail by E1*/E0* and a/t:",
                kDefaultTolerance, kLooseTolerance);
  print_table(title, by_ratio_loose, ratio_keys);

  std::printf("\npoints that did not pass at tol %g (and what happened at %g):\n", kDefaultTolerance,
              kLooseTolerance);
  auto tag = [](Outcome o) {
    return o == Outcome::kOk               ? "ok"
           : o == Outcome::kNumericalError ? "fail"
           : o == Outcome::kUnchecked      ? "unchecked"
                                           : "WRONG";
  };
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    for (int j = 0; j < kRadii; ++j) {
      const PointResult& r = results[i][j];
      if (r.outcome == Outcome::kOk || !errors[i].empty()) continue;
      std::printf("  %-9s %-32s a/t=%-6g %s\n", tag(r.outcome), pair_name(pairs[i]).c_str(),
                  kAOverT[j], r.message.c_str());
      if (r.outcome == Outcome::kNumericalError) {
        const PointResult& again = retried[i][j];
        std::printf("            at tol %g: %s%s%s\n", kLooseTolerance, tag(again.outcome),
                    again.message.empty() ? "" : ": ", again.message.c_str());
      }
    }
  }

  const int total = static_cast<int>(pairs.size()) * kRadii;
  std::printf("\nsummary over %d points (%zu material pairs x %d a/t):\n", total, pairs.size(), kRadii);
  char label[64];
  std::snprintf(label, sizeof label, "  tol %g", kDefaultTolerance);
  first.print(label);
  std::snprintf(label, sizeof label, "  retried at tol %g", kLooseTolerance);
  second.print(label);
  if (exceptions != 0) std::printf("  %d material pair(s) threw an unexpected exception\n", exceptions);
  const int wrong = first.wrong + second.wrong + exceptions;
  check::that(wrong == 0, std::to_string(wrong) + " wrong values or unexpected errors");
  check::that(first.numerical <= kMaxNumericalFailures, std::to_string(first.numerical) +
                                                            " NumericalError points at tol 1e-8, at most " +
                                                            std::to_string(kMaxNumericalFailures) + " known");
  return check::exit_code();
}
