// `coatcontact afm show|export|fit`: real AFM force curves read from the instruments' files
// (cpp/measure/afm/): what a file holds, one curve as TSV in SI units, and the adhesionless
// Hertz/Sneddon fit of one segment with its contact point and baseline (THEORY.md section 15).
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "afm_fit_map.hpp"
#include "coatcontact/afm_batch_table.hpp"
#include "afm_depth_profile_script.hpp"
#include "afm_fit_plot_script.hpp"
#include "coatcontact/gnuplot_run.hpp"
#include "coatcontact/afm_curve_fit.hpp"
#include "coatcontact/afm_depth_profile.hpp"
#include "coatcontact/afm_fit.hpp"
#include "coatcontact/afm_models.hpp"
#include "coatcontact/afm_preprocess.hpp"
#include "coatcontact/afm_readers.hpp"
#include "coatcontact/cli_support.hpp"
#include "coatcontact/limits.hpp"
#include "commands.hpp"

namespace coatcontact::cli {

namespace {

OptionSpec spring_constant_option() {
  return {"--spring-constant", "K", "cantilever spring constant [N/m]; overrides the file's", false};
}
OptionSpec sensitivity_option() {
  return {"--sensitivity", "S", "deflection sensitivity [m/V] (InvOLS); overrides the file's", false};
}

const std::vector<OptionSpec> kShowSpec = {
    spring_constant_option(),
    sensitivity_option(),
    {"--output", "FILE", "write the table to FILE (atomically) instead of stdout", false},
};

const std::vector<OptionSpec> kExportSpec = {
    {"--index", "N", "the curve of a map to export (0-based, default 0; `afm show` lists them)", false},
    spring_constant_option(),
    sensitivity_option(),
    {"--preprocess", "", "add the baseline-corrected force and the contact point (steps in the header)", false},
    {"--contact-point", "METHOD", "with --preprocess: piecewise-fit (default, robust to noise) or deviation", false},
    {"--baseline-fraction", "F", "with --preprocess: leading part of the approach fitted as baseline (default 0.5)", false},
    {"--output", "FILE", "write the curve to FILE (atomically) instead of stdout", false},
};

constexpr const char* kFormats =
    "Formats (chosen by content and extension): JPK .jpk-force, .jpk-force-map, .jpk-qi-data,\n"
    ".jpk-qi-series; Asylum Research .ibw; AFM Workshop .csv and zipped maps (.zip); NT-MDT\n"
    "Nova text exports (.txt). Units: SI (N, m, s); spring constant N/m, sensitivity m/V.";

// --index N: the curve of a map (0 without the option).
std::size_t parse_curve_index(const Arguments& arguments) {
  const auto text = arguments.get("--index");
  if (!text) return 0;
  const double value = parse_number(*text, "--index");
  if (!(value >= 0.0 && value <= 1e9) || value != static_cast<double>(static_cast<long>(value))) {
    throw InputError("--index: '" + *text + "' is not allowed; expected a curve index 0, 1, 2, ...");
  }
  return static_cast<std::size_t>(value);
}

afm::Calibration parse_calibration(const Arguments& arguments) {
  afm::Calibration calibration;
  if (auto k = arguments.get("--spring-constant")) {
    calibration.spring_constant = parse_number(*k, "--spring-constant");
    if (!(*calibration.spring_constant > 0.0)) {
      throw InputError("--spring-constant: '" + *k + "' must be > 0 (a spring constant in N/m)");
    }
  }
  if (auto s = arguments.get("--sensitivity")) {
    calibration.sensitivity = parse_number(*s, "--sensitivity");
    if (!(*calibration.sensitivity > 0.0)) {
      throw InputError("--sensitivity: '" + *s + "' must be > 0 (a sensitivity in m/V)");
    }
  }
  return calibration;
}

std::string calibration_text(double value, afm::CalibrationSource source, const std::string& name) {
  if (source == afm::CalibrationSource::kNone) return "not in the file";
  return format_parameter(value, name) + " (" + afm::calibration_source_name(source) + ")";
}

// Header lines of one curve: everything the reader found.
void add_curve_header(std::vector<std::pair<std::string, std::string>>& items, const afm::ForceCurve& curve) {
  const afm::CurveMetadata& m = curve.metadata;
  items.push_back({"file", m.source_file});
  items.push_back({"format", m.format});
  items.push_back({"vendor", m.vendor});
  if (!m.instrument.empty()) items.push_back({"instrument", m.instrument});
  if (!m.date.empty()) items.push_back({"date", m.date});
  if (!m.time.empty()) items.push_back({"time", m.time});
  items.push_back({"curve index", std::to_string(m.curve_index) + " of " + std::to_string(m.curve_count)});
  if (!m.entry.empty()) items.push_back({"archive entry", m.entry});
  if (m.grid_index_x && m.grid_index_y) {
    items.push_back({"grid index x, y", std::to_string(*m.grid_index_x) + ", " + std::to_string(*m.grid_index_y)});
  }
  if (m.grid_shape_x && m.grid_shape_y) {
    items.push_back({"grid shape x, y", std::to_string(*m.grid_shape_x) + ", " + std::to_string(*m.grid_shape_y)});
  }
  if (m.position_x) items.push_back({"position x [m]", format_parameter(*m.position_x, "position x")});
  if (m.position_y) items.push_back({"position y [m]", format_parameter(*m.position_y, "position y")});
  items.push_back({"spring constant [N/m]", calibration_text(m.spring_constant, m.spring_constant_source, "spring constant")});
  items.push_back({"sensitivity [m/V]", calibration_text(m.sensitivity, m.sensitivity_source, "sensitivity")});
  items.push_back({"point count", std::to_string(curve.point_count())});
  for (std::size_t s = 0; s < curve.segments.size(); ++s) {
    const afm::Segment& segment = curve.segments[s];
    std::string text = std::string(afm::segment_kind_name(segment.kind)) + ", points " + std::to_string(segment.begin) +
                       ".." + std::to_string(segment.end - 1) + " (" + std::to_string(segment.size()) + ")";
    if (segment.duration > 0.0) text += ", " + format_parameter(segment.duration, "duration") + " s";
    if (!segment.name.empty()) text += ", " + segment.name;
    items.push_back({"segment " + std::to_string(s), text});
  }
  for (const auto& detail : m.details) items.push_back(detail);
}

std::string optional_text(const std::optional<long>& v) { return v ? std::to_string(*v) : "-"; }
std::string optional_text(const std::optional<double>& v, const char* name) { return v ? format_parameter(*v, name) : "-"; }

// The rows of `afm show`, curve by curve: a curve that cannot be read is one row of kind
// 'unreadable' (its place from its header where that can be read), not the end of the listing;
// a file none of whose curves can be read is an InputError (the first curve's).
struct ShowRows {
  std::string text;
  afm::ForceCurve first;  // the first readable curve (its header lines)
  std::size_t unreadable = 0;
  std::string first_error;
};

ShowRows show_rows(const afm::CurveSource& source) {
  ShowRows rows;
  bool have_first = false;
  std::ostringstream out;
  for (std::size_t i = 0; i < source.size(); ++i) {
    afm::ForceCurve curve;
    try {
      curve = source.read(i);
    } catch (const InputError& error) {
      if (source.size() == 1) throw;
      const afm::CurveMetadata m = source.place(i);
      out << i << '\t' << optional_text(m.grid_index_x) << '\t' << optional_text(m.grid_index_y) << '\t'
          << optional_text(m.position_x, "x") << '\t' << optional_text(m.position_y, "y") << "\t-\tunreadable\t-\t-\t-\t-\t-\n";
      if (rows.unreadable++ == 0) rows.first_error = error.what();
      continue;
    }
    const afm::CurveMetadata& m = curve.metadata;
    for (std::size_t s = 0; s < curve.segments.size(); ++s) {
      const afm::Segment& segment = curve.segments[s];
      out << m.curve_index << '\t' << optional_text(m.grid_index_x) << '\t' << optional_text(m.grid_index_y) << '\t'
          << optional_text(m.position_x, "x") << '\t' << optional_text(m.position_y, "y") << '\t' << s << '\t'
          << afm::segment_kind_name(segment.kind) << '\t' << segment.begin << '\t' << segment.size() << '\t'
          << (segment.duration > 0.0 ? format_parameter(segment.duration, "duration") : "-") << '\t'
          << (m.spring_constant_source != afm::CalibrationSource::kNone ? format_parameter(m.spring_constant, "k") : "-") << '\t'
          << (m.sensitivity_source != afm::CalibrationSource::kNone ? format_parameter(m.sensitivity, "sensitivity") : "-")
          << '\n';
    }
    if (!have_first) {
      curve.force.clear(), curve.height_piezo.clear(), curve.height_measured.clear(), curve.time.clear();
      rows.first = std::move(curve);
      have_first = true;
    }
  }
  if (!have_first) throw InputError(rows.first_error);
  rows.text = out.str();
  return rows;
}

int run_show(const Args& args) {
  return run_guarded("afm show", [&]() -> int {
    const Arguments arguments(args, kShowSpec, 1);
    if (arguments.help()) {
      std::cout << usage("afm show", "FILE [--spring-constant K] [--sensitivity S] [--output FILE]",
                         "What an AFM file holds: its metadata, calibration and segments (header\n"
                         "lines, for the first curve), then one row per curve and segment (all the\n"
                         "curves of a map). A missing spring constant or sensitivity is reported,\n"
                         "not required.\n" + std::string(kFormats),
                         kShowSpec);
      return kExitSuccess;
    }
    if (arguments.positionals().size() != 1) throw InputError("expected one FILE (see --help)");
    const std::string path = arguments.positionals().front();
    afm::Calibration calibration = parse_calibration(arguments);
    calibration.allow_missing = true;
    register_input(path, "AFM file");
    const auto output_path = arguments.get("--output").value_or("");
    check_output_path(output_path, "--output");
    const afm::CurveSource source(path, calibration);
    const ShowRows rows = show_rows(source);

    std::vector<std::pair<std::string, std::string>> items = {{"coatcontact afm show", "AFM force curves read from an instrument file"}};
    items.push_back({"curves in the file", std::to_string(source.size())});
    if (rows.unreadable > 0) items.push_back({"unreadable curves", std::to_string(rows.unreadable) + " (kind 'unreadable'; first: " + rows.first_error + ")"});
    add_curve_header(items, rows.first);
    const std::vector<std::string> columns = {"curve", "grid_x", "grid_y", "x_m", "y_m", "segment", "kind",
                                              "first_point", "points", "duration_s", "k_N_per_m", "sensitivity_m_per_V"};
    Output output(output_path);
    std::ostream& out = output.stream();
    write_header(out, items, columns);
    out << rows.text;
    output.commit();
    return kExitSuccess;
  });
}

int run_export(const Args& args) {
  return run_guarded("afm export", [&]() -> int {
    const Arguments arguments(args, kExportSpec, 1);
    if (arguments.help()) {
      std::cout << usage("afm export", "FILE [--index N] [--spring-constant K] [--sensitivity S] [--preprocess "
                         "[--contact-point METHOD] [--baseline-fraction F]] [--output FILE]",
                         "One curve of an AFM file as TSV in SI units: time_s (when the file has a\n"
                         "time base), segment (0, 1, ... as listed in the header), the piezo and\n"
                         "measured heights (when recorded), force_N and tip_position_m = height\n"
                         "(measured, else piezo) + F/k. The header holds all the curve's metadata.\n"
                         "--preprocess adds force_corrected_N: the force less a baseline offset + tilt\n"
                         "fitted on the leading part of the approach, and the contact point on the\n"
                         "tip-position axis; each step is recorded with its parameters.\n" +
                             std::string(kFormats),
                         kExportSpec);
      return kExitSuccess;
    }
    if (arguments.positionals().size() != 1) throw InputError("expected one FILE (see --help)");
    const std::string path = arguments.positionals().front();
    const afm::Calibration calibration = parse_calibration(arguments);
    const std::size_t index = parse_curve_index(arguments);
    const bool preprocess = arguments.has("--preprocess");
    afm::PreprocessOptions options;
    if (auto method = arguments.get("--contact-point")) {
      if (!preprocess) throw InputError("--contact-point: needs --preprocess");
      if (*method == "piecewise-fit") options.contact_method = afm::ContactPointMethod::kPiecewiseFit;
      else if (*method == "deviation") options.contact_method = afm::ContactPointMethod::kDeviation;
      else throw InputError("--contact-point: '" + method->substr(0, 60) + "' is not a method; expected piecewise-fit or deviation");
    }
    if (auto fraction = arguments.get("--baseline-fraction")) {
      if (!preprocess) throw InputError("--baseline-fraction: needs --preprocess");
      options.baseline_fraction = parse_number(*fraction, "--baseline-fraction");
      if (!(options.baseline_fraction > 0.0 && options.baseline_fraction < 1.0)) {
        throw InputError("--baseline-fraction: '" + *fraction + "' is not allowed; expected a number in (0, 1)");
      }
    }
    register_input(path, "AFM file");
    const auto output_path = arguments.get("--output").value_or("");
    check_output_path(output_path, "--output");
    // Only the curve asked for is read (a JPK map is read curve by curve).
    const afm::CurveSource source(path, calibration);
    if (index >= source.size()) {
      throw InputError("--index: " + std::to_string(index) + " is not allowed; " + path + " holds " +
                       std::to_string(source.size()) + (source.size() == 1 ? " curve (index 0)" : " curves (indices 0.." + std::to_string(source.size() - 1) + ")"));
    }
    const afm::ForceCurve curve = source.read(index);
    // The tip position needs k; a file whose force is stored in newtons may lack it.
    const bool has_tip = curve.metadata.spring_constant_source != afm::CalibrationSource::kNone;
    const std::vector<double> tip = has_tip ? curve.tip_position() : std::vector<double>{};

    std::vector<std::pair<std::string, std::string>> items = {{"coatcontact afm export", "one AFM force curve in SI units"}};
    add_curve_header(items, curve);
    items.push_back({"tip position", has_tip ? std::string(curve.tip_position_height_name()) + " + force / spring constant"
                                             : std::string("not available: no spring constant (give --spring-constant)")});
    afm::PreprocessedCurve steps;
    if (preprocess) {
      steps = afm::preprocess(curve, options);
      items.push_back({"step 1, tip position", std::string(curve.tip_position_height_name()) + " + force / spring constant"});
      items.push_back({"step 2, baseline", "force = offset + slope * tip position, least squares on the first " +
                                               std::to_string(steps.baseline_points) + " approach points (fraction " +
                                               format_parameter(options.baseline_fraction, "fraction") + ")"});
      items.push_back({"baseline offset [N]", format_parameter(steps.baseline_offset, "baseline offset") + " +- " +
                                                  format_parameter(steps.baseline_offset_error, "error")});
      items.push_back({"baseline slope [N/m]", format_parameter(steps.baseline_slope, "baseline slope") + " +- " +
                                                   format_parameter(steps.baseline_slope_error, "error")});
      items.push_back({"baseline residual sigma [N]", format_parameter(steps.baseline_sigma, "sigma")});
      std::string method = afm::contact_point_method_name(steps.contact_method);
      if (steps.contact_method == afm::ContactPointMethod::kDeviation) {
        method += " (" + format_parameter(options.deviation_sigmas, "sigmas") + " baseline sigmas)";
      } else {
        method += " (F = A (z_c - z)^" + format_parameter(options.piecewise_exponent, "exponent") + ")";
      }
      items.push_back({"step 3, contact point", method});
      items.push_back({"contact point [m]", format_parameter(steps.contact_point, "contact point") + " (tip position, point " +
                                                std::to_string(steps.contact_index) + ")"});
    }
    std::vector<std::string> columns;
    if (!curve.time.empty()) columns.push_back("time_s");
    columns.push_back("segment");
    if (curve.has_height_piezo()) columns.push_back("height_piezo_m");
    if (curve.has_height_measured()) columns.push_back("height_measured_m");
    columns.push_back("force_N");
    if (has_tip) columns.push_back("tip_position_m");
    if (preprocess) columns.push_back("force_corrected_N");
    Output output(output_path);
    std::ostream& out = output.stream();
    write_header(out, items, columns);
    std::vector<double> row;
    for (std::size_t i = 0; i < curve.point_count(); ++i) {
      row.clear();
      if (!curve.time.empty()) row.push_back(curve.time[i]);
      row.push_back(curve.segment[i]);
      if (curve.has_height_piezo()) row.push_back(curve.height_piezo[i]);
      if (curve.has_height_measured()) row.push_back(curve.height_measured[i]);
      row.push_back(curve.force[i]);
      if (has_tip) row.push_back(tip[i]);
      if (preprocess) row.push_back(steps.force_corrected[i]);
      write_row(out, row, columns);
    }
    output.commit();
    return kExitSuccess;
  });
}

// ---- afm fit ----------------------------------------------------------------------------------

// --model's help from the registry: "hertz (...), jkr (...) or dmt (...)".
std::string model_help() {
  const auto& models = fit::afm_models();
  std::string text;
  for (std::size_t k = 0; k < models.size(); ++k) {
    text += (k == 0 ? "" : k + 1 == models.size() ? " or " : ", ") + models[k]->name + " (" + models[k]->help + ")";
  }
  return text;
}

const std::vector<OptionSpec> kFitSpec = {
    {"--index", "N", "fit only curve N of a map (0-based; `afm show` lists them); without it every curve, one row each", false},
    {"--model", "MODEL", model_help(), false},
    {"--work", "W", "jkr, md: the work of adhesion w [J/m2] (the value if fixed; if free, the centre of its search; default "
                    "from the segment's most tensile force)", false},
    {"--range", "Z0", "jkr, md: the surface-force range z0 [m] (default 0.3nm): Tabor's and Maugis's lambda, and md's "
                      "Dugdale range h0 = w/sigma0 = 0.97 z0", false},
    {"--tilt", "M", "jkr, md: the baseline slope [N/m] when it is fixed (default 0; free by default)", false},
    {"--radius", "R", "tip radius of a spherical (paraboloidal) tip [m], e.g. 10um", false},
    {"--shape", "SPEC", "the tip instead: sphere:R, cone:BETA, pyramid:THETA (face half angle; the cone of equal area), "
                        "pyramid3:THETA (three-sided, face angle; nanite's hertz_pyr3s), sneddon-sphere:R (the exact sphere), "
                        "punch:A, power:N,R, blunted-cone:R,BETA, profile:FILE (as `contact --shape`)", false},
    {"--halfspace", "E,nu", "the sample: a homogeneous half-space; E is the value if fixed (any > 0 if free), nu fixed", false},
    {"--film", "E1,nu1", "the sample: a coating (with --substrate, --thickness); E1 the value if fixed, else the centre of its search", false},
    {"--substrate", "E0,nu0|rigid", "the coating's substrate (fixed)", false},
    {"--thickness", "t", "the coating's thickness [m] (the value if fixed, else the centre of its search)", false},
    {"--layer", "h,E,nu[,slip]", "the sample: a stack of layers, top first, repeated (with --substrate; instead of --film, "
                                 "--thickness): thickness [m], E (the value if fixed, else the centre of its search), nu; "
                                 "',slip' a frictionless interface below it. --free E<K> frees layer K's modulus (default E1); "
                                 "models hertz, jkr and dmt (not md), thicknesses fixed (THEORY.md sections 12, 15)", false, true},
    {"--free", "LIST", "free parameters: E, contact_point, baseline on a half-space (default all three); "
                       "E1 and/or t, contact_point, baseline on a coating (default E1,contact_point,baseline); "
                       "tilt adds a baseline slope (hertz: fitted instead of the preprocessing's being subtracted); "
                       "jkr and md add w and tilt (default E or E1, w, contact_point, baseline, tilt)", false},
    {"--contact-point", "Z", "the contact point [m, tip position] when it is fixed", false},
    {"--baseline", "B", "the force baseline [N] when it is fixed", false},
    {"--baseline-model", "tilt|offset", "tilt (default): the preprocessing's baseline slope is subtracted from the forces "
                                        "(b: the baseline at its contact point); offset: the forces as measured, b constant. "
                                        "With tilt in --free the model fits the slope (offset)", false},
    {"--weight-cp", "D", "hertz on a half-space: nanite's contact-point weighting, each residual times min(|z - z_c|/D, 1), "
                         "e.g. 500nm (default: none)", false},
    {"--segment", "KIND", "approach (default) or retract", false},
    spring_constant_option(),
    sensitivity_option(),
    {"--tip-range", "MIN,MAX", "fit only tip positions in [MIN, MAX] [m; units as 18um]", false},
    {"--indentation-range", "MIN,MAX", "fit only indentations (z_ref - z) in [MIN, MAX] [m], relative to the "
                                       "preprocessing's contact point z_ref (MIN < 0 keeps baseline points)", false},
    {"--max-indentation", "D", "fit only indentations z_ref - z <= D [m] (relative to z_ref as above)", false},
    {"--max-force", "F", "fit only forces up to F [N] above the preprocessing's baseline", false},
    {"--output", "FILE", "write the table to FILE (atomically) instead of stdout", false},
    {"--plot", "FILE", "draw data, fit, residuals, contact point and pull-off with gnuplot (.png or .pdf); with --depth-profile "
                       "the profile; of a batch: the map images (--map-plot)", false},
    {"--jobs", "N", "batch: curves fitted in parallel (default: the machine's cores); the table is the same for any N", false},
    {"--resume", "", "batch: continue the interrupted run whose rows are in OUTPUT.partial (needs --output)", false},
    {"--map-plot", "FILE", "batch: heat maps of the estimates, chi2/dof and flags on the grid (.png or .pdf; several map files: FILE-K.png, one per file)", false},
    {"--curve-plots", "FILE", "batch: one control-plot page per curve (data, fit, residuals, contact point, flag, rating, "
                              "estimates) in FILE.pdf", false},
    {"--color-range", "MIN,MAX", "--map-plot: colour range of the moduli [Pa; units as 1kPa,10kPa] (default: their min and max)", false},
    {"--color-log", "", "--map-plot: moduli on a log colour scale", false},
    {"--depth-profile", "", "one curve, hertz: the modulus (E, or E1 with E of the half-space fit beside it on a coating) "
                            "fitted at 10 increasing maximum indentations; the table has one row per depth (docs/afm.md)", false},
    {"--sort-by", "KEY", "batch: rating sorts the rows by their curve rating, highest first (stable; docs/afm.md)", false},
};

constexpr double kDegree = 3.14159265358979323846 / 180.0;
// FILEs and FOLDERs of one `afm fit` run (a folder counts as one).
constexpr std::size_t kMaxFitInputs = 100000;

// "70deg", "1.2rad" or degrees without a unit; in (0, 90) degrees.
double parse_half_angle(const std::string& text, const std::string& what) {
  std::string value = text;
  double unit = kDegree;
  for (const auto& [suffix, factor] : {std::pair<std::string, double>{"deg", kDegree}, {"rad", 1.0}}) {
    if (value.size() > suffix.size() && value.compare(value.size() - suffix.size(), suffix.size(), suffix) == 0) {
      value = value.substr(0, value.size() - suffix.size());
      unit = factor;
      break;
    }
  }
  const double angle = parse_number(value, "--shape") * unit;
  if (!(angle > 0.0 && angle < 90.0 * kDegree)) {
    throw InputError("--shape: " + what + " '" + text + "' not allowed (need 0deg < angle < 90deg, e.g. 35deg)");
  }
  return angle;
}

fit::AfmTip parse_tip(const Arguments& arguments) {
  const auto radius = arguments.get("--radius");
  const auto shape = arguments.get("--shape");
  if (radius && shape) throw InputError("--radius and --shape: give one tip, not both");
  if (radius) return fit::afm_paraboloid(parse_quantity(*radius, Quantity::kLength, "--radius"));
  if (!shape) throw InputError("afm fit needs the tip: --radius R (sphere) or --shape SPEC (see --help)");
  const std::string& text = *shape;
  const std::size_t colon = text.find(':');
  const std::string kind = colon == std::string::npos ? text : text.substr(0, colon);
  const std::string rest = colon == std::string::npos ? std::string() : text.substr(colon + 1);
  if (kind == "sphere" && rest.find(',') == std::string::npos) {
    return fit::afm_paraboloid(parse_quantity(rest, Quantity::kLength, "--shape"));
  }
  if (kind == "cone" && rest.find(',') == std::string::npos) return fit::afm_cone(parse_half_angle(rest, "half included angle"));
  if (kind == "pyramid3" && !rest.empty() && rest.find(',') == std::string::npos) {
    return fit::afm_pyramid3(parse_half_angle(rest, "face angle"));
  }
  if (kind == "sneddon-sphere" && rest.find(',') == std::string::npos) {
    return fit::afm_sneddon_sphere(parse_quantity(rest, Quantity::kLength, "--shape"));
  }
  if (kind == "pyramid") {
    if (rest.empty() || rest.find(',') != std::string::npos) {
      throw InputError("--shape: '" + text + "' needs 1 parameter: pyramid:THETA (face half angle, e.g. 35deg)");
    }
    return fit::afm_pyramid(parse_half_angle(rest, "face half angle"));
  }
  std::string profile_end;
  return fit::afm_shape(parse_shape(text, profile_end));
}

// A length of any sign: a plain number (SI), or "-1um", "250nm" (the units of parse_quantity).
double parse_signed_length(std::string text, const std::string& option) {
  text.erase(0, text.find_first_not_of(" \t"));
  text.erase(text.find_last_not_of(" \t") + 1);
  try {
    return parse_number(text, option);
  } catch (const InputError&) {
  }
  const bool negative = !text.empty() && text[0] == '-';
  return (negative ? -1.0 : 1.0) * parse_quantity(negative ? text.substr(1) : text, Quantity::kLength, option);
}

std::pair<double, double> parse_pair(const std::string& text, const std::string& option, const std::string& what) {
  const std::size_t comma = text.find(',');
  if (comma == std::string::npos || text.find(',', comma + 1) != std::string::npos) {
    throw InputError(option + ": '" + text + "' is not allowed; expected MIN,MAX (" + what + ")");
  }
  const double lo = parse_signed_length(text.substr(0, comma), option);
  const double hi = parse_signed_length(text.substr(comma + 1), option);
  if (!(lo < hi)) throw InputError(option + ": '" + text + "' is not allowed; MIN must be below MAX");
  return {lo, hi};
}

// A number for gnuplot's settings (NaN for absent values, which its plots skip).
std::string gp_number(double v) {
  if (!std::isfinite(v)) return "NaN";
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

// Runs gnuplot on the embedded script (gnuplot/afm_fit_plot.gp) in a private temporary folder;
// returns the picture (the caller writes it atomically). InputError when gnuplot fails.
std::string render_afm_plot(const std::string& table, const std::string& settings) {
  return run_gnuplot({{"fit.tsv", table}}, "afm_fit_plot.gp", kAfmFitPlotScript, [&](const std::string& dir) {
    return "fitfile=" + gnuplot_string(dir + "/fit.tsv") + "; " + settings;
  });
}

// "1.2345(67)e-3"-free plain text: value +- error with the error's two significant digits.
std::string with_error(double value, double error, const std::string& name) {
  return format_parameter(value, name) + " +- " + format_parameter(error, name + " error");
}

// The engineering prefix of a quantity's largest magnitude, for the plot's axes.
std::pair<double, std::string> prefix_of(double magnitude) {
  static const std::vector<std::pair<int, std::string>> prefixes = {{-15, "f"}, {-12, "p"}, {-9, "n"}, {-6, "µ"},
                                                                    {-3, "m"},  {0, ""},    {3, "k"},  {6, "M"}};
  int e = magnitude > 0.0 ? 3 * static_cast<int>(std::floor(std::log10(magnitude) / 3.0 + 1e-9)) : 0;
  e = std::clamp(e, -15, 6);
  for (const auto& [exponent, name] : prefixes) {
    if (exponent == e) return {std::pow(10.0, -e), name};
  }
  return {1.0, ""};
}

// The model, tip, sample, free parameters, segment and fit range of `afm fit` (one curve or a batch).
// The free layer of a --layer stack: the K of an item E<K> in --free (at most one; default 1),
// which the list then names E1 (the fit's name for the free layer's modulus).
std::size_t stack_free_layer(std::string& free_text, std::size_t layers) {
  const std::string allowed = "E1..E" + std::to_string(layers);
  std::size_t free_layer = 0, found = 0, start = 0;
  std::string rewritten;
  while (start <= free_text.size()) {
    const std::size_t comma = std::min(free_text.find(',', start), free_text.size());
    std::string item = free_text.substr(start, comma - start);
    item.erase(0, item.find_first_not_of(" \t"));
    item.erase(item.find_last_not_of(" \t") + 1);
    if (item.size() >= 2 && item[0] == 'E' && item.find_first_not_of("0123456789", 1) == std::string::npos) {
      const unsigned long k = item.size() > 6 ? 0 : std::stoul(item.substr(1));
      if (k < 1 || k > layers) {
        throw InputError("--free: '" + item.substr(0, 60) + "' is not a layer's modulus; allowed with " + std::to_string(layers) +
                         " --layer: " + allowed);
      }
      if (++found > 1) throw InputError("--free: one layer's modulus is free at a time (got '" + free_text.substr(0, 60) + "')");
      free_layer = k - 1;
      item = "E1";
    }
    rewritten += (rewritten.empty() ? "" : ",") + item;
    start = comma + 1;
  }
  free_text = rewritten;
  return free_layer;
}

AfmFitSetup parse_fit_setup(const Arguments& arguments) {
  const std::string model = arguments.get("--model").value_or("hertz");
  const fit::AfmModelInfo& info = fit::afm_model_by_name(model, "--model");
  const bool jkr = info.needs_spring;  // the adhesive models share their options
  fit::AfmFitProblem problem;
  problem.model = info.model();
  problem.tip = parse_tip(arguments);
  if (auto text = arguments.get("--weight-cp")) {
    problem.weight_cp = parse_quantity(*text, Quantity::kLength, "--weight-cp");
    if (!(problem.weight_cp > 0.0)) throw InputError("--weight-cp: '" + *text + "' is not allowed; expected a length > 0, e.g. 500nm");
  }
  if (jkr) {
    if (problem.tip.kind != fit::AfmTip::Kind::kParaboloid) {
      throw InputError("--model: " + model + " takes a sphere tip (--radius R or --shape sphere:R); got " + problem.tip.description);
    }
    if (auto text = arguments.get("--work")) problem.work = parse_quantity(*text, Quantity::kEnergy, "--work");
    if (auto text = arguments.get("--range")) {
      problem.surface_force_range = parse_quantity(*text, Quantity::kLength, "--range");
      if (!(problem.surface_force_range > 0.0)) throw InputError("--range: '" + *text + "' is not allowed; expected a length > 0, e.g. 0.3nm");
    }
    if (auto text = arguments.get("--tilt")) problem.tilt = parse_number(*text, "--tilt");
  } else {
    for (const char* option : {"--work", "--range", "--tilt"}) {
      if (arguments.has(option)) throw InputError(std::string(option) + ": needs --model " + fit::afm_spring_model_names());
    }
  }
  const bool stacked = arguments.has("--layer");
  const bool coated = stacked || arguments.has("--film") || arguments.has("--substrate") || arguments.has("--thickness");
  // --free E<K> with --layer: layer K's modulus is the fit's E1 (AfmCoating's free layer).
  std::string free_text = arguments.get("--free").value_or(fit::afm_free_default(info, coated));
  const std::string free_given = free_text;  // the header's (a stack's E<K> before it becomes E1)
  if (stacked) {
    if (arguments.has("--halfspace")) throw InputError("--halfspace: give one sample, a half-space or a stack (--layer ...)");
    if (arguments.has("--thickness")) throw InputError("--thickness: not with --layer (each layer carries its thickness h)");
    const Stack stack = parse_stack(arguments);
    problem.coating = fit::afm_coating(stack, stack_free_layer(free_text, stack.layers().size()));
    problem.poisson = problem.coating->film.poisson_ratio;
  } else if (coated) {
    if (arguments.has("--halfspace")) throw InputError("--halfspace: give one sample, a half-space or a coating (--film ...)");
    for (const char* option : {"--film", "--substrate", "--thickness"}) {
      if (!arguments.has(option)) throw InputError(std::string("a coating needs --film E1,nu1, --substrate E0,nu0|rigid and --thickness t (") + option + " is missing)");
    }
    fit::AfmCoating coating;
    coating.film = parse_material(*arguments.get("--film"), "--film");
    coating.substrate = parse_substrate(*arguments.get("--substrate"), "--substrate");
    coating.thickness = parse_quantity(*arguments.get("--thickness"), Quantity::kLength, "--thickness");
    problem.coating = coating;
    problem.poisson = coating.film.poisson_ratio;
  } else {
    if (!arguments.has("--halfspace")) {
      throw InputError("afm fit needs the sample: --halfspace E,nu (E any > 0 when free), or a coating --film --substrate --thickness");
    }
    const Material sample = parse_material(*arguments.get("--halfspace"), "--halfspace");
    problem.modulus = sample.youngs_modulus;
    problem.poisson = sample.poisson_ratio;
  }
  problem.free = {false, false, false, false};
  // A stack's free modulus is named by its layer (E2: the second layer's), as --free named it.
  const std::string modulus_name =
      !coated ? "E" : stacked ? "E" + std::to_string(problem.coating->free_layer + 1) : "E1";
  const std::string allowed = fit::afm_free_allowed(info, coated);
  std::size_t start = 0;
  while (start <= free_text.size()) {
    const std::size_t comma = std::min(free_text.find(',', start), free_text.size());
    std::string item = free_text.substr(start, comma - start);
    item.erase(0, item.find_first_not_of(" \t"));
    item.erase(item.find_last_not_of(" \t") + 1);
    const fit::AfmParameterInfo* parameter = fit::afm_parameter(info, item, coated);
    if (!parameter) throw InputError("--free: '" + item.substr(0, 60) + "' is not a parameter of this fit; allowed: " + allowed);
    problem.free.*parameter->free = true;
    start = comma + 1;
  }
  if (!problem.free.modulus && !problem.free.contact_point && !problem.free.baseline && !problem.free.thickness &&
      !problem.free.work && !problem.free.tilt) {
    throw InputError("--free: '" + free_text + "' names no parameter; allowed: " + allowed);
  }
  if (jkr && !problem.free.work && !(problem.work > 0.0)) throw InputError("--free: a fixed w needs --work W");
  if (jkr && problem.free.tilt && arguments.has("--tilt")) {
    throw InputError("--tilt: the tilt is free; drop it from --free to fix it");
  }
  if (auto text = arguments.get("--contact-point")) {
    if (problem.free.contact_point) throw InputError("--contact-point: the contact point is free; drop it from --free to fix it");
    problem.contact_point = parse_number(*text, "--contact-point");
  } else if (!problem.free.contact_point) {
    throw InputError("--free: a fixed contact point needs --contact-point Z");
  }
  if (auto text = arguments.get("--baseline")) {
    if (problem.free.baseline) throw InputError("--baseline: the baseline is free; drop it from --free to fix it");
    problem.baseline = parse_number(*text, "--baseline");
  }
  const std::string segment_name = arguments.get("--segment").value_or(afm::segment_kind_name(info.segment));
  afm::SegmentKind kind = afm::SegmentKind::kApproach;
  if (segment_name == "retract") kind = afm::SegmentKind::kRetract;
  else if (segment_name != "approach") throw InputError("--segment: '" + segment_name.substr(0, 60) + "' is not allowed; expected approach or retract");
  fit::AfmRange range;
  fit::AfmBaselineModel baseline = fit::kAfmDefaultBaseline;
  if (auto text = arguments.get("--baseline-model")) {
    if (*text == "tilt") baseline = fit::AfmBaselineModel::kTilt;
    else if (*text == "offset") baseline = fit::AfmBaselineModel::kOffset;
    else throw InputError("--baseline-model: '" + text->substr(0, 60) + "' is not allowed; expected tilt or offset");
    if (baseline == fit::AfmBaselineModel::kTilt && problem.free.tilt) {
      throw InputError("--baseline-model: tilt with tilt in --free would count the slope twice; drop one");
    }
  }
  if (auto text = arguments.get("--tip-range")) {
    const auto [lo, hi] = parse_pair(*text, "--tip-range", "tip positions in m");
    range.tip_min = lo;
    range.tip_max = hi;
  }
  if (auto text = arguments.get("--indentation-range")) {
    const auto [lo, hi] = parse_pair(*text, "--indentation-range", "indentations in m");
    range.indentation_min = lo;
    range.indentation_max = hi;
  }
  if (auto text = arguments.get("--max-indentation")) {
    const double d = parse_quantity(*text, Quantity::kLength, "--max-indentation");
    range.indentation_max = range.indentation_max ? std::min(*range.indentation_max, d) : d;
  }
  if (auto text = arguments.get("--max-force")) range.max_force = parse_quantity(*text, Quantity::kForce, "--max-force");
  return {problem, coated, modulus_name, free_given, segment_name, kind, range, baseline};
}

// The help text of `afm fit` (one curve, or one row per curve of many).
void print_fit_help() {
  std::cout << usage("afm fit",
                     "FILE|FILE...|FOLDER [--index N] [--model " + fit::afm_model_names("|") + "] [--work W] [--range Z0] [--tilt M] (--radius R | --shape SPEC) (--halfspace E,nu | --film E1,nu1 "
                     "--substrate E0,nu0|rigid --thickness t) [--free E,contact_point,baseline | E1,t,...] [--contact-point Z] [--baseline B] [--segment approach|retract] "
                     "[--spring-constant K] [--sensitivity S] [--tip-range MIN,MAX] [--indentation-range MIN,MAX] "
                     "[--max-indentation D] [--max-force F] [--output FILE] [--plot FILE.png|pdf] [--depth-profile] [--jobs N] [--resume] [--map-plot FILE.png|pdf] [--color-range MIN,MAX] [--color-log] [--curve-plots FILE.pdf]",
                     "Adhesionless fit of one segment of an AFM force curve (THEORY.md section 15):\n"
                     "F(z) = b + E/(1 - nu^2) g(z_c - z) on the tip-position axis z (decreasing toward\n"
                     "the sample), g the Hertz/Sneddon force of the tip per reduced modulus, zero out of\n"
                     "contact. E, the contact point z_c and the baseline b are free by default; z_c is\n"
                     "found by profiling the least-squares sum over the whole fitted range (the global\n"
                     "optimum), E and b in closed form at each z_c. Range options are combined; the\n"
                     "relative ones refer to the preprocessing's contact point and baseline (`afm export\n"
                     "--preprocess`), fixed before the fit. chi2 uses the noise of the baseline fit\n"
                     "(its residual sigma). The pull-off is measured, the same for every model: the\n"
                     "retract's most tensile force against its free-cantilever baseline (a line on its\n"
                     "last half). --baseline-model tilt (default) subtracts the preprocessing's baseline\n"
                     "slope before the fit (b: the baseline at its contact point); offset fits the\n"
                     "forces as measured; the one-curve fit, the rows of a map and Python agree. Output: the segment's points with indentation, model,\n"
                     "residual and whether each was fitted; the header holds the estimates.\n"
                     "On a coating (--film, --substrate, --thickness; sphere, cone or pyramid tip) the\n"
                     "force is the exact adhesionless one of the film on its substrate; E1 and/or t are\n"
                     "searched on a log grid within a factor 10 of the given values, then refined.\n"
                     "--model jkr (retract by default): F(z) = b + m (z - z_c) + F_JKR(z_c - z), the JKR force of\n"
                     "the sphere on the half-space or the coating on the branch stable under the cantilever's\n"
                     "spring k (the file's, or --spring-constant), zero past its jump-off; E (E1, t), w, z_c, b\n"
                     "and the tilt m free by default. Reports Tabor's mu and Maugis's lambda for the surface-\n"
                     "force range --range and warns when lambda is below the JKR range.\n"
                     "--model md: the same with F_MD, the Maugis-Dugdale force of the cohesive-zone table with\n"
                     "sigma0 = w/h0, h0 = 0.97 z0 (--range), so lambda follows w and E; warns when lambda leaves\n"
                     "the table's [1e-3, 1e4] or the spring holds the tip down to the curve's end (a = 0).\n"
                     "--model dmt: F_DMT, the adhesionless force of the sphere on the sample less 2 pi w R while in\n"
                     "contact; any spring lets go at the contact point (pull-off -2 pi w R); warns above lambda 0.1.\n"
                     "Many curves: a map (without --index), several FILEs or a FOLDER (its AFM files\n"
                     "by extension) give one row per curve instead: file, curve, grid index and position,\n"
                     "flag and reason (0 fitted), each free estimate and its _error, chi2, pull-off, rating (0-10),\n"
                     "tabor_mu, maugis_lambda and warnings; --sort-by rating puts the best curves first.\n"
                     "Flags 10 undetermined (a free E, E1, t or w whose error exceeds it) and 11 no_detachment\n"
                     "(a fitted retract that ends off the free level) keep the estimates, with a warning.\n"
                     "A curve that cannot be fitted, or a file of several that cannot be read, is flagged\n"
                     "and the run goes on (exit 0; the count in the header and on stderr). Each row is\n"
                     "the one-curve fit of its curve (same pipeline and defaults). --jobs N fits in parallel with the same table; with --output FILE the rows\n"
                     "go to FILE.partial chunk by chunk and FILE is written at the end; --resume\n"
                     "continues an interrupted FILE.partial. --curve-plots FILE.pdf: one control-plot page per curve;\n"
                     "--plot of a batch is --map-plot. --depth-profile (one curve): the fit at 10 increasing maximum\n"
                     "indentations, one row per depth (on a coating with the half-space fit's apparent E beside E1).\n"
                     "Units: SI (N, m, Pa); lengths take m, mm, um, nm suffixes where noted.\n" +
                         std::string(kFormats),
                     kFitSpec);
}

}  // namespace

void add_afm_stack_lines(std::vector<std::pair<std::string, std::string>>& items, const fit::AfmCoating& coating) {
  fit::add_afm_stack_items(items, coating);
}

namespace {

// The model, tip and sample lines of a one-curve fit's header.
void add_fit_model_lines(std::vector<std::pair<std::string, std::string>>& items, const fit::AfmFitProblem& problem) {
  items.push_back({"model", problem.model.info().formula(problem, false)});
  items.push_back({"tip", problem.tip.description});
  if (problem.coating && !problem.coating->layers.empty()) {
    add_afm_stack_lines(items, *problem.coating);
  } else if (problem.coating) {
    const fit::AfmCoating& c = *problem.coating;
    items.push_back({"sample", "coating: film nu1 = " + format_parameter(c.film.poisson_ratio, "nu1") + ", substrate " +
                                   (c.substrate.rigid ? std::string("rigid")
                                                      : "E0 = " + format_parameter(c.substrate.material.youngs_modulus, "E0") +
                                                            " Pa, nu0 = " + format_parameter(c.substrate.material.poisson_ratio, "nu0")) +
                                   " (THEORY.md sections 5, 14: reduced solver swept over a/t, log-log table)"});
  } else {
    items.push_back({"sample", "homogeneous half-space, nu = " + format_parameter(problem.poisson, "nu")});
  }
}

// The estimates, statistics, lambda and pull-off lines of a one-curve fit's header (the JKR
// warnings also to stderr).
void add_fit_estimates(std::vector<std::pair<std::string, std::string>>& items, const fit::AfmFitProblem& problem,
                       const fit::AfmFitResult& r, const std::string& modulus_name, const fit::AfmMeasuredPulloff& pulloff) {
  const bool jkr = problem.model.info().needs_spring;  // the adhesive models
  items.push_back({modulus_name + " [Pa]", problem.free.modulus ? with_error(r.modulus, r.modulus_error, modulus_name)
                                                                : format_parameter(r.modulus, modulus_name) + " (fixed)"});
  if (problem.coating) {
    items.push_back({"t [m]", problem.free.thickness ? with_error(r.thickness, r.thickness_error, "t")
                                                     : format_parameter(r.thickness, "t") + " (fixed)"});
  }
  if (jkr) {
    items.push_back({"w [J/m2]", problem.free.work ? with_error(r.work, r.work_error, "w") : format_parameter(r.work, "w") + " (fixed)"});
  }
  if (jkr || problem.free.tilt) {
    items.push_back({"tilt [N/m]", (problem.free.tilt ? with_error(r.tilt, r.tilt_error, "tilt") : format_parameter(r.tilt, "tilt") + " (fixed)") +
                                       " (baseline slope about the contact point)"});
  }
  items.push_back({"contact point [m]", problem.free.contact_point ? with_error(r.contact_point, r.contact_point_error, "contact point")
                                                                   : format_parameter(r.contact_point, "contact point") + " (fixed)"});
  items.push_back({"baseline [N]", problem.free.baseline ? with_error(r.baseline, r.baseline_error, "baseline")
                                                         : format_parameter(r.baseline, "baseline") + " (fixed)"});
  items.push_back({modulus_name + "* [Pa]", format_parameter(r.reduced_modulus, "E*")});
  items.push_back({"max indentation [m]", format_parameter(r.max_indentation, "max indentation")});
  items.push_back({"residual sigma [N]", format_parameter(r.residual_sigma, "residual sigma")});
  items.push_back({"chi2", format_parameter(r.chi2, "chi2") + " (chi2/dof " + format_parameter(r.chi2_per_dof, "chi2/dof") + ", " +
                               std::to_string(r.points - static_cast<std::size_t>(r.free_count)) + " dof)"});
  items.push_back({"R^2", format_parameter(r.r_squared, "R^2")});
  if (jkr) {
    items.push_back({"spring constant [N/m]", format_parameter(problem.spring_constant, "k")});
    items.push_back({"model jump-off", format_parameter(r.jump_off_force, "jump-off force") + " N above the baseline at indentation " +
                                           format_parameter(r.jump_off_indentation, "jump-off indentation") + " m"});
    items.push_back({"Tabor mu", format_parameter(r.tabor_mu, "mu") + " (surface-force range z0 = " +
                                     format_parameter(problem.surface_force_range, "z0") + " m, --range)"});
    items.push_back({"Maugis lambda", format_parameter(r.maugis_lambda, "lambda") + " (Dugdale stress w/(0.97 z0); " +
                                          problem.model.info().lambda_note +
                                          ")"});
    for (const std::string& warning : r.warnings) {
      items.push_back({"warning", warning});
      std::cerr << "coatcontact afm fit: warning: " << warning << "\n";
    }
  }
  if (pulloff.found) {
    items.push_back({"pull-off (retract, measured) [N]", format_parameter(pulloff.force, "pull-off force") + " at tip position " +
                                                              format_parameter(pulloff.tip_position, "pull-off position") + " m"});
    items.push_back({"pull-off baseline", "the retract's free cantilever: F = " + format_parameter(pulloff.baseline_offset, "offset") +
                                              " N + " + format_parameter(pulloff.baseline_slope, "slope") + " N/m * z, least squares on its last " +
                                              std::to_string(pulloff.baseline_points) + " points (the same for every model)"});
  } else {
    items.push_back({"pull-off (retract, measured)", "no retract segment (or too short for its baseline)"});
  }
}

// The gnuplot settings of a one-curve fit's plot: scales and SI prefixes, the contact region,
// the title and the estimates' label.
std::string fit_plot_settings(const std::string& term, const std::string& path, std::size_t index,
                              const std::string& segment_name, const std::string& modulus_name,
                              const fit::AfmFitProblem& problem, const fit::AfmFitResult& r,
                              const std::vector<double>& z_segment, const std::vector<double>& f_segment,
                              const fit::AfmMeasuredPulloff& pulloff) {
  const bool jkr = problem.model.info().needs_spring;  // the adhesive models
  double z_big = 0.0, f_big = 0.0;
  for (std::size_t i = 0; i < z_segment.size(); ++i) {
    z_big = std::max(z_big, std::abs(z_segment[i]));
    f_big = std::max(f_big, std::abs(f_segment[i] - r.baseline));
  }
  const auto [z_scale, z_prefix] = prefix_of(z_big);
  // The contact region: from the deepest point to 2 largest indentations above z_c.
  const double z_low = *std::min_element(z_segment.begin(), z_segment.end());
  double z_high = r.contact_point + 2.0 * std::max(r.contact_point - z_low, 1e-12);
  if (jkr) z_high = std::max(z_high, r.contact_point - 2.0 * r.jump_off_indentation);
  const auto [f_scale, f_prefix] = prefix_of(f_big);
  const std::string title = std::filesystem::path(path).filename().string() + " #" + std::to_string(index) + ", " +
                            segment_name + ": " + problem.tip.description;
  char label[400];
  char thickness_text[160] = "";
  if (problem.coating) std::snprintf(thickness_text, sizeof thickness_text, ", t = %.4g ± %.2g µm", r.thickness * 1e6, r.thickness_error * 1e6);
  if (jkr) {
    const std::size_t used = std::strlen(thickness_text);
    std::snprintf(thickness_text + used, sizeof thickness_text - used, ", w = %.3g ± %.2g mJ/m², λ = %.3g", r.work * 1e3,
                  r.work_error * 1e3, r.maugis_lambda);
  }
  std::snprintf(label, sizeof label, "%s = %.4g ± %.2g Pa (ν = %g)%s, z_c = %.6g ± %.2g µm, σ = %.3g %sN, χ²/dof = %.3g",
                modulus_name.c_str(), r.modulus, r.modulus_error, problem.poisson, thickness_text, r.contact_point * 1e6,
                r.contact_point_error * 1e6, r.residual_sigma * f_scale, f_prefix.c_str(), r.chi2_per_dof);
  return "term='" + term + "'; plottitle=" + gnuplot_string(title) + "; fitlabel=" + gnuplot_string(label) +
                               "; zs=" + gp_number(z_scale) + "; zunit='" + z_prefix + "m'; fs=" + gp_number(f_scale) +
                               "; funit='" + f_prefix + "N'; zc=" + gp_number(r.contact_point) + "; zlo=" + gp_number(z_low) +
                               "; zhi=" + gp_number(z_high) + "; base=" +
                               gp_number(r.baseline) + "; po_z=" + gp_number(pulloff.found ? pulloff.tip_position : NAN) +
                               "; po_F=" + gp_number(pulloff.found ? pulloff.force + pulloff.baseline_offset + pulloff.baseline_slope * pulloff.tip_position : NAN);
}

// A cell of the depth-profile table: the number, or "-" where a depth has no estimate.
std::string profile_cell(double v, const std::string& column) { return std::isfinite(v) ? format_value(v, column) : "-"; }

// `afm fit FILE --depth-profile`: the table (one row per depth) replaces the points' table, the
// header keeps the whole-range fit; --plot draws the profile (gnuplot/afm_depth_profile.gp).
int write_depth_profile(const afm::ForceCurve& curve, const fit::AfmCurveRequest& request, const std::string& modulus_name,
                        const std::string& path, std::size_t index, const std::string& output_path,
                        const std::optional<std::string>& plot_path, const std::string& term) {
  fit::AfmDepthProfile profile;
  try {
    profile = fit::afm_depth_profile(curve, request, {});
  } catch (const fit::AfmCurveInputError&) {
    throw;  // the curve's own failure, as the one-curve fit reports it
  } catch (const InputError& error) {
    std::string message = error.what();  // the library's "depth profile: ..." names the option here
    if (message.rfind("depth profile: ", 0) == 0) message = "--depth-profile: " + message.substr(15);
    throw InputError(message);
  }
  const fit::AfmCurveFit& whole = profile.reference;
  std::vector<std::pair<std::string, std::string>> items = {
      {"coatcontact afm fit", "modulus against depth: the adhesionless fit of one AFM curve at increasing maximum indentation "
                              "(THEORY.md section 15, \"Modulus against depth\")"}};
  add_curve_header(items, curve);
  add_fit_model_lines(items, whole.problem);
  items.push_back({"whole-range fit", "the estimates below; its contact point is the depths' origin"});
  add_fit_estimates(items, whole.problem, whole.result, modulus_name, whole.pulloff);
  items.push_back({"depths", std::to_string(profile.steps.size()) + " maximum indentations from the whole-range fit's contact point, "
                             "evenly in log from the " + std::to_string(fit::kDepthProfileFirstPoints) +
                             "th fitted point past it (at least the deepest / " + format_parameter(fit::kDepthProfileSpan, "span") +
                             ") to the deepest; each fit is the one-curve fit with that --max-indentation"});
  if (profile.coated) {
    items.push_back({"apparent E", "the half-space fit of the same points (E free, nu = the film's): the substrate shows as its rise with depth"});
    items.push_back({"thickness fraction", format_parameter(fit::kDepthProfileThicknessFraction, "fraction") + " t = " +
                                               format_parameter(fit::kDepthProfileThicknessFraction * profile.thickness, "limit") +
                                               " m: deeper, the film's strain (about delta/t) leaves the linear model's range"});
  }
  for (const std::string& warning : profile.warnings) items.push_back({"warning", warning});
  if (!profile.warnings.empty()) {
    std::cerr << "coatcontact afm fit: warning: " << profile.warnings.size() << " of " << profile.steps.size()
              << " depths exceed " << format_parameter(fit::kDepthProfileThicknessFraction, "fraction")
              << " t (the over_thickness_fraction column; THEORY.md section 15)\n";
  }
  std::vector<std::string> columns = {"depth", "max_indentation", modulus_name, modulus_name + "_error"};
  std::string units = "m\tm\tPa\tPa";
  if (profile.coated) columns.insert(columns.end(), {"E_apparent", "E_apparent_error"}), units += "\tPa\tPa";
  columns.insert(columns.end(), {"points_in_contact", "chi2_per_dof", "flag", "reason"});
  units += "\t-\t-\t-\t-";
  if (profile.coated) columns.push_back("over_thickness_fraction"), units += "\t-";
  items.push_back({"units", units});
  std::ostringstream table, data;
  write_header(table, items, columns);
  double z_big = 0.0, e_big = 0.0;
  for (const fit::AfmDepthStep& s : profile.steps) {
    const bool kept = fit::afm_flag_keeps_estimates(s.flag);
    table << format_value(s.depth, "depth") << '\t' << profile_cell(s.max_indentation, "max_indentation") << '\t'
          << profile_cell(s.modulus, modulus_name) << '\t' << profile_cell(s.modulus_error, modulus_name + "_error");
    if (profile.coated) {
      table << '\t' << profile_cell(s.apparent_modulus, "E_apparent") << '\t' << profile_cell(s.apparent_modulus_error, "E_apparent_error");
    }
    table << '\t' << (kept ? std::to_string(s.points_in_contact) : "-") << '\t' << profile_cell(s.chi2_per_dof, "chi2_per_dof") << '\t'
          << static_cast<int>(s.flag) << '\t' << fit::afm_flag_name(s.flag);
    if (profile.coated) table << '\t' << (s.beyond_thickness_fraction ? 1 : 0);
    table << '\n';
    const auto gp = [](double v) { return std::isfinite(v) ? gp_number(v) : std::string("NaN"); };
    data << gp(s.depth) << '\t' << gp(s.max_indentation) << '\t' << gp(s.modulus) << '\t' << gp(s.modulus_error) << '\t'
         << gp(s.apparent_modulus) << '\t' << gp(s.apparent_modulus_error) << '\n';
    if (std::isfinite(s.max_indentation)) z_big = std::max(z_big, s.max_indentation);
    for (const auto& [e, de] : {std::pair{s.modulus, s.modulus_error}, std::pair{s.apparent_modulus, s.apparent_modulus_error}}) {
      if (!std::isfinite(e)) continue;
      e_big = std::max(e_big, e + de);
    }
  }
  std::string picture;
  if (plot_path) {
    if (!(z_big > 0.0 && e_big > 0.0)) throw NumericalError("--plot: no depth of the profile has an estimate to draw");
    // The axes from 0 to the values and their error bars, a margin of 10 % and room for the key.
    const double z_high = z_big * 1.1, e_high = e_big * 1.35;
    const auto [zs, zunit] = prefix_of(z_big);
    const auto [es, eunit] = prefix_of(e_big);
    const std::string title = std::filesystem::path(path).filename().string() + " #" + std::to_string(index) + ": " +
                              modulus_name + " against depth, " + whole.problem.tip.description;
    const double limit = profile.coated ? fit::kDepthProfileThicknessFraction * profile.thickness : NAN;
    char tlabel[120];
    std::snprintf(tlabel, sizeof tlabel, "δ = %g t (t = %.4g µm)", fit::kDepthProfileThicknessFraction, profile.thickness * 1e6);
    picture = run_gnuplot({{"profile.tsv", data.str()}}, "afm_depth_profile.gp", kAfmDepthProfileScript, [&](const std::string& dir) {
      return "datafile=" + gnuplot_string(dir + "/profile.tsv") + "; term='" + term + "'; plottitle=" + gnuplot_string(title) +
             "; modname=" + gnuplot_string(modulus_name) + "; coated=" + (profile.coated ? "1" : "0") + "; tlimit=" + gp_number(limit) +
             "; tlabel=" + gnuplot_string(tlabel) + "; zs=" + gp_number(zs) + "; zunit='" + zunit + "m'; es=" + gp_number(es) +
             "; eunit='" + eunit + "Pa'; xhi=" + gp_number(z_high * zs) + "; yhi=" + gp_number(e_high * es);
    }, "--plot", true);
  }
  write_table_and_picture(output_path, table.str(), plot_path, picture);
  return kExitSuccess;
}

int run_fit_curve(const Args& args) {
  return run_guarded("afm fit", [&]() -> int {
    const Arguments arguments(args, kFitSpec, kMaxFitInputs);
    if (arguments.help()) {
      print_fit_help();
      return kExitSuccess;
    }
    if (arguments.positionals().empty()) throw InputError("expected a FILE, several FILEs or a FOLDER (see --help)");
    const std::string path = arguments.positionals().front();
    const afm::Calibration calibration = parse_calibration(arguments);
    const std::size_t index = parse_curve_index(arguments);
    const AfmFitSetup setup = parse_fit_setup(arguments);
    if (batch_mode(arguments, calibration)) return run_fit_map(arguments, setup, calibration);
    fit::AfmFitProblem problem = setup.problem;
    const std::string& modulus_name = setup.modulus_name;
    const std::string& free_text = setup.free_text;
    const std::string& segment_name = setup.segment_name;
    const afm::SegmentKind kind = setup.kind;
    const fit::AfmRange& range = setup.range;
    std::optional<std::string> plot_path = arguments.get("--plot");
    std::string term;
    if (plot_path) {
      const std::size_t dot = plot_path->rfind('.');
      term = dot == std::string::npos ? "" : plot_path->substr(dot + 1);
      if (term != "png" && term != "pdf") {
        throw InputError("--plot: '" + *plot_path + "' must end in .png or .pdf (the format follows the extension)");
      }
    }
    register_input(path, "AFM file");
    const auto output_path = arguments.get("--output").value_or("");
    check_output_paths({{"--output", output_path}, {"--plot", plot_path.value_or("")}});
    if (plot_path && plot_path->empty()) throw InputError("--plot: needs a file name ending in .png or .pdf");

    // Only the curve asked for is read (another curve of a map may be unreadable).
    const afm::CurveSource source(path, calibration);
    if (index >= source.size()) {
      throw InputError("--index: " + std::to_string(index) + " is not allowed; " + path + " holds " +
                       std::to_string(source.size()) + (source.size() == 1 ? " curve (index 0)" : " curves (indices 0.." + std::to_string(source.size() - 1) + ")"));
    }
    const afm::ForceCurve curve = source.read(index);
    fit::AfmCurveRequest request;
    request.problem = problem;
    request.segment = kind;
    request.range = range;
    request.baseline = setup.baseline;
    if (arguments.has("--depth-profile")) {
      return write_depth_profile(curve, request, modulus_name, path, index, output_path, plot_path, term);
    }
    const fit::AfmCurveFit fitted = fit::afm_fit_curve(curve, request);
    problem = fitted.problem;
    const afm::PreprocessedCurve& steps = fitted.preprocessed;
    const afm::Segment* segment = &fitted.segment;
    const std::vector<double>& z_segment = fitted.z_segment;
    const std::vector<std::size_t>& kept = fitted.kept;
    const double reference_baseline = fitted.reference_baseline;
    const fit::AfmFitResult& r = fitted.result;
    const fit::AfmMeasuredPulloff& pulloff = fitted.pulloff;
    // The forces as measured; the model with the subtracted tilt added back (the table's
    // residual is model - data on the measured forces).
    const std::vector<double> f_segment(curve.force.begin() + segment->begin, curve.force.begin() + segment->end);
    std::vector<double> model_segment = fit::afm_model_force(fitted.fitted, z_segment);
    for (std::size_t i = 0; i < model_segment.size(); ++i) {
      model_segment[i] += fitted.subtracted_tilt * (z_segment[i] - fitted.reference_contact);
    }

    std::vector<std::pair<std::string, std::string>> items = {
        {"coatcontact afm fit", problem.model.info().summary + " of one AFM force-curve segment (THEORY.md section 15)"}};
    add_curve_header(items, curve);
    items.push_back({"tip position", std::string(curve.tip_position_height_name()) + " + force / spring constant"});
    add_fit_model_lines(items, problem);
    items.push_back({"segment", segment_name + " (" + std::to_string(z_segment.size()) + " points)"});
    items.push_back({"free", free_text});
    for (std::size_t k = 0; k < fitted.steps.size(); ++k) {
      items.push_back({"step " + std::to_string(k + 1) + ", " + fitted.steps[k].name, fitted.steps[k].parameters});
    }
    items.push_back({"preprocessing contact point [m]", format_parameter(steps.contact_point, "contact point") +
                                                            " (piecewise-fit; reference of the relative ranges)"});
    items.push_back({"preprocessing baseline [N]", format_parameter(reference_baseline, "baseline") + " at the contact point, sigma " +
                                                       format_parameter(steps.baseline_sigma, "sigma") + " (chi2's noise)"});
    const std::string range_text = fit_range_text(range);
    items.push_back({"fit range", range_text + " (" + std::to_string(kept.size()) + " points fitted, " +
                                      std::to_string(r.points_in_contact) + " in contact)"});
    add_fit_estimates(items, problem, r, modulus_name, pulloff);
    items.push_back({"flag", std::to_string(static_cast<int>(fitted.flag)) + " " + fit::afm_flag_name(fitted.flag) +
                                 (fitted.flag == fit::AfmFlag::kFitted ? "" : " (the estimates are kept; see the warning)")});
    for (const std::string& warning : fitted.flag_warnings) {
      items.push_back({"warning", warning});
      std::cerr << "coatcontact afm fit: warning: " << warning << "\n";
    }
    items.push_back({"rating", format_parameter(fitted.rating, "rating") + " of 10 (docs/afm.md, \"Curve rating\")"});
    items.push_back({"fit time [s]", format_parameter(r.seconds, "time") + " (" + std::to_string(r.profile_evaluations) +
                                         " contact-point profile evaluations" +
                                         (problem.coating ? ", " + std::to_string(r.solver_calls) + " reduced-variable solves" : "") + ")"});
    const std::vector<std::string> columns = {"point", "tip_position_m", "indentation_m", "force_N", "model_force_N",
                                              "residual_N", "fitted"};
    std::vector<bool> fitted_flag(z_segment.size(), false);
    for (std::size_t i : kept) fitted_flag[i] = true;
    std::ostringstream table;
    write_header(table, items, columns);
    for (std::size_t i = 0; i < z_segment.size(); ++i) {
      write_row(table,
                {static_cast<double>(segment->begin + i), z_segment[i], r.contact_point - z_segment[i], f_segment[i],
                 model_segment[i], model_segment[i] - f_segment[i], fitted_flag[i] ? 1.0 : 0.0},
                columns);
    }
    std::string picture;
    if (plot_path) {
      picture = render_afm_plot(table.str(), fit_plot_settings(term, path, index, segment_name, modulus_name, problem, r,
                                                               z_segment, f_segment, pulloff));
    }
    write_table_and_picture(output_path, table.str(), plot_path, picture);
    return kExitSuccess;
  });
}

}  // namespace

int run_afm(const Args& args) {
  const std::string overview =
      "usage: coatcontact afm <show|export|fit> FILE [options]   (coatcontact afm <command> --help)\n\n"
      "Real AFM force curves from the instruments' files.\n"
      "  show      metadata, calibration and segments (the curves of a map)\n"
      "  export    one curve as TSV in SI units (--index N of a map)\n"
      "  fit       Hertz/Sneddon fit of one segment (E, contact point, baseline), or JKR through the\n"
      "            cantilever of the retract (--model jkr: also w and the baseline tilt); one row per\n"
      "            curve for a map, several files or a folder\n";
  if (args.empty()) {
    std::cerr << overview;
    return kExitUsage;
  }
  if (args[0] == "--help" || args[0] == "-h") {
    std::cout << overview;
    return kExitSuccess;
  }
  const Args rest(args.begin() + 1, args.end());
  if (args[0] == "show") return run_show(rest);
  if (args[0] == "export") return run_export(rest);
  if (args[0] == "fit") return run_fit_curve(rest);
  std::cerr << "coatcontact afm: error: unknown afm command '" << args[0].substr(0, 60)
            << "' (expected show, export or fit)\n";
  return kExitUsage;
}

}  // namespace coatcontact::cli
