// Crack kinetics at the JKR contact edge through a spring (THEORY.md section 14).
//
// State: u = ln a_bar, the drive work W and the dissipation (in pi w L_a^2). At fixed a_bar the
// force balance is linear in the flat-punch part d = D - D_H, so d, P, D and G/w follow from
// (a_bar, X) in closed form; the edge speed from the kinetic law. While the edge is under
// compression (d >= 0) it sits on the adhesionless curve, X = X_H(a_bar), parametrised by a_bar.
// Integrated with gsl_odeiv2 msbdf (stiff near quasi-static equilibrium, section 14); events
// (target force, compression, stationary P, loss of contact) located by Brent on tau.
#include "coatcontact/crack_kinetics.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_odeiv2.h>
#include <gsl/gsl_roots.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <memory>
#include <string>

#include "coatcontact/contact.hpp"
#include "coatcontact/detail/constants.hpp"
#include "coatcontact/detail/format.hpp"
#include "coatcontact/detail/gsl_handler_off.hpp"
#include "coatcontact/errors.hpp"

namespace coatcontact {

namespace {

using detail::full_precision;
using detail::short_text;

// Reduced variables of the tip at one a_bar and their a_bar derivatives (section 5; the cone in
// its own units, section 14): P_H = a^3 Pi_s/2, D_H = a^2 Delta_s (sphere), a^2 Pi_c/2, a Delta_c
// (cone); K = 2 a E_eq and Gamma(1) for both.
struct Local {
  double a = 0.0;
  double p_h = 0.0, d_h = 0.0, k = 0.0, gamma = 0.0;
  double dp_h = 0.0, dd_h = 0.0, dk = 0.0;
  double dlog_gamma = 0.0;  // d ln Gamma(1)/d ln a_bar
};

Local local_at(const AdhesiveModel& model, KineticsTip tip, double eta, double a_bar) {
  const ReducedPoint r = model.table().at(a_bar / eta, tip == KineticsTip::kCone ? ReducedTable::Variables::kCone
                                                                                 : ReducedTable::Variables::kSphere);
  Local l;
  l.a = a_bar;
  if (tip == KineticsTip::kCone) {
    l.p_h = a_bar * a_bar * r.pi_c / 2.0;
    l.d_h = a_bar * r.delta_c;
    l.dp_h = l.p_h * (2.0 + r.dlog_pi_c) / a_bar;
    l.dd_h = l.d_h * (1.0 + r.dlog_delta_c) / a_bar;
  } else {
    l.p_h = a_bar * a_bar * a_bar * r.pi_s / 2.0;
    l.d_h = a_bar * a_bar * r.delta_s;
    l.dp_h = l.p_h * (3.0 + r.dlog_pi_s) / a_bar;
    l.dd_h = l.d_h * (2.0 + r.dlog_delta_s) / a_bar;
  }
  l.k = 2.0 * a_bar * r.e_eq;
  l.gamma = r.gamma1;
  l.dk = l.k * (1.0 + r.dlog_e_eq) / a_bar;
  l.dlog_gamma = r.dlog_gamma1;
  return l;
}

// Length ratio r of the base's JKR scale to the film's: (E1*/E0*)^(1/3) for the sphere, its cube
// for the cone (L_a ~ 1/E, section 14).
double tip_length_ratio(const AdhesiveModel& model, KineticsTip tip) {
  const double r = model.stack().substrate_length_ratio();
  return tip == KineticsTip::kCone ? r * r * r : r;
}

// Default a_bar of the loss of contact (section 14): a hundredth of the smallest pull-off radius
// the stack can have, the film's (a_bar ~ 1) or the base's (~ r). The cone's r = E1*/E0* can be
// tiny, but the base's regime needs a >> t, i.e. a_bar >> eta: its bound is then 1e-2 eta.
double default_a_end(const AdhesiveModel& model, KineticsTip tip, double eta) {
  const double r = tip_length_ratio(model, tip);
  if (tip == KineticsTip::kCone) return 1e-2 * std::min(1.0, std::max(r, 1e-2 * eta));
  return 1e-2 * std::min(1.0, r);
}

// Default upper a_bar of an approach: 100 max(1, r) for the sphere; the cone's load grows only
// like a_bar^2 (and its F_s is small for sharp cones), so 1e4 max(1, r), within the table's range.
double default_a_max(const AdhesiveModel& model, KineticsTip tip, double eta) {
  const double r = tip_length_ratio(model, tip);
  if (tip == KineticsTip::kCone) return std::min(1e4 * std::max(1.0, r), 0.5 * kMaximumScaled * eta);
  return 100.0 * std::max(1.0, r);
}

// The mechanical state at (a_bar, X) for a drive of compliance c = 1/k_bar (load control
// separately): d, P, D, Z, G/w and the partial derivatives of P and D.
struct Mechanics {
  double d = 0.0, load = 0.0, penetration = 0.0, z = 0.0, g = 0.0;
  double dload_da = 0.0, dload_dx = 0.0, dpen_da = 0.0, dpen_dx = 0.0;
  double dd_da = 0.0, dd_dx = 0.0, dg_da = 0.0, dg_dx = 0.0;  // of d and G/w
};

struct Drive {
  bool load_control = false;
  double compliance = 0.0;  // 1/k_bar (0: displacement control)
};

Mechanics mechanics(const Local& l, const Drive& drive, double x) {
  Mechanics m;
  double dd_da, dd_dx;
  if (drive.load_control) {
    m.d = (x - l.p_h) / l.k;
    dd_da = (-l.dp_h - m.d * l.dk) / l.k;
    dd_dx = 1.0 / l.k;
  } else {
    const double c = drive.compliance;
    const double s = 1.0 + c * l.k;
    m.d = (x - l.d_h - c * l.p_h) / s;
    dd_da = (-l.dd_h - c * l.dp_h - c * l.dk * m.d) / s;
    dd_dx = 1.0 / s;
  }
  m.load = drive.load_control ? x : l.p_h + l.k * m.d;
  m.penetration = l.d_h + m.d;
  m.z = drive.load_control ? m.penetration : m.penetration + drive.compliance * m.load;
  m.g = l.gamma * l.gamma * m.d * m.d / (2.0 * l.a);
  m.dd_da = dd_da;
  m.dd_dx = dd_dx;
  // G/w = Gamma^2 d^2/(2 a): d ln(G/w)/d a_bar = 2 d'/d + 2 Gamma'/Gamma - 1/a_bar.
  m.dg_da = l.gamma * l.gamma / (2.0 * l.a) * (2.0 * m.d * dd_da) + m.g * (2.0 * l.dlog_gamma / l.a - 1.0 / l.a);
  m.dg_dx = l.gamma * l.gamma / (2.0 * l.a) * (2.0 * m.d * dd_dx);
  m.dpen_da = l.dd_h + dd_da;
  m.dpen_dx = dd_dx;
  if (drive.load_control) {
    m.dload_da = 0.0;
    m.dload_dx = 1.0;
  } else {
    m.dload_da = l.dp_h + l.dk * m.d + l.k * dd_da;
    m.dload_dx = l.k * dd_dx;
  }
  return m;
}

// d a_bar/d tau from the law (section 14); an edge at d >= 0 has G = 0 on the advancing side.
double edge_speed(const KineticLaw& law, const Mechanics& m) {
  const double g = m.d >= 0.0 ? 0.0 : m.g;
  if (g > 1.0) return -std::pow(g - 1.0, 1.0 / law.n);
  return law.speed_ratio_adv * std::pow(1.0 - g, 1.0 / law.n_adv);
}

// d(edge speed)/d(G/w): the Jacobian of the stepper needs it exactly; a finite difference
// across G = w (where the law has a kink in its curvature) stalls the Newton iteration.
double edge_speed_slope(const KineticLaw& law, const Mechanics& m) {
  if (m.d >= 0.0) return 0.0;
  const double g = m.g;
  if (g > 1.0) return -(1.0 / law.n) * std::pow(g - 1.0 + 1e-300, 1.0 / law.n - 1.0);
  return -(law.speed_ratio_adv / law.n_adv) * std::pow(1.0 - g + 1e-300, 1.0 / law.n_adv - 1.0);
}

// X_H(a_bar): the drive on the adhesionless curve, and its derivative.
double hertz_drive(const Local& l, const Drive& drive) {
  return drive.load_control ? l.p_h : l.d_h + drive.compliance * l.p_h;
}
double hertz_drive_slope(const Local& l, const Drive& drive) {
  return drive.load_control ? l.dp_h : l.dd_h + drive.compliance * l.dp_h;
}

double call_function(double x, void* params) {
  return (*static_cast<std::function<double(double)>*>(params))(x);
}

// Root of f in [lo, hi] (a sign change) by Brent, to `tolerance` relative to the interval.
double brent(const std::function<double(double)>& f, double lo, double hi, const std::string& what) {
  std::function<double(double)> copy = f;
  gsl_function gf{&call_function, &copy};
  const double flo = f(lo), fhi = f(hi);
  if (flo == 0.0) return lo;
  if (fhi == 0.0) return hi;
  gsl_root_fsolver* s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
  if (s == nullptr || gsl_root_fsolver_set(s, &gf, lo, hi) != GSL_SUCCESS) {
    gsl_root_fsolver_free(s);
    throw NumericalError("kinetics: cannot bracket " + what + " in [" + full_precision(lo) + ", " +
                         full_precision(hi) + "]");
  }
  const double width = hi - lo;
  for (int iter = 0; iter < 200; ++iter) {
    if (gsl_root_fsolver_iterate(s) != GSL_SUCCESS) break;
    const double xl = gsl_root_fsolver_x_lower(s), xu = gsl_root_fsolver_x_upper(s);
    if (xu - xl <= 1e-14 * width + 4e-16 * std::max(std::fabs(xl), std::fabs(xu))) break;
  }
  const double root = gsl_root_fsolver_root(s);
  gsl_root_fsolver_free(s);
  return root;
}

// Elastic energy of the adhesionless curve, U_H(a_bar) = int_0^a_bar P_H dD_H (section 14).
double hertz_energy(const AdhesiveModel& model, KineticsTip tip, double eta, double a_bar, double a_bar_floor) {
  const double a0 = std::min(a_bar, a_bar_floor);
  const Local l0 = local_at(model, tip, eta, a0);
  // Below a0 (film-dominated): sphere P_H ~ a^3, D_H ~ a^2; cone P_H ~ a^2, D_H ~ a.
  double u = (tip == KineticsTip::kCone ? 1.0 / 3.0 : 0.4) * l0.p_h * l0.d_h;
  if (a_bar > a0) {
    std::function<double(double)> f = [&](double a) {
      const Local l = local_at(model, tip, eta, a);
      return l.p_h * l.dd_h;
    };
    detail::GslHandlerOff guard;
    gsl_function gf{&call_function, &f};
    gsl_integration_workspace* w = gsl_integration_workspace_alloc(200);
    double value = 0.0, error = 0.0;
    const int status = gsl_integration_qag(&gf, a0, a_bar, 0.0, 1e-12, 200, GSL_INTEG_GAUSS31, w,
                                           &value, &error);
    gsl_integration_workspace_free(w);
    if (status != GSL_SUCCESS && std::fabs(error) > 1e-9 * std::fabs(value)) {
      throw NumericalError("kinetics: energy of the adhesionless curve not converged at a_bar = " +
                           full_precision(a_bar));
    }
    u += value;
  }
  return u;
}

struct State {
  double tau = 0.0, x = 0.0, a = 0.0;
  bool hertz = true;
  double work = 0.0, dissipation = 0.0;
  bool lost = false;
  std::size_t steps = 0;
};

class Engine {
 public:
  Engine(const AdhesiveModel& model, KineticsTip tip, double eta, const KineticLaw& law, double k_bar,
         const KineticsOptions& options)
      : model_(model), tip_(tip), eta_(eta), law_(law), options_(options) {
    drive_.load_control = k_bar == 0.0;
    drive_.compliance = (k_bar == 0.0 || std::isinf(k_bar)) ? 0.0 : 1.0 / k_bar;
    k_bar_ = k_bar;
    a_end_ = options.a_bar_end > 0.0 ? options.a_bar_end : default_a_end(model, tip, eta);
    a_max_ = options.a_bar_max > 0.0 ? options.a_bar_max : default_a_max(model, tip, eta);
    if (!(a_end_ / eta >= kMinimumScaled && a_max_ / eta <= kMaximumScaled)) {
      throw InputError("kinetics: eta = " + full_precision(eta) + " puts the contact radii [" +
                       full_precision(a_end_) + ", " + full_precision(a_max_) +
                       "] outside the table's range of a/t");
    }
    // One batch for the usual range; the cone's approach may reach further, a decade of the table
    // at a time (built on demand, the solver's cost growing with a/t).
    model_.table().prepare(a_end_ / eta, std::min(a_max_, 100.0 * std::max(1.0, tip_length_ratio(model, tip))) / eta);
    const Local l = local(a_end_);
    state_.a = a_end_;
    state_.x = hertz_drive(l, drive_);
    state_.hertz = true;
    sys_ = gsl_odeiv2_system{&Engine::rhs, &Engine::jacobian, 3, this};
  }

