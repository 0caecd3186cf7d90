// Surface compliance C(q) of the coated half-space (THEORY.md section 3) against an
// independent direct solve of the Hankel-space boundary-value problem, and its limits.
// THEORY.md section 6 checks made here: the kernel facts of section 3 that every later check
// relies on (C(0) = E1*/E0*, C -> 1, C = 1 for identical materials, rigid substrate limit).
//
// The direct solve: Navier solution in the film, in s = k z (z into the solid, surface at
// s = 0, interface at s = q), with two families
//   e^{-s}:  U = (a + b s) e^{-s},  W = (a + g b + b s) e^{-s},
//            Szz/mu = -2 (a + 2(1-nu) b + b s) e^{-s},  Srz/mu = -2 (a + (1-2nu) b + b s) e^{-s}
//   e^{+s}:  the mirror image (U(-s), -W(-s)), written around the interface (e^{s-q}) so that
//            no coefficient exceeds 1 (the e^{-q}-factored form of the issue),
// and the decaying family in the substrate (2 constants): 6 unknowns, 6 equations
// (Szz = -1, Srz = 0 on top; U, W, Szz, Srz continuous at s = q). With mu1 = 1 and p = 1,
// C = W(0) / (1 - nu1). Derived independently of the closed form of C (none of A, B, x
// appear). Solved twice: LAPACKE_dgesvx (equilibration + iterative refinement, with its own
// forward-error bound) and a hand-written long double Gaussian elimination with partial
// pivoting (64-bit mantissa), the reference where the double solve is not accurate enough.
#include <lapacke.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "check.hpp"
#include "coatcontact/cc_kernel.h"

namespace {

namespace tier = check::tier;
// Limits that hold to rounding: tier::kMachine. C against the direct 6x6 solve: the issue's
// requirement, tier::kReference.
constexpr double kDirectTier = tier::kReference;
// Rigid vs E0 = 1e12 E1 differs physically by O(1e-12) relative.
constexpr double kLimitTier = 1e-10;

struct Pair {
  double e1, nu1, e0, nu0;
  bool rigid;
};

using Real = long double;

// Builds the 6x6 (or 4x4 for a rigid substrate) system in type T. Unknown order:
// a1, b1 (e^{-s}), a2, b2 (e^{s-q}), a0, b0 (substrate).
template <typename T>
int build_system(const Pair& p, T q, std::array<T, 36>& m, std::array<T, 6>& rhs) {
  const T nu1 = p.nu1, nu0 = p.nu0;
  const T mu1 = 1;
  // mu0 = mu1 / alpha, alpha = (E1/E0)(1+nu0)/(1+nu1)
  const T mu0 = p.rigid ? T(0) : (T(p.e0) / T(p.e1)) * ((1 + nu1) / (1 + nu0));
  const T g1 = 3 - 4 * nu1, g0 = 3 - 4 * nu0;
  const T e = std::exp(-q);
  const int n = p.rigid ? 4 : 6;
  m.fill(0);
  rhs.fill(0);
  auto at = [&](int r, int c) -> T& { return m[static_cast<std::size_t>(r * n + c)]; };
  // top: Szz = -1
  at(0, 0) = -2;
  at(0, 1) = -2 * 2 * (1 - nu1);
  at(0, 2) = -2 * e;
  at(0, 3) = -2 * e * (2 * (1 - nu1) + q);
  rhs[0] = -1;
  // top: Srz = 0
  at(1, 0) = -2;
  at(1, 1) = -2 * (1 - 2 * nu1);
  at(1, 2) = 2 * e;
  at(1, 3) = 2 * e * ((1 - 2 * nu1) + q);
  // interface: U
  at(2, 0) = e;
  at(2, 1) = e * q;
  at(2, 2) = 1;
  // interface: W
  at(3, 0) = e;
  at(3, 1) = e * (g1 + q);
  at(3, 2) = -1;
  at(3, 3) = -g1;
  if (p.rigid) return n;  // U = W = 0 at a rigid interface
  at(2, 4) = -1;
  at(3, 4) = -1;
  at(3, 5) = -g0;
  // interface: Szz (film) = Szz (substrate)
  at(4, 0) = -2 * mu1 * e;
  at(4, 1) = -2 * mu1 * e * (2 * (1 - nu1) + q);
  at(4, 2) = -2 * mu1;
  at(4, 3) = -2 * mu1 * 2 * (1 - nu1);
  at(4, 4) = 2 * mu0;
  at(4, 5) = 2 * mu0 * 2 * (1 - nu0);
  // interface: Srz
  at(5, 0) = -2 * mu1 * e;
  at(5, 1) = -2 * mu1 * e * ((1 - 2 * nu1) + q);
  at(5, 2) = 2 * mu1;
  at(5, 3) = 2 * mu1 * (1 - 2 * nu1);
  at(5, 4) = 2 * mu0;
  at(5, 5) = 2 * mu0 * (1 - 2 * nu0);
  return n;
}

// C = W(0)/(1 - nu1). `cancellation` = (sum of |terms|)/|W(0)|: how much the solution's
// relative error is amplified in C (large for the incompressible film on a rigid substrate at
// small q, where C ~ q^3 comes out of O(1) terms).
template <typename T>
T compliance_from_solution(const Pair& p, T q, const T* x, double* cancellation = nullptr) {
  const T g1 = 3 - 4 * T(p.nu1);
  const T e = std::exp(-q);
  const T w0 = (x[0] + g1 * x[1]) - (x[2] + g1 * x[3] + x[3] * q) * e;
  if (cancellation) {
    const T size = std::fabs(x[0]) + std::fabs(g1 * x[1]) +
                   (std::fabs(x[2]) + std::fabs(g1 * x[3]) + std::fabs(x[3] * q)) * e;
    *cancellation = static_cast<double>(size / std::fabs(w0));
  }
  return w0 / (1 - T(p.nu1));
}

// Long double Gaussian elimination with partial pivoting.
Real direct_long_double(const Pair& p, double q_in, double* cancellation = nullptr) {
  std::array<Real, 36> m;
  std::array<Real, 6> b;
  const Real q = q_in;
  const int n = build_system<Real>(p, q, m, b);
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
      for (int c = k; c < n; ++c) at(r, c) -= factor * at(k, c);
      b[r] -= factor * b[k];
    }
  }
  std::array<Real, 6> x{};
  for (int k = n - 1; k >= 0; --k) {
    Real s = b[k];
    for (int c = k + 1; c < n; ++c) s -= at(k, c) * x[c];
    x[k] = s / at(k, k);
  }
  return compliance_from_solution<Real>(p, q, x.data(), cancellation);
}

