// Surface compliance C(q) of a stack of layers (THEORY.md section 12) through the C interface
// cc_stack_compliance: against an independent direct global boundary-value solve, the one-layer
// closed form of section 3, the exact free-plate results of section 12, its limits, and the
// status codes. Every physics check names the section-12 check it makes.
//
// The direct solve: in every layer the Navier solution (the two families of
// test_compliance.cpp, z into the solid, s = k z):
//   down (referred to the layer top, s from the top):
//     U = (a + b s) e^-s, W = (a + g b + b s) e^-s,
//     Szz = -2 mu (a + 2(1-nu) b + b s) e^-s, Srz = -2 mu (a + (1-2nu) b + b s) e^-s
//   up (its mirror image, referred to the layer bottom, t = distance above the bottom):
//     U = (c + d t) e^-t, W = -(c + g d + d t) e^-t,
//     Szz = -2 mu (c + 2(1-nu) d + d t) e^-t, Srz = +2 mu (c + (1-2nu) d + d t) e^-t
// and the down family in an elastic base: 4N + 2 unknowns (4N on a rigid base), all assembled
// into ONE linear system (no recursion, no chart, no propagator): Szz = -1, Srz = 0 on top;
// bonded interface: U, W, Szz, Srz continuous; frictionless: Srz = 0 on both sides, W and Szz
// continuous; rigid base: U = W = 0 (bonded) or W = Srz = 0 (frictionless). With k = 1,
// C = mu_top W(0) / (1 - nu_top). Unknowns are scaled by mu of their layer (so stresses are
// O(1)), rows equilibrated. Solved by a long double Gaussian elimination with partial pivoting
// (64-bit mantissa: the reference) and by LAPACKE_dgesvx (double, equilibration and refinement;
// its reciprocal condition number sizes the reference's own error, see kDirectTier).
#include <lapacke.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <ctime>
#include <cstdio>
#include <string>
#include <vector>

#include "check.hpp"
#include "coatcontact/cc_kernel.h"

