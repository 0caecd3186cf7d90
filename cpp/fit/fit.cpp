// Nonlinear least-squares fit of adhesive sphere-contact data to the coated-substrate JKR model
// (THEORY.md section 5). See fit.hpp for the model, the branch choice and the error policy.
#include "coatcontact/detail/gsl_handler_off.hpp"
#include "coatcontact/fit.hpp"

#include <gsl/gsl_blas.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_multifit_nlinear.h>
#include <gsl/gsl_roots.h>
#include <gsl/gsl_spline.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <utility>

#include "coatcontact/errors.hpp"
#include "coatcontact/reduced.hpp"

namespace coatcontact::fit {
namespace {

using detail::GslHandlerOff;  // GSL reports errors by return codes here, never aborts

std::string show(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

// Range of a/t the lattice may cover: far beyond both limits of THEORY.md section 6 (the reduced
// variables have reached their asymptotes), so leaving it means a parameter ran away.
constexpr double kMinAOverT = 1e-5;
constexpr double kMaxAOverT = 1e5;
// Extra lattice nodes beyond the range in use on each side: the natural end condition of the
// cubic spline perturbs the interpolant by a factor (2 - sqrt 3)^k ~ 0.27^k k nodes inward.
constexpr int kPadNodes = 4;
// Physical ranges of the parameters; leaving them means the data do not determine them.
constexpr double kWorkRange[2] = {1e-9, 1e4};        // J/m2
constexpr double kModulusRange[2] = {1e-2, 1e13};    // Pa
// Relative step of the central difference in ln E1 for the E1 column of the Jacobian:
// truncation ~h^2/6 ~ 2e-7, lattice noise ~tolerance/h ~ 1e-6 relative.
constexpr double kModulusStep = 1e-3;
// Loosest solver tolerance accepted for a lattice node (still far below any measurement noise;
// the interpolation check of the result reports the model error actually reached).
constexpr double kLoosestTolerance = 1e-6;

// Reduced variables and their derivatives with respect to x = ln(a/t).
struct Reduced {
  double pi_s, delta_s, e_eq, gamma1;
  double dpi_s, ddelta_s, de_eq, dgamma1;
};

// The reduced variables of one material pair on the lattice a/t = 10^(k/N): natural cubic
// splines of ln X versus ln(a/t) for X = Pi_s, Delta_s, E_eq, Gamma(1).
class Lattice {
 public:
  Lattice(const Material& film, const Substrate& substrate, int nodes_per_decade, double tolerance)
      : solver_(Stack::film_on(film, substrate)), per_decade_(nodes_per_decade), tolerance_(tolerance),
        tolerance_used_(tolerance) {}

  // Makes the spline cover [lo, hi] (values of a/t), solving missing nodes.
  void cover(double lo, double hi) {
    if (!(lo >= kMinAOverT) || !(hi <= kMaxAOverT) || !(lo <= hi)) {
      throw NumericalError("the model needs a/t in [" + show(lo) + ", " + show(hi) +
                           "], outside the range [1e-05, 1e+05] it is tabulated for");
    }
    int k_lo = static_cast<int>(std::floor(per_decade_ * std::log10(lo))) - kPadNodes;
    int k_hi = static_cast<int>(std::ceil(per_decade_ * std::log10(hi))) + kPadNodes;
    if (built_ && k_lo >= k_lo_ && k_hi <= k_hi_) return;
    if (built_) {
      k_lo = std::min(k_lo, k_lo_);
      k_hi = std::max(k_hi, k_hi_);
    }
    std::vector<int> missing;
    std::vector<double> missing_x;
    for (int k = k_lo; k <= k_hi; ++k) {
      if (nodes_.count(k) == 0) {
        missing.push_back(k);
        missing_x.push_back(node(k));
      }
    }
    if (!missing.empty()) {
      try {
        const std::vector<ReducedVariables> solved = solver_.sweep(missing_x, tolerance_);
        solver_calls_ += static_cast<long>(missing.size());
        for (std::size_t i = 0; i < missing.size(); ++i) nodes_[missing[i]] = solved[i];
      } catch (const NumericalError&) {
        // Some node cannot reach the tolerance (the kernel table limits the solver at large
        // a/t): solve node by node, relaxing the tolerance tenfold up to kLoosestTolerance there.
        for (std::size_t i = 0; i < missing.size(); ++i) nodes_[missing[i]] = solve_relaxed(missing_x[i]);
      }
    }
    const std::size_t count = static_cast<std::size_t>(k_hi - k_lo + 1);
    x_.assign(count, 0.0);
    std::array<std::vector<double>, 4> y;
    for (auto& column : y) column.assign(count, 0.0);
    for (int k = k_lo; k <= k_hi; ++k) {
      const std::size_t i = static_cast<std::size_t>(k - k_lo);
      const ReducedVariables& v = nodes_.at(k);
      x_[i] = std::log(node(k));
      // ln X: the variables grow like powers of a/t (E_eq ~ (a/t)^3 for a confined
      // incompressible film), which a spline of ln X in ln(a/t) follows almost exactly.
      if (!(v.pi_s > 0.0 && v.delta_s > 0.0 && v.e_eq > 0.0 && v.gamma1 > 0.0)) {
        throw NumericalError("reduced variables not all positive at a/t = " + show(node(k)));
      }
      y[0][i] = std::log(v.pi_s);
      y[1][i] = std::log(v.delta_s);
      y[2][i] = std::log(v.e_eq);
      y[3][i] = std::log(v.gamma1);
    }
    for (int j = 0; j < 4; ++j) {
      splines_[j].reset(gsl_spline_alloc(gsl_interp_cspline, count));
      accel_[j].reset(gsl_interp_accel_alloc());
      if (!splines_[j] || !accel_[j] ||
          gsl_spline_init(splines_[j].get(), x_.data(), y[j].data(), count) != GSL_SUCCESS) {
        throw NumericalError("could not build the spline of the reduced variables");
      }
    }
    k_lo_ = k_lo;
    k_hi_ = k_hi;
    built_ = true;
  }

  Reduced eval(double a_over_t) const {
    const double x = std::log(a_over_t);
    if (!built_ || !(x >= x_.front() && x <= x_.back())) {
      throw NumericalError("internal: a/t = " + show(a_over_t) + " outside the lattice");
    }
    double value[4];
    double slope[4];
    for (int j = 0; j < 4; ++j) {
      if (gsl_spline_eval_e(splines_[j].get(), x, accel_[j].get(), &value[j]) != GSL_SUCCESS ||
          gsl_spline_eval_deriv_e(splines_[j].get(), x, accel_[j].get(), &slope[j]) != GSL_SUCCESS) {
        throw NumericalError("spline evaluation failed at a/t = " + show(a_over_t));
      }
    }
    for (int j = 0; j < 4; ++j) {
      value[j] = std::exp(value[j]);  // X from ln X; dX/dx = X d(ln X)/dx
      slope[j] *= value[j];
    }
    return {value[0], value[1], value[2], value[3], slope[0], slope[1], slope[2], slope[3]};
  }

  Reduced exact(double a_over_t) {
    const ReducedVariables v = solve_relaxed(a_over_t);
    return {v.pi_s, v.delta_s, v.e_eq, v.gamma1, 0.0, 0.0, 0.0, 0.0};
  }

  // The loosest tolerance any node needed (>= the requested one).
  double tolerance_used() const { return tolerance_used_; }

  // a/t of the spline nodes in use.
  std::vector<double> nodes_in_use() const {
    std::vector<double> result;
    for (int k = k_lo_; k <= k_hi_; ++k) result.push_back(node(k));
    return result;
  }
  int node_count() const { return static_cast<int>(nodes_.size()); }
  long solver_calls() const { return solver_calls_; }

 private:
  ReducedVariables solve_relaxed(double a_over_t) {
    for (double tolerance = tolerance_;; tolerance *= 10.0) {
      try {
        ++solver_calls_;
        const ReducedVariables v = solver_.solve(a_over_t, tolerance);
        tolerance_used_ = std::max(tolerance_used_, tolerance);
        return v;
      } catch (const NumericalError&) {
        if (tolerance * 10.0 > kLoosestTolerance * 1.000001) throw;
      }
    }
  }

  double node(int k) const { return std::pow(10.0, static_cast<double>(k) / per_decade_); }

  struct SplineFree {
    void operator()(gsl_spline* s) const { gsl_spline_free(s); }
  };
  struct AccelFree {
    void operator()(gsl_interp_accel* a) const { gsl_interp_accel_free(a); }
  };

  ReducedSolver solver_;
  int per_decade_;
  double tolerance_;
  std::map<int, ReducedVariables> nodes_;
  bool built_ = false;
  int k_lo_ = 0;
  int k_hi_ = 0;
  std::vector<double> x_;
  std::array<std::unique_ptr<gsl_spline, SplineFree>, 4> splines_;
  std::array<std::unique_ptr<gsl_interp_accel, AccelFree>, 4> accel_;
  long solver_calls_ = 0;
  double tolerance_used_;
};

// A few lattices keyed by E1 (the E1 column of the Jacobian needs E1 e^{+-h}).
class LatticeCache {
 public:
  LatticeCache(const Problem& problem) : problem_(problem) {}

  Lattice& get(double film_modulus) {
    for (auto it = entries_.begin(); it != entries_.end(); ++it) {
      if (it->first == film_modulus) {
        std::rotate(entries_.begin(), it, it + 1);  // most recently used first
        return *entries_.front().second;
      }
    }
    if (entries_.size() >= kCapacity) {
      retired_calls_ += entries_.back().second->solver_calls();
      entries_.pop_back();
    }
    Material film = problem_.film;
    film.youngs_modulus = film_modulus;
    entries_.insert(entries_.begin(),
                    {film_modulus, std::make_unique<Lattice>(film, problem_.substrate,
                                                             problem_.nodes_per_decade,
                                                             problem_.solver_tolerance)});
    return *entries_.front().second;
  }
  long solver_calls() const {
    long calls = retired_calls_;
    for (const auto& e : entries_) calls += e.second->solver_calls();
    return calls;
  }

 private:
  static constexpr std::size_t kCapacity = 4;
  const Problem& problem_;
  std::vector<std::pair<double, std::unique_ptr<Lattice>>> entries_;
  long retired_calls_ = 0;
};

struct Parameters {
  double work, thickness, film_modulus;
};

// Force, penetration and their derivatives at contact radius a (THEORY.md section 5,
// [selfconsistenceInhom], [EqPenetrationCS], [EqForceCS]); derivatives with respect to a at
// fixed parameters, and with respect to ln w and ln t at fixed a.
struct PointModel {
  double force, penetration;
  double force_a, penetration_a;
  double force_lnw, penetration_lnw;
  double force_lnt, penetration_lnt;
};

PointModel point_model(const Reduced& v, double reduced_modulus, double sphere_radius,
                       const Parameters& p, double a) {
  const double E = reduced_modulus;
  const double R = sphere_radius;
  // c = -delta_fp * Gamma(1) = sqrt(2 pi a w / E1*).
  const double c = std::sqrt(2.0 * M_PI * a * p.work / E);
  const double cg = c / v.gamma1;                      // -delta_fp
  const double cg_x = -c * v.dgamma1 / (v.gamma1 * v.gamma1);  // d(c/G)/dx at fixed a
  PointModel m{};
  m.force = a * a * a * E * v.pi_s / (2.0 * R) - 2.0 * a * E * v.e_eq * cg;
  m.penetration = a * a * v.delta_s / R - cg;
  // d/da = explicit + (1/a) d/dx; dc/da = c/(2a).
  m.force_a = a * a * E * (3.0 * v.pi_s + v.dpi_s) / (2.0 * R) -
              2.0 * E * cg * (1.5 * v.e_eq + v.de_eq - v.e_eq * v.dgamma1 / v.gamma1);
  m.penetration_a = a * (2.0 * v.delta_s + v.ddelta_s) / R - cg / (2.0 * a) - cg_x / a;
  // c ~ sqrt(w).
  m.force_lnw = -a * E * v.e_eq * cg;
  m.penetration_lnw = -0.5 * cg;
  // x = ln a - ln t: d/d ln t = -d/dx at fixed a.
  m.force_lnt = -(a * a * a * E * v.dpi_s / (2.0 * R) - 2.0 * a * E * (v.de_eq * cg + v.e_eq * cg_x));
  m.penetration_lnt = -(a * a * v.ddelta_s / R - cg_x);
  return m;
}

double reduced_modulus_of(const Problem& problem, double film_modulus) {
  return film_modulus / (1.0 - problem.film.poisson_ratio * problem.film.poisson_ratio);
}

// Brent root of f on [lo, hi] (f(lo), f(hi) of opposite signs or zero).
double find_root(const std::function<double(double)>& f, double lo, double hi) {
  const double f_lo = f(lo);
  const double f_hi = f(hi);
  if (f_lo == 0.0) return lo;
  if (f_hi == 0.0) return hi;
  if ((f_lo < 0.0) == (f_hi < 0.0)) throw NumericalError("internal: root not bracketed");
  gsl_function gf;
  gf.function = [](double x, void* params) {
    return (*static_cast<const std::function<double(double)>*>(params))(x);
  };
  gf.params = const_cast<std::function<double(double)>*>(&f);
  std::unique_ptr<gsl_root_fsolver, void (*)(gsl_root_fsolver*)> solver(
      gsl_root_fsolver_alloc(gsl_root_fsolver_brent), gsl_root_fsolver_free);
  if (!solver || gsl_root_fsolver_set(solver.get(), &gf, lo, hi) != GSL_SUCCESS) {
    throw NumericalError("could not start the root finder");
  }
  for (int iteration = 0; iteration < 200; ++iteration) {
    if (gsl_root_fsolver_iterate(solver.get()) != GSL_SUCCESS) break;
    const double x_lo = gsl_root_fsolver_x_lower(solver.get());
    const double x_hi = gsl_root_fsolver_x_upper(solver.get());
    if (gsl_root_test_interval(x_lo, x_hi, 0.0, 1e-13) == GSL_SUCCESS) {
      return gsl_root_fsolver_root(solver.get());
    }
  }
  throw NumericalError("root finder on the model curve did not converge");
}

// The model evaluated at every data point, with the derivatives of the model force there.
struct ModelAtData {
  std::vector<double> radius, penetration, force, force_lnw, force_lnt;
  std::vector<bool> clamped;
  double pulloff_radius = 0.0, pulloff_penetration = 0.0, pulloff_force = 0.0;
  // For the interpolation check: d F/d delta along the curve (delta,F data, unclamped).
  std::vector<double> slope;
};

class Model {
 public:
  Model(const Problem& problem, const Measurements& data) : problem_(problem), data_(data), cache_(problem) {}

  // The model at every data point; a failure names the parameters it happened at.
  ModelAtData at_data(const Parameters& p) {
    check_range(p);
    try {
      return at_data_unchecked(p);
    } catch (const NumericalError& error) {
      throw NumericalError("model evaluation failed at w = " + show(p.work) + " J/m2, t = " + show(p.thickness) +
                           " m, E1 = " + show(p.film_modulus) + " Pa (" + error.what() +
                           "); if the fit wandered there, try start values closer to the solution");
    }
  }

  Lattice& lattice(double film_modulus) { return cache_.get(film_modulus); }
  long solver_calls() const { return cache_.solver_calls(); }

 private:
  ModelAtData at_data_unchecked(const Parameters& p) {
    Lattice& lattice = cache_.get(p.film_modulus);
    const double E = reduced_modulus_of(problem_, p.film_modulus);
    ModelAtData out;
    const std::size_t n = data_.size();
    out.radius.resize(n);
    out.penetration.resize(n);
    out.force.resize(n);
    out.force_lnw.resize(n);
    out.force_lnt.resize(n);
    out.clamped.assign(n, false);
    out.slope.assign(n, 0.0);
    const auto at = [&](double a) {
      return point_model(lattice.eval(a / p.thickness), E, problem_.sphere_radius, p, a);
    };

    if (data_.kind == DataKind::kRadiusForce) {
      const auto [lo, hi] = std::minmax_element(data_.abscissa.begin(), data_.abscissa.end());
      lattice.cover(*lo / p.thickness, *hi / p.thickness);
      for (std::size_t i = 0; i < n; ++i) {
        const double a = data_.abscissa[i];
        const PointModel m = at(a);
        out.radius[i] = a;
        out.penetration[i] = m.penetration;
        out.force[i] = m.force;
        out.force_lnw[i] = m.force_lnw;
        out.force_lnt[i] = m.force_lnt;
      }
      displacement_pulloff(at, *lo, *hi, out);
      return out;
    }

    // delta,F data: the curve delta(a) must reach below its first minimum and above max delta.
    const double delta_max = *std::max_element(data_.abscissa.begin(), data_.abscissa.end());
    const double film_length =
        std::cbrt(M_PI * p.work * problem_.sphere_radius * problem_.sphere_radius / E);
    double a_lo = std::max(0.1 * film_length, 1.01 * kMinAOverT * p.thickness);
    double a_hi = std::max(4.0 * a_lo, 2.0 * std::sqrt(problem_.sphere_radius * std::max(delta_max, 0.0)));
    bool ready = false;
    for (int attempt = 0; attempt < 80 && !ready; ++attempt) {
      lattice.cover(a_lo / p.thickness, a_hi / p.thickness);
      if (at(a_lo).penetration_a >= 0.0) {
        a_lo = std::max(a_lo / 4.0, 1.01 * kMinAOverT * p.thickness);
        continue;
      }
      const PointModel top = at(a_hi);
      if (top.penetration < delta_max || top.penetration_a <= 0.0) {
        a_hi *= 2.0;
        continue;
      }
      ready = true;
    }
    if (!ready) throw NumericalError("could not bracket the measured penetrations on the model curve");

    // Grid in a: the lattice nodes inside [a_lo, a_hi] and both ends.
    std::vector<double> grid{a_lo};
    for (double node : lattice.nodes_in_use()) {
      const double a = node * p.thickness;
      if (a > a_lo && a < a_hi) grid.push_back(a);
    }
    grid.push_back(a_hi);
    // First minimum of delta(a): the displacement-controlled pull-off point a_c.
    std::size_t j = 1;
    while (j < grid.size() && at(grid[j]).penetration_a < 0.0) ++j;
    if (j == grid.size()) throw NumericalError("internal: no minimum of delta(a) in the bracket");
    const double a_c = find_root([&](double a) { return at(a).penetration_a; }, grid[j - 1], grid[j]);
    const PointModel pulloff = at(a_c);
    out.pulloff_radius = a_c;
    out.pulloff_penetration = pulloff.penetration;
    out.pulloff_force = pulloff.force;
    // Stable branch a >= a_c: nodes beyond a_c with their delta.
    std::vector<double> branch_a{a_c};
    std::vector<double> branch_delta{pulloff.penetration};
    for (std::size_t k = j; k < grid.size(); ++k) {
      branch_a.push_back(grid[k]);
      branch_delta.push_back(at(grid[k]).penetration);
    }
    for (std::size_t i = 0; i < n; ++i) {
      const double delta = data_.abscissa[i];
      double a = a_c;
      if (delta <= pulloff.penetration) {
        out.clamped[i] = true;
      } else {
        std::size_t k = 1;
        while (k < branch_a.size() && branch_delta[k] < delta) ++k;
        if (k == branch_a.size()) throw NumericalError("internal: penetration above the bracket");
        a = find_root([&](double r) { return at(r).penetration - delta; }, branch_a[k - 1], branch_a[k]);
      }
      const PointModel m = at(a);
      out.radius[i] = a;
      out.penetration[i] = m.penetration;
      out.force[i] = m.force;
      if (out.clamped[i]) {
        // Jacobian approximation: the motion of a_c with the parameters is ignored.
        out.force_lnw[i] = m.force_lnw;
        out.force_lnt[i] = m.force_lnt;
      } else {
        // Implicit a*(p) from delta(a*, p) = delta_i: da*/dp = -delta_p / delta_a.
        const double ratio = m.force_a / m.penetration_a;
        out.force_lnw[i] = m.force_lnw - ratio * m.penetration_lnw;
        out.force_lnt[i] = m.force_lnt - ratio * m.penetration_lnt;
        out.slope[i] = ratio;
      }
    }
    return out;
  }

  // For a,F data the displacement-controlled pull-off point is reported when it lies inside
  // the covered range (otherwise left at 0).
  template <class At>
  void displacement_pulloff(const At& at, double lo, double hi,
                            ModelAtData& out) {
    const int steps = 64;
    double previous_a = lo;
    double previous_slope = at(lo).penetration_a;
    for (int s = 1; s <= steps; ++s) {
      const double a = lo * std::pow(hi / lo, static_cast<double>(s) / steps);
      const double slope = at(a).penetration_a;
      if (previous_slope < 0.0 && slope >= 0.0) {
        const double a_c = find_root([&](double r) { return at(r).penetration_a; }, previous_a, a);
        const PointModel m = at(a_c);
        out.pulloff_radius = a_c;
        out.pulloff_penetration = m.penetration;
        out.pulloff_force = m.force;
        return;
      }
      previous_a = a;
      previous_slope = slope;
    }
  }

  void check_range(const Parameters& p) const {
    if (!(p.work >= kWorkRange[0] && p.work <= kWorkRange[1])) {
      throw NumericalError("w ran to " + show(p.work) + " J/m2, outside [" + show(kWorkRange[0]) +
                           ", " + show(kWorkRange[1]) + "]: the data do not determine w");
    }
    if (!(p.film_modulus >= kModulusRange[0] && p.film_modulus <= kModulusRange[1])) {
      throw NumericalError("E1 ran to " + show(p.film_modulus) + " Pa, outside [" +
                           show(kModulusRange[0]) + ", " + show(kModulusRange[1]) +
                           "]: the data do not determine E1");
    }
    if (!(p.thickness > 0.0) || !std::isfinite(p.thickness)) {
      throw NumericalError("t ran to " + show(p.thickness) + " m: the data do not determine t");
    }
  }

  const Problem& problem_;
  const Measurements& data_;
  LatticeCache cache_;
};

// GSL works on x_j = kOffset + ln(p_j / p_start_j): the relative step test
// |dx| <= xtol (|x| + xtol) then acts as a test on the relative change of p_j.
constexpr double kOffset = 10.0;

struct FitContext {
  const Problem* problem;
  const Measurements* data;
  Model* model;
  std::vector<int> free_index;  // parameter index of each GSL variable
  std::array<double, kParameterCount> start{};
  double force_scale = 1.0;
  std::exception_ptr error;

  Parameters parameters(const gsl_vector* x) const {
    std::array<double, kParameterCount> value = start;
    for (std::size_t j = 0; j < free_index.size(); ++j) {
      value[free_index[j]] = start[free_index[j]] * std::exp(gsl_vector_get(x, j) - kOffset);
    }
    return {value[kWork], value[kThickness], value[kFilmModulus]};
  }
};

int residual_callback(const gsl_vector* x, void* params, gsl_vector* f) {
  auto* ctx = static_cast<FitContext*>(params);
  try {
    const ModelAtData m = ctx->model->at_data(ctx->parameters(x));
    for (std::size_t i = 0; i < ctx->data->size(); ++i) {
      gsl_vector_set(f, i, (m.force[i] - ctx->data->force[i]) / ctx->force_scale);
    }
    return GSL_SUCCESS;
  } catch (...) {
    ctx->error = std::current_exception();
    return GSL_EBADFUNC;
  }
}

// Jacobian of the scaled residuals in x: analytic for w and t, central difference in ln E1.
void jacobian(FitContext& ctx, const gsl_vector* x, gsl_matrix* J) {
  const Parameters p = ctx.parameters(x);
  const ModelAtData m = ctx.model->at_data(p);
  const std::size_t n = ctx.data->size();
  for (std::size_t j = 0; j < ctx.free_index.size(); ++j) {
    const int which = ctx.free_index[j];
    if (which == kWork || which == kThickness) {
      const std::vector<double>& column = which == kWork ? m.force_lnw : m.force_lnt;
      for (std::size_t i = 0; i < n; ++i) gsl_matrix_set(J, i, j, column[i] / ctx.force_scale);
    } else {
      Parameters up = p;
      Parameters down = p;
      up.film_modulus = p.film_modulus * std::exp(kModulusStep);
      down.film_modulus = p.film_modulus * std::exp(-kModulusStep);
      const ModelAtData mu = ctx.model->at_data(up);
      const ModelAtData md = ctx.model->at_data(down);
      for (std::size_t i = 0; i < n; ++i) {
        gsl_matrix_set(J, i, j, (mu.force[i] - md.force[i]) / (2.0 * kModulusStep * ctx.force_scale));
      }
    }
  }
}

int jacobian_callback(const gsl_vector* x, void* params, gsl_matrix* J) {
  auto* ctx = static_cast<FitContext*>(params);
  try {
    jacobian(*ctx, x, J);
    return GSL_SUCCESS;
  } catch (...) {
    ctx->error = std::current_exception();
    return GSL_EBADFUNC;
  }
}

std::string estimates_text(const FitContext& ctx, const gsl_vector* x) {
  const Parameters p = ctx.parameters(x);
  const double value[3] = {p.work, p.thickness, p.film_modulus};
  std::string text;
  for (int which : ctx.free_index) {
    if (!text.empty()) text += ", ";
    text += std::string(parameter_name(which)) + " = " + show(value[which]);
  }
  return text;
}

// One trust-region solve (Levenberg-Marquardt steps, More scaling, QR) over ctx.free_index.
struct Stage {
  int status = GSL_FAILURE;
  int info = 0;
  int iterations = 0;
  std::vector<double> x;                          // GSL variables at the end
  std::array<double, kParameterCount> values{};  // parameters at the end
  bool gradient_small = false;                    // for GSL_ENOPROG
};

Stage run_stage(FitContext& ctx, int max_iterations) {
  const std::size_t n = ctx.data->size();
  const std::size_t p_count = ctx.free_index.size();
  gsl_multifit_nlinear_fdf fdf;
  fdf.f = residual_callback;
  fdf.df = jacobian_callback;
  fdf.fvv = nullptr;
  fdf.n = n;
  fdf.p = p_count;
  fdf.params = &ctx;
  gsl_multifit_nlinear_parameters fit_parameters = gsl_multifit_nlinear_default_parameters();
  std::unique_ptr<gsl_multifit_nlinear_workspace, void (*)(gsl_multifit_nlinear_workspace*)> work(
      gsl_multifit_nlinear_alloc(gsl_multifit_nlinear_trust, &fit_parameters, n, p_count),
      gsl_multifit_nlinear_free);
  std::unique_ptr<gsl_vector, void (*)(gsl_vector*)> x0(gsl_vector_alloc(p_count), gsl_vector_free);
  if (!work || !x0) throw NumericalError("out of memory allocating the fit workspace");
  gsl_vector_set_all(x0.get(), kOffset);
  ctx.error = nullptr;
  if (gsl_multifit_nlinear_init(x0.get(), &fdf, work.get()) != GSL_SUCCESS) {
    if (ctx.error) std::rethrow_exception(ctx.error);
    throw NumericalError("could not evaluate the model at the start values");
  }
  const double xtol = 1e-10;  // relative change of each parameter ~ xtol * kOffset = 1e-9
  const double gtol = 1e-10;
  const double ftol = 0.0;
  Stage stage;
  stage.status = gsl_multifit_nlinear_driver(static_cast<std::size_t>(max_iterations), xtol, gtol, ftol,
                                             nullptr, nullptr, &stage.info, work.get());
  if (ctx.error) std::rethrow_exception(ctx.error);
  stage.iterations = static_cast<int>(gsl_multifit_nlinear_niter(work.get()));
  const gsl_vector* x = gsl_multifit_nlinear_position(work.get());
  for (std::size_t j = 0; j < p_count; ++j) stage.x.push_back(gsl_vector_get(x, j));
  const Parameters p = ctx.parameters(x);
  stage.values = {p.work, p.thickness, p.film_modulus};
  if (stage.status == GSL_ENOPROG) {
    // No step decreases the cost any more: accept only if the gradient is at the noise level
    // of the model (the lattice values carry relative noise ~ solver tolerance).
    const gsl_vector* f = gsl_multifit_nlinear_residual(work.get());
    const gsl_matrix* J = gsl_multifit_nlinear_jac(work.get());
    const double f_norm = gsl_blas_dnrm2(f);
    stage.gradient_small = true;
    for (std::size_t j = 0; j < p_count; ++j) {
      double g = 0.0;
      double column_norm = 0.0;
      for (std::size_t i = 0; i < n; ++i) {
        g += gsl_matrix_get(J, i, j) * gsl_vector_get(f, i);
        column_norm += gsl_matrix_get(J, i, j) * gsl_matrix_get(J, i, j);
      }
      if (std::fabs(g) > 1e-6 * std::sqrt(column_norm) * f_norm) stage.gradient_small = false;
    }
  }
  return stage;
}

}  // namespace

const char* parameter_name(int parameter) {
  switch (parameter) {
    case kWork: return "w";
    case kThickness: return "t";
    case kFilmModulus: return "E1";
    default: return "?";
  }
}

Measurements select_branch(const Measurements& data, Branch branch) {
  if (branch == Branch::kAll || data.size() == 0) return data;
  const std::size_t top = static_cast<std::size_t>(
      std::max_element(data.abscissa.begin(), data.abscissa.end()) - data.abscissa.begin());
  const std::size_t begin = branch == Branch::kLoading ? 0 : top;
  const std::size_t end = branch == Branch::kLoading ? top + 1 : data.size();
  Measurements out;
  out.kind = data.kind;
  out.abscissa.assign(data.abscissa.begin() + begin, data.abscissa.begin() + end);
  out.force.assign(data.force.begin() + begin, data.force.begin() + end);
  if (data.line_numbers.size() == data.size()) {
    out.line_numbers.assign(data.line_numbers.begin() + begin, data.line_numbers.begin() + end);
  }
  return out;
}

Result fit(const Measurements& data, const Problem& problem) {
  const auto clock_start = std::chrono::steady_clock::now();
  GslHandlerOff handler_off;
  // ---- validate the problem (InputError: the user's input is not usable) ----
  const std::size_t n = data.size();
  if (data.abscissa.size() != n) throw InputError("fit: abscissa and force columns differ in length");
  if (!(problem.sphere_radius > 0.0) || !std::isfinite(problem.sphere_radius)) {
    throw InputError("sphere radius must be > 0 (got " + show(problem.sphere_radius) + ")");
  }
  Stack::film_on(problem.film, problem.substrate);  // validates the constants
  if (!(problem.thickness > 0.0) || !std::isfinite(problem.thickness)) {
    throw InputError("film thickness must be > 0 (got " + show(problem.thickness) + ")");
  }
  if (!(problem.work > 0.0) || !std::isfinite(problem.work)) {
    throw InputError("adhesion energy must be > 0 (got " + show(problem.work) + ")");
  }
  if (problem.nodes_per_decade < 4 || problem.nodes_per_decade > 1000) {
    throw InputError("nodes per decade must be in [4, 1000]");
  }
  FitContext ctx;
  ctx.problem = &problem;
  ctx.data = &data;
  ctx.start = {problem.work, problem.thickness, problem.film.youngs_modulus};
  for (int which = 0; which < kParameterCount; ++which) {
    if (problem.free[which]) ctx.free_index.push_back(which);
  }
  const std::size_t p_count = ctx.free_index.size();
  if (p_count == 0) throw InputError("no free parameter: name at least one of w, t, E1");
  if (n <= p_count) {
    throw InputError(std::to_string(n) + " data point" + (n == 1 ? "" : "s") + " for " +
                     std::to_string(p_count) + " free parameter" + (p_count == 1 ? "" : "s") +
                     ": a fit needs more points than free parameters");
  }
  double force_scale = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(data.abscissa[i]) || !std::isfinite(data.force[i])) {
      throw InputError("data point " + std::to_string(i + 1) + " is not finite");
    }
    if (data.kind == DataKind::kRadiusForce && !(data.abscissa[i] > 0.0)) {
      const std::string where = data.line_numbers.size() == n
                                    ? "line " + std::to_string(data.line_numbers[i])
                                    : "point " + std::to_string(i + 1);
      throw InputError(where + ": contact radius must be > 0 (got " + show(data.abscissa[i]) + ")");
    }
    force_scale = std::max(force_scale, std::fabs(data.force[i]));
  }
  // Residuals are scaled by the largest measured force (any constant scale gives the same
  // estimates and standard errors; this one keeps GSL's tolerances meaningful).
  if (!(force_scale > 0.0)) throw InputError("all measured forces are zero: nothing to fit");
  ctx.force_scale = force_scale;

