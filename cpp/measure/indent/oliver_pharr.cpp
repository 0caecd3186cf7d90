// Oliver–Pharr on one test and the calibration on a reference (THEORY.md section 16).
#include "coatcontact/oliver_pharr.hpp"

#include <gsl/gsl_multifit.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include "coatcontact/detail/brent.hpp"
#include "coatcontact/detail/format.hpp"
#include "coatcontact/detail/gsl_handler_off.hpp"
#include "coatcontact/errors.hpp"

namespace coatcontact::indent {
namespace {

constexpr double kPi = 3.14159265358979323846;

bool positive(double x) { return std::isfinite(x) && x > 0.0; }

std::string num(double x) { return detail::short_text(x); }

void require_option(bool ok, const std::string& name, double value, const std::string& allowed) {
  if (!ok) throw InputError(name + " = " + num(value) + " is not allowed: " + allowed);
}

void check_options(const OliverPharrOptions& o) {
  require_option(positive(o.beta), "beta", o.beta, "a positive number (1 by default, ~1.05 for a Berkovich)");
  require_option(std::isfinite(o.epsilon) && o.epsilon >= 0.0 && o.epsilon <= 1.0, "epsilon", o.epsilon,
                 "a number in [0, 1] (0.75 for a Berkovich or a paraboloid, 0.727 for a cone)");
  require_option(std::isnan(o.frame_stiffness) || positive(o.frame_stiffness), "frame stiffness",
                 o.frame_stiffness, "a positive stiffness in N/m, or none");
  require_option(o.unload_lower >= 0.0 && o.unload_lower < o.unload_upper && o.unload_upper <= 1.0,
                 "unloading fit range lower", o.unload_lower, "0 <= lower < upper <= 1 (fractions of P_max)");
  require_option(std::isnan(o.depth_min) || (std::isfinite(o.depth_min) && o.depth_min >= 0.0),
                 "depth range minimum", o.depth_min, "a depth >= 0 in m");
  require_option(std::isnan(o.depth_max) || (positive(o.depth_max) && !(o.depth_max <= o.depth_min)),
                 "depth range maximum", o.depth_max, "a depth in m above the minimum");
  validate(o.indenter);
}

std::size_t max_load_index(const std::vector<double>& load) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < load.size(); ++i)
    if (load[i] > load[best]) best = i;
  return best;
}

// Linear least squares of y = c + m x; returns {c, m}.
std::pair<double, double> line_fit(const std::vector<double>& x, const std::vector<double>& y) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    sx += x[i]; sy += y[i]; sxx += x[i] * x[i]; sxy += x[i] * y[i];
  }
  const double m = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  return {(sy - m * sx) / n, m};
}

void average(OliverPharrResult& r) {
  double se = 0, sh = 0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < r.depth.size(); ++i) {
    if (!r.in_range[i]) continue;
    se += r.modulus[i]; sh += r.hardness[i]; ++n;
  }
  r.range_points = n;
  if (n == 0)
    throw InputError("no analysed point lies in the depth range [" + num(r.range_min) + ", " + num(r.range_max) +
                     "] m; give a range inside [" + num(r.depth.front()) + ", " + num(r.depth.back()) + "] m");
  r.modulus_mean = se / n;
  r.hardness_mean = sh / n;
  double ve = 0, vh = 0;
  for (std::size_t i = 0; i < r.depth.size(); ++i) {
    if (!r.in_range[i]) continue;
    ve += (r.modulus[i] - r.modulus_mean) * (r.modulus[i] - r.modulus_mean);
    vh += (r.hardness[i] - r.hardness_mean) * (r.hardness[i] - r.hardness_mean);
  }
  r.modulus_sd = n > 1 ? std::sqrt(ve / (n - 1)) : 0.0;
  r.hardness_sd = n > 1 ? std::sqrt(vh / (n - 1)) : 0.0;
}

