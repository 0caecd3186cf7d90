// The film's modulus or thickness from the Oliver–Pharr stiffness (THEORY.md section 16): per
// depth a root of S = 2 beta a E_ref E_eq(a/t), over a range a Gauss–Newton fit of ln S with
// the standard error from the scatter; the empirical models the same way on their formulas.
#include "coatcontact/indent_film.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <string>

#include "coatcontact/detail/brent.hpp"
#include "coatcontact/detail/format.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/reduced.hpp"
#include "coatcontact/reduced_table.hpp"
#include "parallel.hpp"

namespace coatcontact::indent {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kConeEpsilon = 2.0 - 4.0 / kPi;  // the homogeneous cone's sink-in factor

std::string num(double x) { return detail::short_text(x); }

struct TableAt;

// One analysed depth: the measured values and the half-space contact geometry.
struct Pt {
  double h, p, s, hc, a;
};

// The geometry a prediction used (the coated contact depth moves a with the stack).
struct Geo {
  double hc = 0, a = 0, x = 0;
};

// Everything the predictions need besides the parameter.
struct Setup {
  FilmOptions o;
  Indenter indenter;
  double beta = 1.0, epsilon = 0.75;
  std::function<double(double)> area;  // A(h_c) [m^2]; empty when the area is P/H
  double thickness = 0.0;              // total T (modulus unknown)
  double top_modulus = 0.0;            // kThickness: the film's given E
  std::shared_ptr<const TableAt> fixed;  // kThickness, exact: the one stack
};

Stack stack_of(const Setup& st, double top_modulus) {
  std::vector<Layer> layers = st.o.layers;
  layers.front().material.youngs_modulus = top_modulus;
  return Stack(layers, st.o.substrate, st.indenter);
}

// kappa = eps_c(a/t) / (2 - 4/pi) from the cone's reduced variables (section 16).
double kappa_of(const ReducedValues& v) {
  return 8.0 * v.e_eq / (kPi * v.pi_c) * (0.5 * kPi * v.delta_c - 1.0) / kConeEpsilon;
}

// The contact geometry at thickness t: half-space, or the coated sink-in iterated with
// kappa(x) from `cone` (x -> reduced values).
Geo geometry(const Setup& st, const Pt& pt, double t, const std::function<ReducedValues(double)>& cone) {
  Geo g{pt.hc, pt.a, pt.a / t};
  if (st.o.contact_depth != ContactDepth::kCoated) return g;
  for (int it = 0; it < 50; ++it) {
    const double hc = pt.h - st.epsilon * kappa_of(cone(g.x)) * pt.p / pt.s;
    const double a = std::sqrt(st.area(hc) / kPi);
    if (!(a > 0.0)) throw NumericalError("the coated contact depth at h = " + num(pt.h) + " m is not positive");
    const bool done = std::fabs(a - g.a) <= 1e-12 * a;
    g = {hc, a, a / t};
    if (done) break;
  }
  return g;
}

// ln of the predicted stiffness at one point from the composite's E_r = E_ref E_eq.
double log_stiffness(const Setup& st, const Geo& g, double er) { return std::log(2.0 * st.beta * g.a * er); }

// ---- the stack at one parameter value, interpolated over the points' a/t --------------

struct TableAt {
  std::unique_ptr<Stack> stack;
  std::unique_ptr<ReducedSolver> solver;
  std::unique_ptr<SolverSource> source;
  std::unique_ptr<ReducedTable> table;
  TableAt(const Stack& s, double tolerance)
      : stack(std::make_unique<Stack>(s)),
        solver(std::make_unique<ReducedSolver>(*stack)),
        source(std::make_unique<SolverSource>(*solver, tolerance)),
        table(std::make_unique<ReducedTable>(*source)) {}
  ReducedValues at(double x) const { return table->at(x, ReducedTable::Variables::kCone); }
};

// The empirical prediction of E_r at one geometry for film E_f' = exp(u).
double empirical_er(const Setup& st, const Geo& g, double u, double alpha) {
  const Material& f = st.o.layers.front().material;
  EmpiricalConstants c;
  c.substrate_reduced = st.o.substrate.material.reduced_modulus();
  c.film_poisson = f.poisson_ratio;
  c.substrate_poisson = st.o.substrate.material.poisson_ratio;
  c.alpha = alpha;
  const double ep = empirical_apparent(st.o.model, {st.thickness, g.a, g.hc}, std::exp(u), c);
  return reduced_of_sample(ep * (1.0 - f.poisson_ratio * f.poisson_ratio), f.poisson_ratio, st.indenter);
}

// ln S predicted at every point for parameter u (ln E1, ln t or ln E_f').
std::vector<double> predict(const Setup& st, const std::vector<Pt>& pts, double u, double alpha) {
  std::vector<double> out(pts.size());
  if (st.o.model != FilmModel::kExact) {
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const Geo g{pts[i].hc, pts[i].a, pts[i].a / st.thickness};
      out[i] = log_stiffness(st, g, empirical_er(st, g, u, alpha));
    }
    return out;
  }
  const bool modulus = st.o.unknown == FilmUnknown::kModulus;
  std::shared_ptr<const TableAt> own;
  if (modulus) own = std::make_shared<const TableAt>(stack_of(st, std::exp(u)), st.o.tolerance);
  const TableAt& tab = modulus ? *own : *st.fixed;
  const double t = modulus ? st.thickness : std::exp(u);
  const double eref = tab.stack->reference_modulus();
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const Geo g = geometry(st, pts[i], t, [&](double x) { return tab.at(x); });
    out[i] = log_stiffness(st, g, eref * tab.at(g.x).e_eq);
  }
  return out;
}