  Model model(problem, data);
  ctx.model = &model;

  // ---- GSL trust-region solve ----
  // With several free parameters, w alone is fitted first (a 1-D problem that always has a
  // good start from the pull-off force) and the full fit starts from there: a start far from w
  // can otherwise lead the joint fit into a secondary minimum.
  Result result;
  if (p_count > 1 && problem.free[kWork]) {
    FitContext first = ctx;
    first.free_index = {kWork};
    try {
      const Stage stage = run_stage(first, problem.max_iterations);
      if (stage.status == GSL_SUCCESS || stage.status == GSL_ENOPROG) {
        ctx.start[kWork] = stage.values[kWork];
        result.iterations += stage.iterations;
      }
    } catch (const NumericalError&) {
      // Keep the user's start; the full fit reports its own failure if there is one.
    }
  }
  const Stage stage = run_stage(ctx, problem.max_iterations);
  result.iterations += stage.iterations;
  std::unique_ptr<gsl_vector, void (*)(gsl_vector*)> x_best(gsl_vector_alloc(p_count), gsl_vector_free);
  for (std::size_t j = 0; j < p_count; ++j) gsl_vector_set(x_best.get(), j, stage.x[j]);
  const gsl_vector* x = x_best.get();
  if (stage.status == GSL_SUCCESS) {
    result.converged = true;
    result.stop_reason = stage.info == 1 ? "small step" : "small gradient";
  } else if (stage.status == GSL_ENOPROG) {
    if (!stage.gradient_small) {
      throw NumericalError("the fit stopped making progress after " + std::to_string(result.iterations) +
                           " iterations without converging (last estimates " +
                           estimates_text(ctx, x) + ")");
    }
    result.converged = true;
    result.stop_reason = "no further decrease (gradient at model noise level)";
  } else if (stage.status == GSL_EMAXITER) {
    throw NumericalError("the fit did not converge in " + std::to_string(problem.max_iterations) +
                         " iterations (last estimates " + estimates_text(ctx, x) + ")");
  } else {
    throw NumericalError(std::string("the fit failed: ") + gsl_strerror(stage.status) +
                         " (last estimates " + estimates_text(ctx, x) + ")");
  }

