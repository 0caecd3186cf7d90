// `coatcontact indent analyse | calibrate | film` (THEORY.md section 16): Oliver–Pharr on one
// test or every test of a file, the area function and frame compliance from a reference, and
// the film's modulus (or thickness) from the exact coated stiffness beside the empirical models.
#include <cmath>
#include <iostream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "coatcontact/cli_support.hpp"
#include "coatcontact/gnuplot_run.hpp"
#include "coatcontact/indent_film.hpp"
#include "coatcontact/oliver_pharr.hpp"
#include "indent_commands.hpp"
#include "indent_plot_script.hpp"

namespace coatcontact::cli {

namespace {

using Items = std::vector<std::pair<std::string, std::string>>;

// ---- the Oliver–Pharr options shared by analyse and film ------------------------------------

std::vector<OptionSpec> oliver_pharr_spec() {
  return {
      indent_test_option(),
      indent_index_option(),
      {"--area", "C0,C1,..|hardness", "area function A [nm^2] = C0 h^2 + C1 h + C2 h^(1/2) + .. (h_c in nm), "
                                     "or A = P/H from the file's hardness column (default: the file's coefficients)", false},
      {"--poisson", "NU", "the sample's Poisson ratio (default: the file's)", false},
      {"--indenter", "E,nu|rigid", "the tip (default diamond, 1141GPa,0.07)", false},
      {"--beta", "B", "E_r = sqrt(pi) S / (2 B sqrt(A)) (default 1)", false},
      {"--epsilon", "EPS", "h_c = h - EPS P/S (default 0.75)", false},
      {"--frame-stiffness", "K", "a frame stiffness [N/m] to remove from depth and stiffness (default: none, the vendors' channels are corrected)", false},
      {"--range", "MIN:MAX", "depth range of the averages (unit allowed: 100nm:200nm; default: the file's, else all)", false},
      {"--stiffness", "auto|csm|unloading", "CSM channel or power-law fit of the unloading (default auto: CSM when present)", false},
      {"--unload-range", "LO:HI", "fractions of P_max fitted on the unloading (default 0.5:0.95)", false},
      {"--output", "FILE", "write the table to FILE (atomically) instead of stdout", false},
      {"--plot", "FILE", "draw the result with gnuplot (.png or .pdf)", false},
  };
}

std::pair<double, double> parse_range(const std::string& text, const std::string& option, Quantity kind) {
  const auto colon = text.find(':');
  if (colon == std::string::npos) throw InputError(option + ": '" + text.substr(0, 60) + "' is not MIN:MAX");
  const std::string lo = text.substr(0, colon), hi = text.substr(colon + 1);
  const double a = kind == Quantity::kLength ? (lo == "0" ? 0.0 : parse_quantity(lo, kind, option)) : parse_number(lo, option);
  const double b = kind == Quantity::kLength ? parse_quantity(hi, kind, option) : parse_number(hi, option);
  if (!(b > a)) throw InputError(option + ": '" + text.substr(0, 60) + "' needs MIN < MAX");
  return {a, b};
}

indent::OliverPharrOptions oliver_pharr_options(const Arguments& args) {
  indent::OliverPharrOptions o;
  if (const auto v = args.get("--area")) {
    if (*v == "hardness") o.area_from_hardness = true;
    else o.area.coefficients = parse_list(*v, "--area");
  }
  if (const auto v = args.get("--poisson")) o.poisson = parse_number(*v, "--poisson");
  if (const auto v = args.get("--indenter")) o.indenter = parse_indenter(*v, "--indenter");
  if (const auto v = args.get("--beta")) o.beta = parse_number(*v, "--beta");
  if (const auto v = args.get("--epsilon")) o.epsilon = parse_number(*v, "--epsilon");
  if (const auto v = args.get("--frame-stiffness")) o.frame_stiffness = parse_number(*v, "--frame-stiffness");
  if (const auto v = args.get("--range")) std::tie(o.depth_min, o.depth_max) = parse_range(*v, "--range", Quantity::kLength);
  if (const auto v = args.get("--unload-range"))
    std::tie(o.unload_lower, o.unload_upper) = parse_range(*v, "--unload-range", Quantity::kPressure);
  const std::string s = args.get("--stiffness").value_or("auto");
  if (s == "csm") o.stiffness = indent::StiffnessSource::kCsm;
  else if (s == "unloading") o.stiffness = indent::StiffnessSource::kUnloading;
  else if (s != "auto") throw InputError("--stiffness: '" + s.substr(0, 60) + "' is not allowed; use auto, csm or unloading");
  return o;
}

void add_options_header(Items& items, const indent::OliverPharrOptions& o, const indent::IndentTest& t) {
  const auto& area = o.area.coefficients.empty() ? t.calibration.area.coefficients : o.area.coefficients;
  std::string c;
  for (double v : area) c += (c.empty() ? "" : " ") + format_parameter(v, "area coefficient");
  items.push_back({"area", o.area_from_hardness ? std::string("A = P/H (the file's hardness column)")
                                                : "C0.. = " + c + (o.area.coefficients.empty() ? " (the file's)" : " (--area)")});
  items.push_back({"indenter", o.indenter.rigid ? std::string("rigid")
                                                : format_parameter(o.indenter.material.youngs_modulus, "E_i") + " Pa, nu " +
                                                      format_parameter(o.indenter.material.poisson_ratio, "nu_i")});
  items.push_back({"beta", format_parameter(o.beta, "beta")});
  items.push_back({"epsilon", format_parameter(o.epsilon, "epsilon")});
  items.push_back({"frame stiffness removed [N/m]", std::isnan(o.frame_stiffness) ? std::string("none") : format_parameter(o.frame_stiffness, "K")});
}

std::string plot_term(const std::optional<std::string>& path) {
  if (!path) return "";
  const std::size_t dot = path->rfind('.');
  const std::string term = dot == std::string::npos ? "" : path->substr(dot + 1);
  if (term != "png" && term != "pdf")
    throw InputError("--plot: '" + path->substr(0, 80) + "' must end in .png or .pdf (the format follows the extension)");
  return term;
}

void write_plot(const std::optional<std::string>& path, const std::string& table, const std::string& settings) {
  if (!path) return;
  const std::string picture = run_gnuplot({{"table.tsv", table}}, "indent_plot.gp", kIndentPlotScript,
                                          [&](const std::string& dir) { return "datafile=" + gnuplot_string(dir + "/table.tsv") + "; " + settings; });
  Output out(*path, "--plot");
  out.stream().write(picture.data(), static_cast<std::streamsize>(picture.size()));
  out.commit();
}

// ---- analyse ------------------------------------------------------------------------------

// Every test of the file: one summary row each (and the vendor's averages where it has them).
void write_all_tests(std::ostream& out, Items items, const std::vector<indent::IndentTest>& tests,
                     const indent::OliverPharrOptions& o) {
  const std::vector<std::string> columns = {"test", "E_mean_Pa", "E_sd_Pa", "H_mean_Pa", "H_sd_Pa", "points",
                                            "vendor_E_mean_Pa", "vendor_H_mean_Pa"};
  std::ostringstream body;
  for (std::size_t k = 0; k < tests.size(); ++k) {
    const auto& t = tests[k];
    const indent::OliverPharrResult r = indent::oliver_pharr(t, o);
    const auto vendor = [&](const char* key) {
      const auto it = t.vendor_results.find(key);
      return it == t.vendor_results.end() ? std::string("-") : format_value(it->second, key);
    };
    body << t.name << '\t' << format_value(r.modulus_mean, "E") << '\t' << format_value(r.modulus_sd, "E") << '\t'
         << format_value(r.hardness_mean, "H") << '\t' << format_value(r.hardness_sd, "H") << '\t' << r.range_points
         << '\t' << vendor("E_mean") << '\t' << vendor("H_mean") << '\n';
  }
  items.push_back({"rows", "one per test: Oliver-Pharr means and standard deviations over the range; the vendor's own averages (- where none)"});
  write_header(out, items, columns);
  out << body.str();
}

const std::vector<std::string> kAnalyseColumns = {"depth_m", "load_N", "stiffness_N_per_m", "contact_depth_m", "area_m2",
                                                  "contact_radius_m", "reduced_modulus_Pa", "modulus_Pa", "hardness_Pa", "in_range"};

std::string analyse_table(const indent::OliverPharrResult& r, Items items) {
  std::ostringstream out;
  write_header(out, items, kAnalyseColumns);
  for (std::size_t i = 0; i < r.depth.size(); ++i)
    write_row(out, {r.depth[i], r.load[i], r.stiffness[i], r.contact_depth[i], r.area[i], r.contact_radius[i],
                    r.reduced_modulus[i], r.modulus[i], r.hardness[i], r.in_range[i] ? 1.0 : 0.0},
              kAnalyseColumns);
  return out.str();
}

// The one input file and the two outputs of `analyse` and `film`, checked before any work.
struct FileAndOutputs {
  std::string path, output_path;
  std::optional<std::string> plot_path;
  std::string term;
};

FileAndOutputs file_and_outputs(const Arguments& arguments) {
  if (arguments.positionals().size() != 1) throw InputError("expected one FILE (see --help)");
  FileAndOutputs run;
  run.path = arguments.positionals().front();
  register_input(run.path, "indentation file");
  run.output_path = arguments.get("--output").value_or("");
  run.plot_path = arguments.get("--plot");
  run.term = plot_term(run.plot_path);
  check_output_paths({{"--output", run.output_path}, {"--plot", run.plot_path.value_or("")}});
  return run;
}

int analyse(const Args& args) {
  std::vector<OptionSpec> spec = oliver_pharr_spec();
  spec.push_back({"--all", "", "every test of the file: one summary row per test", false});
  const Arguments arguments(args, spec, 1);
  if (arguments.help()) {
    std::cout << usage("indent analyse", "FILE [--test NAME | --index N | --all] [options]",
                       "Oliver-Pharr (THEORY.md section 16): contact depth h_c = h - eps P/S, area A(h_c),\n"
                       "E_r = sqrt(pi) S/(2 beta sqrt(A)), the sample's E with the indenter's compliance removed,\n"
                       "H = P/A, per point (CSM) or at the start of the unloading (power-law fit), and their\n"
                       "means and standard deviations over the depth range. --plot: load-depth, E and H.",
                       spec);
    return kExitSuccess;
  }
  const FileAndOutputs run = file_and_outputs(arguments);
  const std::string& path = run.path;
  const std::string& output_path = run.output_path;
  const auto& plot_path = run.plot_path;
  const std::string& term = run.term;
  const indent::OliverPharrOptions o = oliver_pharr_options(arguments);
  const auto tests = indent::read_indentation(path);
  Items items = {{"coatcontact indent analyse", "Oliver-Pharr (THEORY.md section 16), SI units"}};
  if (arguments.has("--all")) {
    if (plot_path) throw InputError("--plot draws one test: drop --all or --plot");
    items.push_back({"file", path});
    add_options_header(items, o, tests.front());
    Output output(output_path);
    write_all_tests(output.stream(), items, tests, o);
    output.commit();
    return kExitSuccess;
  }
  const std::size_t index = choose_indent_test(tests, arguments, path);
  const indent::OliverPharrResult r = indent::oliver_pharr(tests[index], o);
  add_indent_test_header(items, tests, index, path);
  add_options_header(items, o, tests[index]);
  items.push_back({"stiffness", r.csm ? std::string("CSM channel") : "unloading power law P = alpha (h - h_f)^m"});
  if (!r.csm) {
    items.push_back({"unloading alpha [N/m^m], h_f [m], m", format_parameter(r.unloading.alpha, "alpha") + ", " +
                                                              format_parameter(r.unloading.final_depth, "h_f") + ", " +
                                                              format_parameter(r.unloading.exponent, "m")});
    items.push_back({"unloading points, rms relative residual", std::to_string(r.unloading.points) + ", " + format_parameter(r.unloading.rms_relative, "rms")});
  }
  items.push_back({"poisson (sample)", format_parameter(r.poisson, "poisson")});
  items.push_back({"range [m]", format_parameter(r.range_min, "range") + " to " + (std::isinf(r.range_max) ? std::string("end") : format_parameter(r.range_max, "range"))});
  items.push_back({"E mean [Pa]", format_parameter(r.modulus_mean, "E")});
  items.push_back({"E standard deviation [Pa]", format_parameter(r.modulus_sd, "E")});
  items.push_back({"H mean [Pa]", format_parameter(r.hardness_mean, "H")});
  items.push_back({"H standard deviation [Pa]", format_parameter(r.hardness_sd, "H")});
  items.push_back({"points in range", std::to_string(r.range_points)});
  items.push_back({"points dropped (h_c, A <= 0 or E_r above the indenter's: first contact)", std::to_string(r.dropped)});
  const std::string table = analyse_table(r, items);
  std::string raw;  // the load-depth curve of the whole test, for the plot
  for (std::size_t i = 0; i < tests[index].depth.size(); ++i)
    raw += format_value(tests[index].depth[i], "h") + '\t' + format_value(tests[index].load[i], "P") + '\n';
  if (plot_path)
    write_plot(plot_path, table + "\n\n" + raw,
               "mode='analyse'; term='" + term + "'; plottitle=" + gnuplot_string(tests[index].name + " - " + path) +
                   "; emean=" + format_parameter(r.modulus_mean, "E") + "; hmean=" + format_parameter(r.hardness_mean, "H"));
  Output output(output_path);
  output.stream() << table;
  output.commit();
  return kExitSuccess;
}

// ---- calibrate -----------------------------------------------------------------------------

int calibrate(const Args& args) {
  const std::vector<OptionSpec> spec = {
      {"--reference", "E,nu", "the reference sample (default fused silica 72GPa,0.17)", false},
      {"--indenter", "E,nu|rigid", "the tip (default diamond, 1141GPa,0.07)", false},
      {"--beta", "B", "default 1", false},
      {"--epsilon", "EPS", "default 0.75", false},
      {"--terms", "N", "area coefficients C0..C(N-1) (default 3)", false},
      {"--c0", "C0", "hold C0 (24.5 for a perfect Berkovich) instead of fitting it", false},
      {"--range", "MIN:MAX", "depths used (unit allowed; default: all)", false},
      {"--output", "FILE", "write the table to FILE (atomically) instead of stdout", false},
  };
  const Arguments arguments(args, spec, 1);
  if (arguments.help()) {
    std::cout << usage("indent calibrate", "FILE [options]",
                       "The tip's area function and the frame compliance from every test of FILE on a\n"
                       "reference of known modulus (THEORY.md section 16): A_i = pi S_i^2/(4 beta^2 E_r^2) fitted\n"
                       "linearly in C0.. (weights 1/A^2); 1/S = 1/K_f + slope/sqrt(P) (constant hardness).",
                       spec);
    return kExitSuccess;
  }
  if (arguments.positionals().size() != 1) throw InputError("expected one FILE (see --help)");
  const std::string path = arguments.positionals().front();
  register_input(path, "indentation file");
  const std::string output_path = arguments.get("--output").value_or("");
  check_output_path(output_path, "--output");
  indent::CalibrationOptions c;
  c.terms = 3;
  if (const auto v = arguments.get("--reference")) c.reference = parse_material(*v, "--reference");
  if (const auto v = arguments.get("--indenter")) c.indenter = parse_indenter(*v, "--indenter");
  if (const auto v = arguments.get("--beta")) c.beta = parse_number(*v, "--beta");
  if (const auto v = arguments.get("--epsilon")) c.epsilon = parse_number(*v, "--epsilon");
  if (const auto v = arguments.get("--terms")) {
    const double n = parse_number(*v, "--terms");
    if (!(n >= 1 && n <= 9 && n == std::floor(n))) throw InputError("--terms: '" + v->substr(0, 20) + "' is not allowed; 1 to 9");
    c.terms = static_cast<std::size_t>(n);
  }
  if (const auto v = arguments.get("--c0")) c.fixed_c0 = parse_number(*v, "--c0");
  if (const auto v = arguments.get("--range")) std::tie(c.depth_min, c.depth_max) = parse_range(*v, "--range", Quantity::kLength);
  const auto tests = indent::read_indentation(path);
  const indent::AreaCalibration a = indent::calibrate_area(tests, c);
  const indent::FrameCalibration f = indent::calibrate_frame(tests, c);
  Items items = {{"coatcontact indent calibrate", "area function and frame compliance on a reference (THEORY.md section 16)"},
                 {"file", path},
                 {"tests", std::to_string(tests.size())},
                 {"reference E [Pa], nu", format_parameter(c.reference.youngs_modulus, "E") + ", " + format_parameter(c.reference.poisson_ratio, "nu")},
                 {"area points", std::to_string(a.points)},
                 {"area rms relative residual", format_parameter(a.rms_relative, "rms")},
                 {"frame points", std::to_string(f.points)},
                 {"frame: 1/S = 1/K_f + slope/sqrt(P); slope [m/N^(1/2)]", format_parameter(f.slope, "slope")},
                 {"rows", "C0.. of A [nm^2] = C0 h^2 + C1 h + C2 h^(1/2) + .. (h_c in nm); frame compliance [m/N]; frame stiffness [N/m] (inf when the compliance is <= 0)"}};
  Output output(output_path);
  std::ostream& out = output.stream();
  write_header(out, items, {"quantity", "value", "standard_error"});
  for (std::size_t k = 0; k < a.area.coefficients.size(); ++k)
    out << "C" << k << '\t' << format_value(a.area.coefficients[k], "C") << '\t' << format_value(a.errors[k], "C") << '\n';
  out << "frame_compliance_m_per_N\t" << format_value(f.compliance, "C_f") << '\t' << format_value(f.compliance_error, "C_f") << '\n';
  const double k_err = f.compliance > 0 ? f.compliance_error / (f.compliance * f.compliance) : 0.0;
  out << "frame_stiffness_N_per_m\t" << (std::isinf(f.frame_stiffness) ? std::string("inf") : format_value(f.frame_stiffness, "K_f"))
      << '\t' << format_value(k_err, "K_f") << '\n';
  output.commit();
  return kExitSuccess;
}

// ---- film -----------------------------------------------------------------------------------

std::vector<OptionSpec> film_spec() {
  std::vector<OptionSpec> spec;
  for (const OptionSpec& o : oliver_pharr_spec())
    if (o.name != "--poisson" && o.name != "--stiffness" && o.name != "--unload-range") spec.push_back(o);
  const std::vector<OptionSpec> more = {
      {"--thickness", "T", "the film's thickness (unit allowed: 500nm); with --solve thickness the start", false},
      {"--film-poisson", "NU", "the film's Poisson ratio", true},
      {"--substrate", "E0,nu0|rigid", "the substrate below the film (and the layers)", true},
      {"--layer", "h,E,nu[,slip]", "a known layer below the film, top first (repeatable; THEORY.md section 12)", false, true},
      {"--model", "NAME|all", "exact (default), doerner-nix, king, saha-nix, mencik-linear, mencik-exponential, "
                              "mencik-reciprocal, gao, hay-crawford, bec, perriot-barthel, or all", false},
      {"--alpha", "A", "the empirical models' alpha (default: fitted over the range)", false},
      {"--contact-depth", "half-space|coated", "h - h_c = eps P/S, or eps scaled by the coated cone's kappa(a/t) (exact model)", false},
      {"--solve", "modulus|thickness", "the unknown (default modulus; thickness needs --film-modulus)", false},
      {"--film-modulus", "E", "the film's Young's modulus when solving for the thickness", false},
      {"--max-points", "N", "per-depth values at most at N depths, evenly spread (default 200)", false},
  };
  spec.insert(spec.end(), more.begin(), more.end());
  return spec;
}

indent::FilmOptions film_options(const Arguments& args) {
  indent::FilmOptions o;
  const bool thickness = args.get("--solve").value_or("modulus") == "thickness";
  if (!thickness && args.get("--solve").value_or("modulus") != "modulus")
    throw InputError("--solve: '" + args.get("--solve")->substr(0, 40) + "' is not allowed; use modulus or thickness");
  o.unknown = thickness ? indent::FilmUnknown::kThickness : indent::FilmUnknown::kModulus;
  Layer film;
  film.material.poisson_ratio = parse_number(args.require("--film-poisson"), "--film-poisson");
  film.material.youngs_modulus = 1.0;
  if (thickness) film.material = parse_material(args.require("--film-modulus") + "," + args.require("--film-poisson"), "--film-modulus");
  else if (args.has("--film-modulus")) throw InputError("--film-modulus is the given modulus of --solve thickness");
  if (!thickness || args.has("--thickness")) film.thickness = parse_quantity(args.require("--thickness"), Quantity::kLength, "--thickness");
  else film.thickness = 100e-9;
  o.layers = {film};
  for (const std::string& l : args.get_all("--layer")) o.layers.push_back(parse_layer(l, "--layer"));
  o.substrate = parse_substrate(args.require("--substrate"), "--substrate");
  if (const auto v = args.get("--alpha")) o.alpha = parse_number(*v, "--alpha");
  const std::string cd = args.get("--contact-depth").value_or("half-space");
  if (cd == "coated") o.contact_depth = indent::ContactDepth::kCoated;
  else if (cd != "half-space") throw InputError("--contact-depth: '" + cd.substr(0, 40) + "' is not allowed; use half-space or coated");
  if (const auto v = args.get("--max-points")) {
    const double n = parse_number(*v, "--max-points");
    if (!(n >= 1 && n <= 1e6 && n == std::floor(n))) throw InputError("--max-points: '" + v->substr(0, 20) + "' is not allowed; 1 to 1e6");
    o.max_points = static_cast<std::size_t>(n);
  }
  return o;
}

std::vector<indent::FilmModel> chosen_models(const Arguments& args) {
  const std::string m = args.get("--model").value_or("exact");
  if (m == "all") return indent::film_models();
  try {
    return {indent::film_model_from_name(m)};
  } catch (const InputError& e) {
    throw InputError(std::string("--model: ") + e.what());
  }
}

// Per depth: the geometry of the first model, then each model's value and error ("-" where a
// model has no root at that depth).
std::string film_table(const std::vector<indent::FilmResult>& rs, Items items, bool modulus) {
  std::vector<std::string> columns = {"depth_m", "load_N", "stiffness_N_per_m", "contact_depth_m", "contact_radius_m",
                                      "a_over_t", "E_apparent_Pa", "in_range"};
  for (const auto& r : rs) {
    std::string name = indent::film_model_name(r.model);
    for (char& c : name) if (c == '-') c = '_';
    columns.push_back((modulus ? "E_film_" : "thickness_") + name + (modulus ? "_Pa" : "_m"));
    columns.push_back((modulus ? "E_film_" : "thickness_") + name + (modulus ? "_error_Pa" : "_error_m"));
  }
  std::ostringstream out;
  write_header(out, items, columns);
  const indent::FilmResult& g = rs.front();
  for (std::size_t i = 0; i < g.depth.size(); ++i) {
    out << format_value(g.depth[i], columns[0]) << '\t' << format_value(g.load[i], columns[1]) << '\t'
        << format_value(g.stiffness[i], columns[2]) << '\t' << format_value(g.contact_depth[i], columns[3]) << '\t'
        << format_value(g.contact_radius[i], columns[4]) << '\t' << format_value(g.a_over_t[i], columns[5]) << '\t'
        << format_value(g.apparent_modulus[i], columns[6]) << '\t' << (g.in_range[i] ? 1 : 0);
    for (std::size_t m = 0; m < rs.size(); ++m) {
      const bool ok = rs[m].status[i].delivered;
      out << '\t' << (ok ? format_value(rs[m].value[i], columns[8 + 2 * m]) : std::string("-")) << '\t'
          << (ok ? format_value(rs[m].value_error[i], columns[9 + 2 * m]) : std::string("-"));
    }
    out << '\n';
  }
  return out.str();
}

void add_film_header(Items& items, const indent::FilmOptions& o, const std::vector<indent::FilmResult>& rs, bool modulus) {
  std::string layers;
  for (std::size_t k = 0; k < o.layers.size(); ++k)
    layers += (k ? "; " : "") + format_parameter(o.layers[k].thickness, "t") + " m, " +
              (k == 0 && modulus ? std::string("E unknown") : format_parameter(o.layers[k].material.youngs_modulus, "E") + " Pa") +
              ", nu " + format_parameter(o.layers[k].material.poisson_ratio, "nu");
  items.push_back({"layers (top first; the top is the film)", layers});
  items.push_back({"substrate", o.substrate.rigid ? std::string("rigid")
                                                  : format_parameter(o.substrate.material.youngs_modulus, "E0") + " Pa, nu " +
                                                        format_parameter(o.substrate.material.poisson_ratio, "nu0")});
  items.push_back({"contact depth", o.contact_depth == indent::ContactDepth::kCoated ? "h - h_c = eps kappa(a/t) P/S (coated cone)" : "h - h_c = eps P/S (half-space)"});
  items.push_back({"range [m]", format_parameter(rs.front().range_min, "range") + " to " +
                                    (std::isinf(rs.front().range_max) ? std::string("end") : format_parameter(rs.front().range_max, "range"))});
  items.push_back({"points in range", std::to_string(rs.front().points)});
  const std::string unit = modulus ? " [Pa]" : " [m]";
  for (const auto& r : rs) {
    const std::string m = indent::film_model_name(r.model);
    items.push_back({m + ": fitted " + (modulus ? "E_film" : "thickness") + unit, format_parameter(r.mean, "fit")});
    items.push_back({m + ": standard error" + unit, format_parameter(r.mean_error, "fit")});
    items.push_back({m + ": rms relative stiffness residual", format_parameter(r.rms_relative, "rms")});
    if (!std::isnan(r.alpha)) items.push_back({m + ": alpha", format_parameter(r.alpha, "alpha")});
    const std::size_t failed = failed_points(r.status);
    if (failed) items.push_back({m + ": depths without a root (- in the table)", std::to_string(failed) + "; first: " +
                                     [&] { for (const auto& s : r.status) if (!s.delivered) return s.reason; return std::string(); }()});
  }
  items.push_back({"per-depth error", "the fit's rms relative residual carried through that depth's sensitivity"});
}

// The composite's Oliver–Pharr modulus averaged over the range: the film plot's scale.
double film_plot_scale(const indent::FilmResult& r) {
  double sum = 0;
  int n = 0;
  for (std::size_t i = 0; i < r.depth.size(); ++i)
    if (r.in_range[i]) sum += r.apparent_modulus[i], ++n;
  if (n == 0) for (double e : r.apparent_modulus) sum += e, ++n;
  return sum / n;
}

int film(const Args& args) {
  const std::vector<OptionSpec> spec = film_spec();
  const Arguments arguments(args, spec, 1);
  if (arguments.help()) {
    std::cout << usage("indent film", "FILE --thickness T --film-poisson NU --substrate E0,nu0|rigid [options]",
                       "The film's modulus (or, with --solve thickness, its thickness) from the Oliver-Pharr\n"
                       "stiffness and contact radius at each depth, against the exact flat-punch stiffness of the\n"
                       "stack S = 2 beta a E_ref E_eq(a/t) (THEORY.md section 16; the diamond's compliance in\n"
                       "E_ref), per depth and fitted over the range with its standard error; --model all adds\n"
                       "every empirical model. --plot: the film's modulus against depth, each model, and the\n"
                       "Oliver-Pharr modulus of the composite.",
                       spec);
    return kExitSuccess;
  }
  const FileAndOutputs run = file_and_outputs(arguments);
  const std::string& path = run.path;
  const std::string& output_path = run.output_path;
  const auto& plot_path = run.plot_path;
  const std::string& term = run.term;
  const indent::OliverPharrOptions op = oliver_pharr_options(arguments);
  indent::FilmOptions o = film_options(arguments);
  const auto models = chosen_models(arguments);
  const bool modulus = o.unknown == indent::FilmUnknown::kModulus;
  const auto tests = indent::read_indentation(path);
  const std::size_t index = choose_indent_test(tests, arguments, path);
  o.depth_min = op.depth_min;
  o.depth_max = op.depth_max;
  std::vector<indent::FilmResult> rs;
  Items skipped;
  for (indent::FilmModel m : models) {
    indent::FilmOptions om = o;
    om.model = m;
    const bool empirical_fits = o.layers.size() == 1 && !o.substrate.rigid && modulus &&
                                o.contact_depth == indent::ContactDepth::kHalfSpace;
    if (m != indent::FilmModel::kExact && !empirical_fits && models.size() > 1) {  // one model: the library says why
      skipped.push_back({std::string(indent::film_model_name(m)) + ": skipped",
                         "needs one film on an elastic substrate, the half-space contact depth and --solve modulus"});
      continue;
    }
    try {
      rs.push_back(indent::film(tests[index], op, om));
    } catch (const NumericalError& e) {
      if (models.size() == 1) throw;
      skipped.push_back({std::string(indent::film_model_name(m)) + ": not delivered", e.what()});
    }
  }
  if (rs.empty()) throw NumericalError("no model delivered a film " + std::string(modulus ? "modulus" : "thickness"));
  Items items = {{"coatcontact indent film", "the film from the exact coated stiffness and the empirical models (THEORY.md section 16)"}};
  add_indent_test_header(items, tests, index, path);
  add_options_header(items, op, tests[index]);
  add_film_header(items, o, rs, modulus);
  items.insert(items.end(), skipped.begin(), skipped.end());
  const std::string table = film_table(rs, items, modulus);
  if (plot_path) {
    std::string names;
    for (const auto& r : rs) names += std::string(names.empty() ? "" : " ") + indent::film_model_name(r.model);
    write_plot(plot_path, table, "mode='" + std::string(modulus ? "film" : "thickness") + "'; term='" + term +
                                     "'; plottitle=" + gnuplot_string(tests[index].name + " - " + path) +
                                     "; models=" + gnuplot_string(names) + "; nmodels=" + std::to_string(rs.size()) +
                                     "; ymax=" + format_parameter(2.0 * film_plot_scale(rs.front()), "ymax"));
  }
  Output output(output_path);
  output.stream() << table;
  output.commit();
  return kExitSuccess;
}

}  // namespace

int run_indent_analyse(const Args& args) { return run_guarded("indent analyse", [&] { return analyse(args); }); }
int run_indent_calibrate(const Args& args) { return run_guarded("indent calibrate", [&] { return calibrate(args); }); }
int run_indent_film(const Args& args) { return run_guarded("indent film", [&] { return film(args); }); }

}  // namespace coatcontact::cli