// ---- per depth: a root in u -------------------------------------------------------------

// ln S predicted at one point, and its geometry, without a table (the exact modulus: each
// trial E1 is its own stack, solved at one a/t).
double predict_one(const Setup& st, const Pt& pt, double u, double alpha, Geo* geo) {
  if (st.o.model != FilmModel::kExact) {
    const Geo g{pt.hc, pt.a, pt.a / st.thickness};
    if (geo) *geo = g;
    return log_stiffness(st, g, empirical_er(st, g, u, alpha));
  }
  const bool modulus = st.o.unknown == FilmUnknown::kModulus;
  std::unique_ptr<ReducedSolver> own;
  if (modulus) own = std::make_unique<ReducedSolver>(stack_of(st, std::exp(u)));
  const ReducedSolver& solver = modulus ? *own : *st.fixed->solver;
  const double t = modulus ? st.thickness : std::exp(u);
  auto cone = [&](double x) -> ReducedValues { return solver.solve(x, st.o.tolerance); };
  const Geo g = geometry(st, pt, t, cone);
  if (geo) *geo = g;
  return log_stiffness(st, g, solver.stack().reference_modulus() * cone(g.x).e_eq);
}

double root_one(const Setup& st, const Pt& pt, double u0, double alpha, Geo* geo) {
  const double target = std::log(pt.s);
  auto f = [&](double u) { return predict_one(st, pt, u, alpha, nullptr) - target; };
  // Step u towards the sign change (S grows with E1; with t it grows or falls with the substrate).
  double lo = u0, flo = f(u0), hi = u0, fhi = flo;
  const double slope = f(u0 + 0.02) - flo;
  double step = 0.02 * ((flo > 0) == (slope > 0) ? -1.0 : 1.0);  // doubled until the sign changes
  for (int k = 0; k < 40 && (flo > 0) == (fhi > 0); ++k, step *= 2.0) {
    lo = hi; flo = fhi;
    hi = hi + step;
    fhi = f(hi);
  }
  if ((flo > 0) == (fhi > 0))
    throw NumericalError("no film " + std::string(st.o.unknown == FilmUnknown::kModulus ? "modulus" : "thickness") +
                         " reproduces the stiffness " + num(pt.s) + " N/m at depth " + num(pt.h) + " m");
  const auto r = detail::brent_root(f, std::min(lo, hi), std::max(lo, hi), {1e-11, 0.0, 200});
  if (!r || !r->converged) throw NumericalError("the film root at depth " + num(pt.h) + " m did not converge");
  predict_one(st, pt, r->x, alpha, geo);
  return r->x;
}

// ---- per depth, exact modulus, half-space contact depth: stacks on a grid of ln E1 -------
//
// Each trial E1 is a new kernel table (~15 ms), and the roots of neighbouring depths lie close
// together: so the stacks sit on nodes u_j = u_c + j du (du = 0.05) shared by every depth, and a
// depth's root is that of the cubic through the four nodes around it (interpolation error
// ~du^4/24 times the fourth derivative of the smooth ln(E_ref E_eq) in ln E1).
class ModulusNodes {
 public:
  ModulusNodes(const Setup& st, double centre) : st_(st), centre_(centre) {}
  static constexpr double kStep = 0.05;
  static constexpr int kReach = 200;  // nodes each way: E1 within e^(+-10) of the centre

