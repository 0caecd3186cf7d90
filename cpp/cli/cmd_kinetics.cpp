// `coatcontact kinetics`: rate-dependent JKR adhesion of a sphere or a cone on a coating, the contact
// edge obeying a crack-kinetics law, driven through a spring (THEORY.md section 14).
#include <gsl/gsl_errno.h>

#include <chrono>
#include <cstdlib>
#include <cmath>
#include <iostream>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "coatcontact/cli_support.hpp"
#include "coatcontact/curve_plot.hpp"
#include "coatcontact/si_text.hpp"
#include "coatcontact/contact.hpp"
#include "coatcontact/crack_kinetics.hpp"
#include "coatcontact/detail/constants.hpp"
#include "coatcontact/data_file.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/kinetics_fit.hpp"
#include "coatcontact/reduced.hpp"
#include "checks.hpp"
#include "commands.hpp"
#include "number_text.hpp"

namespace coatcontact::cli {

namespace {

using Header = std::vector<std::pair<std::string, std::string>>;

std::string num(double v) { return format_parameter(v, "header value"); }

constexpr auto split_on = detail::split;
using detail::trim;

const std::vector<std::pair<std::string, double>> kTimeUnits = {{"ms", 1e-3}, {"s", 1.0}, {"min", 60.0}};

// A number with one of `units` (suffix, optionally after one space); bare numbers are SI.
double with_unit(const std::string& raw, const std::vector<std::pair<std::string, double>>& units,
                 const std::string& option, const std::string& what) {
  const std::string text = trim(raw);
  for (const auto& [suffix, factor] : units) {
    if (text.size() > suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0) {
      const std::string number = trim(text.substr(0, text.size() - suffix.size()));
      if (!number.empty() && (std::isdigit(static_cast<unsigned char>(number.back())) || number.back() == '.')) {
        return to_si(parse_number(number, option), factor);
      }
    }
  }
  try {
    return parse_number(text, option);
  } catch (const InputError&) {
    std::string allowed;
    for (const auto& u : units) allowed += (allowed.empty() ? "" : " ") + u.first;
    throw InputError(option + ": " + what + " '" + raw + "' not understood (a number, optionally with a unit: " +
                     allowed + ")");
  }
}

// A speed (m/s, um/s ...) or, under load control, a force rate (N/s, mN/s ...): the CLI's one
// rate parser (cli_support.hpp), > 0.
double positive_speed(const std::string& text, bool load_control, const std::string& option) {
  return parse_rate(text, load_control ? Rate::kForceRate : Rate::kSpeed, option);
}

// "approach:V:F,dwell:T,retract:V[:F]" (V a speed, or a force rate under load control).
std::vector<KineticsSegmentSI> parse_protocol(const std::string& text, bool load_control) {
  const std::string option = "--protocol";
  const std::string expected = "expected segments approach:SPEED:FORCE, dwell:TIME, retract:SPEED[:FORCE], "
                               "separated by commas";
  std::vector<KineticsSegmentSI> protocol;
  for (const std::string& raw : split_on(text, ',')) {
    const std::vector<std::string> f = split_on(trim(raw), ':');
    const std::string kind = trim(f[0]);
    KineticsSegmentSI s;
    // A target force may be tensile (negative): the sign, then a force with its unit.
    auto force = [&](const std::string& t) {
      const std::string v = trim(t);
      double bare = 0.0;
      if (detail::parse_decimal(v, bare) == detail::NumberStatus::kOk) return bare;
      const bool negative = !v.empty() && v[0] == '-';
      const double magnitude = parse_quantity(negative ? v.substr(1) : v, Quantity::kForce, option);
      return negative ? -magnitude : magnitude;
    };
    if (kind == "approach" && f.size() == 3) {
      s.kind = DriveSegment::Kind::kApproach;
      s.speed = positive_speed(f[1], load_control, option);
      s.target_force = force(f[2]);
      s.has_target = true;
    } else if (kind == "dwell" && f.size() == 2) {
      s.kind = DriveSegment::Kind::kDwell;
      s.duration = with_unit(f[1], kTimeUnits, option, "time");
      if (!(s.duration > 0.0)) {
        throw InputError(option + ": dwell time '" + f[1] + "' not allowed (need a time > 0 s)");
      }
    } else if (kind == "retract" && (f.size() == 2 || f.size() == 3)) {
      s.kind = DriveSegment::Kind::kRetract;
      s.speed = positive_speed(f[1], load_control, option);
      if (f.size() == 3) {
        s.target_force = force(f[2]);
        s.has_target = true;
      }
    } else {
      throw InputError(option + ": segment '" + raw + "' not understood; " + expected);
    }
    protocol.push_back(s);
  }
  return protocol;
}

// The same segments in reduced units: plain numbers (rate > 0, load P, time tau).
std::vector<DriveSegment> parse_reduced_protocol(const std::string& text) {
  const std::string option = "--protocol";
  std::vector<DriveSegment> protocol;
  for (const std::string& raw : split_on(text, ',')) {
    const std::vector<std::string> f = split_on(trim(raw), ':');
    const std::string kind = trim(f[0]);
    DriveSegment s;
    auto rate = [&](const std::string& t) {
      const double v = parse_number(t, option);
      if (!(v > 0.0)) throw InputError(option + ": rate '" + t + "' not allowed (need a reduced rate > 0)");
      return v;
    };
    if (kind == "approach" && f.size() == 3) {
      s.kind = DriveSegment::Kind::kApproach;
      s.rate = rate(f[1]);
      s.target_load = parse_number(f[2], option);
      s.has_target = true;
    } else if (kind == "dwell" && f.size() == 2) {
      s.kind = DriveSegment::Kind::kDwell;
      s.duration = parse_number(f[1], option);
      if (!(s.duration > 0.0)) throw InputError(option + ": dwell '" + f[1] + "' not allowed (need tau > 0)");
    } else if (kind == "retract" && (f.size() == 2 || f.size() == 3)) {
      s.kind = DriveSegment::Kind::kRetract;
      s.rate = rate(f[1]);
      if (f.size() == 3) {
        s.target_load = parse_number(f[2], option);
        s.has_target = true;
      }
    } else {
      throw InputError(option + ": segment '" + raw + "' not understood; expected approach:RATE:P, dwell:TAU, "
                       "retract:RATE[:P] (reduced units, with --eta)");
    }
    protocol.push_back(s);
  }
  return protocol;
}

const std::vector<OptionSpec> kSpec = {
    {"--radius", "R", "sphere radius (m, or with a unit: mm um nm); the same as --shape sphere:R", false},
    {"--shape", "SHAPE", "indenter, as for `contact`: sphere:R or cone:BETA (half included angle, e.g. 70deg), "
                         "the shapes the JKR table serves", false},
    {"--thickness", "t", "film thickness (m, or with a unit); not with --layer", false},
    film_option(),
    layer_option(true),
    substrate_option(),
    indenter_option(),
    {"--work", "w", "work of adhesion (J/m2, or mJ/m2)", false},
    {"--v-star", "V", "speed v* of the receding law G - w = w (|v|/v*)^n (m/s, or um/s nm/s mm/s)", false},
    {"--n", "N", "exponent n > 0 of the receding law", true},
    {"--v-star-adv", "V", "speed v_a* of the advancing law w - G = w (v/v_a*)^n_adv (default v*)", false},
    {"--n-adv", "N", "exponent n_adv > 0 of the advancing law (default n)", false},
    {"--spring", "k", "spring stiffness in N/m between base and sphere; 0 is load control (then speeds are "
                      "force rates, N/s), inf displacement control", false},
    {"--eta", "ETA", "reduced run (THEORY.md section 14): film thickness over L_a; then --k-bar and a protocol in "
                     "reduced units (rates dZ/dtau or dP/dtau, loads P, times tau) replace --radius, "
                     "--thickness, --work, --v-star and --spring", false},
    {"--k-bar", "K", "reduced spring stiffness k L_D/F_s with --eta (F_s = pi w R for the sphere): 0 load "
                     "control, inf displacement control", false},
    {"--protocol", "SEGMENTS", "approach:SPEED:FORCE,dwell:TIME,retract:SPEED[:FORCE],... starting at first "
                               "contact and ending with a retract until contact is lost (e.g. "
                               "approach:1um/s:1mN,dwell:1s,retract:10um/s)", true},
    {"--retract-speeds", "LIST", "sweep the last retract's speed: v1,v2,... (units allowed) or MIN:MAX:N in "
                                 "m/s (log-spaced); prints one pull-off row per speed", false},
    {"--fit", "FILE", "fit the law to measured curves instead of simulating: FILE has columns curve t F [sigma_F] "
                      "(curve 1..N, t in s since first contact, F in N; units by a '# units:' line); each curve "
                      "runs --protocol with its retract at its entry of --retract-speeds; --work, --v-star, --n "
                      "are start values (THEORY.md section 14, fitting)", false},
    {"--free", "LIST", "with --fit: the fitted parameters among w, v_star, n, t, E1 (default w,v_star,n; E1 starts "
                       "at the --film value, each value builds its own table)", false},
    tol_option("1e-8"),
    {"--output", "FILE", "write to FILE atomically instead of stdout", false},
    plot_option("F(t) and a(t), or with --retract-speeds the pull-off against the speed (SI runs)"),
};

// --plot of an SI run: F and a against time (the pull-off marked), or with --retract-speeds the
// pull-off force against the retract speed; for the sphere the quasi-static JKR pull-off of
// the homogeneous film, -3/2 pi w R, as the reference.
std::string kinetics_picture(const std::string& path, const std::vector<KineticsResultSI>& runs,
                             const KineticsSetupSI& setup, const Stack& stack, bool sweep) {
  const bool sphere = setup.tip == KineticsTip::kSphere;
  const std::string title =
      (sphere ? "sphere R = " + si_text(setup.radius, "m") : "cone β = " + num(setup.half_angle * 180.0 / detail::kPi) + "°") +
      " on " + si_text(setup.thickness, "m") + " of " + si_text(stack.top().youngs_modulus, "Pa") + ", w = " +
      si_text(setup.work, "J/m^2") + ", v* = " + si_text(setup.v_star, "m/s") + ", n = " + num(setup.n);
  const double jkr = -1.5 * detail::kPi * setup.work * setup.radius;
  if (sweep) {
    PlotSeries pulloff{"pull-off (this run)", {}, {}, PlotSeries::Style::kLine, kPlotCoated};
    for (const KineticsResultSI& r : runs) {
      pulloff.x.push_back(r.retract_speed);
      pulloff.y.push_back(r.pulloff.force);
    }
    if (runs.size() == 1) pulloff.style = PlotSeries::Style::kPoints;
    const bool load_control = setup.spring == 0.0;
    PlotPanel panel{load_control ? "retract force rate" : "retract speed V", load_control ? "N/s" : "m/s",
                    "pull-off force", "N", true, {pulloff}, ""};
    if (sphere) {
      panel.series.push_back({"JKR quasi-static, homogeneous film: -3/2 π w R",
                              {pulloff.x.front(), pulloff.x.back()}, {jkr, jkr}, PlotSeries::Style::kDashed,
                              kPlotReference});
    }
    return render_curve_plot({panel}, title, path);
  }
  const KineticsResultSI& r = runs.front();
  PlotPanel force{"time t since first contact", "s", "force F", "N", false,
                  {{"F (this run)", r.t, r.force, PlotSeries::Style::kLine, kPlotCoated},
                   {"pull-off", {r.pulloff.time}, {r.pulloff.force}, PlotSeries::Style::kPoints, kPlotCoated}},
                  ""};
  if (sphere && !r.t.empty()) {
    force.series.push_back({"JKR quasi-static, homogeneous film: -3/2 π w R", {r.t.front(), r.t.back()}, {jkr, jkr},
                            PlotSeries::Style::kDashed, kPlotReference});
  }
  PlotPanel radius{"time t since first contact", "s", "contact radius a", "m", false,
                   {{"a (this run)", r.t, r.a, PlotSeries::Style::kLine, kPlotSecond},
                    {"pull-off", {r.pulloff.time}, {r.pulloff.radius}, PlotSeries::Style::kPoints, kPlotSecond}},
                   ""};
  return render_curve_plot({force, radius}, title, path);
}

// The header item of the wall-clock time the command took (not a simulated time).
constexpr const char* kRunTime = "run time (wall clock, this computation) [s]";

// A library InputError in the user's terms: which options set what it refuses.
std::string kinetics_input_message(const std::string& message, bool si) {
  if (message.rfind("protocol", 0) == 0) return "--protocol: " + message;
  if (si && message.rfind("thickness t =", 0) == 0) return "--thickness: " + message;
  if (message.rfind("a/t", 0) == 0) {
    return std::string(si ? "--protocol, --thickness, --radius/--shape, --work, --film" : "--protocol, --eta") +
           ": the contact radius this run reaches is outside what the solver serves (" + message +
           "); allowed: a thicker film relative to the contact (a larger --thickness" +
           (si ? std::string(" or a smaller --work or --radius") : std::string(" or --eta")) +
           "), or a gentler protocol (a smaller approach force)";
  }
  return message;
}

// A library NumericalError with GSL's status code spelled out (gsl_strerror) and what to try.
std::string kinetics_numerical_message(const std::string& message) {
  const std::size_t at = message.find("(status ");
  if (at == std::string::npos) {
    if (message.find("kinetics: ODE") == std::string::npos) return message;
    return message + "; the contact edge's ODE could not be integrated there: try a larger --tol, or a protocol "
                     "that keeps the contact inside the model's range (a smaller approach force, a slower drive)";
  }
  const int status = std::atoi(message.c_str() + at + 8);
  const std::size_t close = message.find(')', at);
  std::string text = message.substr(0, at) + "(" + gsl_strerror(status) + ")" +
                     (close == std::string::npos ? std::string() : message.substr(close + 1));
  return text + "; the contact edge's ODE could not be integrated there: try a larger --tol, or a protocol "
                "that keeps the contact inside the model's range (a smaller approach force, a slower drive)";
}

// --retract-speeds with many speeds: the approach and dwell run once, then one retract per
// speed. After a first run (it builds the table the runs share), a run with one speed and one
// with nine spread over the list give the cost of the prefix and of a retract; a sweep estimated
// above kMaxWorkSeconds is refused, otherwise the estimate goes to the progress line.
constexpr std::size_t kSweepPlanned = 50;  // fewer speeds cost less than the plan
void plan_sweep(const AdhesiveModel& model, const KineticsSetupSI& setup, const std::vector<double>& speeds) {
  const auto timed = [&](const std::vector<double>& v) {
    const double start = thread_cpu_seconds();
    simulate_kinetics_si(model, setup, v, false);
    return thread_cpu_seconds() - start;
  };
  std::vector<double> sample;
  for (std::size_t k = 0; k < 9; ++k) sample.push_back(speeds[k * (speeds.size() - 1) / 8]);
  timed({speeds.front()});
  const double one = timed({speeds.front()});
  const double retract = std::max((timed(sample) - one) / 8.0, 0.0);
  const double estimate = one + retract * static_cast<double>(speeds.size());
  if (estimate > kMaxWorkSeconds) {
    throw InputError("--retract-speeds: estimated run time " + num(std::round(estimate)) + " s (" +
                     std::to_string(speeds.size()) + " retracts at ~" + num(std::round(retract * 1e5) / 1e5) +
                     " s each) is over the limit of " + num(kMaxWorkSeconds) + " s; allowed: fewer speeds (N of "
                     "MIN:MAX:N), or several runs");
  }
  progress_set_estimate(estimate);
}

// --spring: 0 (load control), inf (displacement control) or a stiffness (500, 500N/m, 0.5mN/um).
double parse_spring(const std::string& text) {
  const std::string k = trim(text);
  if (k == "inf") return HUGE_VAL;
  double bare = 0.0;
  if (detail::parse_decimal(k, bare) == detail::NumberStatus::kOk && bare == 0.0) return 0.0;
  try {
    return parse_rate(k, Rate::kStiffness, "--spring");
  } catch (const InputError& e) {
    throw InputError(std::string(e.what()) + " (or 0 for load control, inf for displacement control)");
  }
}

// --tol: the solver's relative tolerance (default 1e-8).
double solver_tolerance(const Arguments& args) {
  double tol = kDefaultTolerance;
  if (const auto text = args.get("--tol")) {
    tol = parse_number(*text, "--tol");
    if (!(tol >= kMinimumTolerance && tol <= kMaximumTolerance)) {
      throw InputError("--tol: value '" + *text + "' not allowed (need 1e-13 <= T <= 0.1)");
    }
  }
  return tol;
}

// A kinetic exponent: 0 < n <= 100.
double parse_exponent(const Arguments& args, const std::string& option) {
  const std::string text = args.require(option);
  const double n = parse_number(text, option);
  if (!(n > 0.0 && n <= 100.0)) throw InputError(option + ": value '" + text + "' not allowed (need 0 < n <= 100)");
  return n;
}

ExitCode run_reduced_kinetics(const Arguments& args, std::chrono::steady_clock::time_point started) {
  for (const char* option : {"--radius", "--thickness", "--work", "--v-star", "--spring", "--plot"}) {
    if (args.has(option)) {
      throw InputError(std::string(option) + ": not with --eta (a reduced run; see --help)");
    }
  }
  KineticsTip tip = KineticsTip::kSphere;
  if (const auto text = args.get("--shape")) {
    const std::string shape = trim(*text);
    if (shape == "cone") {
      tip = KineticsTip::kCone;
    } else if (shape != "sphere") {
      throw InputError("--shape: '" + *text + "' not allowed with --eta (need sphere or cone: the reduced units "
                       "carry no R or beta)");
    }
  }
  const std::string eta_text = args.require("--eta");
  const double eta = parse_number(eta_text, "--eta");
  if (!(eta >= kMinimumScaled && eta <= kMaximumScaled)) {
    throw InputError("--eta: value '" + eta_text + "' not allowed (need 1e-6 <= eta <= 1e6)");
  }
  const Stack stack = parse_stack(args);
  if (args.has("--layer")) throw InputError("--layer: not with --eta (give --film)");
  KineticLaw law;
  auto exponent = [&](const std::string& option) { return parse_exponent(args, option); };
  law.n = exponent("--n");
  law.n_adv = args.has("--n-adv") ? exponent("--n-adv") : law.n;
  if (const auto text = args.get("--v-star-adv")) {
    law.speed_ratio_adv = parse_number(*text, "--v-star-adv");
    if (!(law.speed_ratio_adv > 0.0)) {
      throw InputError("--v-star-adv: value '" + *text + "' not allowed (with --eta: v_a*/v* > 0)");
    }
  }
  const std::string k_text = args.require("--k-bar");
  const double k_bar = trim(k_text) == "inf" ? HUGE_VAL : parse_number(k_text, "--k-bar");
  if (!(k_bar >= 0.0)) throw InputError("--k-bar: value '" + k_text + "' not allowed (need >= 0, or inf)");
  const std::vector<DriveSegment> protocol = parse_reduced_protocol(args.require("--protocol"));
  std::vector<double> rates;
  if (const auto text = args.get("--retract-speeds")) rates = parse_list(*text, "--retract-speeds");
  for (double v : rates) {
    if (!(v > 0.0)) throw InputError("--retract-speeds: " + num(v) + " not allowed (need rates > 0)");
  }
  const double tol = solver_tolerance(args);
  const std::string output_path = args.get("--output").value_or("");
  check_output_path(output_path, "--output");
  const ReducedSolver solver(stack);
  const AdhesiveModel model(solver, tol);
  std::vector<KineticsResult> runs;
  try {
    runs = rates.empty() ? std::vector<KineticsResult>{simulate_kinetics(model, tip, eta, law, k_bar, protocol)}
                         : sweep_kinetics(model, tip, eta, law, k_bar, protocol, rates);
  } catch (const InputError& e) {
    throw InputError(kinetics_input_message(e.what(), false));
  } catch (const NumericalError& e) {
    throw NumericalError(kinetics_numerical_message(e.what()));
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  Header h{{"command", "kinetics"}};
  add_material_header(h, stack);
  if (tip == KineticsTip::kCone) {
    h.emplace_back("indenter", "cone (Pi_c, Delta_c)");
    h.emplace_back("units", "reduced (THEORY.md section 14, the cone): a_bar = a/L_a, D = delta/L_D, Z = z/L_D, "
                            "P = F/F_s, tau = t v*/L_a; L_a = 4 w tan^2(beta)/(pi E1*), L_D = 2 w tan(beta)/E1*, "
                            "F_s = E1* L_a L_D");
  } else {
    h.emplace_back("units", "reduced (THEORY.md section 14): a_bar = a/L_a, D = delta/L_D, Z = z/L_D, "
                            "P = F/(pi w R), tau = t v*/L_a");
  }
  h.emplace_back("eta = t/L_a", num(eta));
  h.emplace_back("k_bar", std::isinf(k_bar) ? std::string("inf (displacement control)")
                          : k_bar == 0.0    ? std::string("0 (load control: rates are dP/dtau)")
                                            : num(k_bar));
  h.emplace_back("n, n_adv, v_a*/v*", num(law.n) + ", " + num(law.n_adv) + ", " + num(law.speed_ratio_adv));
  h.emplace_back("protocol", args.require("--protocol"));
  h.emplace_back(kRunTime, num(std::round(seconds * 1e3) / 1e3));
  Output out(output_path);
  std::ostream& os = out.stream();
  if (rates.empty()) {
    const KineticsResult& r = runs.front();
    h.emplace_back("pull-off P, tau, a_bar", num(r.pulloff.load) + ", " + num(r.pulloff.tau) + ", " +
                                                 num(r.pulloff.a_bar));
    h.emplace_back("loss of contact P, tau, a_bar", num(r.loss.load) + ", " + num(r.loss.tau) + ", " +
                                                        num(r.loss.a_bar));
    h.emplace_back("drive work, dissipation [pi w L_a^2]", num(r.work) + ", " + num(r.dissipation));
    h.emplace_back("ODE steps (gsl_odeiv2 msbdf)", std::to_string(r.steps));
    const std::vector<std::string> columns = {"tau", "Z", "D", "a_bar", "P", "G_over_w", "segment"};
    write_header(os, h, columns);
    for (const KineticsSample& p : r.samples) {
      write_row(os, {p.tau, p.z, p.penetration, p.a_bar, p.load, p.g_over_w, p.segment + 1.0}, columns);
    }
  } else {
    const std::vector<std::string> columns = {"V", "P_pulloff", "tau_pulloff", "a_bar_pulloff", "P_loss",
                                              "tau_loss"};
    write_header(os, h, columns);
    for (std::size_t i = 0; i < runs.size(); ++i) {
      const KineticsResult& r = runs[i];
      write_row(os, {rates[i], r.pulloff.load, r.pulloff.tau, r.pulloff.a_bar, r.loss.load, r.loss.tau}, columns);
    }
  }
  out.commit();
  return kExitSuccess;
}

// The SI run's stack and setup (--radius .. --protocol), in the order the options are checked.
struct SiSetup {
  Stack stack;
  KineticsSetupSI setup;
};

// --radius R or --shape sphere:R|cone:BETA (the shapes the JKR table serves, section 14).
void parse_tip(const Arguments& args, KineticsSetupSI& setup) {
  const auto shape = args.get("--shape");
  if (shape && args.has("--radius")) throw InputError("--radius: not with --shape (give sphere:R there)");
  if (!shape) {
    setup.radius = parse_quantity(args.require("--radius"), Quantity::kLength, "--radius");
    return;
  }
  const std::string text = trim(*shape);
  const std::size_t colon = text.find(':');
  const std::string kind = text.substr(0, colon);
  const std::string value = colon == std::string::npos ? "" : text.substr(colon + 1);
  if (kind == "sphere" && !value.empty()) {
    setup.radius = parse_quantity(value, Quantity::kLength, "--shape");
  } else if (kind == "cone" && !value.empty()) {
    setup.tip = KineticsTip::kCone;
    setup.half_angle = parse_angle(value, "--shape");
  } else {
    throw InputError("--shape: '" + *shape + "' not allowed (kinetics serves sphere:R and cone:BETA, the shapes "
                     "the JKR table serves)");
  }
}

SiSetup parse_si_setup(const Arguments& args) {
  KineticsSetupSI setup;
  parse_tip(args, setup);
  const double film_thickness =
      args.has("--layer") ? 0.0 : parse_quantity(args.require("--thickness"), Quantity::kLength, "--thickness");
  Stack stack = parse_stack(args);
  setup.thickness = args.has("--layer") ? coating_thickness(args, stack) : film_thickness;
  setup.work = parse_quantity(args.require("--work"), Quantity::kEnergy, "--work");
  setup.v_star = positive_speed(args.require("--v-star"), false, "--v-star");
  auto exponent = [&](const std::string& option) { return parse_exponent(args, option); };
  setup.n = exponent("--n");
  if (args.has("--v-star-adv")) setup.v_star_adv = positive_speed(*args.get("--v-star-adv"), false, "--v-star-adv");
  if (args.has("--n-adv")) setup.n_adv = exponent("--n-adv");
  setup.spring = parse_spring(args.require("--spring"));
  setup.protocol = parse_protocol(args.require("--protocol"), setup.spring == 0.0);
  return {std::move(stack), std::move(setup)};
}

// --fit FILE: the curves (columns curve t F [sigma_F]; curve numbers 1..N in any row order),
// each driven by --protocol with its retract at the curve's entry of --retract-speeds.
std::vector<fit::KineticsCurve> read_fit_curves(const Arguments& args, const KineticsSetupSI& setup) {
  const std::string path = args.require("--fit");
  DataTable table;
  try {
    table = read_data_file(path, 0);
  } catch (const InputError& e) {
    throw InputError("--fit: " + std::string(e.what()));
  }
  const std::size_t columns = table.columns.size();
  if (columns != 3 && columns != 4) {
    throw InputError("--fit: " + short_name(path) + " has " + std::to_string(columns) +
                     " columns; expected curve t F [sigma_F] (curve number, time in s since first contact, force in N, "
                     "its uncertainty)");
  }
  std::vector<fit::KineticsCurve> curves;
  for (std::size_t row = 0; row < table.rows(); ++row) {
    const double index = table.columns[0][row];
    const std::string where = "--fit: " + short_name(path) + ":" + std::to_string(table.line_numbers[row]) + ": ";
    if (!(index >= 1.0 && index <= 1000.0 && index == std::floor(index))) {
      throw InputError(where + "curve number " + num(index) + " not allowed (need an integer 1..1000)");
    }
    const auto c = static_cast<std::size_t>(index);
    if (c > curves.size()) curves.resize(c);
    curves[c - 1].time.push_back(table.columns[1][row]);
    curves[c - 1].force.push_back(table.columns[2][row]);
    if (columns == 4) curves[c - 1].sigma_force.push_back(table.columns[3][row]);
  }
  std::vector<double> speeds;
  const bool load_control = setup.spring == 0.0;
  if (const auto text = args.get("--retract-speeds")) {
    speeds = parse_rate_list(*text, load_control ? Rate::kForceRate : Rate::kSpeed, "--retract-speeds");
    if (speeds.size() != curves.size()) {
      throw InputError("--retract-speeds: " + std::to_string(speeds.size()) + " speeds for the " +
                       std::to_string(curves.size()) + " curves of --fit (one per curve, in curve order)");
    }
  }
  for (std::size_t c = 0; c < curves.size(); ++c) {
    if (curves[c].time.empty()) {
      throw InputError("--fit: " + short_name(path) + " has no rows of curve " + std::to_string(c + 1) +
                       " (curves are numbered 1..N)");
    }
    curves[c].protocol = setup.protocol;
    curves[c].spring = setup.spring;
    if (!speeds.empty()) curves[c].protocol.back().speed = speeds[c];
  }
  return curves;
}

ExitCode run_kinetics_fit(const Arguments& args, std::chrono::steady_clock::time_point started) {
  if (args.has("--plot")) throw InputError("--plot: not with --fit (a simulation's plot; the fit's table has the model)");
  const SiSetup parsed = parse_si_setup(args);
  const Header notes = report_plausibility("kinetics", args);
  const KineticsSetupSI& setup = parsed.setup;
  if (setup.tip != KineticsTip::kSphere) throw InputError("--shape: with --fit only sphere:R (or --radius)");
  if (setup.protocol.back().kind != DriveSegment::Kind::kRetract || setup.protocol.back().has_target) {
    throw InputError("--protocol: with --fit the last segment is the retract until contact is lost (retract:SPEED)");
  }
  fit::KineticsFitProblem problem;
  problem.radius = setup.radius;
  problem.thickness = setup.thickness;
  problem.work = setup.work;
  problem.v_star = setup.v_star;
  problem.n = setup.n;
  problem.v_star_adv = setup.v_star_adv;
  problem.n_adv = setup.n_adv;
  problem.solver_tolerance = solver_tolerance(args);
  if (const auto text = args.get("--free")) {
    problem.free = {{false, false, false, false, false}};
    for (const std::string& raw : split_on(*text, ',')) {
      const std::string name = trim(raw);
      int which = -1;
      for (int j = 0; j < fit::kKineticsParameterCount; ++j) {
        if (name == fit::kinetics_parameter_name(j)) which = j;
      }
      if (which < 0) throw InputError("--free: '" + name + "' not allowed (names among w, v_star, n, t, E1)");
      problem.free[static_cast<std::size_t>(which)] = true;
    }
  }
  const std::vector<fit::KineticsCurve> curves = read_fit_curves(args, setup);
  const std::string output_path = args.get("--output").value_or("");
  check_output_path(output_path, "--output");
  fit::Result r;
  try {
    r = fit::fit_kinetics(parsed.stack, curves, problem);
  } catch (const InputError& e) {
    const std::string message = e.what();
    throw InputError((message.find("v_star and n") != std::string::npos ? "--retract-speeds, --free: " : "--fit: ") +
                     message);
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  Header h{{"command", "kinetics --fit"}};
  h.emplace_back("sphere radius R [m]", num(setup.radius));
  add_material_header(h, parsed.stack);
  h.emplace_back("model", "crack kinetics, receding G - w = w (|v|/v*)^n (THEORY.md section 14, fitting); "
                          "residual F at the measured times");
  h.emplace_back("protocol", args.require("--protocol"));
  std::string speeds;
  for (const auto& c : curves) speeds += (speeds.empty() ? "" : ", ") + num(c.protocol.back().speed);
  h.emplace_back("retract speed of each curve", speeds);
  h.emplace_back("drive", setup.spring == 0.0 ? std::string("load control (force ramp)")
                          : std::isinf(setup.spring) ? std::string("displacement control")
                                                     : "spring k = " + num(setup.spring) + " N/m");
  for (std::size_t j = 0; j < r.parameters.size(); ++j) {
    const auto& info = r.parameters[j];
    const std::string unit = std::string(info.unit).empty() ? "" : " [" + std::string(info.unit) + "]";
    h.emplace_back(info.name + unit, num(r.value[j]) + (r.free[j] ? " +- " + num(r.standard_error[j]) : " (fixed)"));
  }
  for (std::size_t a = 0; a < r.parameters.size(); ++a) {
    for (std::size_t b = a + 1; b < r.parameters.size(); ++b) {
      if (!r.free[a] || !r.free[b]) continue;
      const std::string pair = r.parameters[a].name + ", " + r.parameters[b].name;
      const double c = r.correlation[a][b];
      h.emplace_back("correlation " + pair, num(c));
      if (std::fabs(c) > 0.99) {  // as `fit`: the data hardly separate the two
        const std::string w = "correlation " + pair + " = " + num(std::round(c * 1e4) / 1e4) +
                              " (|r| > 0.99): the curves hardly separate them; fix one or add curves that do";
        h.emplace_back("warning", w);
        std::cerr << "coatcontact kinetics: warning: " << w << "\n";
      }
    }
  }
  h.insert(h.end(), notes.begin(), notes.end());
  h.emplace_back("points fitted (up to each pull-off), rows, curves",
                 std::to_string(r.points) + ", " + std::to_string(r.model_force.size()) + ", " + std::to_string(curves.size()));
  h.emplace_back("R^2", num(r.r_squared));
  h.emplace_back(r.weighted ? "chi2/dof" : "residual sigma [N]", num(r.weighted ? r.chi2_per_dof : r.residual_sigma));
  h.emplace_back("iterations, simulations", std::to_string(r.iterations) + ", " + std::to_string(r.solver_calls));
  h.emplace_back(kRunTime, num(std::round(seconds * 1e3) / 1e3));
  Output out(output_path);
  std::ostream& os = out.stream();
  // fitted 0: after the curve's pull-off, outside the residual (THEORY.md section 14, fitting).
  const std::vector<std::string> table_columns = {"curve", "t_s", "F_N", "F_model_N", "residual_N", "fitted"};
  write_header(os, h, table_columns);
  std::size_t i = 0;
  for (std::size_t c = 0; c < curves.size(); ++c) {
    for (std::size_t k = 0; k < curves[c].time.size(); ++k, ++i) {
      write_row(os, {c + 1.0, curves[c].time[k], curves[c].force[k], r.model_force[i], r.residual[i],
                     r.clamped[i] ? 0.0 : 1.0}, table_columns);
    }
  }
  out.commit();
  return kExitSuccess;
}

// The header of an SI run up to its results: the setup, the scales (THEORY.md section 14) and
// the homogeneous JKR reference.
Header si_header(const Arguments& args, const Stack& stack, const KineticsSetupSI& setup, const KineticsScales& scales,
                 const Header& notes) {
  const bool cone = setup.tip == KineticsTip::kCone;
  const bool load_control = setup.spring == 0.0;
  Header h{{"command", "kinetics"}};
  if (cone) {
    h.emplace_back("cone half included angle beta [deg]", num(setup.half_angle * 180.0 / detail::kPi));
  } else {
    h.emplace_back("sphere radius R [m]", num(setup.radius));
  }
  h.emplace_back("film thickness t [m]", num(setup.thickness));
  h.emplace_back("work of adhesion w [J/m2]", num(setup.work));
  add_material_header(h, stack);
  h.emplace_back("kinetic law", "receding G - w = w (|v|/v*)^n, advancing w - G = w (v/v_a*)^n_adv "
                                "(THEORY.md section 14)");
  h.emplace_back("v* [m/s]", num(setup.v_star));
  h.emplace_back("n", num(setup.n));
  h.emplace_back("v_a* [m/s]", num(setup.v_star_adv > 0.0 ? setup.v_star_adv : setup.v_star));
  h.emplace_back("n_adv", num(setup.n_adv > 0.0 ? setup.n_adv : setup.n));
  h.emplace_back("drive", load_control ? std::string("load control (force ramp)")
                          : std::isinf(setup.spring) ? std::string("displacement control")
                                                     : "spring k = " + num(setup.spring) + " N/m, F = k (z - delta)");
  h.emplace_back("protocol", args.require("--protocol"));
  if (cone) {
    h.emplace_back("length scale L_a = 4 w tan^2(beta)/(pi E1*) [m]", num(scales.length));
    h.emplace_back("penetration scale L_D = 2 w tan(beta)/E1* [m]", num(scales.penetration));
    h.emplace_back("force scale F_s = E1* L_a L_D [N]", num(scales.force));
  } else {
    h.emplace_back("length scale L_a = (pi w R^2/E1*)^(1/3) [m]", num(scales.length));
    h.emplace_back("penetration scale L_D = L_a^2/R [m]", num(scales.penetration));
    h.emplace_back("force scale pi w R [N]", num(scales.force));
  }
  h.emplace_back("time scale L_a/v* [s]", num(scales.time));
  h.insert(h.end(), notes.begin(), notes.end());
  h.emplace_back("eta = t/L_a", num(scales.eta));
  if (!load_control) {
    h.emplace_back(cone ? "k_bar = k L_D/F_s" : "k_bar = k L_D/(pi w R)",
                   std::isinf(scales.k_bar) ? std::string("inf (displacement control)") : num(scales.k_bar));
  }
  h.emplace_back(load_control ? "reduced force rate dP/dtau per N/s" : "reduced base speed dZ/dtau per m/s",
                 num(scales.drive_rate));
  if (!cone) {
    h.emplace_back("JKR reference pull-off (quasi-static, homogeneous film, load control: -3/2 pi w R) [N]",
                   num(-1.5 * detail::kPi * setup.work * setup.radius));
  }
  return h;
}

}  // namespace

int run_kinetics(const Args& raw) {
  return run_guarded("kinetics", [&]() {
    const Arguments args(raw, kSpec);
    if (args.help()) {
      std::cout << usage("kinetics",
                         "--radius R|--shape sphere:R|cone:BETA --thickness t --film E1,nu1 "
                         "--substrate E0,nu0|rigid --work w "
                         "--v-star V --n N --spring k --protocol SEGMENTS [--retract-speeds LIST]\n"
                         "       coatcontact kinetics --fit FILE [--free w,v_star,n,t,E1] (and the options above; "
                         "--retract-speeds: one per curve)\n"
                         "       coatcontact kinetics --eta ETA [--shape sphere|cone] --film E1,nu1 "
                         "--substrate E0,nu0|rigid --n N --k-bar K --protocol SEGMENTS [--retract-speeds LIST]",
                         "Rate-dependent JKR adhesion of a sphere or a cone on a coating (THEORY.md section 14): the\n"
                         "contact edge moves at the speed the crack-kinetics law gives for G - w, the base\n"
                         "moves z(t) through a spring (F = k (z - delta)). Prints t, z, delta, a, F, G from\n"
                         "first contact to the loss of contact, with the pull-off (most tensile force of the\n"
                         "last retract) and the loss of contact in the header; with --retract-speeds one\n"
                         "pull-off row per retract speed instead.",
                         kSpec);
      return kExitSuccess;
    }
    const auto started = std::chrono::steady_clock::now();
    if (args.has("--eta")) return run_reduced_kinetics(args, started);
    if (!args.has("--radius") && !args.has("--shape")) {
      throw InputError("missing required option --radius or --shape (or --eta for a reduced run)");
    }
    for (const char* option : {"--work", "--v-star", "--spring"}) {
      if (!args.has(option)) {
        throw InputError(std::string("missing required option ") + option + " (or --eta for a reduced run)");
      }
    }
    if (args.has("--k-bar")) throw InputError("--k-bar: only with --eta (use --spring in N/m)");
    if (args.has("--fit")) return run_kinetics_fit(args, started);
    if (args.has("--free")) throw InputError("--free: only with --fit");
    const SiSetup parsed = parse_si_setup(args);
    const Header notes = report_plausibility("kinetics", args);
    const Stack& stack = parsed.stack;
    const KineticsSetupSI& setup = parsed.setup;
    const bool load_control = setup.spring == 0.0;
    std::vector<double> speeds;
    if (const auto text = args.get("--retract-speeds")) {
      speeds = parse_rate_list(*text, load_control ? Rate::kForceRate : Rate::kSpeed, "--retract-speeds");
    }
    const double tol = solver_tolerance(args);
    const std::string output_path = args.get("--output").value_or("");
    check_output_path(output_path, "--output");
    const auto plot = plot_path(args);

    const ReducedSolver solver(stack);
    const AdhesiveModel model(solver, tol);
    KineticsScales scales;
    try {
      scales = kinetics_scales(model, setup);
    } catch (const InputError& e) {
      throw InputError(std::string(args.has("--shape") ? "--shape" : "--radius") + ", --thickness, --work, --film: " +
                       std::string(e.what()));
    }
    std::vector<KineticsResultSI> runs;
    try {
      if (speeds.size() > kSweepPlanned) plan_sweep(model, setup, speeds);
      runs = simulate_kinetics_si(model, setup, speeds, speeds.empty());
    } catch (const InputError& e) {
      throw InputError(kinetics_input_message(e.what(), true));
    } catch (const NumericalError& e) {
      throw NumericalError(kinetics_numerical_message(e.what()));
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();

    Header h = si_header(args, stack, setup, scales, notes);
    h.emplace_back(kRunTime, num(std::round(seconds * 1e3) / 1e3));
    std::optional<Output> plot_out;
    if (plot) stage_plot(plot_out, *plot, kinetics_picture(*plot, runs, setup, stack, !speeds.empty()));
    Output out(output_path);
    std::ostream& os = out.stream();
    if (speeds.empty()) {
      const KineticsResultSI& r = runs.front();
      h.emplace_back("pull-off (most tensile force of the last retract) [N]", num(r.pulloff.force));
      h.emplace_back("pull-off time [s]", num(r.pulloff.time));
      h.emplace_back("pull-off contact radius [m]", num(r.pulloff.radius));
      h.emplace_back("loss of contact force [N]", num(r.loss.force));
      h.emplace_back("loss of contact time [s]", num(r.loss.time));
      h.emplace_back("loss of contact radius (a_bar_end L_a) [m]", num(r.loss.radius));
      h.emplace_back("drive work, dissipation [pi w L_a^2]",
                     num(r.reduced.work) + ", " + num(r.reduced.dissipation));
      h.emplace_back("ODE steps (gsl_odeiv2 msbdf)", std::to_string(r.reduced.steps));
      for (const auto& w : r.reduced.warnings) h.emplace_back("warning", w);
      const std::vector<std::string> columns = {"t_s", "z_m", "delta_m", "a_m", "F_N", "G_J_m2"};
      write_header(os, h, columns);
      for (std::size_t i = 0; i < r.t.size(); ++i) {
        write_row(os, {r.t[i], r.z[i], r.delta[i], r.a[i], r.force[i], r.g[i]}, columns);
      }
    } else {
      const std::string unit = load_control ? "N_s" : "m_s";
      const std::vector<std::string> columns = {"V_" + unit, "F_pulloff_N", "t_pulloff_s", "a_pulloff_m",
                                                "F_loss_N", "t_loss_s", "V_reduced", "P_pulloff"};
      write_header(os, h, columns);
      for (const KineticsResultSI& r : runs) {
        write_row(os, {r.retract_speed, r.pulloff.force, r.pulloff.time, r.pulloff.radius, r.loss.force,
                       r.loss.time, r.retract_speed * scales.drive_rate, r.reduced.pulloff.load},
                  columns);
      }
    }
    out.commit();
    if (plot_out) plot_out->commit();
    return kExitSuccess;
  });
}

}  // namespace coatcontact::cli
