// Minimal checking helpers for the adhesive tests: each failed check prints one line and
// makes the program return non-zero.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace adhesive_test {

inline int& failures() {
  static int n = 0;
  return n;
}

inline void check(bool ok, const std::string& what) {
  if (!ok) {
    ++failures();
    std::printf("FAIL: %s\n", what.c_str());
  }
}

// |got - want| <= tol * max(1, |want|), printed either way.
inline void check_close(double got, double want, double tol, const std::string& what) {
  const double err = std::abs(got - want) / std::max(1.0, std::abs(want));
  const bool ok = std::isfinite(got) && err <= tol;
  std::printf("%s %-58s got % .17g want % .17g err %.2e (tier %.0e)\n", ok ? "ok  " : "FAIL", what.c_str(),
              got, want, err, tol);
  if (!ok) ++failures();
}

inline int finish(const char* name) {
  if (failures() == 0) {
    std::printf("%s: all checks passed\n", name);
    return 0;
  }
  std::printf("%s: %d check(s) FAILED\n", name, failures());
  return 1;
}

}  // namespace adhesive_test