  const State& state() const { return state_; }
  void set_state(const State& s) { state_ = s; }

  // The reduced variables at a_bar; the last two radii are remembered, since the stepper asks
  // for the right-hand side, its Jacobian and the events at the same state (each a table lookup
  // of eight Chebyshev series).
  Local local(double a) const {
    for (const Local& l : recent_) {
      if (l.a == a) return l;
    }
    recent_[next_recent_] = local_at(model_, tip_, eta_, a);
    const Local& l = recent_[next_recent_];
    next_recent_ = 1 - next_recent_;
    return l;
  }
  std::vector<KineticsSample>& samples() { return samples_; }
  std::size_t steps() const { return state_.steps; }
  std::vector<std::string>& warnings() { return warnings_; }
  double a_end() const { return a_end_; }

  KineticsSample sample(double tau, double x, double a, bool hertz) const {
    const Local l = local(a);
    KineticsSample s;
    s.tau = tau;
    s.drive = x;
    s.a_bar = a;
    s.segment = segment_index_;
    s.on_hertz = hertz;
    if (hertz) {
      s.load = l.p_h;
      s.penetration = l.d_h;
      s.z = drive_.load_control ? l.d_h : l.d_h + drive_.compliance * l.p_h;
      s.g_over_w = 0.0;
    } else {
      const Mechanics m = mechanics(l, drive_, x);
      s.load = m.load;
      s.penetration = m.penetration;
      s.z = m.z;
      s.g_over_w = m.d >= 0.0 ? 0.0 : m.g;
    }
    return s;
  }
  void record() { samples_.push_back(sample(state_.tau, state_.x, state_.a, state_.hertz)); }