// LAPACKE_dgesvx with equilibration and refinement; `forward_error` is its bound on the
// relative error of the solution vector.
double direct_lapacke(const Pair& p, double q, double* forward_error) {
  std::array<double, 36> m;
  std::array<double, 6> b;
  const lapack_int n = build_system<double>(p, q, m, b);
  std::vector<double> af(static_cast<std::size_t>(n * n)), r(n), c(n), x(n);
  std::vector<lapack_int> ipiv(n);
  char equed = 'N';
  double rcond = 0, ferr = 0, berr = 0, rpivot = 0;
  const lapack_int info = LAPACKE_dgesvx(LAPACK_ROW_MAJOR, 'E', 'N', n, 1, m.data(), n, af.data(),
                                         n, ipiv.data(), &equed, r.data(), c.data(), b.data(), 1,
                                         x.data(), 1, &rcond, &ferr, &berr, &rpivot);
  double cancellation = 1;
  const double c_value = compliance_from_solution<double>(p, q, x.data(), &cancellation);
  *forward_error = (info == 0) ? ferr * cancellation : 1.0;
  return c_value;
}

double library_c(const Pair& p, double q) {
  double c = NAN;
  const int status = cc_compliance(p.e1, p.nu1, p.e0, p.nu0, p.rigid ? 1 : 0, 1, &q, &c);
  check::that(status == CC_OK, "cc_compliance status " + std::to_string(status));
  return c;
}

double library_f(const Pair& p, double q) {
  double f = NAN;
  cc_compliance_minus_one(p.e1, p.nu1, p.e0, p.nu0, p.rigid ? 1 : 0, 1, &q, &f);
  return f;
}

double reduced(double e, double nu) { return e / (1 - nu * nu); }

// Deterministic pseudo-random numbers (xorshift), so failures are reproducible.
struct Random {
  std::uint64_t state = 0x9E3779B97F4A7C15ull;
  double uniform() {
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    return static_cast<double>(state >> 11) * (1.0 / 9007199254740992.0);
  }
};

}  // namespace

