// The one assertion header of the C++ tests: named tolerance tiers, one call style and one
// failure counter. Every check prints its call site on failure; main() ends with
//   return check::exit_code();
//
//   check::that(condition, "what");
//   check::close(actual, expected, check::tier::kMachine, "what");  // relative to |expected|
//   check::close(actual, expected, tier, "what", floor);            // ... to max(|expected|, floor)
//   check::below(measured, bound, "what");                          // finite and <= bound
//   check::throws<InputError>([&] { ... }, {"fragment", ...});      // type and message ({}: any)
#pragma once
#include <cmath>
#include <cstdio>
#include <exception>
#include <initializer_list>
#include <string>
#include <vector>

#include "coatcontact/reduced.hpp"

namespace check {

// Tolerance tiers, relative unless a check says otherwise. A test uses the tier that matches
// where its error comes from; a bound that is a measurement of one test stays in that test.
// A value in messages, %g.
inline std::string text(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

namespace tier {
// One correctly rounded operation: 1 ulp (2.2e-16) plus the rounding of the decimal literal.
inline constexpr double kRounding = 1e-15;
// Rounding accumulated over ~100 operations, or a few ulps of exp/log/pow/cbrt each.
inline constexpr double kMachine = 1e-13;
// Rounding amplified ~order^2 by spectral differentiation, or by high powers and cancellation.
inline constexpr double kAmplified = 1e-12;
// Agreement with an independent reference computed to ~1e-12 (direct solve, brute force, root).
inline constexpr double kReference = 1e-11;
// Tabulated or interpolated functions: the kernel table's 1e-10 max|H| target, the tail test.
inline constexpr double kInterpolation = 1e-10;
// What a converged solve at the solver's default tolerance guarantees (also the pull-off
// location requirement, which is set by it).
inline constexpr double kSolver = coatcontact::kDefaultTolerance;
// Identities through a numerical derivative of solver output (finite differences or a
// differentiated interpolant): the 1e-6 asked of [EqGde1], THEORY.md section 6, item 1.
inline constexpr double kIdentityByDifferences = 1e-6;
}  // namespace tier

// Call site of a check (the C++20 std::source_location idea, through the builtins that GCC
// and Clang provide in C++17).
struct Where {
  const char* file;
  int line;
  static Where here(const char* file = __builtin_FILE(), int line = __builtin_LINE()) { return {file, line}; }
};

// Set to print passing close()/below() checks too (tests whose log reports measured errors).
inline bool verbose = false;

namespace detail {
inline int& failures() {
  static int count = 0;
  return count;
}
inline int& checks() {
  static int count = 0;
  return count;
}
inline bool record(bool ok, const Where& where, const std::string& text, bool print_pass = false) {
  ++checks();
  if (!ok) ++failures();
  if (!ok || print_pass) {
    std::printf("%s %s:%d: %s\n", ok ? "ok  " : "FAIL", where.file, where.line, text.c_str());
    std::fflush(stdout);
  }
  return ok;
}
}  // namespace detail

inline int failures() { return detail::failures(); }

inline bool that(bool condition, const std::string& what, Where where = Where::here()) {
  return detail::record(condition, where, what);
}

// |actual - expected| <= tier * max(|expected|, floor), with actual finite. floor > 0 turns the
// check absolute where |expected| < floor (e.g. values that pass through zero).
inline bool close(double actual, double expected, double tolerance, const std::string& what,
                  double floor = 0.0, Where where = Where::here()) {
  const double scale = std::fmax(std::fabs(expected), floor);
  const double difference = std::fabs(actual - expected);
  const bool ok = std::isfinite(actual) && difference <= tolerance * scale;
  char text[160];
  std::snprintf(text, sizeof text, ": got %.17g, want %.17g, relative error %.3g (tier %.3g)", actual,
                expected, scale > 0.0 ? difference / scale : difference, tolerance);
  return detail::record(ok, where, what + text, verbose);
}

// A measured error or quantity against its bound: finite and <= bound.
inline bool below(double value, double bound, const std::string& what, Where where = Where::here()) {
  const bool ok = std::isfinite(value) && value <= bound;
  char text[96];
  std::snprintf(text, sizeof text, ": %.6g (bound %.3g)", value, bound);
  return detail::record(ok, where, what + text, verbose);
}

// Fragments that an exception's what() must all contain.
struct Fragments {
  std::vector<std::string> items;
  Fragments() = default;  // {}: any message
  Fragments(const char* one) : items{one} {}
  Fragments(const std::string& one) : items{one} {}
  Fragments(std::initializer_list<std::string> many) : items(many) {}
};

// fn() must throw E (or a type derived from it) whose what() contains every fragment.
template <class E, class F>
bool throws(F&& fn, const Fragments& fragments, Where where = Where::here()) {
  std::string expected = "exception with";
  for (const auto& f : fragments.items) expected += " '" + f + "'";
  try {
    fn();
  } catch (const E& error) {
    const std::string message = error.what();
    for (const auto& f : fragments.items) {
      if (message.find(f) == std::string::npos) {
        return detail::record(false, where, "message lacks '" + f + "': " + message);
      }
    }
    return detail::record(true, where, expected);
  } catch (const std::exception& other) {
    return detail::record(false, where, "wrong exception (wanted " + expected + "): " + other.what());
  } catch (...) {
    return detail::record(false, where, "non-standard exception (wanted " + expected + ")");
  }
  return detail::record(false, where, "no exception (wanted " + expected + ")");
}

// The program's exit status: 0 when every check passed, 1 otherwise (with a summary line).
inline int exit_code() {
  if (detail::failures() == 0) {
    std::printf("all %d checks passed\n", detail::checks());
    return 0;
  }
  std::printf("%d of %d checks FAILED\n", detail::failures(), detail::checks());
  return 1;
}

}  // namespace check