  double energy_now() const {
    const KineticsSample s = sample(state_.tau, state_.x, state_.a, state_.hertz);
    return kinetics_energy(model_, eta_, s.a_bar, s.penetration, s.load, k_bar_, tip_);
  }

  // Runs one segment; returns false when contact is lost during it.
  bool run(const DriveSegment& seg, int index) {
    segment_index_ = index;
    rate_ = seg.kind == DriveSegment::Kind::kApproach  ? seg.rate
            : seg.kind == DriveSegment::Kind::kRetract ? -seg.rate
                                                       : 0.0;
    tau0_ = state_.tau;
    x0_ = state_.x;
    segment_ = seg;
    tau_stop_ = seg.kind == DriveSegment::Kind::kDwell ? tau0_ + seg.duration : HUGE_VAL;
    if (seg.kind == DriveSegment::Kind::kApproach) {
      const double p = sample(state_.tau, state_.x, state_.a, state_.hertz).load;
      if (!(seg.target_load > p)) {
        throw InputError("protocol segment " + std::to_string(index + 1) + " (approach): target load " +
                         full_precision(seg.target_load) + " not above the load " + full_precision(p) +
                         " at its start");
      }
    }
    if (seg.kind == DriveSegment::Kind::kRetract && seg.has_target) {
      const double p = sample(state_.tau, state_.x, state_.a, state_.hertz).load;
      if (!(seg.target_load < p)) {
        throw InputError("protocol segment " + std::to_string(index + 1) + " (retract): target load " +
                         full_precision(seg.target_load) + " not below the load " + full_precision(p) +
                         " at its start");
      }
    }
    for (;;) {
      if (state_.hertz) {
        const int outcome = run_hertz();
        if (outcome == 1) return true;  // segment done
        continue;                       // released into kinetics
      }
      const int outcome = run_kinetic();
      if (outcome == 1) return true;
      if (outcome == 2) return false;  // contact lost
    }
  }