int main() {
  // ---- C(q) against the direct solve: 240 random points + the corners ----------------
  Random rng;
  double max_rel_ld = 0, max_rel_lapacke = 0, max_f_rel = 0;
  int lapacke_used = 0;
  std::vector<Pair> pairs;
  std::vector<double> qs;
  for (int i = 0; i < 240; ++i) {
    const double ratio = std::pow(10.0, -3 + 6 * rng.uniform());
    const double nu1 = 0.499 * rng.uniform(), nu0 = 0.499 * rng.uniform();
    pairs.push_back({ratio, nu1, 1.0, nu0, false});
    qs.push_back(std::pow(10.0, -3 + std::log10(30.0 / 1e-3) * rng.uniform()));
  }
  for (double ratio : {1e-3, 1e3})
    for (double nu : {0.0, 0.499})
      for (double q : {1e-3, 30.0}) {
        pairs.push_back({ratio, nu, 1.0, 0.499 - nu, false});
        qs.push_back(q);
      }
  // rigid substrates and the incompressible limit (direct solve has no 1/(1-2nu))
  for (double nu : {0.0, 0.25, 0.45, 0.499, 0.5})
    for (double q : {1e-3, 1e-2, 0.3, 3.0, 30.0}) {
      pairs.push_back({1.0, nu, 1.0, 0.3, true});
      qs.push_back(q);
      pairs.push_back({0.02, nu, 1.0, 0.5, false});
      qs.push_back(q);
    }
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const Pair& p = pairs[i];
    const double q = qs[i];
    const double c = library_c(p, q);
    double cancellation = 1;
    const Real ref = direct_long_double(p, q, &cancellation);
    const double rel = static_cast<double>(std::fabs((Real(c) - ref) / ref));
    // The reference's own error: long double rounding (~1e-19, times a modest condition
    // number) amplified by the cancellation in W(0); only the rigid nu1 -> 1/2 points at
    // q <= 1e-2 have cancellation > 1e4 (there the closed form below is the reference).
    const double ref_error = 1e-17 * cancellation;
    if (ref_error <= 0.1 * kDirectTier) max_rel_ld = std::max(max_rel_ld, rel);
    check::below(rel, kDirectTier + ref_error, "C vs long double 6x6 solve");
    if (rel > kDirectTier + ref_error)
      std::printf("  at E1/E0=%g nu1=%g nu0=%g rigid=%d q=%g: C=%.17g ref=%.17Lg\n", p.e1 / p.e0,
                  p.nu1, p.nu0, p.rigid, q, c, ref);
    // C - 1 relative to |C - 1| (the reference's own precision is ~1e-18/|C-1|)
    const Real fref = ref - 1;
    if (std::fabs(fref) > 1e-6L) {
      const double frel = static_cast<double>(std::fabs((Real(library_f(p, q)) - fref) / fref));
      max_f_rel = std::max(max_f_rel, frel);
      check::below(frel, kDirectTier, "C-1 vs long double 6x6 solve");
    }
    double ferr = 1;
    const double lap = direct_lapacke(p, q, &ferr);
    // LAPACKE's own bound ferr is on the solution vector (returned here times the
    // cancellation in W(0)); compare only where that bound is far below the tier.
    if (ferr <= 1e-13) {
      ++lapacke_used;
      const double lrel = std::fabs((c - lap) / lap);
      max_rel_lapacke = std::max(max_rel_lapacke, lrel);
      check::below(lrel, kDirectTier, "C vs LAPACKE 6x6 solve");
    }
  }
  std::printf("C vs direct solve: %zu points, max rel diff %.3g (long double GE), %.3g (LAPACKE "
              "dgesvx, %d points with ferr <= 1e-13); C-1 max rel diff %.3g\n",
              pairs.size(), max_rel_ld, max_rel_lapacke, lapacke_used, max_f_rel);

  // ---- incompressible film on a rigid substrate: C ~ q^3, no cancellation ------------
  // Reference: the bonded incompressible layer on a rigid base,
  //   C = (sinh 2q - 2q) / (2 (cosh^2 q + q^2)),
  // evaluated in long double with the series of sinh z - z (no cancellation), where the
  // direct solve loses digits (see above); cross-checked against the solve at q >= 0.1.
  {
    const Pair p{1.0, 0.5, 1.0, 0.0, true};
    auto closed = [](Real q) {
      const Real z = 2 * q;
      Real term = z * z * z / 6, sum = term;
      for (int k = 2; k < 40; ++k) {
        term *= z * z / ((2 * k) * (2 * k + 1));
        sum += term;
      }
      const Real ch = std::cosh(q);
      return sum / (2 * (ch * ch + q * q));
    };
    for (double q : {1e-4, 1e-3, 1e-2, 0.1, 1.0, 3.0}) {
      const double c = library_c(p, q);
      const double ref = static_cast<double>(closed(q));
      check::close(c, ref, kDirectTier, "rigid nu=0.5 closed form");
      if (q >= 0.1) {
        const double solve = static_cast<double>(direct_long_double(p, q));
        check::close(solve, ref, kDirectTier, "closed form vs solve");
      }
    }
  }

  // ---- nu = 0.5 as a limit ----------------------------------------------------------
  for (double q : {1e-3, 0.1, 1.0, 10.0}) {
    for (bool rigid : {false, true}) {
      const Pair at{3.0, 0.5, 1.0, 0.5, rigid};
      const Pair near{3.0, 0.5 - 1e-7, 1.0, 0.5 - 1e-7, rigid};
      const double a = library_c(at, q), b = library_c(near, q);
      // C is smooth in nu up to 1/2 with |dC/dnu| = O(1) (rigid, small q: ~4q): a change
      // of 1e-7 in nu moves C by far less than 1e-6.
      check::below(std::fabs(a - b), 1e-6, "nu=0.5 continuity");
    }
  }

  // ---- limits: C(0) = E1*/E0*, C(inf) = 1, homogeneous, rigid = stiff limit ----------
  for (const Pair& p : {Pair{0.1, 0.25, 1, 0.25, false}, Pair{10, 0.25, 1, 0.25, false},
                        Pair{1e-4, 0.3, 1, 0.1, false}, Pair{1e4, 0.5, 1, 0.5, false},
                        Pair{2, -0.5, 1, 0.4, false}}) {
    const double c0 = library_c(p, 0.0);
    const double expect = reduced(p.e1, p.nu1) / reduced(p.e0, p.nu0);
    check::close(c0, expect, tier::kMachine, "C(0) = E1*/E0*");
    for (double q : {60.0, 400.0, 1e3, 1e6}) {
      const double c = library_c(p, q);
      check::that(c == 1.0, "C(inf) = 1 exactly");
    }
  }
  {
    const Pair rigid{1.0, 0.3, 1.0, 0.3, true};
    check::that(library_c(rigid, 0.0) == 0.0, "rigid C(0) = 0");
    for (double q : {1e-3, 0.1, 1.0, 5.0}) {
      const double c = library_c(rigid, q);
      const double limit = library_c(Pair{1.0, 0.3, 1e12, 0.3, false}, q);
      // the physical difference is O(E1*/E0*) = O(1e-12) absolute
      check::below(std::fabs(c - limit), kLimitTier * c + 1e-11, "rigid = E0 -> inf limit");
    }
    for (double q : {0.0, 1e-3, 1.0, 20.0}) {
      const double c = library_c(Pair{2.5, 0.2, 2.5, 0.2, false}, q);
      const double f = library_f(Pair{2.5, 0.2, 2.5, 0.2, false}, q);
      check::that(c == 1.0 && f == 0.0, "homogeneous C = 1");
    }
  }

  // ---- Taylor coefficients: the series sums to C - 1 well inside its radius ----------
  for (const Pair& p : {Pair{0.1, 0.25, 1, 0.25, false}, Pair{10, 0.25, 1, 0.25, false},
                        Pair{1, 0.5, 1, 0, true}, Pair{1, 0.3, 1, 0.2, false}}) {
    double f[16];
    cc_compliance_taylor(p.e1, p.nu1, p.e0, p.nu0, p.rigid, 15, f);
    for (double q : {1e-3, 3e-3}) {
      double s = 0;
      for (int k = 15; k >= 0; --k) s = s * q + f[k];
      const double ref = library_f(p, q);
      check::close(s, ref, tier::kMachine, "Taylor series sum", 1.0);
    }
  }

  // ---- status codes at the library boundary ------------------------------------------
  {
    double q = 1.0, c = 0;
    const double bad_q[] = {-1.0, NAN, INFINITY};
    check::that(cc_compliance(-1, 0.3, 1, 0.3, 0, 1, &q, &c) == CC_ERR_FILM_MODULUS, "status E1<0");
    check::that(cc_compliance(NAN, 0.3, 1, 0.3, 0, 1, &q, &c) == CC_ERR_FILM_MODULUS, "status E1 NaN");
    check::that(cc_compliance(1, 0.6, 1, 0.3, 0, 1, &q, &c) == CC_ERR_FILM_POISSON, "status nu1=0.6");
    check::that(cc_compliance(1, -1, 1, 0.3, 0, 1, &q, &c) == CC_ERR_FILM_POISSON, "status nu1=-1");
    check::that(cc_compliance(1, 0.3, 0, 0.3, 0, 1, &q, &c) == CC_ERR_SUBSTRATE_MODULUS, "status E0=0");
    check::that(cc_compliance(1, 0.3, INFINITY, 0.3, 0, 1, &q, &c) == CC_ERR_SUBSTRATE_MODULUS,
                "status E0=inf");
    check::that(cc_compliance(1, 0.3, 1, 0.51, 0, 1, &q, &c) == CC_ERR_SUBSTRATE_POISSON, "status nu0");
    check::that(cc_compliance(1, 0.3, -5, 2.0, 1, 1, &q, &c) == CC_OK, "rigid ignores E0, nu0");
    for (double bq : bad_q)
      check::that(cc_compliance(1, 0.3, 1, 0.3, 0, 1, &bq, &c) == CC_ERR_ARGUMENT, "status bad q");
    check::that(cc_compliance(1, 0.3, 1, 0.3, 0, -1, &q, &c) == CC_ERR_ARGUMENT, "status n<0");
    // Arrays are explicit-size (cc_kernel.h): valid pointers are required only for n > 0.
    check::that(cc_compliance(1, 0.3, 1, 0.3, 0, 0, nullptr, nullptr) == CC_OK, "empty arrays");
    double f[17];
    check::that(cc_compliance_taylor(1, 0.3, 2, 0.3, 0, 16, f) == CC_ERR_ARGUMENT, "status order");
    check::that(cc_status_message(3) != nullptr && cc_status_message(99) != nullptr, "messages");
  }

  // ---- one status vocabulary (cc_status.h): every detail code has a class and a message of
  // its own, distinct from the classes' codes 2, 3, 4 ----------------------------------------
  {
    const int input_details[] = {CC_ERR_FILM_MODULUS, CC_ERR_FILM_POISSON, CC_ERR_SUBSTRATE_MODULUS,
                                 CC_ERR_SUBSTRATE_POISSON, CC_ERR_ARGUMENT, CC_ERR_THICKNESS,
                                 CC_ERR_LAYER_COUNT};
    for (int code : input_details) {
      check::that(cc_status_class(code) == CC_INPUT_ERROR, "input detail class");
      check::that(code != CC_INPUT_ERROR && code != CC_NUMERICAL_ERROR && code != CC_INTERNAL_ERROR,
                  "detail codes distinct from the classes");
    }
    check::that(cc_status_class(CC_ERR_ACCURACY) == CC_NUMERICAL_ERROR, "accuracy class");
    check::that(cc_status_class(CC_ERR_FFT) == CC_INTERNAL_ERROR, "FFT class");
    check::that(cc_status_class(CC_ERR_ALLOCATION) == CC_INTERNAL_ERROR, "allocation class");
    check::that(cc_status_class(CC_OK) == CC_OK, "success class");
    check::that(cc_status_class(CC_INTERRUPTED) == CC_INTERRUPTED, "interrupted class");
    check::that(cc_status_class(12345) == CC_INTERNAL_ERROR, "unknown code class");
    const std::string unknown = cc_status_message(12345);
    for (int code : {CC_OK, CC_INPUT_ERROR, CC_NUMERICAL_ERROR, CC_INTERNAL_ERROR, CC_INTERRUPTED, CC_ERR_FFT,
                     CC_ERR_ACCURACY, CC_ERR_LAYER_COUNT})
      check::that(std::string(cc_status_message(code)) != unknown, "every code has its message");
  }

  return check::exit_code();
}