namespace {

// Tolerance tiers (why each value):
// kDirectTier: the requirement against the direct global solve. Section 12 measured
//   2e-15 for the recursion; the slack is for the reference itself, whose long double rounding
//   (1e-19) is amplified by the condition number of the global system (up to ~1e6 here) and the
//   cancellation in W(0) (points where that product exceeds kDirectTier / 10 are not counted).
constexpr double kDirectTier = 1e-11;
// kRecursionTier: the same stack computed two ways by the kernel (a layer split into identical
//   sublayers, the one-layer closed form, exact free-plate algebra): a few hundred roundings
//   of O(1) quantities through the recursion (section 12: 2e-15 measured, 1e-14 required for
//   one layer) -- 1e-13 leaves a margin for up to 20 layers.
constexpr double kRecursionTier = 1e-13;
// kLongStackTier: 1000 sublayers accumulate 1000 steps of rounding.
constexpr double kLongStackTier = 1e-11;

// The text of a bounded measurement, for check::that.
std::string measured(const char* what, double value, double bound) {
  char text[256];
  std::snprintf(text, sizeof text, "%s: %.6g (bound %.3g)", what, value, bound);
  return text;
}

struct Layer {
  double h, e, nu;
  bool slip;  // interface below this layer frictionless
};

struct Stack {
  std::vector<Layer> layers;  // top first
  bool rigid = false;
  double eb = 1, nub = 0.3;
};

double reduced(double e, double nu) { return e / ((1 - nu) * (1 + nu)); }
double shear(double e, double nu) { return e / (2 * (1 + nu)); }

int call_library(const Stack& s, double q, double* out, bool minus_one) {
  std::vector<double> h, e, nu;
  std::vector<int> slip;
  for (const Layer& l : s.layers) {
    h.push_back(l.h);
    e.push_back(l.e);
    nu.push_back(l.nu);
    slip.push_back(l.slip ? 1 : 0);
  }
  const int n = static_cast<int>(s.layers.size());
  return minus_one ? cc_stack_compliance_minus_one(n, h.data(), e.data(), nu.data(), slip.data(),
                                                   s.rigid, s.eb, s.nub, 1, &q, out)
                   : cc_stack_compliance(n, h.data(), e.data(), nu.data(), slip.data(), s.rigid,
                                         s.eb, s.nub, 1, &q, out);
}

double stack_c(const Stack& s, double q) {
  double c = NAN;
  const int status = call_library(s, q, &c, false);
  check::that(status == CC_OK, "cc_stack_compliance status " + std::to_string(status));
  return c;
}

double stack_f(const Stack& s, double q) {
  double f = NAN;
  const int status = call_library(s, q, &f, true);
  check::that(status == CC_OK, "cc_stack_compliance_minus_one status " + std::to_string(status));
  return f;
}

double rel(double a, double b) { return std::fabs(a - b) / std::fabs(b); }

// ---- the direct global solve -----------------------------------------------------------

using Real = long double;

enum Field { kU = 0, kW = 1, kSzz = 2, kSrz = 3 };

// Coefficients of (a', b', c', d') (a' = mu a, ...) in one field of a layer, at its top
// (at_top) or its bottom; x = k h.
template <typename T>
void layer_row(const Layer& l, T x, Field f, bool at_top, T* row) {
  const T nu = l.nu, mu = shear(l.e, l.nu), g = 3 - 4 * nu;
  const T s = at_top ? T(0) : x, t = at_top ? x : T(0);
  const T ed = std::exp(-s), eu = std::exp(-t);
  switch (f) {
    case kU:
      row[0] = ed / mu, row[1] = s * ed / mu, row[2] = eu / mu, row[3] = t * eu / mu;
      break;
    case kW:
      row[0] = ed / mu, row[1] = (g + s) * ed / mu;
      row[2] = -eu / mu, row[3] = -(g + t) * eu / mu;
      break;
    case kSzz:
      row[0] = -2 * ed, row[1] = -2 * (2 * (1 - nu) + s) * ed;
      row[2] = -2 * eu, row[3] = -2 * (2 * (1 - nu) + t) * eu;
      break;
    case kSrz:
      row[0] = -2 * ed, row[1] = -2 * ((1 - 2 * nu) + s) * ed;
      row[2] = 2 * eu, row[3] = 2 * ((1 - 2 * nu) + t) * eu;
      break;
  }
}

// Coefficients of (a', b') of the base's decaying family at its top.
template <typename T>
void base_row(const Stack& st, Field f, T* row) {
  const T nu = st.nub, mu = shear(st.eb, st.nub), g = 3 - 4 * nu;
  switch (f) {
    case kU: row[0] = 1 / mu, row[1] = 0; break;
    case kW: row[0] = 1 / mu, row[1] = g / mu; break;
    case kSzz: row[0] = -2, row[1] = -4 * (1 - nu); break;
    case kSrz: row[0] = -2, row[1] = -2 * (1 - 2 * nu); break;
  }
}

// Row-major system m (n x n), right-hand side b.
template <typename T>
int build_global(const Stack& st, double q, std::vector<T>& m, std::vector<T>& b) {
  const int nl = static_cast<int>(st.layers.size());
  double total = 0;
  for (const Layer& l : st.layers) total += l.h;
  const int n = 4 * nl + (st.rigid ? 0 : 2);
  m.assign(static_cast<std::size_t>(n * n), T(0));
  b.assign(static_cast<std::size_t>(n), T(0));
  int r = 0;
  T tmp[4];
  auto put = [&](int row, int col0, const T* v, int count, T sign) {
    for (int k = 0; k < count; ++k) m[static_cast<std::size_t>(row * n + col0 + k)] += sign * v[k];
  };
  auto x_of = [&](int i) { return T(q) * T(st.layers[i].h) / T(total); };
  // surface: Szz = -1, Srz = 0
  layer_row<T>(st.layers[0], x_of(0), kSzz, true, tmp);
  put(r, 0, tmp, 4, 1);
  b[r++] = -1;
  layer_row<T>(st.layers[0], x_of(0), kSrz, true, tmp);
  put(r++, 0, tmp, 4, 1);
  for (int i = 0; i < nl; ++i) {
    const Layer& l = st.layers[i];
    const bool last = i == nl - 1;
    if (last && st.rigid) {
      // rigid base: U = W = 0 (bonded) or W = Srz = 0 (frictionless)
      for (Field f : {l.slip ? kSrz : kU, kW}) {
        layer_row<T>(l, x_of(i), f, false, tmp);
        put(r++, 4 * i, tmp, 4, 1);
      }
      continue;
    }
    const int below = 4 * (i + 1);
    auto below_row = [&](Field f, T* v) {
      if (last) {
        base_row<T>(st, f, v);
        return 2;
      }
      layer_row<T>(st.layers[i + 1], x_of(i + 1), f, true, v);
      return 4;
    };
    if (l.slip) {
      // Srz = 0 on both sides; W, Szz continuous
      layer_row<T>(l, x_of(i), kSrz, false, tmp);
      put(r++, 4 * i, tmp, 4, 1);
      const int cnt = below_row(kSrz, tmp);
      put(r++, below, tmp, cnt, 1);
      for (Field f : {kW, kSzz}) {
        layer_row<T>(l, x_of(i), f, false, tmp);
        put(r, 4 * i, tmp, 4, 1);
        const int c2 = below_row(f, tmp);
        put(r++, below, tmp, c2, -1);
      }
    } else {
      for (Field f : {kU, kW, kSzz, kSrz}) {
        layer_row<T>(l, x_of(i), f, false, tmp);
        put(r, 4 * i, tmp, 4, 1);
        const int c2 = below_row(f, tmp);
        put(r++, below, tmp, c2, -1);
      }
    }
  }
  // equilibrate rows
  for (int i = 0; i < n; ++i) {
    T big = 0;
    for (int k = 0; k < n; ++k) big = std::max(big, std::fabs(m[static_cast<std::size_t>(i * n + k)]));
    for (int k = 0; k < n; ++k) m[static_cast<std::size_t>(i * n + k)] /= big;
    b[i] /= big;
  }
  return n;
}

// C = mu_top W(0) / (1 - nu_top) from the solution; `cancellation` = sum |terms| / |sum|.
template <typename T>
T compliance_from(const Stack& st, double q, const T* x, double* cancellation) {
  double total = 0;
  for (const Layer& l : st.layers) total += l.h;
  const Layer& top = st.layers[0];
  const T xt = T(q) * T(top.h) / T(total), g = 3 - 4 * T(top.nu), e = std::exp(-xt);
  const T terms[4] = {x[0], g * x[1], -x[2] * e, -(g + xt) * x[3] * e};
  T sum = 0, size = 0;
  for (T v : terms) sum += v, size += std::fabs(v);
  if (cancellation) *cancellation = static_cast<double>(size / std::fabs(sum));
  return sum / (1 - T(top.nu));
}

Real direct_long_double(const Stack& st, double q, double* cancellation) {
  std::vector<Real> m, b;
  const int n = build_global<Real>(st, q, m, b);
  auto at = [&](int r, int c) -> Real& { return m[static_cast<std::size_t>(r * n + c)]; };
  for (int k = 0; k < n; ++k) {
    int piv = k;
    for (int r = k + 1; r < n; ++r)
      if (std::fabs(at(r, k)) > std::fabs(at(piv, k))) piv = r;
    if (piv != k) {
      for (int c = 0; c < n; ++c) std::swap(at(k, c), at(piv, c));
      std::swap(b[k], b[piv]);
    }
    for (int r = k + 1; r < n; ++r) {
      const Real factor = at(r, k) / at(k, k);
      if (factor == 0) continue;
      for (int c = k; c < n; ++c) at(r, c) -= factor * at(k, c);
      b[r] -= factor * b[k];
    }
  }
  std::vector<Real> x(static_cast<std::size_t>(n));
  for (int k = n - 1; k >= 0; --k) {
    Real s = b[k];
    for (int c = k + 1; c < n; ++c) s -= at(k, c) * x[c];
    x[k] = s / at(k, k);
  }
  return compliance_from<Real>(st, q, x.data(), cancellation);
}

// LAPACKE_dgesvx; returns C, its reciprocal condition number and forward-error bound.
double direct_lapacke(const Stack& st, double q, double* rcond_out, double* ferr_out) {
  std::vector<double> m, b;
  const lapack_int n = build_global<double>(st, q, m, b);
  std::vector<double> af(static_cast<std::size_t>(n * n)), r(n), c(n), x(n);
  std::vector<lapack_int> ipiv(n);
  char equed = 'N';
  double rcond = 0, ferr = 0, berr = 0, rpivot = 0;
  const lapack_int info = LAPACKE_dgesvx(LAPACK_ROW_MAJOR, 'E', 'N', n, 1, m.data(), n, af.data(),
                                         n, ipiv.data(), &equed, r.data(), c.data(), b.data(), 1,
                                         x.data(), 1, &rcond, &ferr, &berr, &rpivot);
  double cancellation = 1;
  const double value = compliance_from<double>(st, q, x.data(), &cancellation);
  *rcond_out = info == 0 ? rcond : 0.0;
  *ferr_out = info == 0 ? ferr * cancellation : 1.0;
  return value;
}

// ---- exact results of section 12 ---------------------------------------------------------

// sinh z - z by its series for small z.
Real sinh_minus(Real z) {
  if (z > 1) return std::sinh(z) - z;
  Real term = z * z * z / 6, sum = term;
  for (int k = 2; k < 30; ++k) {
    term *= z * z / ((2 * k) * (2 * k + 1));
    sum += term;
  }
  return sum;
}

// s(q) = (1 - e^-2q)^2 / (1 - e^-4q + 4q e^-2q): one layer on a frictionless rigid base.
Real plate_s_of_q(Real q) {
  const Real y = -std::expm1(-2 * q);
  return y * y / (-std::expm1(-4 * q) + 4 * q * std::exp(-2 * q));
}

// One layer sliding on a half-space: rho = E_top*/E_base*, s and a at x = q/2:
//   s = (cosh 2x - 1)/(sinh 2x + 2x),  a = (cosh 2x + 1)/(sinh 2x - 2x),
//   C = (rho(s + a) + 2as)/(2rho + s + a).
// Cancellation-free at small q (a ~ 1/z^3 divided out):
Real plate_on_half_space(Real q, Real rho) {
  const Real z = q;
  const Real half = std::sinh(z / 2);
  const Real s = 2 * half * half / (std::sinh(z) + z);
  const Real inv_a = sinh_minus(z) / (std::cosh(z) + 1);
  return (rho * (s * inv_a + 1) + 2 * s) / (2 * rho * inv_a + s * inv_a + 1);
}

// For q >= 1 (where C ~ 1), C - 1 = ((rho + 1)(a - 1 - (1 - s)) - 2(a - 1)(1 - s))/(2rho + s + a) with, at z = 2x,
//   a - 1 - (1 - s) = 2z(1 + z)/(sinh^2 z - z^2) + e^-z (1/(sinh z - z) + 1/(sinh z + z)),
// every piece positive: no cancellation, also where C ~ 1. cosh z - 1 = 2 sinh^2(z/2).
Real plate_on_half_space_minus_one(Real q, Real rho) {
  const Real z = q, sh = std::sinh(z), ez = std::exp(-z);
  const Real smz = sinh_minus(z), spz = sh + z;
  const Real half = std::sinh(z / 2);
  const Real s = 2 * half * half / spz;
  const Real one_minus_s = (1 + z - ez) / spz;
  const Real a_minus_one = (ez + 1 + z) / smz;
  const Real diff = 2 * z * (1 + z) / (smz * spz) + ez * (1 / smz + 1 / spz);
  // 2 rho + s + a, divided by a (a ~ 1/z^3 at small z) to stay finite
  const Real inv_a = smz / (std::cosh(z) + 1);
  const Real den_over_a = (2 * rho + s) * inv_a + 1;
  return ((rho + 1) * diff - 2 * a_minus_one * one_minus_s) * inv_a / den_over_a;
}

// Deterministic pseudo-random numbers (xorshift), so failures are reproducible.
struct Random {
  std::uint64_t state = 0x2545F4914F6CDD1Dull;
  double uniform() {
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    return static_cast<double>(state >> 11) * (1.0 / 9007199254740992.0);
  }
  double log_uniform(double lo, double hi) {
    return std::pow(10.0, std::log10(lo) + (std::log10(hi) - std::log10(lo)) * uniform());
  }
};

Stack one_layer(double e1, double nu1, bool slip, bool rigid, double eb, double nub) {
  Stack s;
  s.layers = {{1.0, e1, nu1, slip}};
  s.rigid = rigid;
  s.eb = eb;
  s.nub = nub;
  return s;
}

// The same stack with layer i split into `parts` sublayers of the given fractions, bonded
// to each other (the last keeps the layer's slip flag).
Stack split(const Stack& s, std::size_t i, const std::vector<double>& fractions) {
  Stack out = s;
  out.layers.clear();
  for (std::size_t k = 0; k < s.layers.size(); ++k) {
    if (k != i) {
      out.layers.push_back(s.layers[k]);
      continue;
    }
    for (std::size_t p = 0; p < fractions.size(); ++p) {
      Layer l = s.layers[k];
      l.h *= fractions[p];
      if (p + 1 < fractions.size()) l.slip = false;
      out.layers.push_back(l);
    }
  }
  return out;
}

}  // namespace

