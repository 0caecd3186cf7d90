// The reduced table of the Maugis-Dugdale cohesive zone (THEORY.md section 13, "The cohesive
// zone as a table"); see md_table.hpp.
#include "md_table.hpp"

#include <gsl/gsl_interp2d.h>
#include <gsl/gsl_spline.h>
#include <gsl/gsl_spline2d.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <string>
#include <vector>

#include "coatcontact/detail/constants.hpp"
#include "coatcontact/detail/brent.hpp"
#include "coatcontact/detail/format.hpp"
#include "coatcontact/detail/gsl_handler_off.hpp"
#include "coatcontact/errors.hpp"

namespace coatcontact::detail {

namespace {

using detail::kPi;
constexpr int kTwoD = 4;  // d, f, g_r, g_s
constexpr int kOneD = 2;  // delta_h, force_h
constexpr double kOneDRefinement = 8.0;
// Points per coarse interval (2-D: per direction) at which fine and coarse are compared.
constexpr int kSamples = 5;

// T - atan T without cancellation (series below T = 0.1: T^17/17 is 1e-14 of T^3/3).
double tan_minus_angle(double t) {
  if (t >= 0.1) return t - std::atan(t);
  double sum = 0.0, power = t * t * t, t2 = t * t;
  for (int k = 1; k <= 7; ++k, power *= t2) sum += (k % 2 == 1 ? 1.0 : -1.0) * power / (2 * k + 1);
  return sum;
}

// The ratio stored for each function: value / homogeneous value (THEORY.md section 13).
void to_array_2d(const CohesiveFunctions& v, double* out) {
  out[0] = v.d;
  out[1] = v.f;
  out[2] = v.g_r;
  out[3] = v.g_s;
}
void from_array_2d(const double* in, CohesiveFunctions& v) {
  v.d = in[0];
  v.f = in[1];
  v.g_r = in[2];
  v.g_s = in[3];
}

struct Spline2d {
  gsl_spline2d* spline = nullptr;
  ~Spline2d() { gsl_spline2d_free(spline); }
};
struct Spline1d {
  gsl_spline* spline = nullptr;
  ~Spline1d() { gsl_spline_free(spline); }
};

// Index of the interval of the sorted grid g holding v (clamped to the first and last).
std::size_t cell_of(const std::vector<double>& g, double v) {
  const auto it = std::upper_bound(g.begin(), g.end(), v);
  const auto k = static_cast<std::size_t>(std::max<std::ptrdiff_t>(it - g.begin() - 1, 0));
  return std::min(k, g.size() - 2);
}

// Cubic splines of y against x on all nodes and on every other node (x_coarse), and the
// largest |fine - coarse| in each coarse interval: the error estimate of the fine one.
void fit_pair(const std::vector<double>& x, const std::vector<double>& x_coarse, const std::vector<double>& y,
              std::vector<double>& y_coarse, Spline1d& fine, Spline1d& coarse, std::vector<double>& error) {
  y_coarse.clear();
  for (std::size_t i = 0; i < x.size(); i += 2) y_coarse.push_back(y[i]);
  fine.spline = gsl_spline_alloc(gsl_interp_cspline, x.size());
  coarse.spline = gsl_spline_alloc(gsl_interp_cspline, x_coarse.size());
  if (!fine.spline || !coarse.spline || gsl_spline_init(fine.spline, x.data(), y.data(), x.size()) != 0 ||
      gsl_spline_init(coarse.spline, x_coarse.data(), y_coarse.data(), x_coarse.size()) != 0) {
    throw NumericalError("Maugis-Dugdale table: GSL refused a 1-D spline");
  }
  error.assign(x_coarse.size() - 1, 0.0);
  for (std::size_t i = 0; i + 1 < x_coarse.size(); ++i) {
    for (int p = 1; p < 2 * kSamples; ++p) {
      const double v = x_coarse[i] + (x_coarse[i + 1] - x_coarse[i]) * p / (2 * kSamples);
      error[i] = std::max(error[i], std::abs(gsl_spline_eval(fine.spline, v, nullptr) -
                                             gsl_spline_eval(coarse.spline, v, nullptr)));
    }
  }
}

std::vector<double> grid(double lo, double hi, double step) {
  const int half = std::max(2, static_cast<int>(std::ceil((hi - lo) / (2.0 * step))));
  const int n = 2 * half + 1;
  std::vector<double> g(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) g[static_cast<std::size_t>(k)] = lo + (hi - lo) * k / (n - 1);
  return g;
}

}  // namespace

CohesiveFunctions cohesive_functions(const CohesiveZone& zone, double excess) {
  // The problem is linear in σ̂: the σ̂-parts from a second solve at a σ̂ large enough that
  // the 1/R-part's rounding (~1e-16 of it) is negligible against them.
  const double a = zone.contact_radius();
  const double big = 1e6 * std::max(1.0, a);
  const CohesiveState zero = zone.evaluate(0.0, excess);
  const CohesiveState loaded = zone.evaluate(big, excess);
  CohesiveFunctions out;
  out.delta_h = zero.delta;
  out.force_h = zero.force;
  out.g_r = zero.gap;
  out.d = (loaded.delta - zero.delta) / big;
  out.f = (loaded.force - zero.force) / big;
  out.g_s = (loaded.gap - zero.gap) / big;
  return out;
}

CohesiveFunctions homogeneous_functions(double a, double excess) {
  const double e = excess;
  const double t = std::sqrt(e * (2.0 + e));  // tan φa = sqrt(c² - a²)/a
  const double phi = std::atan(t);             // φa = arccos(a/c)
  CohesiveFunctions h;
  h.delta_h = a * a;
  h.force_h = 4.0 * a * a * a / 3.0;
  h.d = -a * t;
  h.f = -a * a * (t + (1.0 + e) * (1.0 + e) * phi);
  h.g_r = a * a / kPi * (phi * t * t + tan_minus_angle(t));
  h.g_s = 2.0 * a / kPi * (t * phi - e);
  return h;
}

CohesiveFunctions homogeneous_end_functions(double c) {
  CohesiveFunctions h;
  h.d = -c;
  h.f = -0.5 * kPi * c * c;
  h.g_r = 0.5 * c * c;
  h.g_s = c * (1.0 - 2.0 / kPi);
  return h;
}

struct MaugisDugdaleTable::Grids {
  // x = ln(a/t); τ in [0, 1] maps to s = ln(c/a - 1) = s_min + τ (s_max(x) - s_min).
  std::vector<double> x, tau, x_coarse, tau_coarse;
  std::vector<double> x1, x1_coarse;  // the 1-D functions' grid, kOneDRefinement times finer
  std::vector<double> z[kTwoD], z_coarse[kTwoD], y[kOneD], y_coarse[kOneD];
  Spline2d fine[kTwoD], coarse[kTwoD];
  // Largest |fine - coarse| in each coarse cell (2-D: index i + j (cx - 1)) or interval.
  std::vector<double> cell_error[kTwoD], interval_error[kOneD];
  Spline1d fine1[kOneD], coarse1[kOneD];
  // The end of the curve a = 0 against ln(c/t): d, f, g_r, g_s as ratios.
  std::vector<double> xe, xe_coarse, ye[kTwoD], ye_coarse[kTwoD], end_error[kTwoD];
  Spline1d fine_end[kTwoD], coarse_end[kTwoD];
  double seconds = 0.0;
};

MaugisDugdaleTable::MaugisDugdaleTable(const KernelSource& kernel, const Discretization& disc,
                                       const CohesiveQuadrature& quadrature, const MdTableOptions& options)
    : kernel_(kernel), disc_(disc), quadrature_(quadrature), options_(options) {
  if (!(options.a_over_t_min > 0.0 && options.a_over_t_min < options.a_over_t_max && options.excess_min > 0.0 &&
        options.excess_min < 1.0 && options.c_over_t_max >= 10.0 * options.a_over_t_max && options.step > 0.0 &&
        std::isfinite(options.c_over_t_max))) {
    throw InputError("Maugis-Dugdale table: need 0 < a_over_t_min < a_over_t_max, c_over_t_max >= 10 a_over_t_max, "
                     "0 < excess_min < 1 and step > 0");
  }
}

MaugisDugdaleTable::~MaugisDugdaleTable() = default;

double MaugisDugdaleTable::excess_max(double a) const { return options_.c_over_t_max / a - 1.0; }

void MaugisDugdaleTable::build() const {
  std::call_once(once_, [this] {
    const auto start = std::chrono::steady_clock::now();
    auto g = std::make_unique<Grids>();
    const double s_min = std::log(options_.excess_min);
    g->x = grid(std::log(options_.a_over_t_min), std::log(options_.a_over_t_max), options_.step);
    // τ spacing: `step` in s where the s range is widest (the smallest a).
    const double widest = std::log(excess_max(options_.a_over_t_min)) - s_min;
    g->tau = grid(0.0, 1.0, options_.step / widest);
    const std::size_t nx = g->x.size(), ns = g->tau.size();
    for (int k = 0; k < kTwoD; ++k) g->z[k].assign(nx * ns, 0.0);
    std::vector<std::exception_ptr> errors(nx);
    // One factorization per contact radius; the radii are independent.
#pragma omp parallel for schedule(dynamic, 1)
    for (long il = 0; il < static_cast<long>(nx); ++il) {
      const auto i = static_cast<std::size_t>(il);
      try {
        const double a = std::exp(g->x[i]);
        const double s_max = std::log(excess_max(a));
        const CohesiveZone zone(kernel_, a, 1.0, disc_, quadrature_);
        for (std::size_t j = 0; j < ns; ++j) {
          const double e = std::exp(s_min + g->tau[j] * (s_max - s_min));
          const CohesiveFunctions v = cohesive_functions(zone, e), h = homogeneous_functions(a, e);
          double value[kTwoD], hom[kTwoD];
          to_array_2d(v, value);
          to_array_2d(h, hom);
          for (int k = 0; k < kTwoD; ++k) g->z[k][j * nx + i] = value[k] / hom[k];
        }
      } catch (...) {
        errors[i] = std::current_exception();
      }
    }
    for (const auto& e : errors) {
      if (e) std::rethrow_exception(e);
    }
    // The 1-D functions δ_H, F_H: one adhesionless solve per radius (any c), cheap, so on a
    // finer grid.
    g->x1 = grid(g->x.front(), g->x.back(), options_.step / kOneDRefinement);
    const std::size_t n1 = g->x1.size();
    for (int k = 0; k < kOneD; ++k) g->y[k].assign(n1, 0.0);
    errors.assign(n1, nullptr);
#pragma omp parallel for schedule(dynamic, 4)
    for (long il = 0; il < static_cast<long>(n1); ++il) {
      const auto i = static_cast<std::size_t>(il);
      try {
        const double a = std::exp(g->x1[i]);
        const CohesiveState st = CohesiveZone(kernel_, a, 1.0, disc_, quadrature_).evaluate(0.0, 1e-3);
        const CohesiveFunctions h = homogeneous_functions(a, 1e-3);
        g->y[0][i] = st.delta / h.delta_h;
        g->y[1][i] = st.force / h.force_h;
      } catch (...) {
        errors[i] = std::current_exception();
      }
    }
    for (const auto& e : errors) {
      if (e) std::rethrow_exception(e);
    }
    for (std::size_t i = 0; i < nx; i += 2) g->x_coarse.push_back(g->x[i]);
    for (std::size_t j = 0; j < ns; j += 2) g->tau_coarse.push_back(g->tau[j]);
    const std::size_t cx = g->x_coarse.size(), cs = g->tau_coarse.size();
    GslHandlerOff guard;
    for (int k = 0; k < kTwoD; ++k) {
      g->z_coarse[k].resize(cx * cs);
      for (std::size_t j = 0; j < cs; ++j) {
        for (std::size_t i = 0; i < cx; ++i) g->z_coarse[k][j * cx + i] = g->z[k][2 * j * nx + 2 * i];
      }
      g->fine[k].spline = gsl_spline2d_alloc(gsl_interp2d_bicubic, nx, ns);
      g->coarse[k].spline = gsl_spline2d_alloc(gsl_interp2d_bicubic, cx, cs);
      if (!g->fine[k].spline || !g->coarse[k].spline ||
          gsl_spline2d_init(g->fine[k].spline, g->x.data(), g->tau.data(), g->z[k].data(), nx, ns) != 0 ||
          gsl_spline2d_init(g->coarse[k].spline, g->x_coarse.data(), g->tau_coarse.data(), g->z_coarse[k].data(),
                            cx, cs) != 0) {
        throw NumericalError("Maugis-Dugdale table: GSL refused the 2-D spline");
      }
    }
    // The end of the curve, a = 0 (no contact system), on a grid twice as fine as the table's.
    g->xe = grid(std::log(options_.end_c_over_t_min), std::log(options_.c_over_t_max), 0.5 * options_.step);
    const std::size_t ne = g->xe.size();
    for (int k = 0; k < kTwoD; ++k) g->ye[k].assign(ne, 0.0);
    errors.assign(ne, nullptr);
    {
      const CohesiveZone end_zone(kernel_, 0.0, 1.0, disc_, quadrature_);
#pragma omp parallel for schedule(dynamic, 1)
      for (long il = 0; il < static_cast<long>(ne); ++il) {
        const auto i = static_cast<std::size_t>(il);
        try {
          const double c = std::exp(g->xe[i]);
          double value[kTwoD], hom[kTwoD];
          to_array_2d(cohesive_functions(end_zone, c), value);
          to_array_2d(homogeneous_end_functions(c), hom);
          for (int k = 0; k < kTwoD; ++k) g->ye[k][i] = value[k] / hom[k];
        } catch (...) {
          errors[i] = std::current_exception();
        }
      }
    }
    for (const auto& e : errors) {
      if (e) std::rethrow_exception(e);
    }
    for (std::size_t i = 0; i < n1; i += 2) g->x1_coarse.push_back(g->x1[i]);
    for (int k = 0; k < kOneD; ++k) {
      fit_pair(g->x1, g->x1_coarse, g->y[k], g->y_coarse[k], g->fine1[k], g->coarse1[k], g->interval_error[k]);
    }
    for (std::size_t i = 0; i < ne; i += 2) g->xe_coarse.push_back(g->xe[i]);
    for (int k = 0; k < kTwoD; ++k) {
      fit_pair(g->xe, g->xe_coarse, g->ye[k], g->ye_coarse[k], g->fine_end[k], g->coarse_end[k], g->end_error[k]);
    }
    // Error maps: |fine - coarse| sampled on a 5 x 5 grid inside each coarse cell (which
    // includes the fine nodes between the coarse ones); its largest value is the cell's.
    for (int k = 0; k < kTwoD; ++k) {
      g->cell_error[k].assign((cx - 1) * (cs - 1), 0.0);
      for (std::size_t j = 0; j + 1 < cs; ++j) {
        for (std::size_t i = 0; i + 1 < cx; ++i) {
          double worst = 0.0;
          for (int p = 1; p < kSamples; ++p) {
            for (int q = 1; q < kSamples; ++q) {
              const double x = g->x_coarse[i] + (g->x_coarse[i + 1] - g->x_coarse[i]) * p / kSamples;
              const double t = g->tau_coarse[j] + (g->tau_coarse[j + 1] - g->tau_coarse[j]) * q / kSamples;
              worst = std::max(worst, std::abs(gsl_spline2d_eval(g->fine[k].spline, x, t, nullptr, nullptr) -
                                               gsl_spline2d_eval(g->coarse[k].spline, x, t, nullptr, nullptr)));
            }
          }
          for (std::size_t p = 2 * i; p <= 2 * i + 2; ++p) {
            for (std::size_t q = 2 * j; q <= 2 * j + 2; ++q) {
              const double at_node = g->z[k][q * nx + p];
              worst = std::max(worst, std::abs(at_node - gsl_spline2d_eval(g->coarse[k].spline, g->x[p], g->tau[q],
                                                                           nullptr, nullptr)));
            }
          }
          g->cell_error[k][j * (cx - 1) + i] = worst;
        }
      }
    }
    g->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    grids_ = std::move(g);
  });
}

double MaugisDugdaleTable::build_seconds() const {
  build();
  return grids_->seconds;
}
int MaugisDugdaleTable::nodes_x() const {
  build();
  return static_cast<int>(grids_->x.size());
}
int MaugisDugdaleTable::nodes_s() const {
  build();
  return static_cast<int>(grids_->tau.size());
}

bool MaugisDugdaleTable::covers(double a, double excess) const {
  const MdTableOptions& o = options_;
  // The ends with a margin of rounding: ln and exp of an end need not return it exactly.
  constexpr double kRounding = 1e-12;
  return a >= o.a_over_t_min && a <= o.a_over_t_max && excess >= o.excess_min * (1.0 - kRounding) &&
         excess <= excess_max(a) * (1.0 + kRounding);
}

MdTableValue MaugisDugdaleTable::at(double a, double excess) const {
  if (!covers(a, excess)) {
    throw InputError("Maugis-Dugdale table: (a/t, c/a - 1) = (" + short_text(a) + ", " + short_text(excess) +
                     ") outside the table");
  }
  build();
  const Grids& g = *grids_;
  const double s_min = std::log(options_.excess_min), s_max = std::log(excess_max(a));
  // Clamped: the logarithms of end values may round just outside the grid.
  const double x = std::clamp(std::log(a), g.x.front(), g.x.back());
  const double tau = std::clamp((std::log(excess) - s_min) / (s_max - s_min), 0.0, 1.0);
  const std::size_t cell_x = cell_of(g.x_coarse, x), cell_s = cell_of(g.tau_coarse, tau),
                    cell_1 = cell_of(g.x1_coarse, x);
  const CohesiveFunctions hom = homogeneous_functions(a, excess);
  double hom2[kTwoD], value[kTwoD], error[kTwoD];
  to_array_2d(hom, hom2);
  for (int k = 0; k < kTwoD; ++k) {
    const double r = gsl_spline2d_eval(g.fine[k].spline, x, tau, nullptr, nullptr);
    value[k] = r * hom2[k];
    error[k] = (options_.error_factor * g.cell_error[k][cell_s * (g.x_coarse.size() - 1) + cell_x] +
                options_.source_noise * std::abs(r)) *
               std::abs(hom2[k]);
  }
  MdTableValue out;
  from_array_2d(value, out.value);
  from_array_2d(error, out.error);
  const double hom1[kOneD] = {hom.delta_h, hom.force_h};
  double v1[kOneD], e1[kOneD];
  for (int k = 0; k < kOneD; ++k) {
    const double r = gsl_spline_eval(g.fine1[k].spline, x, nullptr);
    v1[k] = r * hom1[k];
    e1[k] = (options_.error_factor * g.interval_error[k][cell_1] + options_.source_noise * std::abs(r)) *
            std::abs(hom1[k]);
  }
  out.value.delta_h = v1[0];
  out.value.force_h = v1[1];
  out.error.delta_h = e1[0];
  out.error.force_h = e1[1];
  return out;
}

std::optional<MdTableState> MaugisDugdaleTable::solve(double sigma_hat, double h0, double a) const {
  const MdTableOptions& o = options_;
  if (!(a >= o.a_over_t_min && a <= o.a_over_t_max)) return std::nullopt;
  // h(c) - h0 (R = 1) in s = ln(c/a - 1); h grows with c (THEORY.md section 13).
  auto residual = [&](double s) {
    const MdTableValue v = at(a, std::exp(s));
    return v.value.g_r + sigma_hat * v.value.g_s - h0;
  };
  const double lo = std::log(o.excess_min), hi = std::log(excess_max(a));
  const auto root = brent_root(residual, lo, hi, {1e-13, 0.0, 200});
  if (!root) return std::nullopt;
  const double s = root->x, e = std::exp(s);
  const MdTableValue v = at(a, e);
  // Slopes in s by central differences of the interpolant (only for the error estimate).
  const double step = 1e-5;
  const double sp = std::min(s + step, hi), sm = std::max(s - step, lo);
  const MdTableValue vp = at(a, std::exp(sp)), vm = at(a, std::exp(sm));
  const double h_s = (vp.value.g_r - vm.value.g_r + sigma_hat * (vp.value.g_s - vm.value.g_s)) / (sp - sm);
  const double d_s = sigma_hat * (vp.value.d - vm.value.d) / (sp - sm);
  const double f_s = sigma_hat * (vp.value.f - vm.value.f) / (sp - sm);
  const double s_error = (v.error.g_r + sigma_hat * v.error.g_s) / std::abs(h_s);
  MdTableState st;
  st.excess = e;
  st.delta = v.value.delta_h + sigma_hat * v.value.d;
  st.force = v.value.force_h + sigma_hat * v.value.f;
  st.excess_error = e * s_error;
  st.delta_error = v.error.delta_h + sigma_hat * v.error.d + std::abs(d_s) * s_error;
  st.force_error = v.error.force_h + sigma_hat * v.error.f + std::abs(f_s) * s_error;
  return st;
}

std::optional<MdTableState> MaugisDugdaleTable::solve_end(double sigma_hat, double h0) const {
  build();
  const Grids& g = *grids_;
  const double lo = g.xe.front(), hi = g.xe.back();
  // Values and error estimates of d, f, g_r, g_s at u = ln(c/t).
  auto eval = [&](double u, double* value, double* error) {
    u = std::clamp(u, lo, hi);
    const std::size_t cell = cell_of(g.xe_coarse, u);
    double hom[kTwoD];
    to_array_2d(homogeneous_end_functions(std::exp(u)), hom);
    for (int k = 0; k < kTwoD; ++k) {
      const double r = gsl_spline_eval(g.fine_end[k].spline, u, nullptr);
      value[k] = r * hom[k];
      error[k] = (options_.error_factor * g.end_error[k][cell] + options_.source_noise * std::abs(r)) * std::abs(hom[k]);
    }
  };
  auto residual = [&](double u) {
    double v[kTwoD], e[kTwoD];
    eval(u, v, e);
    return v[2] + sigma_hat * v[3] - h0;
  };
  const auto root = brent_root(residual, lo, hi, {1e-13, 0.0, 200});
  if (!root) return std::nullopt;
  const double u = root->x, step = 1e-5;
  double v[kTwoD], e[kTwoD], vp[kTwoD], vm[kTwoD], scratch[kTwoD];
  eval(u, v, e);
  const double up = std::min(u + step, hi), um = std::max(u - step, lo);
  eval(up, vp, scratch);
  eval(um, vm, scratch);
  const double h_u = (vp[2] - vm[2] + sigma_hat * (vp[3] - vm[3])) / (up - um);
  const double u_error = (e[2] + sigma_hat * e[3]) / std::abs(h_u);
  MdTableState st;
  st.excess = std::exp(u);
  st.delta = sigma_hat * v[0];
  st.force = sigma_hat * v[1];
  st.excess_error = st.excess * u_error;
  st.delta_error = sigma_hat * (e[0] + std::abs((vp[0] - vm[0]) / (up - um)) * u_error);
  st.force_error = sigma_hat * (e[1] + std::abs((vp[1] - vm[1]) / (up - um)) * u_error);
  return st;
}

}  // namespace coatcontact::detail
