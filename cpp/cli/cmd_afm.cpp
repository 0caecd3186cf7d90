// `coatcontact afm show|export`: real AFM force curves read from the instruments' files
// (cpp/measure/afm/): what a file holds, and one curve as TSV in SI units.
#include <iostream>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "coatcontact/afm_preprocess.hpp"
#include "coatcontact/afm_readers.hpp"
#include "coatcontact/cli_support.hpp"
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
    const std::vector<afm::ForceCurve> curves = afm::read_force_curves(path, calibration);

    std::vector<std::pair<std::string, std::string>> items = {{"coatcontact afm show", "AFM force curves read from an instrument file"}};
    items.push_back({"curves in the file", std::to_string(curves.size())});
    add_curve_header(items, curves.front());
    const std::vector<std::string> columns = {"curve", "grid_x", "grid_y", "x_m", "y_m", "segment", "kind",
                                              "first_point", "points", "duration_s", "k_N_per_m", "sensitivity_m_per_V"};
    Output output(output_path);
    std::ostream& out = output.stream();
    write_header(out, items, columns);
    for (const auto& curve : curves) {
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
    }
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
    std::size_t index = 0;
    if (auto text = arguments.get("--index")) {
      const double value = parse_number(*text, "--index");
      if (!(value >= 0.0 && value <= 1e9) || value != static_cast<double>(static_cast<long>(value))) {
        throw InputError("--index: '" + *text + "' is not allowed; expected a curve index 0, 1, 2, ...");
      }
      index = static_cast<std::size_t>(value);
    }
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
    const std::vector<afm::ForceCurve> curves = afm::read_force_curves(path, calibration);
    if (index >= curves.size()) {
      throw InputError("--index: " + std::to_string(index) + " is not allowed; " + path + " holds " +
                       std::to_string(curves.size()) + (curves.size() == 1 ? " curve (index 0)" : " curves (indices 0.." + std::to_string(curves.size() - 1) + ")"));
    }
    const afm::ForceCurve& curve = curves[index];
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

}  // namespace

int run_afm(const Args& args) {
  const std::string overview =
      "usage: coatcontact afm <show|export> FILE [options]   (coatcontact afm <command> --help)\n\n"
      "Real AFM force curves from the instruments' files.\n"
      "  show      metadata, calibration and segments (the curves of a map)\n"
      "  export    one curve as TSV in SI units (--index N of a map)\n";
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
  std::cerr << "coatcontact afm: error: unknown afm command '" << args[0].substr(0, 60)
            << "' (expected show or export)\n";
  return kExitUsage;
}

}  // namespace coatcontact::cli