 private:
  // The kinetic ODE runs in a local time s = tau - tau_base_ (rebased when the step becomes
  // small against s, so that fast stages after a long slow one keep their resolution).
  double drive_at(double s) const { return x_base_ + rate_ * s; }
  bool final_retract() const {
    return segment_.kind == DriveSegment::Kind::kRetract && !segment_.has_target;
  }
  // Speed of the adhesionless edge minus the advancing law's speed at G = 0 (> 0: stays on it).
  double hertz_excess(double a) const {
    const Local l = local(a);
    return rate_ / hertz_drive_slope(l, drive_) - law_.speed_ratio_adv;
  }

  // The edge on the adhesionless curve, marched in a_bar. 1: segment done; 0: released.
  int run_hertz() {
    const bool approaching = rate_ > 0.0;
    if (!approaching || hertz_excess(state_.a) <= 0.0) {
      state_.hertz = false;
      record();
      return 0;
    }
    const double a_start = state_.a;
    const double target = segment_.target_load;
    double a = state_.a;
    bool done = false;
    for (;;) {
      double next = a * 1.1;
      if (next > a_max_) {
        throw InputError("protocol segment " + std::to_string(segment_index_ + 1) +
                         " (approach): target load " + full_precision(target) +
                         " not reached below a_bar = " + full_precision(a_max_));
      }
      const Local ln = local(next);
      const bool reach = ln.p_h >= target;
      const bool release = hertz_excess(next) <= 0.0;
      if (reach || release) {
        const double a_target =
            reach ? brent([&](double s) { return local(s).p_h - target; }, a, next,
                          "the approach's target load")
                  : HUGE_VAL;
        const double a_release =
            release ? brent([&](double s) { return hertz_excess(s); }, a, next, "the release of the edge")
                    : HUGE_VAL;
        next = std::min(a_target, a_release);
        done = a_target <= a_release;
        a = next;
        set_hertz_point(a);
        break;
      }
      a = next;
      set_hertz_point(a);
      record();
    }
    add_hertz_energy(a_start, a);
    record();
    if (done) return 1;
    state_.hertz = false;
    return 0;
  }
  void set_hertz_point(double a) {
    const Local l = local(a);
    state_.a = a;
    state_.x = hertz_drive(l, drive_);
    state_.tau = tau0_ + (state_.x - x0_) / rate_;
  }
  void add_hertz_energy(double a1, double a2) {
    if (!(a2 > a1)) return;
    // W = int P_H dX_H (load control: int P_H dD_H); dissipation = w times the area gained.
    std::function<double(double)> f = [&](double s) {
      const Local l = local(s);
      return l.p_h * (drive_.load_control ? l.dd_h : hertz_drive_slope(l, drive_));
    };
    detail::GslHandlerOff guard;
    gsl_function gf{&call_function, &f};
    gsl_integration_workspace* w = gsl_integration_workspace_alloc(200);
    double value = 0.0, error = 0.0;
    gsl_integration_qag(&gf, a1, a2, 0.0, 1e-12, 200, GSL_INTEG_GAUSS31, w, &value, &error);
    gsl_integration_workspace_free(w);
    state_.work += value;
    state_.dissipation += a2 * a2 - a1 * a1;
  }

  // ---- the kinetic ODE ----
  // The edge at the ODE state (tau, y): a_bar = exp(y[0]), the mechanics there and the edge
  // speed; false where a_bar is not a finite positive radius.
  struct Edge {
    double a = 0.0;
    Mechanics m;
    double adot = 0.0;
  };
  bool edge_at(double tau, const double y[], Edge& edge) const {
    edge.a = std::exp(y[0]);
    if (!std::isfinite(edge.a) || edge.a <= 0.0) return false;
    edge.m = mechanics(local(edge.a), drive_, drive_at(tau));
    edge.adot = edge_speed(law_, edge.m);
    return true;
  }

  static int rhs(double tau, const double y[], double f[], void* params) {
    const auto* e = static_cast<const Engine*>(params);
    Edge edge;
    if (!e->edge_at(tau, y, edge)) return GSL_EBADFUNC;
    const double a = edge.a, adot = edge.adot;
    const Mechanics& m = edge.m;
    const double g = m.d >= 0.0 ? 0.0 : m.g;
    f[0] = adot / a;
    const double dpen = m.dpen_da * adot + m.dpen_dx * e->rate_;
    f[1] = e->drive_.load_control ? m.load * dpen : m.load * e->rate_;
    f[2] = -2.0 * (g - 1.0) * a * adot;
    return std::isfinite(f[0]) && std::isfinite(f[1]) && std::isfinite(f[2]) ? GSL_SUCCESS : GSL_EBADFUNC;
  }
  static int jacobian(double tau, const double y[], double* dfdy, double dfdt[], void* params) {
    const auto* e = static_cast<const Engine*>(params);
    Edge edge;
    if (!e->edge_at(tau, y, edge)) return GSL_EBADFUNC;
    const double a = edge.a, adot = edge.adot;
    const Mechanics& m = edge.m;
    const double slope = edge_speed_slope(e->law_, m);
    const double dadot_da = slope * m.dg_da;  // at fixed X
    const double dadot_dx = slope * m.dg_dx;
    const double g = m.d >= 0.0 ? 0.0 : m.g;
    // Rows: u = ln a_bar, W, dissipation; columns u, W, dissipation (W and dissipation are
    // quadratures: their columns vanish). Second derivatives of D are dropped in the W row.
    dfdy[0] = dadot_da - adot / a;
    const double dpen = m.dpen_da * adot + m.dpen_dx * e->rate_;
    dfdy[3] = e->drive_.load_control ? a * (m.dload_da * dpen + m.load * m.dpen_da * dadot_da)
                                     : a * m.dload_da * e->rate_;
    dfdy[6] = -2.0 * a * ((g - 1.0) * (adot + a * dadot_da) + (m.d >= 0.0 ? 0.0 : m.dg_da) * a * adot);
    for (int i : {1, 2, 4, 5, 7, 8}) dfdy[i] = 0.0;
    dfdt[0] = dadot_dx * e->rate_ / a;
    dfdt[1] = e->drive_.load_control ? e->rate_ * (dpen + m.load * m.dpen_da * dadot_dx)
                                     : m.dload_dx * e->rate_ * e->rate_;
    dfdt[2] = -2.0 * a * ((g - 1.0) * a * dadot_dx + (m.d >= 0.0 ? 0.0 : m.dg_dx) * a * adot) * e->rate_;
    return GSL_SUCCESS;
  }

