// `coatcontact contact`: the adhesive (JKR) contact of an indenter of any axisymmetric shape
// on a coated substrate, in SI units (THEORY.md sections 5, 9, 10, 11).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "coatcontact/detail/constants.hpp"
#include "coatcontact/cli_support.hpp"
#include "coatcontact/data_file.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/limits.hpp"
#include "coatcontact/reduced.hpp"
#include "coatcontact/shape_contact.hpp"
#include "coatcontact/shape_maugis_dugdale.hpp"
#include "coatcontact/curve_plot.hpp"
#include "coatcontact/si_text.hpp"
#include "checks.hpp"
#include "commands.hpp"
#include "number_text.hpp"

namespace coatcontact::cli {

namespace {

using detail::kPi;
constexpr std::size_t kDefaultPoints = 200;  // as `sphere` and Python's contact()

using Header = std::vector<std::pair<std::string, std::string>>;

std::string num(double v) { return format_parameter(v, "header value"); }

using detail::split;

}  // namespace

// Declared in commands.hpp (also the cone of `kinetics --shape`).
double parse_angle(const std::string& text, const std::string& option) {
  std::string value = text;
  double unit = kPi / 180.0;
  for (const auto& [suffix, factor] : {std::pair<std::string, double>{"deg", kPi / 180.0}, {"rad", 1.0}}) {
    if (value.size() > suffix.size() && value.compare(value.size() - suffix.size(), suffix.size(), suffix) == 0) {
      value = value.substr(0, value.size() - suffix.size());
      unit = factor;
      break;
    }
  }
  const double beta = parse_number(value, option) * unit;
  if (!(beta > 0.0 && beta < kPi / 2)) {
    throw InputError(option + ": half included angle '" + text +
                     "' not allowed (need 0deg < BETA < 90deg, e.g. 70deg)");
  }
  return beta;
}

namespace {

// A factory's InputError, prefixed with the option and its value.
template <typename Make>
std::shared_ptr<const IndenterShape> named(const std::string& text, Make&& make) {
  try {
    return make();
  } catch (const InputError& e) {
    std::string message = e.what();
    if (message.rfind("--shape: ", 0) == 0) message = message.substr(9);  // named once
    throw InputError("--shape: " + quoted(text) + ": " + message);
  }
}

// The radius R of "sphere:R" (the paraboloid stands for a sphere: its validity limits apply),
// 0 for every other shape.
double sphere_radius_of(const std::string& shape_text) {
  const std::string prefix = "sphere:";
  if (shape_text.rfind(prefix, 0) != 0) return 0.0;
  return parse_quantity(shape_text.substr(prefix.size()), Quantity::kLength, "--shape");
}

// Spring stiffness k: N/m, or with a unit (500N/m, 0.5mN/um), in the range of every SI quantity.
double parse_spring(const std::string& text) { return parse_rate(text, Rate::kStiffness, "--spring"); }

std::string jump_text(const ShapeJump& j) {
  return num(j.force) + " (contact radius " + num(j.radius) + " m, penetration " + num(j.penetration) + " m)";
}

const std::vector<OptionSpec> kSpec = {
    {"--shape", "SHAPE",
     "indenter: sphere:R (paraboloid), cone:BETA (half included angle, e.g. 70deg), pyramid:THETA "
     "(four-sided, face half angle, e.g. 68deg for a Vickers tip; the cone of equal area), punch:A, "
     "power:N,R (z = r^N/(N R^(N-1))), blunted-cone:R,BETA (spherical cap tangent to the cone), "
     "profile:FILE (columns r z, '# units:' line allowed)",
     true},
    {"--thickness", "t", "film thickness (m, or with a unit: mm um nm); not with --layer", false},
    film_option(),
    layer_option(true),
    substrate_option(),
    indenter_option(),
    {"--work", "w", "work of adhesion (J/m2, or mJ/m2)", true},
    {"--cohesive-stress", "sigma0",
     "Maugis-Dugdale zone instead of JKR: adhesive stress (Pa, or kPa MPa GPa), range h0 = w/sigma0 at most 1e6 "
     "film thicknesses; every shape but punch (THEORY.md section 13); adds the zone edge c_m",
     false},
    {"--spring", "k", "spring stiffness (N/m, or with a unit: 500N/m, 0.5mN/um), in [1e-100, 1e100] (cantilever, machine frame): adds the spring-controlled pull-off", false},
    {"--contact-radius", "LIST", "contact radii: v1,v2,... or MIN:MAX:N (log-spaced); m, or with a unit (mm um nm)", false},
    {"--points", "N", "number of contact radii over the default range, which ends at the validity limits (default 200; not with --contact-radius)", false},
    tol_option("1e-8"),
    {"--output", "FILE", "write to FILE atomically instead of stdout", false},
    strict_option(),
    plot_option("F(a) and F(delta) (JKR)"),
};

// --tol: the solver's relative tolerance (default 1e-8).
double solver_tolerance(const Arguments& args) {
  double tol = kDefaultTolerance;
  if (const auto text = args.get("--tol")) {
    tol = parse_number(*text, "--tol");
    if (!(tol >= kMinimumTolerance && tol <= kMaximumTolerance)) {
      throw InputError("--tol: value " + quoted(*text) + " not allowed (need 1e-13 <= T <= 0.1)");
    }
  }
  return tol;
}

// The pull-off lines of the header (JKR), with the homogeneous JKR reference of a sphere.
void add_pulloff_header(Header& h, const std::optional<ShapePulloff>& pulloff, const std::string& missing,
                        double spring, const std::optional<JkrReference>& jkr) {
  if (!pulloff) {
    h.emplace_back("pull-off", "not computed: " + missing + " (--strict: exit 3 instead)");
    return;
  }
  h.emplace_back("pull-off force, load control [N]", jump_text(pulloff->load));
  h.emplace_back("pull-off force, displacement control [N]", jump_text(pulloff->displacement));
  if (spring > 0.0) {
    h.emplace_back("spring stiffness k [N/m]", num(spring));
    h.emplace_back("pull-off force, spring control [N]", jump_text(pulloff->spring));
  }
  h.emplace_back("pull-off scan", "contact radii [" + num(pulloff->scan_min) + ", " + num(pulloff->scan_max) +
                                      "] m, 24 per decade, every local minimum refined (Brent)");
  for (const auto& w : pulloff->warnings) h.emplace_back("warning", w);
  if (jkr) h.push_back(jkr_reference_header(*jkr));
}

// --plot of `contact`: F against a and against delta, adhesive and adhesionless, the pull-offs,
// and for a sphere the homogeneous JKR reference of the film.
std::string contact_picture(const std::string& path, const std::vector<ShapePoint>& points,
                            const std::optional<JkrReference>& jkr, const std::optional<ShapePulloff>& pulloff,
                            const std::string& title) {
  PlotSeries adhesive{"coated, JKR (this run)", {}, {}, PlotSeries::Style::kLine, kPlotCoated};
  PlotSeries adhesionless{"coated, no adhesion", {}, {}, PlotSeries::Style::kLine, kPlotSecond};
  PlotSeries adhesive_d = adhesive, adhesionless_d = adhesionless;
  for (const ShapePoint& p : points) {
    adhesive.x.push_back(p.radius);
    adhesive.y.push_back(p.force);
    adhesionless.x.push_back(p.radius);
    adhesionless.y.push_back(p.force_h);
    adhesive_d.x.push_back(p.penetration);
    adhesive_d.y.push_back(p.force);
    adhesionless_d.x.push_back(p.penetration_h);
    adhesionless_d.y.push_back(p.force_h);
  }
  PlotPanel by_a{"contact radius a", "m", "force F", "N", true, {adhesive, adhesionless}, ""};
  PlotPanel by_delta{"penetration δ", "m", "force F", "N", false, {adhesive_d, adhesionless_d}, ""};
  if (jkr) {
    by_a.series.push_back({"JKR, homogeneous film", jkr->a, jkr->force, PlotSeries::Style::kDashed, kPlotReference});
    by_delta.series.push_back(
        {"JKR, homogeneous film", jkr->delta, jkr->force, PlotSeries::Style::kDashed, kPlotReference});
  } else {
    by_a.note = "homogeneous JKR reference: drawn for sphere:R only";
  }
  if (pulloff) {
    PlotSeries marks{"pull-offs (load, displacement control)", {}, {}, PlotSeries::Style::kPoints, kPlotCoated};
    PlotSeries marks_d = marks;
    for (const ShapeJump* j : {&pulloff->load, &pulloff->displacement}) {
      marks.x.push_back(j->radius);
      marks.y.push_back(j->force);
      marks_d.x.push_back(j->penetration);
      marks_d.y.push_back(j->force);
    }
    by_a.series.push_back(marks);
    by_delta.series.push_back(marks_d);
  }
  return render_curve_plot({by_a, by_delta}, title, path);
}

}  // namespace

// Declared in commands.hpp (also the shapes of `fit --shape`).
std::shared_ptr<const IndenterShape> parse_shape(const std::string& text, std::string& profile_end) {
  const std::string option = "--shape";
  const std::size_t colon = text.find(':');
  const std::string expected =
      "expected sphere:R, cone:BETA, pyramid:THETA, punch:A, power:N,R, blunted-cone:R,BETA or profile:FILE";
  if (colon == std::string::npos) throw InputError(option + ": " + quoted(text) + " has no parameters; " + expected);
  const std::string kind = text.substr(0, colon);
  const std::string rest = text.substr(colon + 1);
  const std::vector<std::string> items = split(rest, ',');
  auto count = [&](std::size_t n) {
    if (items.size() != n) {
      throw InputError(option + ": " + quoted(text) + " needs " + std::to_string(n) + " parameter(s); " + expected);
    }
  };
  auto length = [&](const std::string& item) { return parse_quantity(item, Quantity::kLength, option); };
  if (kind == "sphere") {
    count(1);
    return named(text, [&] { return make_paraboloid(length(items[0])); });
  }
  if (kind == "cone") {
    count(1);
    return named(text, [&] { return make_cone(parse_angle(items[0], option)); });
  }
  if (kind == "pyramid") {
    count(1);
    return named(text, [&] { return make_pyramid(parse_angle(items[0], option)); });
  }
  if (kind == "punch") {
    count(1);
    return named(text, [&] { return make_flat_punch(length(items[0])); });
  }
  if (kind == "power") {
    count(2);
    const double n = parse_number(items[0], option);
    if (!(n > 0.0 && n <= 100.0)) {
      throw InputError(option + ": " + quoted(text) + ": exponent N = " + items[0] + " not allowed (need 0 < N <= 100)");
    }
    return named(text, [&] { return make_power_law(n, length(items[1])); });
  }
  if (kind == "blunted-cone") {
    count(2);
    return named(text, [&] { return make_blunted_cone(length(items[0]), parse_angle(items[1], option)); });
  }
  if (kind == "profile") {
    if (rest.empty()) throw InputError(option + ": " + quoted(text) + " names no file; " + expected);
    // Columns r z (lengths; "# units:" converts them to SI), as the fit's data files.
    const DataTable table = read_data_file(rest, 2, {true, false}, {Quantity::kLength, Quantity::kLength});
    profile_end = rest + ":" + std::to_string(table.line_numbers.back());
    return make_measured_profile(table.columns[0], table.columns[1], rest, table.line_numbers);
  }
  throw InputError(option + ": unknown shape " + quoted(kind) + " in " + quoted(text) + "; " + expected);
}

namespace {

// `contact --shape ... --cohesive-stress`: the Maugis-Dugdale curve by the direct cohesive-zone
// solve per contact radius (THEORY.md section 13, "Any axisymmetric shape"), and the pull-offs
// under load and displacement control.
void write_md_shape_contact(std::ostream& os, const Stack& stack, const ShapeMaugisDugdale& md,
                            const IndenterShape& shape, double thickness, double work,
                            const std::vector<double>& radii, std::pair<double, double> scan, bool strict,
                            double sphere_radius, const std::chrono::steady_clock::time_point& started) {
  std::vector<PointStatus> status(radii.size());
  std::vector<ShapeMdPoint> curve = md.curve(radii, status);
  if (strict) {
    for (const PointStatus& s : status) {
      if (!s.delivered) throw NumericalError(s.reason);
    }
  }
  require_some_delivered(status, "contact radius");
  // Without --strict a pull-off the solve cannot locate leaves the curve standing.
  std::optional<ShapeMdPulloff> pulloff;
  std::string pulloff_missing;
  try {
    pulloff = md.pulloff(scan.first, scan.second);
  } catch (const NumericalError& e) {
    if (strict) throw;
    pulloff_missing = e.what();
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  Header h{{"command", "contact"}};
  h.emplace_back("shape", shape.description());
  h.emplace_back("film thickness t [m]", num(thickness));
  h.emplace_back("work of adhesion w [J/m2]", num(work));
  add_material_header(h, stack);
  h.emplace_back("reference modulus [Pa]", num(stack.reference_modulus()));
  if (shape.interpolation_error() > 0.0) {
    h.emplace_back("profile interpolation error estimate (relative, delta0)", num(shape.interpolation_error()));
  }
  h.emplace_back("Maugis-Dugdale adhesive stress sigma0 [Pa]", num(md.cohesive_stress()));
  h.emplace_back("Maugis-Dugdale range h0 = w/sigma0 [m]", num(work / md.cohesive_stress()));
  h.emplace_back("adhesion", "Maugis-Dugdale: per contact radius the zone edge c from h(c) = h0, then delta and F "
                             "(THEORY.md section 13, 'Any axisymmetric shape'); the shape is one more load");
  h.emplace_back("solver", "per contact radius: factored system (p = 14), Brent root of h(c) = h0 in ln(c/a - 1), "
                           "direct solve (no table)");
  if (pulloff) {
    const auto jump = [](const ShapeMdJump& j) {
      return num(j.point.force) + " (contact radius " + num(j.point.radius) + " m, penetration " +
             num(j.point.penetration) + " m, zone edge " + num(j.point.zone_edge) + " m; " +
             (j.interior ? "stationary minimum" : "end of the curve a -> 0") + ")";
    };
    h.emplace_back("pull-off force, load control [N]", jump(pulloff->load));
    h.emplace_back("pull-off force, displacement control [N]", jump(pulloff->displacement));
    const ShapeMdPoint& end = pulloff->curve_end;
    h.emplace_back("end of the curve a -> 0", "F = " + num(end.force) + " N, delta = " + num(end.penetration) +
                                                  " m, c = " + num(end.zone_edge) + " m");
    h.emplace_back("pull-off scan", "contact radii [" + num(pulloff->scan_min) + ", " + num(pulloff->scan_max) +
                                        "] m, 24 per decade, every local minimum refined (Brent), against a -> 0");
    for (const auto& w : pulloff->warnings) h.emplace_back("warning", w);
  } else {
    h.emplace_back("pull-off", "not computed: " + pulloff_missing + " (--strict: exit 3 instead)");
  }
  const auto where = [&](std::size_t i) { return "a_m = " + format_value(radii[i], "a_m"); };
  progress_pause();
  if (!pulloff) std::cerr << "coatcontact contact: warning: pull-off not computed (the curve is): " << pulloff_missing << "\n";
  report_not_delivered(h, "contact", status, where);
  std::vector<double> a, delta, force;
  for (std::size_t i = 0; i < curve.size(); ++i) {
    if (!status[i].delivered) continue;
    a.push_back(curve[i].radius);
    delta.push_back(curve[i].penetration);
    force.push_back(curve[i].force);
  }
  ValidityLimits limits;
  limits.thickness = thickness;
  limits.modulus = md.reference_modulus();
  limits.sphere_radius = sphere_radius;
  limits.max_contact_radius = shape.max_contact_radius();
  for (const auto& w : validity_warnings(a, delta, force, limits)) {
    h.emplace_back("warning", w);
    std::cerr << "coatcontact contact: warning: " << w << "\n";
  }
  h.emplace_back("run time (wall clock, this computation) [s]", num(std::round(seconds * 1e3) / 1e3));
  const std::vector<std::string> columns = {"a_m", "delta_m", "F_N", "delta_H_m", "F_H_N", "c_m"};
  write_header(os, h, columns);
  for (std::size_t i = 0; i < curve.size(); ++i) {
    const ShapeMdPoint& p = curve[i];
    if (!status[i].delivered) {
      write_not_delivered(os, where(i), status[i].reason);
      continue;
    }
    write_row(os, {p.radius, p.penetration, p.force, p.penetration_h, p.force_h, p.zone_edge}, columns);
  }
}

// --cohesive-stress with --shape (THEORY.md section 13, "Any axisymmetric shape"): sigma0, or
// nothing without the option; the shapes, options and ranges the zone allows.
std::optional<double> parse_shape_cohesive_stress(const Arguments& args, const IndenterShape& shape, double work,
                                                  double thickness) {
  const auto text = args.get("--cohesive-stress");
  if (!text) return std::nullopt;
  const double sigma0 = parse_quantity(*text, Quantity::kPressure, "--cohesive-stress");
  std::string why;
  if (!cohesive_zone_allowed(shape, &why)) {
    throw InputError("--shape: " + quoted(args.require("--shape")) + " not allowed with --cohesive-stress: " + why);
  }
  if (args.has("--spring")) {
    throw InputError("--spring: not used with --cohesive-stress (the cohesive zone's pull-offs are under load and "
                     "displacement control only); omit --spring");
  }
  if (args.has("--tol")) {
    throw InputError("--tol: not used with --cohesive-stress (the zone is solved per contact radius to a fixed "
                     "accuracy, THEORY.md section 13); omit --tol");
  }
  try {
    check_cohesive_range(work / sigma0, thickness);
  } catch (const InputError& e) {
    throw InputError("--cohesive-stress: " + std::string(e.what()));
  }
  return sigma0;
}

}  // namespace

std::size_t parse_point_count(const Arguments& args, std::size_t fallback) {
  const auto text = args.get("--points");
  if (!text) return fallback;
  const double n = parse_number(*text, "--points");
  if (!(n >= 2 && n <= 1e6 && n == std::floor(n))) {
    throw InputError("--points: value " + quoted(*text) + " not allowed (need an integer, 2 <= N <= 1000000)");
  }
  return static_cast<std::size_t>(n);
}

// The help text of `contact`.
void print_contact_help() {
  std::cout << usage("contact",
                     "--shape SHAPE --thickness t --film E1,nu1 --substrate E0,nu0|rigid "
                     "[--indenter E2,nu2] --work w [--cohesive-stress sigma0] [--spring k] [--contact-radius LIST | --points N] [--strict]",
                     "Adhesive (JKR) contact of an axisymmetric indenter on a coated substrate in SI\n"
                     "units: per contact radius the adhesive penetration and force and the adhesionless\n"
                     "ones (THEORY.md sections 5, 11); the pull-off forces under load, displacement and\n"
                     "spring control (section 10) in the header, with a warning when F(a) has several\n"
                     "local minima (the global one is the load-controlled pull-off). A radius the solver\n"
                     "cannot serve at --tol is a '# not delivered' row with its reason (exit 0 while one\n"
                     "radius is delivered); with --strict, exit 3 at the first one.\n"
                     "--cohesive-stress sigma0: the Maugis-Dugdale curve instead (any shape but the punch), with\n"
                     "the zone edge c_m, by the direct cohesive-zone solve per radius (section 13); pull-offs\n"
                     "under load and displacement control (not with --spring).",
                     kSpec);
}

int run_contact(const Args& raw) {
  return run_guarded("contact", [&]() {
    const Arguments args(raw, kSpec);
    if (args.help()) {
      print_contact_help();
      return kExitSuccess;
    }
    const auto started = std::chrono::steady_clock::now();
    // With --layer the layers carry the lengths and T = sum h is the unit (THEORY.md section 12).
    const double film_thickness =
        args.has("--layer") ? 0.0 : parse_quantity(args.require("--thickness"), Quantity::kLength, "--thickness");
    const Stack stack = parse_stack(args);
    const double thickness = args.has("--layer") ? coating_thickness(args, stack) : film_thickness;
    const double work = parse_quantity(args.require("--work"), Quantity::kEnergy, "--work");
    const Header notes = report_plausibility("contact", args);
    double spring = 0.0;
    if (const auto text = args.get("--spring")) spring = parse_spring(*text);
    const double tol = solver_tolerance(args);
    if (args.has("--contact-radius") && args.has("--points")) {
      throw InputError("--contact-radius and --points exclude each other");
    }
    const std::size_t points = parse_point_count(args, kDefaultPoints);
    std::vector<double> radii;
    if (const auto text = args.get("--contact-radius")) {
      radii = parse_quantity_list(*text, Quantity::kLength, "--contact-radius");
    }
    std::string profile_end;
    const auto shape = parse_shape(args.require("--shape"), profile_end);
    const std::optional<double> sigma0 = parse_shape_cohesive_stress(args, *shape, work, thickness);
    if (shape->flat() && args.has("--points")) {
      throw InputError("--points: a flat punch has one contact radius, its own (" + shape->description() +
                       "); omit --points, or give --contact-radius");
    }
    const double sphere_radius = sphere_radius_of(args.require("--shape"));
    try {
      check_sphere_contact_radii(radii, sphere_radius);
    } catch (const InputError& e) {
      throw InputError("--contact-radius with --shape: " + std::string(e.what()));
    }
    for (double a : radii) {
      if (a > shape->max_contact_radius()) {
        throw InputError((profile_end.empty() ? "" : profile_end + ": ") + "--contact-radius: " + num(a) +
                         " m exceeds the shape's largest radius " + num(shape->max_contact_radius()) +
                         " m (" + shape->description() + ")");
      }
    }

    const ShapeSolver solver(stack);
    const ShapeContact contact(solver, shape, thickness, work, tol);
    const auto [lo, hi] = contact.default_range();
    const bool strict = args.has("--strict");
    const auto plot = plot_path(args, sigma0 ? "not with --cohesive-stress (JKR curves only)" : "");
    // Without --contact-radius the curve stops at the model's validity limits (as `sphere`'s),
    // but always reaches the pull-off it reports; the pull-off is located first for that.
    std::optional<ShapePulloff> pulloff;
    std::string pulloff_missing;
    if (!sigma0) {
      try {
        pulloff = contact.pulloff(spring);
      } catch (const NumericalError& e) {
        if (strict) throw;
        pulloff_missing = e.what();
      }
    }
    if (radii.empty()) {
      if (shape->flat()) {
        radii = {lo};
      } else if (sigma0) {
        for (std::size_t k = 0; k < points; ++k) {
          radii.push_back(k + 1 == points ? hi : lo * std::pow(hi / lo, static_cast<double>(k) / (points - 1.0)));
        }
      } else {
        radii = contact_default_radii(contact, lo, hi, pulloff ? 1.2 * pulloff->load.radius : lo, points,
                                      sphere_radius);
      }
    }
    if (sigma0) {
      const ShapeMaugisDugdale md(stack, shape, thickness, work, *sigma0);
      Output out(args.get("--output").value_or(""));
      write_md_shape_contact(out.stream(), stack, md, *shape, thickness, work, radii, {lo, hi}, strict, sphere_radius,
                             started);
      out.commit();
      return kExitSuccess;
    }
    std::vector<PointStatus> status(radii.size());
    const std::vector<ShapePoint> curve = strict ? contact.curve(radii) : contact.curve(radii, status);
    require_some_delivered(status, "contact radius");
    std::vector<ShapePoint> delivered;
    for (std::size_t i = 0; i < curve.size(); ++i) {
      if (status[i].delivered) delivered.push_back(curve[i]);
    }
    // Without --strict a pull-off the solver cannot locate leaves the curve standing (located above).
    double worst = 0.0;
    for (const ShapePoint& p : delivered) worst = std::max(worst, p.error_estimate);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();

    std::optional<JkrReference> jkr;  // for a sphere; radii is not empty here
    if (sphere_radius > 0.0) jkr = jkr_reference(stack.reference_modulus(), sphere_radius, work, radii, kDefaultPoints);
    Header h{{"command", "contact"}};
    h.emplace_back("shape", shape->description());
    h.emplace_back("film thickness t [m]", num(thickness));
    h.emplace_back("work of adhesion w [J/m2]", num(work));
    add_material_header(h, stack);
    h.emplace_back("reference modulus [Pa]", num(stack.reference_modulus()));
    h.insert(h.end(), notes.begin(), notes.end());
    if (shape->interpolation_error() > 0.0) {
      h.emplace_back("profile interpolation error estimate (relative, delta0)", num(shape->interpolation_error()));
    }
    h.emplace_back("adhesion", "JKR: delta_fp = -sqrt(2 pi a w/E)/Gamma(1), delta = delta_H + delta_fp, "
                               "F = F_H + S delta_fp (THEORY.md sections 5, 11)");
    add_pulloff_header(h, pulloff, pulloff_missing, spring, jkr);
    progress_pause();
    if (!pulloff) std::cerr << "coatcontact contact: warning: pull-off not computed (the curve is): " << pulloff_missing << "\n";
    const auto where = [&](std::size_t i) { return "a_m = " + format_value(radii[i], "a_m"); };
    report_not_delivered(h, "contact", status, where);
    for (const auto& w : contact.validity_warnings(delivered, sphere_radius)) {
      h.emplace_back("warning", w);
      std::cerr << "coatcontact contact: warning: " << w << "\n";
    }
    h.emplace_back("solver tolerance", num(tol));
    h.emplace_back("solver error estimate (relative, max over rows)", num(worst));
    h.emplace_back("run time (wall clock, this computation) [s]", num(std::round(seconds * 1e3) / 1e3));
    const std::vector<std::string> columns = {"a_m", "delta_m", "F_N", "delta_H_m", "F_H_N"};
    Output out(args.get("--output").value_or(""));
    std::ostream& os = out.stream();
    write_header(os, h, columns);
    for (std::size_t i = 0; i < curve.size(); ++i) {
      const ShapePoint& p = curve[i];
      if (!status[i].delivered) {
        write_not_delivered(os, where(i), status[i].reason);
        continue;
      }
      write_row(os, {p.radius, p.penetration, p.force, p.penetration_h, p.force_h}, columns);
    }
    std::optional<Output> plot_out;
    if (plot) {
      const std::string title = shape->description() + " on " + si_text(thickness, "m") + " of " +
                                si_text(stack.top().youngs_modulus, "Pa") + ", E1*/E0* = " +
                                si_text(stack.modulus_ratio(), "") + ", w = " + si_text(work, "J/m^2");
      stage_plot(plot_out, *plot, contact_picture(*plot, delivered, jkr, pulloff, title));
    }
    out.commit();
    if (plot_out) plot_out->commit();
    return kExitSuccess;
  });
}

}  // namespace coatcontact::cli