  // ---- statistics at the solution ----
  const Parameters best = ctx.parameters(x);
  const ModelAtData m = model.at_data(best);
  std::unique_ptr<gsl_matrix, void (*)(gsl_matrix*)> J(gsl_matrix_alloc(n, p_count), gsl_matrix_free);
  jacobian(ctx, x, J.get());
  double rss = 0.0;
  double mean = 0.0;
  for (std::size_t i = 0; i < n; ++i) mean += data.force[i] / static_cast<double>(n);
  double tss = 0.0;
  result.residual.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    result.residual[i] = m.force[i] - data.force[i];
    rss += result.residual[i] * result.residual[i];
    tss += (data.force[i] - mean) * (data.force[i] - mean);
  }
  result.points = n;
  result.free_count = static_cast<int>(p_count);
  result.free = problem.free;
  result.value = {best.work, best.thickness, best.film_modulus};
  result.residual_norm = std::sqrt(rss);
  result.residual_sigma = std::sqrt(rss / static_cast<double>(n - p_count));
  result.r_squared = tss > 0.0 ? 1.0 - rss / tss : (rss == 0.0 ? 1.0 : -HUGE_VAL);
  result.model_radius = m.radius;
  result.model_penetration = m.penetration;
  result.model_force = m.force;
  result.clamped = m.clamped;
  result.displacement_pulloff_radius = m.pulloff_radius;
  result.displacement_pulloff_penetration = m.pulloff_penetration;
  result.displacement_pulloff_force = m.pulloff_force;

  // Covariance s^2 (J^T J)^-1 through the SVD of the column-normalized Jacobian J D^-1:
  // (J^T J)^-1 = D^-1 V S^-2 V^T D^-1.
  std::vector<double> column_norm(p_count, 0.0);
  for (std::size_t j = 0; j < p_count; ++j) {
    for (std::size_t i = 0; i < n; ++i) column_norm[j] += std::pow(gsl_matrix_get(J.get(), i, j), 2);
    column_norm[j] = std::sqrt(column_norm[j]);
    if (!(column_norm[j] > 0.0)) {
      throw NumericalError(std::string("the data do not depend on ") + parameter_name(ctx.free_index[j]) +
                           ": it cannot be fitted (fix it instead)");
    }
    for (std::size_t i = 0; i < n; ++i) {
      gsl_matrix_set(J.get(), i, j, gsl_matrix_get(J.get(), i, j) / column_norm[j]);
    }
  }
  std::unique_ptr<gsl_matrix, void (*)(gsl_matrix*)> V(gsl_matrix_alloc(p_count, p_count), gsl_matrix_free);
  std::unique_ptr<gsl_vector, void (*)(gsl_vector*)> S(gsl_vector_alloc(p_count), gsl_vector_free);
  std::unique_ptr<gsl_vector, void (*)(gsl_vector*)> svd_work(gsl_vector_alloc(p_count), gsl_vector_free);
  if (gsl_linalg_SV_decomp(J.get(), V.get(), S.get(), svd_work.get()) != GSL_SUCCESS) {
    throw NumericalError("singular value decomposition of the Jacobian failed");
  }
  const double s_max = gsl_vector_get(S.get(), 0);
  const double s_min = gsl_vector_get(S.get(), p_count - 1);
  if (!(s_min > 0.0) || s_max / s_min > kMaximumCondition) {
    throw NumericalError("the free parameters are not identifiable from these data (Jacobian condition "
                         "number " + (s_min > 0.0 ? show(s_max / s_min) : std::string("infinite")) +
                         "): fix one of them");
  }
  const double s2_scaled = rss / (force_scale * force_scale) / static_cast<double>(n - p_count);
  std::array<std::array<double, kParameterCount>, kParameterCount> covariance{};  // in ln p
  for (std::size_t a = 0; a < p_count; ++a) {
    for (std::size_t b = 0; b < p_count; ++b) {
      double sum = 0.0;
      for (std::size_t k = 0; k < p_count; ++k) {
        const double s = gsl_vector_get(S.get(), k);
        sum += gsl_matrix_get(V.get(), a, k) * gsl_matrix_get(V.get(), b, k) / (s * s);
      }
      covariance[a][b] = s2_scaled * sum / (column_norm[a] * column_norm[b]);
    }
  }
  for (int a = 0; a < kParameterCount; ++a) result.correlation[a][a] = 1.0;
  for (std::size_t a = 0; a < p_count; ++a) {
    const int pa = ctx.free_index[a];
    // Linearized: se(p) = p se(ln p).
    result.standard_error[pa] = result.value[pa] * std::sqrt(covariance[a][a]);
    for (std::size_t b = 0; b < p_count; ++b) {
      const int pb = ctx.free_index[b];
      const double denominator = std::sqrt(covariance[a][a] * covariance[b][b]);
      result.correlation[pa][pb] = denominator > 0.0 ? covariance[a][b] / denominator : (a == b ? 1.0 : 0.0);
    }
  }
  for (int which : ctx.free_index) {
    if (!(result.standard_error[which] < result.value[which])) {
      throw NumericalError(std::string("the data do not determine ") + parameter_name(which) + ": " +
                           parameter_name(which) + " = " + show(result.value[which]) +
                           " with a standard error of " + show(result.standard_error[which]) +
                           " (not smaller than the value)");
    }
  }
  if (!(result.r_squared >= kMinimumRSquared)) {
    throw NumericalError("the model does not describe these data: R^2 = " +
                         show(std::max(result.r_squared, -1e6)) + " (the best fit explains less than " +
                         show(100.0 * kMinimumRSquared) +
                         " % of the variance of the forces; noise, wrong columns or wrong fixed parameters?)");
  }

  // ---- interpolation check: the exact model at (up to 200 of) the data points ----
  Lattice& lattice = model.lattice(best.film_modulus);
  const double E = reduced_modulus_of(problem, best.film_modulus);
  const std::size_t stride = std::max<std::size_t>(1, n / 200);
  double interpolation_error = 0.0;
  for (std::size_t i = 0; i < n; i += stride) {
    const double a = m.radius[i];
    const PointModel exact = point_model(lattice.exact(a / best.thickness), E, problem.sphere_radius, best, a);
    double error = exact.force - m.force[i];
    if (data.kind == DataKind::kPenetrationForce && !m.clamped[i]) {
      // Moving to the exact curve at fixed delta changes F by -dF/ddelta * (delta mismatch).
      error -= m.slope[i] * (exact.penetration - m.penetration[i]);
    }
    interpolation_error = std::max(interpolation_error, std::fabs(error));
  }
  result.interpolation_error = interpolation_error;
  result.lattice_nodes = lattice.node_count();
  result.solver_tolerance = lattice.tolerance_used();
  result.solver_calls = model.solver_calls();
  result.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
  return result;
}

