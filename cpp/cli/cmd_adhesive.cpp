// Subcommands `adhesive`, `pulloff` and `sphere`: the adhesive sphere on a coated substrate
// (THEORY.md section 5) in the Maugis normalization and in physical units.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "coatcontact/adhesion.hpp"
#include "coatcontact/contact.hpp"
#include "coatcontact/cli_support.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/reduced.hpp"
#include "checks.hpp"
#include "coatcontact/curve_plot.hpp"
#include "coatcontact/si_text.hpp"
#include "commands.hpp"
#include "lambda_options.hpp"
#include "pulloff_spring.hpp"

namespace coatcontact::cli {

namespace {

using Header = std::vector<std::pair<std::string, std::string>>;

const char* const kNormalization =
    "P = F/(pi w R), D = delta/(pi^2 w^2 R/E1*^2)^(1/3), a_bar = a/(pi w R^2/E1*)^(1/3), "
    "eta = t/(pi w R^2/E1*)^(1/3) (THEORY.md section 5)";

std::string num(double v) { return format_parameter(v, "header value"); }

std::string short_num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

static_assert(kDefaultAdhesiveTolerance == 1e-8, "--help prints the default tolerance as 1e-8");

// The options every subcommand shares.
std::vector<OptionSpec> material_options(bool si = false) {
  return {
      film_option(),
      layer_option(si),
      substrate_option(),
      indenter_option(),
      tol_option("1e-8"),
      {"--output", "FILE", "write to FILE atomically instead of stdout", false},
  };
}

double parse_tolerance(const Arguments& args) {
  const auto text = args.get("--tol");
  if (!text) return kDefaultAdhesiveTolerance;
  const double tol = parse_number(*text, "--tol");
  try {
    check_tolerance(tol);
  } catch (const InputError&) {
    throw InputError("--tol: value " + quoted(*text) + " not allowed (need " + short_num(kMinimumTolerance) +
                     " <= T <= " + short_num(kMaximumTolerance) + ")");
  }
  return tol;
}


std::vector<double> parse_scaled_list(const std::string& text, const std::string& option) {
  std::vector<double> values = parse_list(text, option);
  for (double v : values) {
    if (!(v >= kMinimumScaled && v <= kMaximumScaled)) {
      throw InputError(option + ": value " + short_num(v) + " in " + quoted(text) + " not allowed (every value must be in [" +
                       short_num(kMinimumScaled) + ", " + short_num(kMaximumScaled) + "])");
    }
  }
  return values;
}

// Runs a model call; an InputError from inside (a derived a/t out of the solver's range) is
// reported with the options that produced it.
template <typename Call>
auto with_options(const std::string& options, Call&& call) {
  try {
    return call();
  } catch (const InputError& e) {
    throw InputError(options + ": " + e.what());
  }
}

// Header lines describing the material pair and the reduced-variable table.
void describe_table(Header& h, const AdhesiveModel& model, double tol) {
  const ReducedTable& t = model.table();
  h.emplace_back("reduced variables",
                 "ReducedSolver at tolerance " + num(tol) +
                     ", interpolated: piecewise Chebyshev series of ln X in ln(a/t), order " +
                     std::to_string(t.options().order) + " per " +
                     (t.options().decades_per_segment == 1.0 ? std::string("decade")
                                                             : short_num(t.options().decades_per_segment) + " decades") +
                     " of a/t (halved where needed)");
  h.emplace_back("solver evaluations", std::to_string(t.source_evaluations()));
  h.emplace_back("interpolation segments", std::to_string(t.segments()));
  h.emplace_back("interpolation error estimate (relative)", num(t.interpolation_error_estimate()));
  h.emplace_back("solver error estimate (relative, max)", num(t.source_error_estimate()));
}

std::string join(const std::vector<double>& values) {
  std::string s;
  for (std::size_t i = 0; i < values.size(); ++i) s += (i ? "," : "") + num(values[i]);
  return s;
}

// --tol sets the accuracy of the JKR blocks (lambda = inf) only: with every lambda finite it
// would be silently unused, so it is refused.
void refuse_unused_tol(const Arguments& args, const std::vector<double>& lambdas) {
  if (!args.has("--tol")) return;
  for (double lambda : lambdas) {
    if (std::isinf(lambda)) return;
  }
  throw InputError("--tol: not used with a finite --lambda (the Maugis-Dugdale zone is solved per contact radius "
                   "to a fixed accuracy, THEORY.md section 13; --tol sets the JKR blocks, lambda = inf); omit --tol");
}

void add_pulloff_warnings(Header& h, const Pulloff& p) {
  for (const auto& w : p.warnings) h.emplace_back("warning", w);
}

void add_si_pulloff_warnings(Header& h, const Pulloff& p, double length) {
  for (const auto& w : p.warnings) h.emplace_back("warning", si_pulloff_warning(w, length));
}

// The curve of `sphere` through the table. The table is built a decade of a/t at a time: when
// the decade holding the requested radii reaches beyond what the solver can deliver at `tol`
// (`solve_alone`: the probe found the request's own radii servable), each radius is solved on
// its own and `note` says so.
std::vector<CurvePoint> sphere_curve(const AdhesiveModel& model, double eta, const std::vector<double>& a_bar,
                                     bool solve_alone, double tol, std::string& note) {
  try {
    return model.curve(eta, a_bar);
  } catch (const NumericalError& e) {
    if (!solve_alone) throw;
    note = "solved at each contact radius at tolerance " + num(tol) +
           " (the interpolation table's decade of a/t around these radii cannot be built: " + e.what() + ")";
    return model.curve_solved(eta, a_bar);
  }
}

// sphere_curve returning every point it can: through the table, points of a decade that cannot
// be built are not delivered; when the radii are solved alone, each radius that cannot be
// solved at `tol` is not delivered (`status`, one per radius, receives the reasons).
std::vector<CurvePoint> sphere_curve_tolerant(const AdhesiveModel& model, double eta, const std::vector<double>& a_bar,
                                              bool solve_alone, double tol, std::string& note,
                                              std::vector<PointStatus>& status) {
  if (!solve_alone) return model.curve(eta, a_bar, status);
  try {
    return sphere_curve(model, eta, a_bar, solve_alone, tol, note);
  } catch (const NumericalError&) {
  }
  // A radius failed its own solve too: each alone, so that the others are delivered.
  note = "solved at each contact radius at tolerance " + num(tol) +
         " (the interpolation table's decades of a/t around these radii cannot be built)";
  std::vector<CurvePoint> points(a_bar.size());
  status.assign(a_bar.size(), PointStatus{});
  for (std::size_t i = 0; i < a_bar.size(); ++i) {
    try {
      points[i] = model.curve_solved(eta, {a_bar[i]}).front();
    } catch (const NumericalError& e) {
      status[i] = {false, e.what()};
      points[i].eta = eta;
      points[i].a_bar = a_bar[i];
    }
  }
  return points;
}

// The pull-off of `sphere` in SI units, header lines.
void add_sphere_pulloff(Header& h, const Contact& sphere, const Pulloff& pulloff) {
  h.emplace_back("pull-off force, load control [N]", num(sphere.pulloff_force_load()));
  h.emplace_back("pull-off contact radius, load control [m]", num(pulloff.load_control.a_bar * sphere.length_scale()));
  h.emplace_back("pull-off penetration, load control [m]",
                 num(pulloff.load_control.penetration * sphere.penetration_scale()));
  h.emplace_back("pull-off force, displacement control [N]", num(sphere.pulloff_force_disp()));
  h.emplace_back("pull-off contact radius, displacement control [m]",
                 num(pulloff.displacement_control.a_bar * sphere.length_scale()));
  h.emplace_back("pull-off penetration, displacement control [m]",
                 num(pulloff.displacement_control.penetration * sphere.penetration_scale()));
  h.emplace_back("normalized pull-off P (load, displacement)",
                 num(pulloff.load_control.load) + ", " + num(pulloff.displacement_control.load));
}

// --spring k [N/m] of `sphere`, 0 without it; not with the cohesive zone.
double parse_sphere_spring(const Arguments& args, bool cohesive_zone) {
  const auto text = args.get("--spring");
  if (!text) return 0.0;
  if (cohesive_zone) {
    throw InputError("--spring: not used with --cohesive-stress/--range (the cohesive zone's pull-offs are under "
                     "load and displacement control only); omit --spring");
  }
  return parse_rate(*text, Rate::kStiffness, "--spring");
}

// `sphere --spring k` (THEORY.md section 10, as `contact --spring`): the pull-off through a spring
// of stiffness k [N/m], k_bar = k L_D/(pi w R), the jump where dF/d(delta) = -k, in SI units.
void add_sphere_spring(Header& h, const AdhesiveModel& model, const Contact& sphere, double spring) {
  const double k_bar = spring * sphere.penetration_scale() / sphere.force_scale();
  const SpringPulloff p = model.pulloff_spring(sphere.eta(), k_bar);
  h.emplace_back("spring stiffness k [N/m]", num(spring));
  h.emplace_back("k_bar = k (pi^2 w^2 R/E1*^2)^(1/3)/(pi w R)", num(k_bar));
  h.emplace_back("pull-off force, spring control [N]",
                 num(p.point.load * sphere.force_scale()) + " (contact radius " +
                     num(p.point.a_bar * sphere.length_scale()) + " m, penetration " +
                     num(p.point.penetration * sphere.penetration_scale()) + " m)");
  for (const auto& w : p.warnings) h.emplace_back("warning", si_pulloff_warning(w, sphere.length_scale()));
}

// Options and inputs shared by `adhesive` and `pulloff`: the material pair, the eta list and
// the solver tolerance.
std::vector<OptionSpec> normalized_options() {
  auto spec = material_options();
  spec.insert(spec.begin() + 2, {"--eta", "LIST",
                                 "film thickness over (pi w R^2/E1*)^(1/3), each in [1e-6, 1e6]: "
                                 "v1,v2,... or MIN:MAX:N",
                                 true});
  spec.push_back(lambda_option());
  spec.push_back(md_direct_option());
  return spec;
}

struct NormalizedInputs {
  Stack stack;
  std::vector<double> etas;
  double tol;
};

NormalizedInputs parse_normalized_inputs(const Arguments& args) {
  return {parse_stack(args), parse_scaled_list(args.require("--eta"), "--eta"), parse_tolerance(args)};
}

}  // namespace

// ---- coatcontact adhesive ---------------------------------------------------------

int run_adhesive(const Args& raw) {
  return run_guarded("adhesive", [&]() {
    auto spec = normalized_options();
    spec.insert(spec.begin() + 3, {"--a-bar", "LIST",
                                   "contact radii a/(pi w R^2/E1*)^(1/3), each in [1e-6, 1e6] (default 0.01:10:400 log-spaced, "
                                   "widened to 0.01 min(1,r):10 max(1,r), r = (E1*/E0*)^(1/3))",
                                   false});
    spec.push_back(strict_option());
    const Arguments args(raw, spec);
    if (args.help()) {
      std::cout << usage("adhesive", "--film E1,nu1 --substrate E0,nu0|rigid --eta LIST [options]",
                         "Normalized adhesive sphere on a coated substrate: load P and penetration D versus\n"
                         "contact radius a_bar, one block per eta (blocks separated by two blank lines).\n"
                         "JKR: a point whose decade of the reduced-variable table cannot be built at --tol\n"
                         "is a '# not delivered' row with its reason (exit 0 while one point is delivered);\n"
                         "with --strict, exit 3 at the first one.\n" +
                             std::string(kNormalization),
                         spec);
      return 0;
    }
    const auto [stack, etas, tol] = parse_normalized_inputs(args);
    std::vector<double> a_bar;
    if (const auto text = args.get("--a-bar")) a_bar = parse_scaled_list(*text, "--a-bar");
    const auto lambdas = parse_lambdas(args);
    std::vector<std::pair<std::string, std::size_t>> lists = {
        {"--eta", etas.size()}, {"--a-bar", a_bar.empty() ? std::size_t{400} : a_bar.size()}};
    if (lambdas) lists.emplace_back("--lambda", lambdas->size());
    check_rows(lists);
    const bool md_direct = parse_md_direct(args, lambdas.has_value(), "a finite --lambda");
    if (lambdas) {
      refuse_unused_tol(args, *lambdas);
    }
    if (lambdas && args.has("--strict")) {
      throw InputError("--strict: not used with --lambda (it selects how the JKR curve's points are delivered); "
                       "omit --strict");
    }
    Output out(args.get("--output").value_or(""));
    if (lambdas) {  // Maugis-Dugdale zone (THEORY.md section 13), lambda_options.cpp
      write_md_adhesive(out.stream(), stack, etas, *lambdas, a_bar, tol, md_direct);
      out.commit();
      return 0;
    }

    const ReducedSolver solver(stack);
    const AdhesiveModel model(solver, tol);
    if (a_bar.empty()) {
      const auto [lo, hi] = model.default_curve_range();
      a_bar = log_spaced(lo, hi, 400);
    }
    const bool strict = args.has("--strict");
    plan_table_work(solver, tol, *std::min_element(a_bar.begin(), a_bar.end()) / *std::max_element(etas.begin(), etas.end()),
                    *std::max_element(a_bar.begin(), a_bar.end()) / *std::min_element(etas.begin(), etas.end()),
                    "--tol " + num(tol) + " with --eta and --a-bar", !strict);
    std::vector<std::vector<CurvePoint>> curves;
    std::vector<PointStatus> status;  // every point of every block, in output order
    for (double eta : etas) {
      curves.push_back(with_options("--eta " + num(eta) + " with --a-bar", [&] {
        if (strict) return model.curve(eta, a_bar);
        std::vector<PointStatus> block;
        auto points = model.curve(eta, a_bar, block);
        status.insert(status.end(), block.begin(), block.end());
        return points;
      }));
    }
    if (strict) status.assign(etas.size() * a_bar.size(), PointStatus{});
    require_some_delivered(status, "point");

    Header h{{"command", "adhesive"}};
    add_material_header(h, stack);
    h.emplace_back("normalization", kNormalization);
    h.emplace_back("eta", join(etas));
    h.emplace_back("a_bar points", std::to_string(a_bar.size()));
    describe_table(h, model, tol);
    h.emplace_back("blocks", "one per eta in the order given, separated by two blank lines (gnuplot index)");
    const auto where = [&](std::size_t i) {
      const CurvePoint& p = curves[i / a_bar.size()][i % a_bar.size()];
      return "eta = " + format_value(p.eta, "eta") + ", a_bar = " + format_value(p.a_bar, "a_bar");
    };
    report_not_delivered(h, "adhesive", status, where);
    const std::vector<std::string> columns = {"eta", "a_bar", "a_over_t", "P", "D"};
    std::ostream& os = out.stream();
    write_header(os, h, columns);
    for (std::size_t b = 0; b < curves.size(); ++b) {
      if (b > 0) os << "\n\n";
      for (std::size_t k = 0; k < curves[b].size(); ++k) {
        const CurvePoint& p = curves[b][k];
        const std::size_t i = b * a_bar.size() + k;
        if (!status[i].delivered) {
          write_not_delivered(os, where(i), status[i].reason);
          continue;
        }
        write_row(os, {p.eta, p.a_bar, p.a_over_t, p.load, p.penetration}, columns);
      }
    }
    out.commit();
    return 0;
  });
}

// ---- coatcontact pulloff ----------------------------------------------------------

namespace {

// --plot of `pulloff`: P = F/(pi w R) at pull-off against eta under load and displacement
// control, with the homogeneous JKR values -3/2 and -5/6 (THEORY.md section 5).
std::string pulloff_picture(const std::string& path, const std::vector<Pulloff>& results, const Stack& stack) {
  PlotSeries load{"coated, load control", {}, {}, PlotSeries::Style::kLine, kPlotCoated};
  PlotSeries disp{"coated, displacement control", {}, {}, PlotSeries::Style::kLine, kPlotSecond};
  for (const Pulloff& r : results) {
    load.x.push_back(r.eta);
    load.y.push_back(r.load_control.load);
    disp.x.push_back(r.eta);
    disp.y.push_back(r.displacement_control.load);
  }
  if (results.size() == 1) load.style = disp.style = PlotSeries::Style::kPoints;
  const double lo = load.x.front(), hi = load.x.back();
  PlotPanel panel{"film thickness η = t/∛(π w R²/E1*)", "", "pull-off P = F/(π w R)", "", true,
                  {load, disp,
                   {"JKR, homogeneous film (-3/2, -5/6)", {lo, hi}, {-1.5, -1.5}, PlotSeries::Style::kDashed,
                    kPlotReference},
                   {"", {lo, hi}, {-5.0 / 6.0, -5.0 / 6.0}, PlotSeries::Style::kDashed, kPlotReference}},
                  ""};
  return render_curve_plot({panel}, "pull-off of a sphere, E1*/E0* = " + si_text(stack.modulus_ratio(), ""), path);
}

// The model of `pulloff`'s JKR rows. Several etas: one verified table over exactly the a/t that
// they scan (THEORY.md section 5, "Pull-off sweeps"; note empty). One eta, --direct, or a node
// the solver cannot deliver: the table of decades, built as each eta reaches them (a failing
// decade then costs only the etas that need it, and an eta's row is the same as from its own
// call); note says why.
std::unique_ptr<AdhesiveModel> pulloff_model(const ReducedSolver& solver, double tol, const std::vector<double>& etas,
                                             bool direct, std::string& note) {
  note = "--direct";
  std::unique_ptr<AdhesiveModel> model;
  if (!direct) model = pulloff_sweep_model(solver, tol, etas, &note);
  if (model) {
    note.clear();
    return model;
  }
  return std::make_unique<AdhesiveModel>(solver, tol);
}

void describe_pulloff_table(Header& h, const AdhesiveModel& model, double tol, const std::string& note) {
  describe_table(h, model, note.empty() ? kPulloffNodeShare * tol : tol);
  h.emplace_back("table", note.empty() ? "verified over the etas' whole a/t range (segments checked against direct "
                                         "solves at their ends; THEORY.md section 5, Pull-off sweeps)"
                                       : "decades of a/t as the etas reach them (" + note + ")");
  h.emplace_back("error estimates", std::string("*_err: absolute, from the table's errors of the reduced variables "
                                                "and their log-derivatives at the pull-off; reduced_err: relative, "
                                                "of the reduced variables there") +
                                        (note.empty() ? " (<= --tol)" : ""));
}

}  // namespace

int run_pulloff(const Args& raw) {
  return run_guarded("pulloff", [&]() {
    auto spec = normalized_options();
    spec.push_back(spring_bar_option());
    spec.push_back(strict_option());
    spec.push_back({"--direct", "",
                    "JKR: build the reduced table a decade of a/t at a time as each eta reaches it (order 24, "
                    "tail 1e-10) instead of one verified table over all the etas' a/t",
                    false});
    spec.push_back(plot_option("P_load and P_disp against eta (JKR)"));
    const Arguments args(raw, spec);
    if (args.help()) {
      std::cout << usage("pulloff", "--film E1,nu1 --substrate E0,nu0|rigid --eta LIST [options]",
                         "Normalized pull-off of the adhesive sphere for each eta: under load control\n"
                         "(minimum of P over a_bar) and under displacement control (minimum of D), with\n"
                         "a_bar, P and D at each. Located by a root of dP/da_bar (dD/da_bar) after a Brent\n"
                         "minimisation; a '# warning' header line flags several minima or none in range.\n"
                         "JKR: an eta whose pull-off cannot be located at --tol (its reduced-variable table\n"
                         "cannot be built) is a '# not delivered' row with its reason (exit 0 while one eta\n"
                         "is delivered); with --strict, exit 3 at the first one.\n" +
                             std::string(kNormalization),
                         spec);
      return 0;
    }
    const auto [stack, etas, tol] = parse_normalized_inputs(args);
    const auto lambdas = parse_lambdas(args);
    if (lambdas) check_rows({{"--eta", etas.size()}, {"--lambda", lambdas->size()}});
    const bool md_direct = parse_md_direct(args, lambdas.has_value(), "a finite --lambda");
    if (const auto text = args.get("--spring-bar")) {
      check_rows({{"--eta", etas.size()}, {"--spring-bar", parse_spring_bar(*text, "--spring-bar").size()}});
    }
    if (lambdas) {
      refuse_unused_tol(args, *lambdas);
    }
    if (lambdas && args.has("--strict")) {
      throw InputError("--strict: not used with --lambda (it selects how the JKR pull-offs are delivered); omit --strict");
    }
    if (lambdas && args.has("--direct")) {
      throw InputError("--direct: not used with --lambda (it selects the JKR pull-offs' table); the Maugis-Dugdale "
                       "zone's direct solve is --md-direct");
    }
    const auto plot = plot_path(args, lambdas ? "not with --lambda (JKR pull-offs only)" : "");
    Output out(args.get("--output").value_or(""));
    if (lambdas) {  // Maugis-Dugdale zone (THEORY.md section 13), lambda_options.cpp
      const std::vector<double> k_bars =
          args.has("--spring-bar") ? parse_spring_bar(*args.get("--spring-bar"), "--spring-bar") : std::vector<double>{};
      write_md_pulloff(out.stream(), stack, etas, *lambdas, tol, md_direct, k_bars);
      out.commit();
      return 0;
    }

    const ReducedSolver solver(stack);
    std::string table_note;
    const std::unique_ptr<AdhesiveModel> model_holder = pulloff_model(solver, tol, etas, args.has("--direct"), table_note);
    const AdhesiveModel& model = *model_holder;
    const auto [scan_lo, scan_hi] = model.default_curve_range();  // pull-off scans from 0.1 scan_lo
    const bool strict = args.has("--strict");
    // One end of the a/t range out of reach may leave the other etas deliverable; a single eta
    // is refused up front (its scan would build the table for minutes, then fail).
    plan_table_work(solver, tol, 0.1 * scan_lo / *std::max_element(etas.begin(), etas.end()),
                    scan_hi / *std::min_element(etas.begin(), etas.end()), "--tol " + num(tol) + " with --eta",
                    !strict && etas.size() > 1);
    // One pull-off per eta; without --strict an eta whose table cannot be built at --tol is not
    // delivered (its reason kept) and the others are.
    std::vector<Pulloff> results;  // the delivered etas', in order
    std::vector<double> delivered_etas;
    std::vector<PointStatus> status(etas.size());
    for (std::size_t i = 0; i < etas.size(); ++i) {
      try {
        results.push_back(with_options("--eta " + num(etas[i]), [&] { return model.pulloff(etas[i]); }));
        delivered_etas.push_back(etas[i]);
      } catch (const NumericalError& e) {
        if (strict) throw;
        status[i] = {false, e.what()};
      }
    }
    require_some_delivered(status, "pull-off");
    const SpringRows springs(args, model, delivered_etas);  // THEORY.md section 10; empty without --spring-bar

    Header h{{"command", "pulloff"}};
    add_material_header(h, stack);
    h.emplace_back("normalization", kNormalization);
    h.emplace_back("eta", join(etas));
    h.emplace_back("minima", "counted on a log grid of " +
                                 std::to_string(model.pulloff_options().scan_points_per_decade) +
                                 " points per decade of a_bar; the lowest is reported");
    for (const auto& r : results) {
      h.emplace_back("a_bar scan range, eta=" + num(r.eta),
                     "[" + num(r.a_bar_scan_min) + ", " + num(r.a_bar_scan_max) + "]");
    }
    h.emplace_back("location", "Brent minimiser, then root of dP/da_bar (load) or dD/da_bar (displacement) "
                               "on the interpolated curve to relative " +
                                   short_num(model.pulloff_options().location_tolerance));
    describe_pulloff_table(h, model, tol, table_note);
    h.emplace_back("JKR reference (homogeneous film; THEORY.md section 5) P_load, P_disp", "-1.5, -0.8333333333333334");
    for (const auto& r : results) add_pulloff_warnings(h, r);
    springs.describe(h);
    const auto where = [&](std::size_t i) { return "eta = " + format_value(etas[i], "eta"); };
    report_not_delivered(h, "pulloff", status, where);
    std::vector<std::string> columns = {"eta",   "P_load",     "a_bar_load", "D_load",
                                        "P_disp", "a_bar_disp", "D_disp"};
    springs.extend(columns);
    for (const char* name : {"P_load_err", "a_bar_load_err", "D_load_err", "P_disp_err", "a_bar_disp_err",
                             "D_disp_err", "reduced_err"}) {
      columns.emplace_back(name);
    }
    std::ostream& os = out.stream();
    write_header(os, h, columns);
    for (std::size_t i = 0, d = 0; i < etas.size(); ++i) {
      if (!status[i].delivered) {
        write_not_delivered(os, where(i), status[i].reason);
        continue;
      }
      const Pulloff& r = results[d];
      const PulloffPoint &l = r.load_control, &m = r.displacement_control;
      std::vector<double> row = {r.eta, l.load, l.a_bar, l.penetration, m.load, m.a_bar, m.penetration};
      const std::vector<double> errors = {l.load_err,        l.a_bar_err, l.penetration_err,
                                          m.load_err,        m.a_bar_err, m.penetration_err,
                                          std::max(l.reduced_err, m.reduced_err)};
      if (springs.empty()) {
        row.insert(row.end(), errors.begin(), errors.end());
        write_row(os, row, columns);
      } else {
        springs.write(os, d, row, columns, errors);
      }
      ++d;
    }
    std::optional<Output> plot_out;
    if (plot) stage_plot(plot_out, *plot, pulloff_picture(*plot, results, stack));
    out.commit();
    if (plot_out) plot_out->commit();
    return 0;
  });
}

// ---- coatcontact sphere -----------------------------------------------------------

namespace {

// Default number of points of a curve in physical units: `sphere`, `contact` and Python's
// contact() and shape_contact() sample the same count.
constexpr std::size_t kSiCurvePoints = 200;

// The options of `sphere`: the materials, the sphere, the work, the curve's radii, the
// cohesive zone and --strict.
std::vector<OptionSpec> sphere_options() {
  auto spec = material_options(true);
  spec.insert(spec.begin(), {"--radius", "R", "sphere radius (m, or with a unit: mm um nm)", true});
  spec.insert(spec.begin() + 1, {"--thickness", "t", "film thickness (m, or mm um nm); not with --layer", false});
  spec.insert(spec.begin() + 5, {"--work", "w", "work of adhesion (J/m2, or mJ/m2)", true});
  spec.insert(spec.begin() + 6, {"--points", "N",
                                 "number of contact radii, log-spaced over a_bar from 0.01 min(1,r) up to 10 max(1,r), "
                                 "r = (E1*/E0*)^(1/3), ending before a > 0.1 R, delta > t or F/(pi a^2) > 0.1 E1* "
                                 "(default 200, as contact and Python's contact)",
                                 false});
  spec.insert(spec.begin() + 7, {"--contact-radius", "LIST",
                                 "contact radii a in m instead: v1,v2,... or MIN:MAX:N (log-spaced); not with --points",
                                 false});
  spec.push_back({"--spring", "k",
                  "spring stiffness (N/m, or with a unit: 500N/m, 0.5mN/um) of the cantilever or frame: adds the "
                  "spring-controlled pull-off to the header (THEORY.md section 10), as contact --spring",
                  false});
  for (const auto& option : cohesive_options()) spec.push_back(option);
  spec.push_back(strict_option());
  spec.push_back(plot_option("F(a) and F(delta)"));
  return spec;
}

// --plot of `sphere`: F against a and against delta, the coated curve beside the homogeneous
// JKR reference of the film, with both pull-offs of each.
std::string sphere_picture(const std::string& path, const std::vector<Contact::Point>& points, const JkrReference& jkr,
                           const Contact& sphere, const Pulloff* pulloff, const Stack& stack, double thickness,
                           double work) {
  const std::string title = "sphere R = " + si_text(sphere.scales().radius, "m") + " on " + si_text(thickness, "m") +
                            " of " + si_text(stack.top().youngs_modulus, "Pa") + ", E1*/E0* = " +
                            si_text(stack.modulus_ratio(), "") + ", w = " + si_text(work, "J/m^2");
  PlotSeries coated{"coated (this run)", {}, {}, PlotSeries::Style::kLine, kPlotCoated};
  PlotSeries coated_d = coated;
  for (const auto& p : points) {
    coated.x.push_back(p.radius);
    coated.y.push_back(p.force);
    coated_d.x.push_back(p.penetration);
    coated_d.y.push_back(p.force);
  }
  PlotSeries ref{"JKR, homogeneous film", jkr.a, jkr.force, PlotSeries::Style::kDashed, kPlotReference};
  PlotSeries ref_d{"JKR, homogeneous film", jkr.delta, jkr.force, PlotSeries::Style::kDashed, kPlotReference};
  PlotPanel by_a{"contact radius a", "m", "force F", "N", true, {coated, ref}, ""};
  PlotPanel by_delta{"penetration δ", "m", "force F", "N", false, {coated_d, ref_d}, ""};
  if (pulloff) {
    const double l = sphere.length_scale(), d = sphere.penetration_scale();
    PlotSeries marks{"pull-offs (load, displacement control)", {}, {}, PlotSeries::Style::kPoints, kPlotCoated};
    PlotSeries marks_d = marks;
    for (const auto* c : {&pulloff->load_control, &pulloff->displacement_control}) {
      marks.x.push_back(c->a_bar * l);
      marks_d.x.push_back(c->penetration * d);
    }
    marks.y = marks_d.y = {sphere.pulloff_force_load(), sphere.pulloff_force_disp()};
    by_a.series.push_back(marks);
    by_delta.series.push_back(marks_d);
  }
  return render_curve_plot({by_a, by_delta}, title, path);
}

void print_sphere_help(const std::vector<OptionSpec>& spec) {
  std::cout << usage("sphere",
                     "--radius R --thickness t --film E1,nu1 --substrate E0,nu0|rigid --work w [options]",
                     "Adhesive rigid sphere on a coated substrate in physical units: penetration and\n"
                     "force versus contact radius, with the pull-off forces under load and displacement\n"
                     "control in the header. F is compressive positive. '# warning:' header lines (also on\n"
                     "stderr) flag a curve beyond the model: penetration above t, a above 0.1 R, mean\n"
                     "pressure above 0.1 E1*. JKR: a contact radius the solver cannot serve at --tol is a\n"
                     "'# not delivered' row with its reason (exit 0 while one radius is delivered); with\n"
                     "--strict, exit 3 at the first one.",
                     spec);
}

}  // namespace

int run_sphere(const Args& raw) {
  return run_guarded("sphere", [&]() {
    const auto spec = sphere_options();
    const Arguments args(raw, spec);
    if (args.help()) {
      print_sphere_help(spec);
      return 0;
    }
    const double radius = parse_quantity(args.require("--radius"), Quantity::kLength, "--radius");
    // With --layer the layers carry the lengths and T = sum h is the unit (THEORY.md section 12).
    const double film_thickness =
        args.has("--layer") ? 0.0 : parse_quantity(args.require("--thickness"), Quantity::kLength, "--thickness");
    const Stack stack = parse_stack(args);
    const double thickness = args.has("--layer") ? coating_thickness(args, stack) : film_thickness;
    const double work = parse_quantity(args.require("--work"), Quantity::kEnergy, "--work");
    const double tol = parse_tolerance(args);
    const std::size_t points = parse_point_count(args, kSiCurvePoints);
    const auto notes = report_plausibility("sphere", args);
    const auto sigma0 = parse_cohesive_stress(args, stack, radius, thickness, work);
    const bool md_direct = parse_md_direct(args, sigma0.has_value(), "--cohesive-stress or --range");
    const double spring = parse_sphere_spring(args, sigma0.has_value());
    std::vector<double> contact_radii;
    if (const auto text = args.get("--contact-radius")) {
      if (args.has("--points")) throw InputError("--points: not allowed with --contact-radius (which gives the points)");
      contact_radii = parse_quantity_list(*text, Quantity::kLength, "--contact-radius");
      // A contact wider than the sphere is no sphere at all: refused before any solve.
      with_options("--contact-radius with --radius", [&] { check_sphere_contact_radii(contact_radii, radius); });
    }
    if (sigma0 && args.has("--strict")) {
      throw InputError("--strict: not used with --cohesive-stress/--range (it selects how the JKR curve's points are "
                       "delivered); omit --strict");
    }
    const bool strict = args.has("--strict");
    const auto plot = plot_path(args, sigma0 ? "not with --cohesive-stress/--range (JKR curves only)" : "");
    Output out(args.get("--output").value_or(""));
    if (sigma0) {  // Maugis-Dugdale zone (THEORY.md section 13), lambda_options.cpp
      // The zone's accuracy is fixed by its discretization (MaugisDugdaleOptions), not by --tol.
      if (args.has("--tol")) {
        throw InputError("--tol: not used with --cohesive-stress/--range (the Maugis-Dugdale zone is solved per "
                         "contact radius to a fixed accuracy, THEORY.md section 13); omit --tol");
      }
      write_md_sphere(out.stream(), stack, radius, thickness, work, *sigma0, points, contact_radii, md_direct);
      out.commit();
      return 0;
    }

    const ReducedSolver solver(stack);
    const AdhesiveModel model(solver, tol);
    // The Maugis scales must exist and put eta = t/length in the range the normalized
    // commands accept; say which options to change when they do not.
    const Contact sphere = with_options("--radius, --thickness, --work, --film",
                                        [&] { return Contact(model, radius, thickness, work); });
    const double eta = sphere.eta();
    const auto [lo, hi] = model.default_curve_range();
    std::vector<double> a_bar =
        with_options("--contact-radius", [&] { return scaled_contact_radii(contact_radii, sphere.scales()); });
    const double a_bar_min = a_bar.empty() ? lo : std::min(lo, *std::min_element(a_bar.begin(), a_bar.end()));
    const double a_bar_max = a_bar.empty() ? hi : std::max(hi, *std::max_element(a_bar.begin(), a_bar.end()));
    // Probe what the request needs: the pull-off scan's a/t range with the curve's, and when
    // the solver cannot serve the pull-off's part, the curve's own range alone; the pull-off
    // is then left out and the header says why.
    const std::string probe_options = "--tol " + num(tol) + " with --thickness, --radius, --work, --film";
    std::string pulloff_missing;
    try {
      plan_table_work(solver, tol, 0.1 * a_bar_min / eta, a_bar_max / eta, probe_options);
    } catch (const InputError& e) {
      if (a_bar.empty()) throw;
      plan_table_work(solver, tol, *std::min_element(a_bar.begin(), a_bar.end()) / eta,
                      *std::max_element(a_bar.begin(), a_bar.end()) / eta, probe_options, !strict);
      pulloff_missing = e.what();
    }
    const Pulloff* pulloff = nullptr;
    if (pulloff_missing.empty()) pulloff = &sphere.pulloff();
    if (a_bar.empty()) {
      // The curve ends inside the validity limits, but not before the pull-off it reports.
      const double reach = std::max(pulloff->load_control.a_bar, pulloff->displacement_control.a_bar);
      a_bar = sphere_default_a_bar(model, sphere, lo, hi, reach, points);
    }
    std::string solved_note;
    std::vector<PointStatus> status(a_bar.size());
    const std::vector<CurvePoint> curve =
        strict ? sphere_curve(model, sphere.eta(), a_bar, !pulloff_missing.empty(), tol, solved_note)
               : sphere_curve_tolerant(model, sphere.eta(), a_bar, !pulloff_missing.empty(), tol, solved_note, status);
    require_some_delivered(status, "contact radius");
    std::vector<Contact::Point> si;  // every point; only the delivered ones are read
    std::vector<Contact::Point> delivered;
    for (std::size_t i = 0; i < curve.size(); ++i) {
      const CurvePoint& p = curve[i];
      si.push_back({p.a_bar * sphere.length_scale(), p.penetration * sphere.penetration_scale(),
                    p.load * sphere.force_scale()});
      if (status[i].delivered) delivered.push_back(si.back());
    }
    const std::vector<std::string> warnings = sphere.validity_warnings(delivered);

    Header h{{"command", "sphere"}};
    h.emplace_back("sphere radius R [m]", num(radius));
    h.emplace_back("film thickness t [m]", num(thickness));
    h.emplace_back("work of adhesion w [J/m2]", num(work));
    add_material_header(h, stack);
    h.emplace_back("length scale (pi w R^2/E1*)^(1/3) [m]", num(sphere.length_scale()));
    h.emplace_back("penetration scale (pi^2 w^2 R/E1*^2)^(1/3) [m]", num(sphere.penetration_scale()));
    h.emplace_back("force scale pi w R [N]", num(sphere.force_scale()));
    h.emplace_back("eta = t/length scale", num(sphere.eta()));
    h.insert(h.end(), notes.begin(), notes.end());
    const JkrReference jkr = jkr_reference(stack.reference_modulus(), radius, work,
                                           a_bar.front() * sphere.length_scale(),
                                           a_bar.back() * sphere.length_scale(), kSiCurvePoints);
    if (pulloff) {
      add_sphere_pulloff(h, sphere, *pulloff);
      h.push_back(jkr_reference_header(jkr));
    } else {
      h.emplace_back("pull-off", "not computed: its scan over contact radii [" +
                                     num(0.1 * a_bar_min * sphere.length_scale()) + ", " +
                                     num(a_bar_max * sphere.length_scale()) + "] m (a_bar [" + num(0.1 * a_bar_min) + ", " +
                                     num(a_bar_max) + "]) needs radii the solver cannot serve (" + pulloff_missing +
                                     "); the curve at the requested radii is complete");
    }
    if (solved_note.empty()) {
      describe_table(h, model, tol);
    } else {
      h.emplace_back("reduced variables", solved_note);
    }
    if (pulloff) add_si_pulloff_warnings(h, *pulloff, sphere.length_scale());
    if (pulloff && spring > 0.0) add_sphere_spring(h, model, sphere, spring);
    progress_pause();
    if (!pulloff) std::cerr << "coatcontact sphere: warning: pull-off not computed (the curve is): " << pulloff_missing << "\n";
    for (const auto& w : warnings) {
      h.emplace_back("warning", w);
      std::cerr << "coatcontact sphere: warning: " << w << "\n";
    }
    const auto where = [&](std::size_t i) { return "a_m = " + format_value(a_bar[i] * sphere.length_scale(), "a_m"); };
    report_not_delivered(h, "sphere", status, where);
    const std::vector<std::string> columns = {"a_m", "delta_m", "F_N"};
    std::ostream& os = out.stream();
    write_header(os, h, columns);
    for (std::size_t i = 0; i < si.size(); ++i) {
      if (!status[i].delivered) {
        write_not_delivered(os, where(i), status[i].reason);
        continue;
      }
      write_row(os, {si[i].radius, si[i].penetration, si[i].force}, columns);
    }
    std::optional<Output> plot_out;
    if (plot) stage_plot(plot_out, *plot, sphere_picture(*plot, delivered, jkr, sphere, pulloff, stack, thickness, work));
    out.commit();
    if (plot_out) plot_out->commit();
    return 0;
  });
}

}  // namespace coatcontact::cli
