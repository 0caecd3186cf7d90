// C++ view of the layered-substrate kernel (THEORY.md sections 3-4, 12 for stacks: q = k T and
// u = r/T with T the total thickness, C normalized by the top layer's E*): surface compliance C(q),
// and the table of H(u) = int_0^inf [C(q)-1] cos(qu) dq and H1(u) = int_0^u H for one
// Stack. Thin header-only wrapper over the C interface cc_kernel.h (Fortran library);
// status codes become exceptions: bad constants -> InputError, numerical -> NumericalError.
// An elastic indenter (THEORY.md section 9) is applied here: with rho = E1*/E2* every value
// is that of C' = (C + rho)/(1 + rho), so C' - 1 and H' = H/(1 + rho) (the Fortran library
// sees only the film and the substrate).
#pragma once
#include <cmath>
#include <cstddef>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "coatcontact/cc_kernel.h"
#include "coatcontact/errors.hpp"
#include "coatcontact/detail/format.hpp"
#include "coatcontact/stack.hpp"

namespace coatcontact {

namespace kernel_detail {

using detail::full_precision;

// Throws the exception matching a cc_status (no-op for CC_OK). `context` names the call.
inline void check_status(int status, const Stack& stack, const std::string& context) {
  const Material& film = stack.top();
  const Substrate& substrate = stack.substrate();
  switch (status) {
    case CC_OK:
      return;
    case CC_ERR_FILM_MODULUS:
      throw InputError(context + ": film Young's modulus E1 = " + full_precision(film.youngs_modulus) +
                       " is not allowed (must be finite and > 0)");
    case CC_ERR_FILM_POISSON:
      throw InputError(context + ": film Poisson ratio nu1 = " + full_precision(film.poisson_ratio) +
                       " is not allowed (must be in (-1, 0.5])");
    case CC_ERR_SUBSTRATE_MODULUS:
      throw InputError(context + ": substrate Young's modulus E0 = " +
                       full_precision(substrate.material.youngs_modulus) +
                       " is not allowed (must be finite and > 0)");
    case CC_ERR_SUBSTRATE_POISSON:
      throw InputError(context + ": substrate Poisson ratio nu0 = " +
                       full_precision(substrate.material.poisson_ratio) +
                       " is not allowed (must be in (-1, 0.5])");
    case CC_ERR_ARGUMENT:
    case CC_ERR_THICKNESS:
    case CC_ERR_LAYER_COUNT:
      throw InputError(context + ": " + cc_status_message(status));
    default:
      throw NumericalError(context + ": " + cc_status_message(status));
  }
}

// The one-layer kernel's scalar arguments (THEORY.md section 3).
struct FilmPair {
  double e1, nu1, e0, nu0;
  int rigid;
};
inline FilmPair film_pair(const Stack& stack) {
  const Material& film = stack.top();
  const Material& base = stack.substrate().material;
  return {film.youngs_modulus, film.poisson_ratio, base.youngs_modulus, base.poisson_ratio,
          stack.substrate().rigid ? 1 : 0};
}

inline int checked_size(std::size_t n, const std::string& context) {
  if (n > static_cast<std::size_t>(1) << 30) throw InputError(context + ": array too long");
  return static_cast<int>(n);
}

// The stack kernel's arrays (THEORY.md section 12), top first.
struct StackArrays {
  std::vector<double> thickness, youngs, poisson;
  std::vector<int> slip;
  int rigid;
  double e_base, nu_base;
  int n() const { return static_cast<int>(thickness.size()); }
};
inline StackArrays stack_arrays(const Stack& stack) {
  StackArrays a;
  for (const Layer& layer : stack.layers()) {
    a.thickness.push_back(layer.thickness);
    a.youngs.push_back(layer.material.youngs_modulus);
    a.poisson.push_back(layer.material.poisson_ratio);
    a.slip.push_back(layer.slip_below ? 1 : 0);
  }
  a.rigid = stack.substrate().rigid ? 1 : 0;
  a.e_base = stack.substrate().material.youngs_modulus;
  a.nu_base = stack.substrate().material.poisson_ratio;
  return a;
}

// C or C - 1 at q. Every stack goes to the stack entry points: the kernel library itself
// decides "one film or a stack" (one bonded layer takes section 3's closed form there, bit for
// bit the film entry's; otherwise section 12's recursion).
inline int compliance_values(const Stack& stack, const std::vector<double>& q, double* out,
                             bool minus_one, const std::string& context) {
  const int n = checked_size(q.size(), context);
  const StackArrays a = stack_arrays(stack);
  return minus_one ? cc_stack_compliance_minus_one(a.n(), a.thickness.data(), a.youngs.data(),
                                                   a.poisson.data(), a.slip.data(), a.rigid,
                                                   a.e_base, a.nu_base, n, q.data(), out)
                   : cc_stack_compliance(a.n(), a.thickness.data(), a.youngs.data(),
                                         a.poisson.data(), a.slip.data(), a.rigid, a.e_base,
                                         a.nu_base, n, q.data(), out);
}

// 1/(1 + rho): C' - 1 = (C - 1)/(1 + rho) (THEORY.md section 9); exactly 1 when rigid.
inline double indenter_scale(const Stack& stack) { return 1.0 / (1.0 + stack.indenter_ratio()); }

inline void scale_values(std::vector<double>& values, double scale) {
  if (scale != 1.0) {
    for (double& v : values) v *= scale;
  }
}


// A stack table's grid is refined ~T/h_top times (THEORY.md section 12: C - 1 decays like
// exp(-2 q h_top/T)) up to cc_kernel_stack_max_refinement(): a thinner top layer is refused
// here with its numbers, not after a failed build.
inline void check_stack_table_supported(const Stack& stack) {
  const double fraction = stack.layers().front().thickness / stack.total_thickness();
  const int refinement = cc_kernel_stack_max_refinement();
  if (fraction * refinement < 1.0) {
    // Six digits can round a fraction just under 1/refinement up to it ("0.03125 of T");
    // then all seventeen show that it is below.
    std::string shown = detail::short_text(fraction);
    if (std::stod(shown) * refinement >= 1.0) shown = detail::full_precision(fraction);
    throw InputError("the top layer is " + shown +
                     " of the stack's total thickness T; kernel tables need at least 1/" +
                     std::to_string(refinement) + " (their grid grows like T/h_top, THEORY.md "
                     "section 12): give the top layer (--layer) at least T/" +
                     std::to_string(refinement) + " or merge it with the layer below");
  }
}

}  // namespace kernel_detail

namespace detail {
// Which table of a stack: cc_kernel_table_create_stack (with H1 unless h_only) or _stack_h on
// grid `variant`, or (compact) _stack_range covering [0, u_range], H only.
struct TableGrid {
  int variant = 0;
  bool compact = false;
  double u_range = 0.0;
  bool h_only = false;
};
// That table, loaded from the solve cache when it holds it, else built and stored there
// (cpp/solver/table_cache.cpp; docs/solver.md "Solve cache"). A cc_status code.
int create_stack_table(const kernel_detail::StackArrays& arrays, const TableGrid& grid, cc_kernel_table** table);
// The text a table's cache entry is keyed by: the exact arrays, the grid and the build id.
std::string kernel_table_key(const kernel_detail::StackArrays& arrays, const TableGrid& grid);
}  // namespace detail

// C(q) at each q >= 0 (InputError for negative or non-finite q or bad constants).
inline std::vector<double> compliance(const Stack& stack, const std::vector<double>& q) {
  std::vector<double> c(q.size());
  kernel_detail::check_status(
      kernel_detail::compliance_values(stack, q, c.data(), false, "compliance"), stack,
      "compliance");
  // C' = (C + rho)/(1 + rho), written as 1 + (C - 1)/(1 + rho) only when rho != 0.
  const double rho = stack.indenter_ratio();
  if (rho != 0.0) {
    for (double& v : c) v = (v + rho) / (1.0 + rho);
  }
  return c;
}

inline double compliance(const Stack& stack, double q) {
  return compliance(stack, std::vector<double>{q}).front();
}

// C(q) - 1, accurate where C is close to 1.
inline std::vector<double> compliance_minus_one(const Stack& stack, const std::vector<double>& q) {
  std::vector<double> c(q.size());
  kernel_detail::check_status(
      kernel_detail::compliance_values(stack, q, c.data(), true, "compliance_minus_one"), stack,
      "compliance_minus_one");
  kernel_detail::scale_values(c, kernel_detail::indenter_scale(stack));
  return c;
}

// Taylor coefficients f_k = f^(k)(0)/k!, k = 0..order (<= 15), of f = C - 1.
inline std::vector<double> compliance_taylor(const Stack& stack, int order) {
  if (order < 0 || order > 15) throw InputError("compliance_taylor: order must be in [0, 15]");
  if (stack.is_multilayer()) {
    throw InputError("compliance_taylor: only for one bonded film (a stack's table computes its "
                     "own series, THEORY.md section 12)");
  }
  std::vector<double> f(static_cast<std::size_t>(order) + 1);
  const auto p = kernel_detail::film_pair(stack);
  kernel_detail::check_status(
      cc_compliance_taylor(p.e1, p.nu1, p.e0, p.nu0, p.rigid, order, f.data()), stack,
      "compliance_taylor");
  kernel_detail::scale_values(f, kernel_detail::indenter_scale(stack));
  return f;
}

struct KernelTableInfo {
  double u_max = 0.0;          // tabulated range [0, u_max] (asymptotic series beyond)
  double du = 0.0;             // table step
  double c_zero = 0.0;         // C'(0) (= E1*/E0* for a rigid indenter)
  double half_integral = 0.0;  // int_0^inf H du = (pi/2)(C(0) - 1)
  double abs_accuracy = 0.0;   // estimated max |H - H_exact|
  double max_abs_h = 0.0;      // max |H|
};

// H(u) and H1(u) for one stack; built once (a few ms), then read-only and safe to
// evaluate from several threads. Movable, not copyable.
class KernelTable {
 public:
  // `grid_variant` 0 is the default grid; the others (see cc_kernel_table_create_ex) compute
  // the same H independently, for a-posteriori estimates of the effect of the table's errors.
  // InputError for a variant out of range.
  explicit KernelTable(const Stack& stack, int grid_variant = 0) : KernelTable(stack, grid_variant, false) {}