  // ln(E_ref E_eq) at node j and a/t = x.
  double value(int j, double x) {
    auto it = solvers_.find(j);
    if (it == solvers_.end())
      it = solvers_.emplace(j, std::make_unique<ReducedSolver>(stack_of(st_, std::exp(u(j))))).first;
    const ReducedSolver& s = *it->second;
    return std::log(s.stack().reference_modulus() * s.solve(x, st_.o.tolerance).e_eq);
  }
  double u(int j) const { return centre_ + kStep * j; }

  // The root in u of ln(E_ref E_eq)(u, x) = y (h only names the depth in messages).
  double root(double x, double y, double h) {
    int j = 0;
    double f0 = value(0, x) - y;
    const int dir = f0 > 0 ? -1 : 1;  // the value grows with E1
    double f1 = value(dir, x) - y;
    while ((f0 > 0) == (f1 > 0)) {
      j += dir;
      if (std::abs(j) > kReach)
        throw NumericalError("no film modulus within e^10 of " + num(std::exp(centre_)) +
                             " Pa reproduces the stiffness at depth " + num(h) + " m");
      f0 = f1;
      f1 = value(j + dir, x) - y;
      // Upwards ln(E_ref E_eq) saturates at the substrate's and the diamond's limit: stop there.
      if (dir > 0 && f1 - f0 < 1e-6 * kStep && (f1 > 0) == (f0 > 0))
        throw NumericalError("the stiffness at depth " + num(h) + " m exceeds what any film modulus gives on this substrate");
    }
    const int lo = std::min(j, j + dir);
    double uu[4], ff[4];
    for (int k = 0; k < 4; ++k) {
      uu[k] = u(lo - 1 + k);
      ff[k] = value(lo - 1 + k, x) - y;
    }
    auto cubic = [&](double v) {
      double sum = 0;
      for (int k = 0; k < 4; ++k) {
        double w = ff[k];
        for (int m = 0; m < 4; ++m)
          if (m != k) w *= (v - uu[m]) / (uu[k] - uu[m]);
        sum += w;
      }
      return sum;
    };
    const auto r = detail::brent_root(cubic, u(lo), u(lo + 1), {1e-13, 0.0, 200});
    if (!r) throw NumericalError("the film root at depth " + num(h) + " m: no sign change between two nodes");
    return r->x;
  }

 private:
  const Setup& st_;
  double centre_;
  std::map<int, std::unique_ptr<ReducedSolver>> solvers_;
};

// ---- over the range: Gauss–Newton in u --------------------------------------------------

struct Fit1 {
  double u = 0, se = 0, s = 0, ssr = 0;
};

Fit1 gauss_newton(const Setup& st, const std::vector<Pt>& pts, double u, double alpha) {
  const double h = 1e-4;
  Fit1 f;
  for (int it = 0; it < 40; ++it) {
    const auto m = predict(st, pts, u, alpha), mp = predict(st, pts, u + h, alpha), mm = predict(st, pts, u - h, alpha);
    double jr = 0, jj = 0, ssr = 0;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const double j = (mp[i] - mm[i]) / (2 * h), r = std::log(pts[i].s) - m[i];
      jr += j * r; jj += j * j; ssr += r * r;
    }
    if (!(jj > 0)) throw NumericalError("the film fit: the stiffness does not depend on the parameter");
    const double du = jr / jj;
    f.ssr = ssr;
    f.s = pts.size() > 1 ? std::sqrt(ssr / (pts.size() - 1)) : 0.0;
    f.se = f.s / std::sqrt(jj);
    f.u = u;
    if (std::fabs(du) < 1e-10) return f;
    u += std::clamp(du, -1.0, 1.0);
  }
  throw NumericalError("the film fit over the depth range did not converge in 40 steps");
}