  // Event functions at (tau, y); a crossing is a change of sign from the step's start.
  enum Event { kLoss = 0, kTarget, kCompression, kStationary, kEvents };
  std::array<double, kEvents> events(double tau, const double y[]) const {
    const double a = std::exp(y[0]);
    const Local l = local(a);
    const double x = drive_at(tau);
    const Mechanics m = mechanics(l, drive_, x);
    std::array<double, kEvents> v{};
    v[kLoss] = y[0] - std::log(a_end_);
    v[kTarget] = 1.0;
    if (segment_.kind == DriveSegment::Kind::kApproach) v[kTarget] = segment_.target_load - m.load;
    if (segment_.kind == DriveSegment::Kind::kRetract && segment_.has_target) {
      v[kTarget] = m.load - segment_.target_load;
    }
    v[kCompression] = rate_ > 0.0 ? -m.d : 1.0;
    v[kStationary] = -1.0;
    if (final_retract()) {
      const double adot = edge_speed(law_, m);
      v[kStationary] = m.dload_da * adot + m.dload_dx * rate_;  // dP/dtau: - to + is a minimum
    }
    return v;
  }
  static bool crossed(int k, double before, double after) {
    if (k == kStationary) return before < 0.0 && after >= 0.0;
    return before > 0.0 && after <= 0.0;
  }

  // Integrates from (t0, y0) to t with a fresh driver.
  void integrate_to(gsl_odeiv2_driver* d, double t0, const double y0[], double t, double y[]) {
    std::copy(y0, y0 + 3, y);
    if (t == t0) return;
    gsl_odeiv2_driver_reset_hstart(d, 1e-3 * (t - t0));
    double tt = t0;
    const int status = gsl_odeiv2_driver_apply(d, &tt, t, y);
    if (status != GSL_SUCCESS) {
      throw NumericalError("kinetics: ODE driver failed (" + std::string(gsl_strerror(status)) + ") at tau = " +
                           full_precision(tt));
    }
  }

  // 1: segment done; 2: contact lost; 0: switched onto the adhesionless curve.
  int run_kinetic() {
    detail::GslHandlerOff guard;
    const double h0 = 1e-6 / std::max({std::fabs(rate_), law_.speed_ratio_adv, 1.0});
    std::unique_ptr<gsl_odeiv2_driver, decltype(&gsl_odeiv2_driver_free)> drv(
        gsl_odeiv2_driver_alloc_y_new(&sys_, gsl_odeiv2_step_msbdf, h0, options_.absolute_tolerance,
                                      options_.relative_tolerance),
        &gsl_odeiv2_driver_free);
    std::unique_ptr<gsl_odeiv2_driver, decltype(&gsl_odeiv2_driver_free)> aux(
        gsl_odeiv2_driver_alloc_y_new(&sys_, gsl_odeiv2_step_msbdf, h0, options_.absolute_tolerance,
                                      options_.relative_tolerance),
        &gsl_odeiv2_driver_free);
    if (!drv || !aux) throw NumericalError("kinetics: cannot allocate the ODE driver");
    gsl_odeiv2_driver_set_nmax(aux.get(), options_.max_steps);
    double y[3] = {std::log(state_.a), state_.work, state_.dissipation};
    tau_base_ = state_.tau;
    x_base_ = state_.x;
    double t = 0.0;
    double h = h0;
    auto before = events(t, y);
    for (;;) {
      if (++state_.steps > options_.max_steps) {
        throw NumericalError("kinetics: more than " + std::to_string(options_.max_steps) + " steps");
      }
      if (t > 0.0 && h < 1e-6 * t) {
        commit(t, y);
        tau_base_ = state_.tau;
        x_base_ = state_.x;
        t = 0.0;
        gsl_odeiv2_driver_reset(drv.get());  // same point: the event values `before` still hold
      }
      // The step's start in the (possibly rebased) local time: an event is bracketed from here.
      const double t_prev = t;
      double y_prev[3] = {y[0], y[1], y[2]};
      const double t1 = std::isfinite(tau_stop_) ? tau_stop_ - tau_base_
                                                 : t + std::max(1e6 * std::fabs(h), 1e3 * (std::fabs(t) + 1.0));
      const int status = gsl_odeiv2_evolve_apply(drv->e, drv->c, drv->s, &sys_, &t, t1, &h, y);
      if (status != GSL_SUCCESS) {
        throw NumericalError("kinetics: ODE step failed (" + std::string(gsl_strerror(status)) + ") at tau = " +
                             full_precision(t) + ", a_bar = " + full_precision(std::exp(y[0])));
      }
      const auto after = events(t, y);
      // The earliest crossing in this step.
      int first = -1;
      double t_event = t;
      double y_event[3];
      for (int k = 0; k < kEvents; ++k) {
        if (!crossed(k, before[k], after[k])) continue;
        const double root = brent(
            [&](double s) {
              // The step's own end point (a fresh integration there may differ by its tolerance).
              if (s == t) return k == kStationary ? after[k] : -after[k];
              double ys[3];
              integrate_to(aux.get(), t_prev, y_prev, s, ys);
              const double v = events(s, ys)[k];
              return k == kStationary ? v : -v;  // sign convention: negative before the crossing
            },
            t_prev, t, "an event of the kinetics");
        if (first < 0 || root < t_event) {
          first = k;
          t_event = root;
        }
      }
      if (first >= 0) {
        if (t_event == t) {
          std::copy(y, y + 3, y_event);
        } else {
          integrate_to(aux.get(), t_prev, y_prev, t_event, y_event);
        }
        if (first == kStationary) {
          // A minimum of P: record it and go on from there.
          commit(t_event, y_event);
          record();
          t = t_event;
          std::copy(y_event, y_event + 3, y);
          gsl_odeiv2_driver_reset(drv.get());
          before = events(t, y);
          before[kStationary] = 0.0;  // do not find it again
          continue;
        }
        if (first == kLoss) y_event[0] = std::log(a_end_);
        commit(t_event, y_event);
        if (first == kCompression) {
          const Local l = local(state_.a);
          if (rate_ / hertz_drive_slope(l, drive_) > law_.speed_ratio_adv) {
            state_.x = hertz_drive(l, drive_);
            state_.hertz = true;
            record();
            return 0;
          }
          // Tangent to the adhesionless curve: the edge touches it and stays kinetic.
          record();
          t = t_event;
          std::copy(y_event, y_event + 3, y);
          gsl_odeiv2_driver_reset(drv.get());
          before = events(t, y);
          before[kCompression] = 0.0;
          continue;
        }
        record();
        if (first == kLoss) {
          state_.lost = true;
          return 2;
        }
        return 1;  // target load reached
      }
      commit(t, y);
      record();
      if (std::isfinite(tau_stop_) && t >= tau_stop_ - tau_base_) return 1;
      before = after;
    }
  }
  void commit(double t, const double y[]) {
    state_.tau = tau_base_ + t;
    state_.a = std::exp(y[0]);
    state_.x = drive_at(t);
    state_.work = y[1];
    state_.dissipation = y[2];
    state_.hertz = false;
  }