// The points to analyse, frame-corrected: CSM loading points or the start of the unloading.
void collect_points(const IndentTest& test, const OliverPharrOptions& o, OliverPharrResult& r) {
  const bool has_csm = !test.stiffness.empty();
  if (o.stiffness == StiffnessSource::kCsm && !has_csm)
    throw InputError("stiffness = csm: test '" + test.name + "' has no CSM stiffness channel");
  r.csm = o.stiffness == StiffnessSource::kCsm || (o.stiffness == StiffnessSource::kAuto && has_csm);
  const double compliance = std::isnan(o.frame_stiffness) ? 0.0 : 1.0 / o.frame_stiffness;
  const bool use_h = o.area_from_hardness;
  if (use_h && test.hardness.size() != test.depth.size())
    throw InputError("area = hardness: test '" + test.name + "' has no hardness column");
  const std::size_t top = max_load_index(test.load);
  if (r.csm) {
    for (std::size_t i = 0; i <= top && i < test.stiffness.size(); ++i) {
      const double p = test.load[i], s_meas = test.stiffness[i];
      if (!positive(p) || !positive(s_meas) || !std::isfinite(test.depth[i])) continue;
      if (use_h && !positive(test.hardness[i])) continue;
      const double inv_s = 1.0 / s_meas - compliance;
      if (!(inv_s > 0.0)) continue;
      r.depth.push_back(test.depth[i] - p * compliance);
      r.load.push_back(p);
      r.stiffness.push_back(1.0 / inv_s);
      if (use_h) r.area.push_back(p / test.hardness[i]);
    }
  } else {
    std::vector<double> h(test.depth);
    for (std::size_t i = 0; i < h.size(); ++i) h[i] -= test.load[i] * compliance;
    r.unloading = fit_unloading(h, test.load, o.unload_lower, o.unload_upper);
    r.depth.push_back(r.unloading.max_depth);
    r.load.push_back(r.unloading.max_load);
    r.stiffness.push_back(r.unloading.stiffness);
    if (use_h) {
      if (!positive(test.hardness[top])) throw InputError("area = hardness: the hardness at P_max is not positive");
      r.area.push_back(r.unloading.max_load / test.hardness[top]);
    }
  }
  if (r.depth.empty())
    throw InputError("test '" + test.name + "': no point with positive load and stiffness to analyse");
}

}  // namespace

double contact_area(const AreaFunction& area, double contact_depth) {
  if (area.coefficients.empty()) throw InputError("the area function has no coefficients");
  if (!(contact_depth > 0.0)) return 0.0;
  const double h = contact_depth * 1e9;  // nm
  double a = 0.0, exponent = 2.0;
  for (double c : area.coefficients) {
    a += c * std::pow(h, exponent);
    exponent *= 0.5;
  }
  return a * 1e-18;
}

double reduced_modulus(double stiffness, double area, double beta) {
  return std::sqrt(kPi) * stiffness / (2.0 * beta * std::sqrt(area));
}

double sample_modulus(double reduced, double poisson, const Indenter& indenter) {
  double inv = 1.0 / reduced;
  if (!indenter.rigid) inv -= 1.0 / indenter.material.reduced_modulus();
  if (!(inv > 0.0))
    throw NumericalError("the reduced modulus " + num(reduced) + " Pa is not below the indenter's E* " +
                         num(indenter.material.reduced_modulus()) + " Pa: no sample modulus");
  return (1.0 - poisson * poisson) / inv;
}

double reduced_of_sample(double modulus, double poisson, const Indenter& indenter) {
  double inv = (1.0 - poisson * poisson) / modulus;
  if (!indenter.rigid) inv += 1.0 / indenter.material.reduced_modulus();
  return 1.0 / inv;
}