// The empirical alpha: the one whose fit leaves the smallest residual (grid, then Brent).
double fit_alpha(const Setup& st, const std::vector<Pt>& pts, double u0) {
  auto cost = [&](double la) {
    try { return gauss_newton(st, pts, u0, std::exp(la)).ssr; } catch (const NumericalError&) { return 1e300; }
  };
  const double lo = std::log(1e-2), hi = std::log(1e2);
  const int n = 40;
  std::vector<double> v(n + 1);
  int best = 0;
  for (int k = 0; k <= n; ++k) {
    v[k] = cost(lo + (hi - lo) * k / n);
    if (v[k] < v[best]) best = k;
  }
  double x = lo + (hi - lo) * best / n;
  if (best > 0 && best < n) {
    const auto m = detail::brent_minimum(cost, lo + (hi - lo) * (best - 1) / n, v[best - 1], x, v[best],
                                         lo + (hi - lo) * (best + 1) / n, v[best + 1], {1e-8, 0.0, 100});
    if (m) x = m->x;
  }
  return std::exp(x);
}

void check_film_options(const FilmOptions& o) {
  if (o.layers.empty()) throw InputError("layers: the film needs at least one layer (the film)");
  if (o.unknown == FilmUnknown::kThickness && o.layers.size() != 1)
    throw InputError("the thickness is found for one film only; " + std::to_string(o.layers.size()) + " layers given");
  if (o.model != FilmModel::kExact && (o.layers.size() != 1 || o.substrate.rigid))
    throw InputError(std::string("model = ") + film_model_name(o.model) +
                     " needs one film on an elastic substrate (use model = exact for layers or a rigid base)");
  if (o.model != FilmModel::kExact && o.unknown == FilmUnknown::kThickness)
    throw InputError(std::string("model = ") + film_model_name(o.model) + " gives the modulus only; the thickness needs model = exact");
  if (o.model != FilmModel::kExact && o.contact_depth == ContactDepth::kCoated)
    throw InputError("contact depth = coated comes from the exact solution: use it with model = exact");
  if (!std::isnan(o.alpha) && !(std::isfinite(o.alpha) && o.alpha > 0))
    throw InputError("alpha = " + num(o.alpha) + " is not allowed: a positive number, or none to fit it");
  if (o.max_points < 1) throw InputError("max points = 0 is not allowed: at least 1");
  check_tolerance(o.tolerance);
  for (const Layer& l : o.layers)
    if (!(std::isfinite(l.thickness) && l.thickness > 0))
      throw InputError("layer thickness = " + num(l.thickness) + " m is not allowed: a positive length");
}

}  // namespace

double stack_contact_modulus(const FilmOptions& o, const Indenter& indenter, double top_modulus, double a_over_t) {
  Setup st;
  st.o = o;
  st.indenter = indenter;
  const Stack s = stack_of(st, top_modulus);
  return s.reference_modulus() * ReducedSolver(s).solve(a_over_t, o.tolerance).e_eq;
}