  const AdhesiveModel& model_;
  KineticsTip tip_;
  double eta_;
  KineticLaw law_;
  KineticsOptions options_;
  Drive drive_;
  double k_bar_ = 0.0;
  double a_end_ = 0.0, a_max_ = 0.0;
  State state_;
  gsl_odeiv2_system sys_{};
  std::vector<KineticsSample> samples_;
  std::vector<std::string> warnings_;
  int segment_index_ = 0;
  DriveSegment segment_;
  double rate_ = 0.0, tau0_ = 0.0, x0_ = 0.0, tau_stop_ = HUGE_VAL;
  double tau_base_ = 0.0, x_base_ = 0.0;
  mutable std::array<Local, 2> recent_{};  // a = 0 marks an empty slot (radii are > 0)
  mutable int next_recent_ = 0;
};

void validate(const KineticLaw& law, double k_bar, const std::vector<DriveSegment>& protocol) {
  if (!(law.n > 0.0 && std::isfinite(law.n))) {
    throw InputError("kinetic exponent n = " + full_precision(law.n) + " not allowed (need n > 0)");
  }
  if (!(law.n_adv > 0.0 && std::isfinite(law.n_adv))) {
    throw InputError("advancing exponent n_adv = " + full_precision(law.n_adv) + " not allowed (need n_adv > 0)");
  }
  if (!(law.speed_ratio_adv > 0.0 && std::isfinite(law.speed_ratio_adv))) {
    throw InputError("v_star_adv/v_star = " + full_precision(law.speed_ratio_adv) + " not allowed (need > 0)");
  }
  if (std::isnan(k_bar) || k_bar < 0.0) {
    throw InputError("k_bar = " + full_precision(k_bar) +
                     " not allowed (need >= 0; 0 is load control, inf displacement control)");
  }
  if (protocol.empty()) throw InputError("protocol: empty (need an approach first)");
  if (protocol.front().kind != DriveSegment::Kind::kApproach) {
    throw InputError("protocol: segment 1 is not an approach, so contact is never reached");
  }
  for (std::size_t i = 0; i < protocol.size(); ++i) {
    const DriveSegment& s = protocol[i];
    const std::string name = "protocol segment " + std::to_string(i + 1);
    if (s.kind == DriveSegment::Kind::kDwell) {
      if (!(s.duration > 0.0 && std::isfinite(s.duration))) {
        throw InputError(name + " (dwell): duration " + full_precision(s.duration) + " not allowed (need > 0)");
      }
    } else if (!(s.rate > 0.0 && std::isfinite(s.rate))) {
      throw InputError(name + ": speed " + full_precision(s.rate) + " not allowed (need a finite speed > 0)");
    }
    if (s.kind == DriveSegment::Kind::kApproach && !std::isfinite(s.target_load)) {
      throw InputError(name + " (approach): target load not finite");
    }
    const bool until_loss = s.kind == DriveSegment::Kind::kRetract && !s.has_target;
    if (until_loss && i + 1 != protocol.size()) {
      throw InputError("protocol segment " + std::to_string(i + 2) +
                       " comes after a retract until contact is lost (the simulation ends there)");
    }
  }
  const DriveSegment& last = protocol.back();
  if (!(last.kind == DriveSegment::Kind::kRetract && !last.has_target)) {
    throw InputError("protocol: the last segment must be a retract until contact is lost");
  }
}

KineticsResult finish(Engine& engine, const AdhesiveModel& model, KineticsTip tip, double eta, double k_bar,
                      double energy_start, int last_index, bool keep_samples) {
  KineticsResult result;
  result.steps = engine.steps();
  result.warnings = engine.warnings();
  const State& s = engine.state();
  result.work = s.work;
  result.dissipation = s.dissipation;
  result.energy_start = energy_start;
  const auto& samples = engine.samples();
  const KineticsSample& end = samples.back();
  result.energy_end = kinetics_energy(model, eta, end.a_bar, end.penetration, end.load, k_bar, tip);
  result.loss = {end.tau, end.load, end.a_bar, end.penetration, end.z};
  bool found = false;
  for (const KineticsSample& p : samples) {
    if (p.segment != last_index) continue;
    if (!found || p.load <= result.pulloff.load) {
      result.pulloff = {p.tau, p.load, p.a_bar, p.penetration, p.z};
      found = true;
    }
  }
  if (keep_samples) result.samples = samples;
  return result;
}

}  // namespace

double kinetics_energy(const AdhesiveModel& model, double eta, double a_bar, double penetration,
                       double load, double k_bar, KineticsTip tip) {
  const Local l = local_at(model, tip, eta, a_bar);
  const double d = penetration - l.d_h;
  const double floor = std::min(a_bar, 0.1 * default_a_end(model, tip, eta));
  const double u_el = hertz_energy(model, tip, eta, a_bar, floor) + l.p_h * d + 0.5 * l.k * d * d;
  const double spring = (k_bar > 0.0 && std::isfinite(k_bar)) ? load * load / (2.0 * k_bar) : 0.0;
  return u_el + spring - a_bar * a_bar;
}

KineticsResult simulate_kinetics(const AdhesiveModel& model, double eta, const KineticLaw& law,
                                 double k_bar, const std::vector<DriveSegment>& protocol,
                                 const KineticsOptions& options) {
  return simulate_kinetics(model, KineticsTip::kSphere, eta, law, k_bar, protocol, options);
}

KineticsResult simulate_kinetics(const AdhesiveModel& model, KineticsTip tip, double eta,
                                 const KineticLaw& law, double k_bar,
                                 const std::vector<DriveSegment>& protocol,
                                 const KineticsOptions& options) {
  return sweep_kinetics(model, tip, eta, law, k_bar, protocol,
                        {protocol.empty() ? 1.0 : protocol.back().rate}, true, options)
      .front();
}

std::vector<KineticsResult> sweep_kinetics(const AdhesiveModel& model, double eta,
                                           const KineticLaw& law, double k_bar,
                                           const std::vector<DriveSegment>& protocol,
                                           const std::vector<double>& retract_rates, bool keep_samples,
                                           const KineticsOptions& options) {
  return sweep_kinetics(model, KineticsTip::kSphere, eta, law, k_bar, protocol, retract_rates,
                        keep_samples, options);
}

std::vector<KineticsResult> sweep_kinetics(const AdhesiveModel& model, KineticsTip tip, double eta,
                                           const KineticLaw& law, double k_bar,
                                           const std::vector<DriveSegment>& protocol,
                                           const std::vector<double>& retract_rates, bool keep_samples,
                                           const KineticsOptions& options) {
  validate(law, k_bar, protocol);
  if (!(eta > 0.0 && std::isfinite(eta))) {
    throw InputError("eta = " + full_precision(eta) + " not allowed (need a finite eta > 0)");
  }
  for (double v : retract_rates) {
    if (!(v > 0.0 && std::isfinite(v))) {
      throw InputError("retract speed " + full_precision(v) + " not allowed (need a finite speed > 0)");
    }
  }
  Engine engine(model, tip, eta, law, k_bar, options);
  engine.record();
  const double energy_start = engine.energy_now();
  const int last = static_cast<int>(protocol.size()) - 1;
  for (int i = 0; i < last; ++i) {
    if (!engine.run(protocol[static_cast<std::size_t>(i)], i)) {
      throw InputError("protocol segment " + std::to_string(i + 1) +
                       ": contact is lost before the last segment");
    }
  }
  const State prefix = engine.state();
  const std::vector<KineticsSample> prefix_samples = engine.samples();
  std::vector<KineticsResult> results;
  for (double rate : retract_rates) {
    engine.set_state(prefix);
    engine.samples() = prefix_samples;
    DriveSegment retract = protocol.back();
    retract.rate = rate;
    if (engine.run(retract, last)) {
      throw NumericalError("kinetics: the final retract ended without loss of contact");
    }
    results.push_back(finish(engine, model, tip, eta, k_bar, energy_start, last, keep_samples));
  }
  return results;
}

KineticsScales kinetics_scales(const AdhesiveModel& model, const KineticsSetupSI& setup) {
  auto positive = [](double v, const char* name, const char* unit) {
    if (!(v > 0.0 && std::isfinite(v))) {
      throw InputError(std::string(name) + " = " + full_precision(v) + " not allowed (need a finite value > 0 " +
                       unit + ")");
    }
  };
  if (setup.tip == KineticsTip::kCone) {
    if (!(setup.half_angle > 0.0 && setup.half_angle < detail::kPi / 2)) {
      throw InputError("cone half angle = " + full_precision(setup.half_angle) +
                       " rad not allowed (need 0 < beta < pi/2)");
    }
  } else {
    positive(setup.radius, "radius", "m");
  }
  positive(setup.thickness, "thickness", "m");
  positive(setup.work, "work", "J/m2");
  positive(setup.v_star, "v_star", "m/s");
  if (!(setup.n > 0.0 && std::isfinite(setup.n))) {
    throw InputError("n = " + full_precision(setup.n) + " not allowed (need n > 0)");
  }
  if (std::isnan(setup.spring) || setup.spring < 0.0) {
    throw InputError("spring = " + full_precision(setup.spring) +
                     " not allowed (need >= 0 N/m: 0 is load control, inf displacement control)");
  }
  KineticsScales s;
  if (setup.tip == KineticsTip::kCone) {
    // The cone's JKR units (section 14): L_a = 4 w tan^2(beta)/(pi E*), L_D = 2 w tan(beta)/E*,
    // F_s = E* L_a L_D.
    const double modulus = model.stack().reference_modulus();
    const double tb = std::tan(setup.half_angle);
    s.length = 4.0 * setup.work * tb * tb / (detail::kPi * modulus);
    s.penetration = 2.0 * setup.work * tb / modulus;
    s.force = modulus * s.length * s.penetration;
    s.eta = setup.thickness / s.length;
  } else {
    const Contact contact(model, setup.radius, setup.thickness, setup.work);
    s.length = contact.length_scale();
    s.penetration = contact.penetration_scale();
    s.force = contact.force_scale();
    s.eta = contact.eta();
  }
  s.time = s.length / setup.v_star;
  s.k_bar = std::isinf(setup.spring) ? setup.spring : setup.spring * s.penetration / s.force;
  s.drive_rate = setup.spring == 0.0 ? s.time / s.force : s.time / s.penetration;
  return s;
}

namespace {

// The Engine's check that the contact radii of a run stay in the table's a/t (the message in
// reduced units, for a run in them), made first in the units of an SI run: the radii in m and
// the thicknesses that keep them in range (issue 40 item 8).
void check_radii_in_table_si(const AdhesiveModel& model, const KineticsSetupSI& setup, const KineticsScales& sc,
                             const KineticsOptions& options) {
  const double a_end = options.a_bar_end > 0.0 ? options.a_bar_end : default_a_end(model, setup.tip, sc.eta);
  const double a_max = options.a_bar_max > 0.0 ? options.a_bar_max : default_a_max(model, setup.tip, sc.eta);
  if (a_end / sc.eta >= kMinimumScaled && a_max / sc.eta <= kMaximumScaled) return;
  const double lo = a_end * sc.length, hi = a_max * sc.length;
  throw InputError("thickness t = " + short_text(setup.thickness) + " m puts the contact radii of the run (" +
                   short_text(lo) + " to " + short_text(hi) + " m) at a/t = " + short_text(lo / setup.thickness) +
                   " to " + short_text(hi / setup.thickness) + ", outside the solver's [" + short_text(kMinimumScaled) +
                   ", " + short_text(kMaximumScaled) + "]; allowed: t in [" + short_text(hi / kMaximumScaled) + ", " +
                   short_text(lo / kMinimumScaled) + "] m for this radius, work and film (eta = t/L_a = " +
                   short_text(sc.eta) + ", L_a = " + short_text(sc.length) + " m)");
}

}  // namespace

std::vector<KineticsResultSI> simulate_kinetics_si(const AdhesiveModel& model, const KineticsSetupSI& setup,
                                                   const std::vector<double>& retract_speeds,
                                                   bool keep_samples, const KineticsOptions& options) {
  const KineticsScales sc = kinetics_scales(model, setup);
  check_radii_in_table_si(model, setup, sc, options);
  KineticLaw law;
  law.n = setup.n;
  law.n_adv = setup.n_adv > 0.0 ? setup.n_adv : setup.n;
  const double v_adv = setup.v_star_adv > 0.0 ? setup.v_star_adv : setup.v_star;
  if (!std::isfinite(v_adv) || !std::isfinite(law.n_adv)) {
    throw InputError("v_star_adv and n_adv must be finite");
  }
  law.speed_ratio_adv = v_adv / setup.v_star;
  std::vector<DriveSegment> protocol;
  for (const KineticsSegmentSI& seg : setup.protocol) {
    DriveSegment d;
    d.kind = seg.kind;
    d.rate = seg.speed * sc.drive_rate;
    d.duration = seg.duration / sc.time;
    d.target_load = seg.target_force / sc.force;
    d.has_target = seg.has_target;
    protocol.push_back(d);
  }
  std::vector<double> rates;
  if (retract_speeds.empty()) {
    if (!setup.protocol.empty()) rates.push_back(protocol.back().rate);
  } else {
    for (double v : retract_speeds) rates.push_back(v * sc.drive_rate);
  }
  const bool keep = keep_samples || retract_speeds.empty();
  const std::vector<KineticsResult> runs =
      sweep_kinetics(model, setup.tip, sc.eta, law, sc.k_bar, protocol, rates, keep, options);
  std::vector<KineticsResultSI> out;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    KineticsResultSI r;
    r.retract_speed = rates[i] / sc.drive_rate;
    r.reduced = runs[i];
    for (const KineticsSample& p : runs[i].samples) {
      r.t.push_back(p.tau * sc.time);
      r.z.push_back(p.z * sc.penetration);
      r.delta.push_back(p.penetration * sc.penetration);
      r.a.push_back(p.a_bar * sc.length);
      r.force.push_back(p.load * sc.force);
      r.g.push_back(p.g_over_w * setup.work);
    }
    r.pulloff = {runs[i].pulloff.load * sc.force, runs[i].pulloff.tau * sc.time, runs[i].pulloff.a_bar * sc.length};
    r.loss = {runs[i].loss.load * sc.force, runs[i].loss.tau * sc.time, runs[i].loss.a_bar * sc.length};
    out.push_back(std::move(r));
  }
  return out;
}

}  // namespace coatcontact