  // The same table without H1 (cc_kernel_table_create_h): H, info() and the accuracy bit for bit,
  // for callers that evaluate H alone (the solver), without the DST of H1 and its FFT planning
  // (eval with an h1 output then throws InputError).
  struct HOnly {};
  KernelTable(const Stack& stack, int grid_variant, HOnly) : KernelTable(stack, grid_variant, true) {}

  // Grid variant 0 on a compact grid tabulating at least [0, u_range], H only
  // (cc_kernel_table_create_range): for callers that never need H beyond u_range nor H1
  // (eval with an h1 output then throws InputError). NumericalError where the compact grid
  // misses the accuracy target (then use a larger range or the full grid).
  KernelTable(const Stack& stack, double u_range)
      : scale_(kernel_detail::indenter_scale(stack)), rho_(stack.indenter_ratio()) {
    kernel_detail::check_stack_table_supported(stack);
    cc_kernel_table* raw = nullptr;
    const kernel_detail::StackArrays a = kernel_detail::stack_arrays(stack);
    const int status = detail::create_stack_table(a, {0, true, u_range, true}, &raw);
    kernel_detail::check_status(status, stack, "kernel table");
    table_.reset(raw);
  }

  // h[i] = H(u[i]), h1[i] = H1(u[i]) (h1 may be null).
  void eval(const double* u, std::size_t n, double* h, double* h1 = nullptr) const {
    const int status = cc_kernel_table_eval(table_.get(), kernel_detail::checked_size(n, "H(u)"),
                                            u, h, h1);
    if (status == CC_ERR_ARGUMENT) {
      throw InputError(h1 != nullptr ? "kernel H(u): u must be finite (and H1 needs a full table)"
                                     : "kernel H(u): u must be finite");
    }
    if (status != CC_OK) throw NumericalError(std::string("kernel H(u): ") + cc_status_message(status));
    if (scale_ != 1.0) {
      for (std::size_t i = 0; i < n; ++i) h[i] *= scale_;
      if (h1 != nullptr) {
        for (std::size_t i = 0; i < n; ++i) h1[i] *= scale_;
      }
    }
  }
  void eval(const std::vector<double>& u, std::vector<double>& h, std::vector<double>& h1) const {
    h.resize(u.size());
    h1.resize(u.size());
    eval(u.data(), u.size(), h.data(), h1.data());
  }
  void eval(const std::vector<double>& u, std::vector<double>& h) const {
    h.resize(u.size());
    eval(u.data(), u.size(), h.data(), nullptr);
  }
  double h(double u) const {
    double value = 0.0;
    eval(&u, 1, &value, nullptr);
    return value;
  }
  double h1(double u) const {
    double value = 0.0;
    double antiderivative = 0.0;
    eval(&u, 1, &value, &antiderivative);
    return antiderivative;
  }