UnloadingFit fit_unloading(const std::vector<double>& depth, const std::vector<double>& load, double lower,
                           double upper) {
  if (depth.size() != load.size() || depth.size() < 4)
    throw InputError("the unloading fit needs depth and load of equal length, at least 4 points");
  const std::size_t top = max_load_index(load);
  const double pmax = load[top];
  std::vector<double> h, p;
  for (std::size_t j = top; j < load.size(); ++j) {
    if (load[j] < lower * pmax) break;
    if (load[j] <= upper * pmax && std::isfinite(depth[j])) { h.push_back(depth[j]); p.push_back(load[j]); }
  }
  if (h.size() < 4)
    throw InputError("the unloading has " + std::to_string(h.size()) + " points between " + num(lower) + " and " +
                     num(upper) + " of P_max (at least 4 needed): is there an unloading segment?");
  const double hmin = *std::min_element(h.begin(), h.end());
  const double hmax = depth[top];
  UnloadingFit fit;
  // For a given h_f the power law is a line in log-log; profile the relative residual over
  // s = hmin - h_f on a log grid, then Brent.
  auto solve = [&](double log_s, UnloadingFit* out) {
    const double hf = hmin - std::exp(log_s);
    std::vector<double> x(h.size()), y(h.size());
    for (std::size_t i = 0; i < h.size(); ++i) { x[i] = std::log(h[i] - hf); y[i] = std::log(p[i]); }
    const auto [c, m] = line_fit(x, y);
    double ss = 0;
    for (std::size_t i = 0; i < h.size(); ++i) {
      const double r = (p[i] - std::exp(c + m * x[i])) / p[i];
      ss += r * r;
    }
    if (out) { out->alpha = std::exp(c); out->exponent = m; out->final_depth = hf; out->rms_relative = std::sqrt(ss / h.size()); }
    return ss;
  };
  const double span = std::max(hmax, 1e-12);
  const double lo = std::log(1e-6 * span), hi = std::log(10.0 * span);
  const int n = 80;
  int best = 0;
  std::vector<double> v(n + 1);
  for (int k = 0; k <= n; ++k) {
    v[k] = solve(lo + (hi - lo) * k / n, nullptr);
    if (v[k] < v[best]) best = k;
  }
  double xbest = lo + (hi - lo) * best / n;
  if (best > 0 && best < n) {
    const auto m = detail::brent_minimum([&](double s) { return solve(s, nullptr); }, lo + (hi - lo) * (best - 1) / n,
                                         v[best - 1], xbest, v[best], lo + (hi - lo) * (best + 1) / n, v[best + 1],
                                         {0.0, 1e-10, 200});
    if (m) xbest = m->x;
  }
  solve(xbest, &fit);
  fit.max_depth = hmax;
  fit.max_load = pmax;
  fit.points = h.size();
  fit.stiffness = fit.exponent * fit.alpha * std::pow(hmax - fit.final_depth, fit.exponent - 1.0);
  if (!positive(fit.stiffness) || !std::isfinite(fit.exponent))
    throw NumericalError("the unloading power-law fit gave no positive stiffness");
  return fit;
}