int main() {
  Random rng;

  // ---- section 12 check "a direct global boundary-value solve agrees" -------------------
  // N = 1..5, thickness and modulus ratios to the top layer 1e-3..1e3, nu 0..0.499 and 0.5,
  // random bonded/frictionless interfaces, elastic or rigid (bonded or frictionless) base,
  // q 1e-3..1e3.
  {
    double max_rel = 0, max_rel_f = 0, max_rel_lapacke = 0, worst_ref = 0;
    int counted = 0, skipped = 0, lapacke_used = 0;
    for (int trial = 0; trial < 200; ++trial) {
      Stack st;
      const int nl = 1 + trial % 5;
      for (int i = 0; i < nl; ++i) {
        const double nu = rng.uniform() < 0.1 ? 0.5 : 0.499 * rng.uniform();
        const double h = i == 0 ? 1.0 : rng.log_uniform(1e-3, 1e3);
        const double e = i == 0 ? 1.0 : rng.log_uniform(1e-3, 1e3);
        st.layers.push_back({h, e, nu, rng.uniform() < 0.3});
      }
      st.rigid = rng.uniform() < 0.25;
      st.eb = rng.log_uniform(1e-3, 1e3);
      st.nub = rng.uniform() < 0.1 ? 0.5 : 0.499 * rng.uniform();
      for (int k = 0; k < 8; ++k) {
        const double q = rng.log_uniform(1e-3, 1e3);
        const double c = stack_c(st, q);
        double cancellation = 1, rcond = 0, ferr = 1;
        const Real ref = direct_long_double(st, q, &cancellation);
        const double lap = direct_lapacke(st, q, &rcond, &ferr);
        // The reference's own relative error: long double rounding times the condition
        // number (LAPACK's estimate for the same equilibrated system) times the cancellation.
        const double ref_error = 1.1e-19 * cancellation / std::max(rcond, 1e-300);
        if (ref_error > 0.1 * kDirectTier) {
          ++skipped;
          continue;
        }
        ++counted;
        worst_ref = std::max(worst_ref, ref_error);
        const double r = static_cast<double>(std::fabs((Real(c) - ref) / ref));
        max_rel = std::max(max_rel, r);
        check::that(r <= kDirectTier, measured("C vs direct global solve", r, kDirectTier));
        if (r > kDirectTier) {
          std::printf("  N=%d rigid=%d q=%g C=%.17g ref=%.17Lg\n", nl, st.rigid, q, c, ref);
          for (const Layer& l : st.layers)
            std::printf("    h=%g E=%g nu=%g slip=%d\n", l.h, l.e, l.nu, l.slip);
          std::printf("    base E=%g nu=%g\n", st.eb, st.nub);
        }
        const Real fref = ref - 1;
        if (std::fabs(fref) > 1e-6L) {
          const double rf =
              static_cast<double>(std::fabs((Real(stack_f(st, q)) - fref) / fref));
          max_rel_f = std::max(max_rel_f, rf);
          check::that(rf <= kDirectTier, measured("C-1 vs direct global solve", rf, kDirectTier));
        }
        if (ferr <= 1e-13) {
          ++lapacke_used;
          const double lr = rel(c, lap);
          max_rel_lapacke = std::max(max_rel_lapacke, lr);
          check::that(lr <= kDirectTier, measured("C vs LAPACKE global solve", lr, kDirectTier));
        }
      }
    }
    std::printf("C vs direct global solve: %d points (%d skipped: reference not reliable), max rel "
                "diff %.3g (long double, own error <= %.2g), %.3g (LAPACKE dgesvx, %d points); "
                "C-1 max rel diff %.3g\n",
                counted, skipped, max_rel, worst_ref, max_rel_lapacke, lapacke_used, max_rel_f);
    check::that(counted >= 1000, measured("enough reliable direct-solve points", counted, 1000));
  }

  // ---- section 12 check "N = 1 equals section 3" ----------------------------------------
  // One bonded layer is the closed form's own code path: equal bit for bit, C and C - 1.
  for (const Stack& st : {one_layer(1, 0.3, false, false, 10, 0.2), one_layer(1, 0.5, false, true, 1, 0),
                          one_layer(1e-4, 0.25, false, false, 1, 0.5), one_layer(2.5, 0.2, false, false, 2.5, 0.2),
                          one_layer(1e4, -0.5, false, false, 1, 0.45)}) {
    const Layer& l = st.layers[0];
    for (double q : {0.0, 1e-4, 0.03, 1.0, 7.0, 60.0, 1e3}) {
      double c1 = NAN, f1 = NAN;
      cc_compliance(l.e, l.nu, st.eb, st.nub, st.rigid, 1, &q, &c1);
      cc_compliance_minus_one(l.e, l.nu, st.eb, st.nub, st.rigid, 1, &q, &f1);
      check::that(stack_c(st, q) == c1 && stack_f(st, q) == f1, measured("N = 1 is the closed form", stack_c(st, q) - c1, 0));
    }
  }

  // ---- section 12 check "a layer split in two identical sublayers gives the same C" ------
  // Splitting one layer sends it through the recursion (thin and thick steps, both charts):
  // against the closed form for one layer, against the unsplit stack for random stacks.
  {
    double worst = 0, worst_f = 0;
    for (const Stack& st : {one_layer(1, 0.3, false, false, 10, 0.2), one_layer(1, 0.5, false, true, 1, 0),
                            one_layer(1, 0.45, false, false, 1e-3, 0.5), one_layer(1, 0.0, false, false, 1e3, 0.3),
                            one_layer(1, 0.5, false, false, 1e-4, 0.1), one_layer(1, 0.2, false, true, 1, 0)}) {
      for (const std::vector<double>& fr : {std::vector<double>{0.5, 0.5}, {0.1, 0.9}, {0.999, 0.001},
                                            {0.2, 0.3, 0.5}}) {
        const Stack sp = split(st, 0, fr);
        for (double q : {1e-3, 0.05, 0.7, 1.3, 3.0, 12.0, 45.0}) {
          const double c1 = stack_c(st, q), c2 = stack_c(sp, q);
          const double f1 = stack_f(st, q), f2 = stack_f(sp, q);
          const double r = rel(c2, c1);
          // C - 1: relative error ~ eps plus absolute ~ eps exp(-2 x_top) (the subspace under a
          // thick top sublayer is rounded at that level; here the interface under it reflects
          // nothing, so the true C - 1 decays faster than that floor)
          const double floor = std::exp(-2 * q * fr[0]);
          const double rf = std::fabs(f2 - f1) / (std::fabs(f1) + floor);
          worst = std::max(worst, r);
          worst_f = std::max(worst_f, rf);
          check::that(r <= kRecursionTier, measured("split layer: C", r, kRecursionTier));
          check::that(rf <= kRecursionTier, measured("split layer: C - 1", rf, kRecursionTier));
        }
      }
    }
    // random stacks with sliding interfaces: split a random layer
    for (int trial = 0; trial < 60; ++trial) {
      Stack st;
      const int nl = 1 + trial % 4;
      for (int i = 0; i < nl; ++i)
        st.layers.push_back({rng.log_uniform(1e-2, 1e2), rng.log_uniform(1e-3, 1e3),
                             rng.uniform() < 0.2 ? 0.5 : 0.499 * rng.uniform(), rng.uniform() < 0.4});
      st.rigid = rng.uniform() < 0.3;
      st.eb = rng.log_uniform(1e-3, 1e3);
      st.nub = 0.499 * rng.uniform();
      const std::size_t which = static_cast<std::size_t>(trial) % st.layers.size();
      const Stack sp = split(st, which, {0.3, 0.7});
      for (double q : {2e-3, 0.2, 2.0, 20.0, 200.0}) {
        const double r = rel(stack_c(sp, q), stack_c(st, q));
        worst = std::max(worst, r);
        check::that(r <= kRecursionTier, measured("split layer in a stack: C", r, kRecursionTier));
      }
    }
    std::printf("split layers: max rel diff C %.3g, C-1 %.3g\n", worst, worst_f);
  }

  // ---- section 12 checks "C(0)" and "C(inf)" ---------------------------------------------
  for (int trial = 0; trial < 40; ++trial) {
    Stack st;
    const int nl = 1 + trial % 5;
    for (int i = 0; i < nl; ++i)
      st.layers.push_back({rng.log_uniform(1e-3, 1e3), rng.log_uniform(1e-4, 1e4),
                           rng.uniform() < 0.2 ? 0.5 : -0.5 + rng.uniform(), rng.uniform() < 0.4});
    st.rigid = trial % 4 == 0;
    st.eb = rng.log_uniform(1e-4, 1e4);
    st.nub = 0.5 * rng.uniform();
    const Layer& top = st.layers[0];
    // C(0) = E_top*/E_base* for every slip pattern; 0 on a rigid base
    const double expect = st.rigid ? 0.0 : reduced(top.e, top.nu) / reduced(st.eb, st.nub);
    const double c0 = stack_c(st, 0.0);
    check::that(st.rigid ? c0 == 0 : rel(c0, expect) <= 1e-15, measured("C(0) = E_top*/E_base*", c0 - expect, 0));
    check::that(stack_f(st, 0.0) == c0 - 1, measured("C(0) - 1", stack_f(st, 0.0) - (c0 - 1), 0));
    double total = 0;
    for (const Layer& l : st.layers) total += l.h;
    // C - 1 decays like exp(-2 q h_top / T): C = 1 to rounding at 20 T/h_top, exactly beyond
    const double q40 = 40 * total / top.h;
    const double f40 = stack_f(st, q40), c40 = stack_c(st, q40);
    check::that(std::isfinite(f40) && std::fabs(f40) < 1e-25, measured("C(40 T/h_top) - 1 ~ exp(-80)", f40, 1e-25));
    check::that(std::fabs(c40 - 1) <= 2.3e-16, measured("C(40 T/h_top) = 1", c40 - 1, 2.3e-16));
    for (double q : {1e3 * total / top.h, 1e300}) {
      check::that(stack_c(st, q) == 1.0 && stack_f(st, q) == 0.0, measured("C(inf) = 1", stack_c(st, q) - 1, 0));
    }
    // the recursion at q -> 0 meets the exact value (C - C(0) = O(q) with coefficients up to
    // ~1e8 for these ratios, sliding plates bend)
    if (!st.rigid) {
      const double c_small = stack_c(st, 1e-16);
      check::that(rel(c_small, expect) <= 1e-7, measured("C(q -> 0) -> C(0)", rel(c_small, expect), 1e-7));
    }
  }

  // ---- tiny q: relative accuracy down to underflow (section 12 check "C(0)") -----------
  // On a rigid base C ~ q (q^3 when incompressible and bonded, q/2 sliding): against the
  // closed form through a split layer, and s(q) ~ q/2; finite for the smallest subnormal q.
  {
    for (double nu : {0.3, 0.5})
      for (double q : {1e-100, 1e-45, 1e-30, 1e-12}) {
        const Stack one = one_layer(1, nu, false, true, 1, 0);
        const Stack two = split(one, 0, {1e-6, 1 - 1e-6});
        const double r = rel(stack_c(two, q), stack_c(one, q));
        check::that(r <= kRecursionTier, measured("tiny q, rigid base: split = closed form", r, kRecursionTier));
      }
    for (double q : {1e-300, 1e-100, 1e-30}) {
      const double r = rel(stack_c(one_layer(2, 0.5, true, true, 1, 0), q), q / 2);
      check::that(r <= kRecursionTier, measured("tiny q, frictionless rigid base: C = q/2", r, kRecursionTier));
    }
    for (bool rigid : {false, true})
      for (int pattern = 0; pattern < 4; ++pattern) {
        Stack st;
        st.layers = {{1e-3, 1.0, 0.3, (pattern & 1) != 0}, {1.0, 1e-3, 0.5, (pattern & 2) != 0}};
        st.rigid = rigid;
        st.eb = 2;
        for (double q : {4.9e-324, 1e-310, 1e-200}) {
          const double c = stack_c(st, q), c0 = stack_c(st, 0.0);
          check::that(std::isfinite(c) && c >= 0 && (rigid || c == c0), measured("tiny q: finite, -> C(0)", c, 0));
        }
      }
  }

  // ---- C - 1 without cancellation at large q (thick top layer) ---------------------------
  // Against cancellation-free references down to C - 1 ~ 1e-170: a film on a substrate cut into
  // bonded layers (closed form's C - 1), one layer sliding on a half-space, one layer on a
  // frictionless rigid base (1 - s(q) = (1 + 2q - e^-2q)/(sinh 2q + 2q)).
  {
    double worst = 0;
    for (double nu : {0.0, 0.3, 0.5}) {
      Stack cut;
      cut.layers = {{0.4, 1.0, 0.3, false}, {0.6, 5.0, nu, false}, {2.0, 5.0, nu, false}};
      cut.eb = 5.0;
      cut.nub = nu;
      for (double q : {10.0, 60.0, 300.0, 1500.0}) {
        double ref = NAN, qf = q * 0.4 / 3.0;
        cc_compliance_minus_one(1.0, 0.3, 5.0, nu, 0, 1, &qf, &ref);
        const double r = rel(stack_f(cut, q), ref);
        worst = std::max(worst, r);
        check::that(r <= kRecursionTier, measured("C - 1 at large q: film on cut substrate", r, kRecursionTier));
      }
    }
    for (double q : {2.0, 20.0, 100.0, 280.0}) {
      const Stack slide = one_layer(0.2, 0.4, true, false, 1.0, 0.25);
      const Real rho = reduced(0.2, 0.4) / reduced(1.0, 0.25);
      const double r1 = rel(stack_f(slide, q), static_cast<double>(plate_on_half_space_minus_one(q, rho)));
      const Stack rigid = one_layer(3.0, 0.5, true, true, 1, 0);
      const Real z = 2 * Real(q);
      const Real one_minus_s = (1 + z - std::exp(-z)) / (std::sinh(z) + z);
      const double r2 = rel(stack_f(rigid, q), static_cast<double>(-one_minus_s));
      worst = std::max({worst, r1, r2});
      check::that(r1 <= kRecursionTier, measured("C - 1 at large q: sliding on a half-space", r1, kRecursionTier));
      check::that(r2 <= kRecursionTier, measured("C - 1 at large q: frictionless rigid base", r2, kRecursionTier));
    }
    std::printf("C-1 at large q (down to ~1e-170): max rel diff %.3g\n", worst);
  }

  // ---- section 12: "a bonded interface between identical materials is invisible" ---------
  {
    double worst = 0;
    for (double nu : {0.0, 0.3, 0.5}) {
      Stack st;
      st.layers = {{0.3, 2.0, nu, false}, {1.7, 2.0, nu, false}, {0.01, 2.0, nu, false}};
      st.eb = 2.0;
      st.nub = nu;
      for (double q : {0.0, 1e-3, 0.1, 1.0, 3.0, 10.0, 100.0}) {
        const double d = std::fabs(stack_c(st, q) - 1) + std::fabs(stack_f(st, q));
        worst = std::max(worst, d);
        check::that(d <= 1e-14, measured("bonded identical layers: C = 1", d, 1e-14));
      }
      // a film of material X on a half-space of Y equals the one-layer closed form, however the
      // Y below the film is cut into bonded layers (q rescaled: T -> h_film)
      Stack cut;
      cut.layers = {{0.4, 1.0, 0.3, false}, {0.6, 5.0, nu, false}, {2.0, 5.0, nu, false}};
      cut.eb = 5.0;
      cut.nub = nu;
      for (double q : {1e-3, 0.1, 1.0, 3.0, 10.0, 100.0}) {
        double ref = NAN, qf = q * 0.4 / 3.0;
        cc_compliance(1.0, 0.3, 5.0, nu, 0, 1, &qf, &ref);
        const double r = rel(stack_c(cut, q), ref);
        worst = std::max(worst, r);
        check::that(r <= kRecursionTier, measured("film on layers of the substrate = closed form", r, kRecursionTier));
      }
    }
    std::printf("identical bonded materials: max deviation %.3g\n", worst);
  }

  // ---- section 12 exact free-plate results ---------------------------------------------
  {
    double worst = 0;
    // one layer on a frictionless rigid base: C = s(q), any nu (even 1/2)
    for (double nu : {-0.5, 0.0, 0.3, 0.499, 0.5})
      for (double q : {1e-6, 1e-3, 0.05, 0.5, 1.0, 2.0, 8.0, 30.0, 200.0}) {
        const Stack st = one_layer(3.0, nu, true, true, 1, 0);
        const double ref = static_cast<double>(plate_s_of_q(q));
        const double r = rel(stack_c(st, q), ref);
        worst = std::max(worst, r);
        check::that(r <= kRecursionTier, measured("sliding on a rigid base: C = s(q)", r, kRecursionTier));
      }
    // one layer sliding on a half-space: C = (rho(s + a) + 2as)/(2 rho + s + a), s, a at q/2
    for (double ratio : {1e-3, 0.1, 1.0, 10.0, 1e3})
      for (double nu : {0.0, 0.3, 0.5})
        for (double q : {1e-4, 1e-2, 0.3, 1.0, 4.0, 25.0, 200.0}) {
          const Stack st = one_layer(ratio, nu, true, false, 1.0, 0.25);
          const Real rho = reduced(ratio, nu) / reduced(1.0, 0.25);
          const Real ref = plate_on_half_space(q, rho);
          const double r = rel(stack_c(st, q), static_cast<double>(ref));
          worst = std::max(worst, r);
          check::that(r <= kRecursionTier, measured("sliding on a half-space: closed form", r, kRecursionTier));
          // C - 1 against the same formula, relative where the top is thick
          if (q >= 1) {
            const double rf =
                rel(stack_f(st, q), static_cast<double>(plate_on_half_space_minus_one(q, rho)));
            check::that(rf <= kRecursionTier, measured("sliding on a half-space: C - 1", rf, kRecursionTier));
          }
        }
    // "a sliding interface is never invisible": identical materials, C - 1 ~ 0.31 near q = 1
    {
      const Stack st = one_layer(1.0, 0.3, true, false, 1.0, 0.3);
      const double f1 = stack_f(st, 1.0);
      check::that(f1 > 0.30 && f1 < 0.32, measured("identical materials sliding: C(1) - 1 ~ 0.31", f1, 0.31));
      for (double q : {1e-3, 0.1, 1.0, 10.0, 50.0})
        check::that(stack_f(st, q) > 0, measured("identical materials sliding: C > 1", stack_f(st, q), 0));
      std::printf("identical materials sliding: C(1) - 1 = %.6f\n", f1);
    }
    // a layer with two shear-free faces, and a half-space under a sliding interface, enter C
    // only through E*: change nu at fixed E*
    for (double q : {1e-3, 0.1, 1.0, 5.0, 40.0}) {
      auto with = [&](double nu_mid, double nu_base) {
        Stack st;
        const double es_mid = 0.2, es_base = 30.0;
        st.layers = {{1.0, 1.0, 0.35, true}, {0.5, es_mid * (1 - nu_mid * nu_mid), nu_mid, true},
                     {0.8, 4.0, 0.2, true}};
        st.eb = es_base * (1 - nu_base * nu_base);
        st.nub = nu_base;
        return stack_c(st, q);
      };
      const double ref = with(0.1, 0.1);
      for (double nu_mid : {-0.5, 0.3, 0.5})
        for (double nu_base : {0.0, 0.5}) {
          const double r = rel(with(nu_mid, nu_base), ref);
          worst = std::max(worst, r);
          check::that(r <= kRecursionTier, measured("shear-free faces: only E* enters", r, kRecursionTier));
        }
    }
    std::printf("free-plate results: max rel diff %.3g\n", worst);
  }

  // ---- nu = 0.5 is regular (section 12: A has no 1/(1 - 2 nu)) --------------------------
  for (double q : {1e-3, 0.1, 1.0, 10.0}) {
    for (bool rigid : {false, true}) {
      Stack at, near;
      at.layers = {{1.0, 1.0, 0.5, false}, {0.05, 1e-3, 0.5, true}, {2.0, 30.0, 0.5, false}};
      at.rigid = rigid;
      at.eb = 100;
      at.nub = 0.5;
      near = at;
      for (Layer& l : near.layers) l.nu = 0.5 - 1e-8;
      near.nub = 0.5 - 1e-8;
      const double a = stack_c(at, q), b = stack_c(near, q);
      // |dC/dnu| is O(1/C0) at worst: 1e-8 in nu moves C by far less than 1e-5 relative
      check::that(std::isfinite(a) && rel(b, a) <= 1e-5, measured("nu = 0.5 continuity", rel(b, a), 1e-5));
    }
  }

  // ---- long stacks and extreme ratios (1e-4..1e4) ----------------------------------------
  {
    // 20 and 1000 identical bonded sublayers = one layer (closed form)
    for (int parts : {20, 1000}) {
      const Stack one = one_layer(1, 0.45, false, false, 1e-2, 0.3);
      const Stack many = split(one, 0, std::vector<double>(static_cast<std::size_t>(parts), 1.0 / parts));
      double worst = 0;
      for (double q : {1e-3, 0.3, 3.0, 30.0, 300.0}) worst = std::max(worst, rel(stack_c(many, q), stack_c(one, q)));
      const double tier = parts > 20 ? kLongStackTier : kRecursionTier;
      check::that(worst <= tier, measured("N identical sublayers = one layer", worst, tier));
      std::printf("%d sublayers vs closed form: max rel diff %.3g\n", parts, worst);
    }
    // extreme ratios: against the direct solve where it is reliable, and finite everywhere
    double worst = 0;
    int counted = 0;
    for (int trial = 0; trial < 60; ++trial) {
      Stack st;
      const int nl = 2 + trial % 4;
      for (int i = 0; i < nl; ++i)
        st.layers.push_back({i == 0 ? 1.0 : (rng.uniform() < 0.5 ? 1e-4 : 1e4),
                             i == 0 ? 1.0 : (rng.uniform() < 0.5 ? 1e-4 : 1e4),
                             rng.uniform() < 0.5 ? 0.5 : 0.3, rng.uniform() < 0.3});
      st.rigid = trial % 3 == 0;
      st.eb = rng.uniform() < 0.5 ? 1e-4 : 1e4;
      st.nub = 0.5;
      for (double q : {1e-4, 1e-2, 1.0, 1e2, 1e4, 1e6}) {
        const double c = stack_c(st, q), f = stack_f(st, q);
        check::that(std::isfinite(c) && std::isfinite(f) && c >= 0, measured("extreme ratios: finite C >= 0", c, 0));
        double cancellation = 1, rcond = 0, ferr = 1;
        if (q > 1e3) continue;
        const Real ref = direct_long_double(st, q, &cancellation);
        direct_lapacke(st, q, &rcond, &ferr);
        if (1.1e-19 * cancellation / std::max(rcond, 1e-300) > 0.1 * kDirectTier) continue;
        ++counted;
        const double r = static_cast<double>(std::fabs((Real(c) - ref) / ref));
        worst = std::max(worst, r);
        check::that(r <= kDirectTier, measured("extreme ratios vs direct solve", r, kDirectTier));
      }
    }
    std::printf("ratios 1e-4..1e4: %d points against the direct solve, max rel diff %.3g\n", counted,
                worst);
  }

  // ---- status codes at the library boundary ----------------------------------------------
  {
    double q = 1.0, c = 0;
    const double h[] = {1, 2}, e[] = {1, 3}, nu[] = {0.3, 0.2};
    const int slip[] = {0, 1};
    auto status = [&](int n, const double* hh, const double* ee, const double* nn, int rigid,
                      double eb, double nub) {
      return cc_stack_compliance(n, hh, ee, nn, slip, rigid, eb, nub, 1, &q, &c);
    };
    const double zero_h[] = {1, 0}, neg_h[] = {-1, 1}, nan_h[] = {1, NAN}, inf_h[] = {INFINITY, 1};
    check::that(status(2, h, e, nu, 0, 1, 0.3) == CC_OK, measured("status ok", 0, 0));
    check::that(status(2, zero_h, e, nu, 0, 1, 0.3) == CC_ERR_THICKNESS, measured("status h = 0", 0, 0));
    check::that(status(2, neg_h, e, nu, 0, 1, 0.3) == CC_ERR_THICKNESS, measured("status h < 0", 0, 0));
    check::that(status(2, nan_h, e, nu, 0, 1, 0.3) == CC_ERR_THICKNESS, measured("status h NaN", 0, 0));
    check::that(status(2, inf_h, e, nu, 0, 1, 0.3) == CC_ERR_THICKNESS, measured("status h inf", 0, 0));
    const double zero_e[] = {1, 0}, neg_e[] = {-2, 1};
    check::that(status(2, h, zero_e, nu, 0, 1, 0.3) == CC_ERR_FILM_MODULUS, measured("status E = 0", 0, 0));
    check::that(status(2, h, neg_e, nu, 1, 1, 0.3) == CC_ERR_FILM_MODULUS, measured("status E < 0", 0, 0));
    for (double bad : {0.51, -1.0, -1.5, double(NAN)}) {
      const double bad_nu[] = {0.3, bad};
      check::that(status(2, h, e, bad_nu, 0, 1, 0.3) == CC_ERR_FILM_POISSON, measured("status layer nu", bad, 0));
    }
    check::that(status(2, h, e, nu, 0, 0, 0.3) == CC_ERR_SUBSTRATE_MODULUS, measured("status base E", 0, 0));
    check::that(status(2, h, e, nu, 0, 1, 0.6) == CC_ERR_SUBSTRATE_POISSON, measured("status base nu", 0, 0));
    check::that(status(2, h, e, nu, 1, -5, 7) == CC_OK, measured("rigid ignores the base constants", 0, 0));
    check::that(status(0, h, e, nu, 0, 1, 0.3) == CC_ERR_LAYER_COUNT, measured("status 0 layers", 0, 0));
    check::that(status(-3, h, e, nu, 0, 1, 0.3) == CC_ERR_LAYER_COUNT, measured("status < 0 layers", 0, 0));
    {
      const std::vector<double> hh(1001, 1.0), ee(1001, 1.0), nn(1001, 0.3);
      const std::vector<int> ss(1001, 0);
      check::that(cc_stack_compliance(1001, hh.data(), ee.data(), nn.data(), ss.data(), 0, 1, 0.3, 1, &q,
                                &c) == CC_ERR_LAYER_COUNT, measured("status 1001 layers", 0, 0));
      check::that(cc_stack_compliance_minus_one(1000, hh.data(), ee.data(), nn.data(), ss.data(), 0, 1,
                                          0.3, 1, &q, &c) == CC_OK, measured("1000 layers accepted", 0, 0));
    }
    for (double bq : {-1.0, double(NAN), double(INFINITY)})
      check::that(cc_stack_compliance(2, h, e, nu, slip, 0, 1, 0.3, 1, &bq, &c) == CC_ERR_ARGUMENT, measured("status bad q", bq, 0));
    check::that(cc_stack_compliance(2, h, e, nu, slip, 0, 1, 0.3, -1, &q, &c) == CC_ERR_ARGUMENT, measured("status n < 0", 0, 0));
    check::that(cc_stack_compliance(2, h, e, nu, slip, 0, 1, 0.3, 0, nullptr, nullptr) == CC_OK, measured("empty q array", 0, 0));
    // every slip pattern on a rigid base is supported (cc_kernel.h): finite, positive C
    for (int pattern = 0; pattern < 4; ++pattern) {
      const int sl[] = {pattern & 1, (pattern >> 1) & 1};
      for (double qq : {1e-3, 1.0, 30.0}) {
        double cc = NAN;
        const int st = cc_stack_compliance(2, h, e, nu, sl, 1, 0, 0, 1, &qq, &cc);
        check::that(st == CC_OK && std::isfinite(cc) && cc > 0, measured("any slip pattern on a rigid base", cc, 0));
      }
    }
    check::that(std::string(cc_status_message(CC_ERR_THICKNESS)).find("thickness") != std::string::npos &&
              std::string(cc_status_message(CC_ERR_LAYER_COUNT)).find("layers") != std::string::npos &&
              std::string(cc_status_message(11)).find("unknown") != std::string::npos, measured("status messages", 0, 0));
  }

  // ---- cost: C on 2^15 q points (informative, not checked) -------------------------------
  {
    const int n = 1 << 15;
    for (int nl : {1, 3, 20}) {
      Stack st;
      for (int i = 0; i < nl; ++i)
        st.layers.push_back({i == 0 ? 1.0 : 0.5 + 0.1 * i, 1.0 + i, 0.3 + 0.01 * (i % 10), false});
      st.eb = 0.5;
      st.nub = 0.25;
      double total = 0;
      for (const Layer& l : st.layers) total += l.h;
      std::vector<double> qs(n), out(n), hh, ee, nn;
      std::vector<int> ss;
      for (int i = 0; i < n; ++i) qs[i] = (i + 0.5) * 40 * total / st.layers[0].h / n;
      for (const Layer& l : st.layers) hh.push_back(l.h), ee.push_back(l.e), nn.push_back(l.nu), ss.push_back(0);
      double best = 1e30;
      for (int rep = 0; rep < 3; ++rep) {
        // process CPU time: the cores are shared, wall time measures the neighbours
        const std::clock_t t0 = std::clock();
        cc_stack_compliance_minus_one(nl, hh.data(), ee.data(), nn.data(), ss.data(), 0, st.eb, st.nub,
                                      n, qs.data(), out.data());
        best = std::min(best, static_cast<double>(std::clock() - t0) / CLOCKS_PER_SEC);
      }
      std::printf("cost: N = %2d, 2^15 q points in [0, 40 T/h_top]: %.2f ms CPU (%.0f ns per q)\n", nl,
                  1e3 * best, 1e9 * best / n);
    }
  }

  return check::exit_code();
}