CurvePoint exact_point(const Problem& problem, double radius) {
  if (!(radius > 0.0) || !(problem.thickness > 0.0)) throw InputError("exact_point: a and t must be > 0");
  GslHandlerOff handler_off;
  ReducedSolver solver(Stack::film_on(problem.film, problem.substrate));
  const ReducedVariables v = solver.solve(radius / problem.thickness, problem.solver_tolerance);
  const Reduced r{v.pi_s, v.delta_s, v.e_eq, v.gamma1, 0.0, 0.0, 0.0, 0.0};
  const Parameters p{problem.work, problem.thickness, problem.film.youngs_modulus};
  const PointModel m =
      point_model(r, problem.film.reduced_modulus(), problem.sphere_radius, p, radius);
  return {radius, m.penetration, m.force};
}

std::vector<CurvePoint> model_curve(const Problem& problem, double radius_min, double radius_max,
                                    int count) {
  if (!(radius_min > 0.0) || !(radius_max >= radius_min) || count < 2) {
    throw InputError("model_curve: need 0 < a_min <= a_max and at least 2 points");
  }
  GslHandlerOff handler_off;
  Lattice lattice(problem.film, problem.substrate, problem.nodes_per_decade, problem.solver_tolerance);
  lattice.cover(radius_min / problem.thickness, radius_max / problem.thickness);
  const Parameters p{problem.work, problem.thickness, problem.film.youngs_modulus};
  std::vector<CurvePoint> curve;
  for (int i = 0; i < count; ++i) {
    const double a = radius_min * std::pow(radius_max / radius_min, static_cast<double>(i) / (count - 1));
    const PointModel m = point_model(lattice.eval(a / problem.thickness), problem.film.reduced_modulus(),
                                     problem.sphere_radius, p, a);
    curve.push_back({a, m.penetration, m.force});
  }
  return curve;
}

}  // namespace coatcontact::fit