OliverPharrResult oliver_pharr(const IndentTest& test, const OliverPharrOptions& o) {
  check_options(o);
  OliverPharrResult r;
  r.poisson = std::isnan(o.poisson) ? test.calibration.poisson : o.poisson;
  if (std::isnan(r.poisson))
    throw InputError("test '" + test.name + "' states no Poisson ratio: give the sample's (poisson; CLI --poisson)");
  require_option(r.poisson > -1.0 && r.poisson <= 0.5, "poisson", r.poisson, "a ratio in (-1, 0.5]");
  const AreaFunction& area = o.area.coefficients.empty() ? test.calibration.area : o.area;
  if (!o.area_from_hardness && area.coefficients.empty())
    throw InputError("test '" + test.name + "' states no area function: give its coefficients (area; CLI --area C0,C1,..)");
  collect_points(test, o, r);
  std::vector<double> keep_depth, keep_load, keep_s, keep_hc, keep_a;
  const double indenter_compliance = o.indenter.rigid ? 0.0 : 1.0 / o.indenter.material.reduced_modulus();
  for (std::size_t i = 0; i < r.depth.size(); ++i) {
    const double hc = r.depth[i] - o.epsilon * r.load[i] / r.stiffness[i];
    const double a = o.area_from_hardness ? r.area[i] : contact_area(area, hc);
    // Near the surface h_c, A or 1/E_r - 1/E_i* can come out <= 0 (the tip's first contact).
    if (!(a > 0.0) || !(hc > 0.0) || !(1.0 / reduced_modulus(r.stiffness[i], a, o.beta) > indenter_compliance)) {
      ++r.dropped;
      continue;
    }
    keep_depth.push_back(r.depth[i]); keep_load.push_back(r.load[i]); keep_s.push_back(r.stiffness[i]);
    keep_hc.push_back(hc); keep_a.push_back(a);
  }
  if (keep_depth.empty()) throw InputError("test '" + test.name + "': no point with a positive contact depth and area");
  r.depth = keep_depth; r.load = keep_load; r.stiffness = keep_s; r.contact_depth = keep_hc; r.area = keep_a;
  r.range_min = !std::isnan(o.depth_min) ? o.depth_min : std::isnan(test.calibration.range_min) ? 0.0 : test.calibration.range_min;
  r.range_max = !std::isnan(o.depth_max) ? o.depth_max
              : std::isnan(test.calibration.range_max) ? std::numeric_limits<double>::infinity() : test.calibration.range_max;
  for (std::size_t i = 0; i < r.depth.size(); ++i) {
    const double er = reduced_modulus(r.stiffness[i], r.area[i], o.beta);
    r.contact_radius.push_back(std::sqrt(r.area[i] / kPi));
    r.reduced_modulus.push_back(er);
    r.modulus.push_back(sample_modulus(er, r.poisson, o.indenter));
    r.hardness.push_back(r.load[i] / r.area[i]);
    r.in_range.push_back(!r.csm || (r.depth[i] >= r.range_min && r.depth[i] <= r.range_max));
  }
  average(r);
  return r;
}

// ---- calibration -----------------------------------------------------------------------

namespace {

struct CalibrationPoint { double depth, load, stiffness; };

std::vector<CalibrationPoint> calibration_points(const std::vector<IndentTest>& tests, const CalibrationOptions& o) {
  std::vector<CalibrationPoint> pts;
  for (const auto& t : tests) {
    if (!t.stiffness.empty()) {
      const std::size_t top = max_load_index(t.load);
      for (std::size_t i = 0; i <= top && i < t.stiffness.size(); ++i) {
        if (!positive(t.load[i]) || !positive(t.stiffness[i]) || !positive(t.depth[i])) continue;
        if (!std::isnan(o.depth_min) && t.depth[i] < o.depth_min) continue;
        if (!std::isnan(o.depth_max) && t.depth[i] > o.depth_max) continue;
        pts.push_back({t.depth[i], t.load[i], t.stiffness[i]});
      }
    } else {
      const UnloadingFit f = fit_unloading(t.depth, t.load);
      pts.push_back({f.max_depth, f.max_load, f.stiffness});
    }
  }
  return pts;
}

struct GslMatrix { gsl_matrix* m; ~GslMatrix() { gsl_matrix_free(m); } };
struct GslVector { gsl_vector* v; ~GslVector() { gsl_vector_free(v); } };

}  // namespace