  KernelTableInfo info() const {
    KernelTableInfo i;
    cc_kernel_table_info(table_.get(), &i.u_max, &i.du, &i.c_zero, &i.half_integral,
                         &i.abs_accuracy);
    cc_kernel_table_scale(table_.get(), &i.max_abs_h, nullptr);
    if (scale_ != 1.0) {  // H' = H/(1 + rho): every absolute quantity scales (section 9)
      i.c_zero = (i.c_zero + rho_) * scale_;
      i.half_integral *= scale_;
      i.abs_accuracy *= scale_;
      i.max_abs_h *= scale_;
    }
    return i;
  }

 private:
  KernelTable(const Stack& stack, int grid_variant, bool h_only)
      : scale_(kernel_detail::indenter_scale(stack)), rho_(stack.indenter_ratio()) {
    if (grid_variant < 0 || grid_variant >= cc_kernel_grid_variants()) {
      throw InputError("kernel table: grid variant " + std::to_string(grid_variant) +
                       " is not allowed (must be in [0, " +
                       std::to_string(cc_kernel_grid_variants() - 1) + "])");
    }
    kernel_detail::check_stack_table_supported(stack);
    cc_kernel_table* raw = nullptr;
    // THEORY.md section 12: q and u in units of T (the film thickness for one layer, whose
    // table the kernel library builds as cc_kernel_table_create_ex's, bit for bit).
    const kernel_detail::StackArrays a = kernel_detail::stack_arrays(stack);
    const int status = detail::create_stack_table(a, {grid_variant, false, 0.0, h_only}, &raw);
    kernel_detail::check_status(status, stack, "kernel table");
    table_.reset(raw);
  }

  struct Deleter {
    void operator()(cc_kernel_table* t) const { cc_kernel_table_destroy(t); }
  };
  double scale_ = 1.0;  // 1/(1 + rho)
  double rho_ = 0.0;
  std::unique_ptr<cc_kernel_table, Deleter> table_;
};

}  // namespace coatcontact