FilmResult film(const IndentTest& test, const OliverPharrOptions& op_options, const FilmOptions& o) {
  check_film_options(o);
  Setup st;
  st.o = o;
  st.indenter = op_options.indenter;
  st.beta = op_options.beta;
  st.epsilon = op_options.epsilon;
  for (const Layer& l : o.layers) st.thickness += l.thickness;
  st.top_modulus = o.layers.front().material.youngs_modulus;
  validate(o.substrate);
  if (o.unknown == FilmUnknown::kThickness && o.model == FilmModel::kExact)
    st.fixed = std::make_shared<const TableAt>(stack_of(st, st.top_modulus), o.tolerance);
  OliverPharrOptions opo = op_options;
  opo.poisson = o.layers.front().material.poisson_ratio;
  if (!std::isnan(o.depth_min)) opo.depth_min = o.depth_min;
  if (!std::isnan(o.depth_max)) opo.depth_max = o.depth_max;
  const OliverPharrResult op = oliver_pharr(test, opo);
  if (o.contact_depth == ContactDepth::kCoated) {
    if (opo.area_from_hardness) throw InputError("contact depth = coated needs an area function (not area = hardness)");
    const AreaFunction af = opo.area.coefficients.empty() ? test.calibration.area : opo.area;
    st.area = [af](double hc) { return contact_area(af, hc); };
  }
  std::vector<Pt> all, range;
  for (std::size_t i = 0; i < op.depth.size(); ++i) {
    all.push_back({op.depth[i], op.load[i], op.stiffness[i], op.contact_depth[i], op.contact_radius[i]});
    if (op.in_range[i]) range.push_back(all.back());
  }
  FilmResult r;
  r.unknown = o.unknown;
  r.model = o.model;
  r.range_min = op.range_min;
  r.range_max = op.range_max;
  const bool modulus = o.unknown == FilmUnknown::kModulus;
  const double nu = opo.poisson;
  // Start: the composite's own modulus (E1) or the film's thickness.
  const double u0 = modulus ? std::log(op.modulus_mean / (o.model == FilmModel::kExact ? 1.0 : 1.0 - nu * nu))
                            : std::log(st.thickness);
  r.alpha = film_model_has_alpha(o.model) ? (std::isnan(o.alpha) ? fit_alpha(st, range, u0) : o.alpha) : kNotGiven;
  const Fit1 fit = gauss_newton(st, range, u0, r.alpha);
  const double to_value = o.model == FilmModel::kExact ? 1.0 : 1.0 - nu * nu;  // E_f' -> E_f
  r.mean = std::exp(fit.u) * to_value;
  r.mean_error = r.mean * fit.se;
  r.points = range.size();
  r.rms_relative = fit.s;
  // Per depth, at most max_points evenly spread.
  const std::size_t n = std::min(all.size(), o.max_points);
  std::vector<std::size_t> pick(n);
  for (std::size_t k = 0; k < n; ++k) pick[k] = n == 1 ? all.size() - 1 : k * (all.size() - 1) / (n - 1);
  std::vector<Geo> geo(n);
  std::vector<double> u;
  if (o.model == FilmModel::kExact && modulus && o.contact_depth == ContactDepth::kHalfSpace) {
    ModulusNodes nodes(st, fit.u);
    r.status.assign(n, PointStatus{});
    for (std::size_t k = 0; k < n; ++k) {
      const Pt& p = all[pick[k]];
      geo[k] = {p.hc, p.a, p.a / st.thickness};
      try {
        u.push_back(nodes.root(geo[k].x, std::log(p.s / (2.0 * st.beta * p.a)), p.h));
      } catch (const NumericalError& e) {
        u.push_back(0.0);
        r.status[k] = PointStatus{false, e.what()};
      }
    }
  } else {
    u = detail::parallel_points<double>(
        n, [&](std::size_t k) { return root_one(st, all[pick[k]], fit.u, r.alpha, &geo[k]); },
        [](std::size_t) { return 0.0; }, r.status);
  }
  // The sensitivity d ln S / du at each depth, at the fitted u (an empirical model can be out
  // of its range at some depths: their error is 0 and they are not delivered anyway).
  std::vector<Pt> picked;
  for (auto k : pick) picked.push_back(all[k]);
  std::vector<double> up(n, 0.0), um(n, 0.0);
  if (o.model == FilmModel::kExact) {
    up = predict(st, picked, fit.u + 1e-4, r.alpha);
    um = predict(st, picked, fit.u - 1e-4, r.alpha);
  } else {
    for (std::size_t k = 0; k < n; ++k) {
      try {
        up[k] = predict_one(st, picked[k], fit.u + 1e-4, r.alpha, nullptr);
        um[k] = predict_one(st, picked[k], fit.u - 1e-4, r.alpha, nullptr);
      } catch (const NumericalError&) {
        up[k] = um[k] = 0.0;
      }
    }
  }
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = pick[k];
    const bool ok = r.status[k].delivered;
    r.depth.push_back(op.depth[i]);
    r.load.push_back(op.load[i]);
    r.stiffness.push_back(op.stiffness[i]);
    r.contact_depth.push_back(ok ? geo[k].hc : op.contact_depth[i]);
    r.contact_radius.push_back(ok ? geo[k].a : op.contact_radius[i]);
    const double t = modulus ? st.thickness : (ok ? std::exp(u[k]) : st.thickness);
    r.a_over_t.push_back(r.contact_radius.back() / t);
    r.apparent_modulus.push_back(op.modulus[i]);
    r.in_range.push_back(op.in_range[i]);
    const double value = ok ? std::exp(u[k]) * to_value : 0.0;
    const double j = std::fabs(up[k] - um[k]) / 2e-4;
    r.value.push_back(value);
    r.value_error.push_back(ok && j > 0 ? value * fit.s / j : 0.0);
  }
  return r;
}

}  // namespace coatcontact::indent