AreaCalibration calibrate_area(const std::vector<IndentTest>& tests, const CalibrationOptions& o) {
  require_option(o.terms >= 1 && o.terms <= 9, "terms", static_cast<double>(o.terms), "1 to 9 coefficients");
  validate(o.reference, "reference");
  const auto pts = calibration_points(tests, o);
  const bool hold = !std::isnan(o.fixed_c0);
  const std::size_t free = o.terms - (hold ? 1 : 0);
  if (pts.size() < free + 1)
    throw InputError("area calibration: " + std::to_string(pts.size()) + " points for " + std::to_string(free) +
                     " coefficients; give more tests or a wider depth range");
  const double er = reduced_of_sample(o.reference.youngs_modulus, o.reference.poisson_ratio, o.indenter);
  const std::size_t n = pts.size();
  GslMatrix x{gsl_matrix_alloc(n, free ? free : 1)};
  GslVector y{gsl_vector_alloc(n)}, w{gsl_vector_alloc(n)}, c{gsl_vector_alloc(free ? free : 1)};
  GslMatrix cov{gsl_matrix_alloc(free ? free : 1, free ? free : 1)};
  std::vector<double> hc_nm(n), a_nm(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double hc = pts[i].depth - o.epsilon * pts[i].load / pts[i].stiffness;
    const double s = pts[i].stiffness / (o.beta * er);
    hc_nm[i] = hc * 1e9;
    a_nm[i] = kPi * s * s / 4.0 * 1e18;
    if (!(hc > 0.0)) throw InputError("area calibration: a point has contact depth <= 0; raise the depth range minimum");
    double e = 2.0, target = a_nm[i];
    std::size_t col = 0;
    for (std::size_t k = 0; k < o.terms; ++k, e *= 0.5) {
      if (k == 0 && hold) { target -= o.fixed_c0 * hc_nm[i] * hc_nm[i]; continue; }
      gsl_matrix_set(x.m, i, col++, std::pow(hc_nm[i], e));
    }
    gsl_vector_set(y.v, i, target);
    gsl_vector_set(w.v, i, 1.0 / (a_nm[i] * a_nm[i]));
  }
  AreaCalibration out;
  out.points = n;
  if (free > 0) {
    detail::GslHandlerOff guard;
    double chisq = 0;
    std::unique_ptr<gsl_multifit_linear_workspace, void (*)(gsl_multifit_linear_workspace*)> ws(
        gsl_multifit_linear_alloc(n, free), gsl_multifit_linear_free);
    if (gsl_multifit_wlinear(x.m, w.v, y.v, c.v, cov.m, &chisq, ws.get()) != 0)
      throw NumericalError("area calibration: the linear least squares failed");
    const double s2 = n > free ? chisq / (n - free) : 0.0;
    std::size_t col = 0;
    for (std::size_t k = 0; k < o.terms; ++k) {
      if (k == 0 && hold) { out.area.coefficients.push_back(o.fixed_c0); out.errors.push_back(0.0); continue; }
      out.area.coefficients.push_back(gsl_vector_get(c.v, col));
      out.errors.push_back(std::sqrt(gsl_matrix_get(cov.m, col, col) * s2));
      ++col;
    }
  } else {
    out.area.coefficients = {o.fixed_c0};
    out.errors = {0.0};
  }
  double ss = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double r = (a_nm[i] - contact_area(out.area, hc_nm[i] * 1e-9) * 1e18) / a_nm[i];
    ss += r * r;
  }
  out.rms_relative = std::sqrt(ss / n);
  return out;
}

FrameCalibration calibrate_frame(const std::vector<IndentTest>& tests, const CalibrationOptions& o) {
  const auto pts = calibration_points(tests, o);
  if (pts.size() < 3) throw InputError("frame calibration: fewer than 3 points; give more tests or a wider range");
  std::vector<double> x, y;
  for (const auto& p : pts) { x.push_back(1.0 / std::sqrt(p.load)); y.push_back(1.0 / p.stiffness); }
  const auto [c, m] = line_fit(x, y);
  const double n = static_cast<double>(x.size());
  double ss = 0, sx = 0, sxx = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double r = y[i] - c - m * x[i];
    ss += r * r; sx += x[i]; sxx += x[i] * x[i];
  }
  const double s2 = ss / (n - 2), d = n * sxx - sx * sx;
  FrameCalibration f;
  f.compliance = c;
  f.slope = m;
  f.compliance_error = std::sqrt(s2 * sxx / d);
  f.frame_stiffness = c > 0 ? 1.0 / c : std::numeric_limits<double>::infinity();
  f.points = pts.size();
  return f;
}

}  // namespace coatcontact::indent
