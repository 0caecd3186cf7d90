// coatcontact fit: least-squares fit of measured a,F or delta,F data to the coated-substrate
// JKR model (THEORY.md section 5; the model, branch choice and error policy are in fit.hpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <sys/stat.h>

#include <cctype>
#include <charconv>
#include <cerrno>
#include <cstring>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <ostream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "coatcontact/cli_support.hpp"
#include "coatcontact/data_file.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/fit.hpp"
#include "coatcontact/gnuplot_run.hpp"
#include "coatcontact/limits.hpp"
#include "coatcontact/measured_curve.hpp"
#include "coatcontact/si_text.hpp"
#include "checks.hpp"
#include "number_text.hpp"
#include "commands.hpp"
#include "fit_plot_script.hpp"

namespace coatcontact::cli {
namespace {

const std::vector<OptionSpec>& fit_options() {
  static const std::vector<OptionSpec> spec = {
      {"--columns", "a,F|delta,F|a=N,F=N,..", "the data columns: a,F / delta,F / z,F (F,a, F,delta, F,z reversed) for a two-column file, or name=position|header-name for any file (names a|delta|z, F, sigma_a|sigma_delta|sigma_z, sigma_F, branch: 1 loading, 0 unloading). z is the base (piezo) displacement z = delta + F/k through the spring k of --spring (k may be free: --free w,k)", true},
      {"--radius", "R", "sphere radius (length, e.g. 5mm); or --shape"},
      {"--shape", "SPEC", "any axisymmetric indenter instead of the sphere, as in 'contact --shape': sphere:R, cone:BETA (half included angle, e.g. 70deg), pyramid:THETA (face half angle; the cone of equal area), punch:A, power:N,R, blunted-cone:R,BETA, profile:FILE (columns r z). The shape's own parameters are fixed; w, t/h_i, E_i are fitted as for the sphere (no --curve, --plot)"},
      {"--film", "E1,nu1", "film Young's modulus and Poisson ratio (E1 is the start value if fitted); or --layer", false},
      layer_option(true),
      substrate_option(),
      {"--free", "w[,t][,E1]|w,h1..hN,E1..EN", "parameters to fit (default w); the others are fixed. With --layer: h1..hN and E1..EN name the layers' thicknesses and moduli, top first (one layer: t = h1). w_load,w_unload in place of w: each branch its own adhesion energy (rows from the branch column, else loading up to the largest a or delta)"},
      {"--start", "w=..,t=..,E1=..", "start values of free parameters (with units; h2=.., E2=.. with --layer)"},
      {"--thickness", "t", "film thickness with --film (required when t is fixed; start value when free); not with --layer"},
      {"--work", "w", "adhesion energy (required when w is fixed; start value when free)"},
      {"--branch", "load|unload|both", "fit only the loading or unloading rows (default both)"},
      {"--output", "FILE", "write the fitted data table here (default stdout)"},
      {"--curve", "FILE", "also write the fitted model curve (a, delta, F; 200 points) here"},
      {"--sigma", "a=..,F=..", "uncertainty per column: absolute with units (F=10uN) or relative (a=0.3%); delta= for delta,F data"},
      {"--bootstrap", "N", "N residual-bootstrap refits: percentile intervals (68 %, 95 %)"},
      {"--seed", "N", "seed of the bootstrap resampling (default 1)"},
      {"--plot", "FILE", "draw data, fit, residuals and pull-off with gnuplot (PNG or PDF by extension)"},
      indenter_option(),
      {"--model", "jkr|md", "adhesion model: jkr (default) or md, the Maugis-Dugdale zone (a,F data of a rigid sphere; --free w,lambda; from the stack's reduced table of the zone)"},
      {"--md-direct", "", "with --model md: every point by the direct per-radius solve (the reference; slow) instead of the reduced table of the cohesive zone"},
      {"--lambda", "L", "Maugis's lambda = 2 sigma0 (R/(pi w K^2))^(1/3), K = 4E1*/3, in [1e-3, 1e4] with --model md: fixed, or the start of the search when --free names lambda (default 1)"},
      {"--spring", "k", "machine or cantilever stiffness in N/m (e.g. 500N/m, 0.5mN/um): report its pull-off. With --columns z,F the spring the data were taken through: fixed, or the start of the search when --free names k"},
  };
  return spec;
}

// Header values: the shortest text that reads back to the same double (0.49, not
// 0.48999999999999999), as every other command's header.
std::string number(double value) {
  char buffer[64];
  if (!std::isfinite(value)) {
    std::snprintf(buffer, sizeof buffer, "%g", value);
    return buffer;
  }
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

// Above this |r| between two free parameters, `fit` warns (header, stderr).
constexpr double kMaxCorrelation = 0.99;

std::string short_number(double value) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

// "below 1e-08" for 3.4e-9: the interpolation check is a rounding-level diagnostic whose
// digits move with the compiler; its decade is what the reader needs.
std::string order_of_magnitude_bound(double value) {
  if (!(value > 0.0) || !std::isfinite(value)) return short_number(value);
  return "below 1e" + std::to_string(static_cast<int>(std::ceil(std::log10(value))));
}

using detail::split;
using detail::trim;

// The index of a parameter named on the command line: w, t, E1 (one film); with --layer also
// h1..hN and E1..EN (t is h1 of a single layer, refused for several).
int parameter_index(const std::string& name, const std::string& option, std::size_t layers, bool stack,
                    bool hysteresis, bool spring, bool md) {
  const std::vector<fit::ParameterInfo> list = fit::parameter_list(layers, hysteresis, spring, md);
  std::string allowed;
  for (const auto& info : list) allowed += (allowed.empty() ? "" : ", ") + info.name;
  if (layers == 1 && stack) allowed += " (h1 = t)";
  if (hysteresis && name == "w") {
    throw InputError(option + ": 'w' is not a parameter when the branches have their own adhesion energies "
                     "(allowed: " + allowed + ")");
  }
  if (!hysteresis && (name == "w_load" || name == "w_unload")) {
    throw InputError(option + ": '" + name + "' needs both branch energies free (--free w_load,w_unload,...)");
  }
  if (name == "lambda" && !md) {
    throw InputError(option + ": 'lambda' is a parameter of the Maugis-Dugdale model only (--model md) (allowed: " +
                     allowed + ")");
  }
  if (name == "k" && !spring) {
    throw InputError(option + ": 'k' (the spring stiffness) is a parameter only of base-displacement data "
                     "(--columns z,F, z = delta + F/k); with a,F or delta,F data k does not enter the curve (allowed: " +
                     allowed + ")");
  }
  if (name == "t" && layers > 1) {
    throw InputError(option + ": 't' is the thickness of a single film; with " + std::to_string(layers) +
                     " layers name the thicknesses h1..h" + std::to_string(layers) + " (allowed: " + allowed + ")");
  }
  const std::string key = layers == 1 && name == "h1" && stack ? "t" : name;
  for (std::size_t which = 0; which < list.size(); ++which) {
    if (list[which].name == key) return static_cast<int>(which);
  }
  throw InputError(option + ": '" + name + "' is not a parameter" +
                   (stack ? " of this " + std::to_string(layers) + "-layer stack" : std::string()) + " (allowed: " +
                   allowed + ")");
}

// Maugis's lambda: a number in [kMinimumLambda, kMaximumLambda] of limits.hpp (InputError
// naming `option`).
double parse_lambda(const std::string& text, const std::string& option) {
  char* end = nullptr;
  const double lambda = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || *end != '\0' || !(lambda >= kMinimumLambda && lambda <= kMaximumLambda)) {
    throw InputError(option + ": '" + text + "' is not allowed (need a number " + short_number(kMinimumLambda) +
                     " <= lambda <= " + short_number(kMaximumLambda) + "; lambda = 2 sigma0 (R/(pi w K^2))^(1/3), "
                     "K = 4E1*/3)");
  }
  return lambda;
}

Quantity parameter_kind(const fit::ParameterInfo& info) {
  return info.kind == fit::ParameterKind::kWork        ? Quantity::kEnergy
         : info.kind == fit::ParameterKind::kThickness ? Quantity::kLength
                                                       : Quantity::kPressure;
}


// ---- columns and data ----------------------------------------------------------------------

// What a user whose file declares no units needs to know (appended to a refusal).
std::string no_units_note(bool radius_data) {
  return std::string("; the file declares no units, so its numbers were read as metres and newtons: add a line "
                     "'# units: um mN' (or name the columns '") +
         (radius_data ? "a" : "delta") + " (um)', 'F (mN)')";
}

struct LoadedData {
  fit::Measurements data;
  std::vector<double> branch;  // the branch column (empty if none)
  bool has_units = false;      // "# units:" or units in the column names
  std::string units;           // as detected (measure::MeasuredCurve::units)
  std::vector<std::string> declared_columns;
  int declared_line = 0;
};

fit::DataKind data_kind(const measure::CurveColumns& columns) {
  return columns.abscissa == measure::Abscissa::kRadius ? fit::DataKind::kRadiusForce
                                                        : fit::DataKind::kPenetrationForce;
}

LoadedData load_data(const std::string& path, const measure::CurveColumns& columns) {
  const std::string name = path == "-" ? std::string("stdin") : short_name(path);
  measure::MeasuredCurve curve = measure::read_curve_text(read_input_text(path), name, columns);
  LoadedData out;
  out.data.kind = data_kind(columns);
  out.data.abscissa = std::move(curve.x);
  out.data.force = std::move(curve.force);
  out.data.line_numbers = std::move(curve.line_numbers);
  out.data.sigma_abscissa = std::move(curve.sigma_x);
  out.data.sigma_force = std::move(curve.sigma_force);
  out.branch = std::move(curve.branch);
  out.has_units = curve.has_units;
  out.units = curve.units;
  out.declared_columns = std::move(curve.declared_columns);
  out.declared_line = curve.declared_line;
  return out;
}

// --spring k: "500", "500N/m" or a force per length ("0.5mN/um").
double parse_stiffness(const std::string& text) {
  const auto slash = text.rfind('/');
  double k;
  if (slash == std::string::npos) {
    char* end = nullptr;
    k = std::strtod(text.c_str(), &end);
    if (end == text.c_str() || *end != '\0') throw InputError("--spring: '" + text + "' is not a stiffness (e.g. 500N/m)");
  } else {
    const double force = parse_quantity(text.substr(0, slash), Quantity::kForce, "--spring");
    const std::string length = text.substr(slash + 1);
    k = force / parse_quantity(length.empty() || !std::isdigit(static_cast<unsigned char>(length[0])) ? "1" + length : length,
                               Quantity::kLength, "--spring");
  }
  if (!(k > 0.0) || !std::isfinite(k)) throw InputError("--spring: the stiffness must be > 0 (got '" + text + "')");
  return k;
}

// --sigma a=0.3%,F=10uN: per-column uncertainties, relative (%) or absolute (with units).
void apply_sigma_option(const std::optional<std::string>& text, fit::Measurements& data, const measure::CurveColumns& choice) {
  if (!text) return;
  const bool radius_data = data.kind == fit::DataKind::kRadiusForce;
  for (const std::string& raw : split(*text, ',')) {
    const std::string item = trim(raw);
    const auto equals = item.find('=');
    if (equals == std::string::npos) {
      throw InputError("--sigma: '" + item + "' is not name=value (e.g. --sigma a=0.3%,F=10uN)");
    }
    const std::string name = trim(item.substr(0, equals));
    const std::string value = trim(item.substr(equals + 1));
    const std::string x = radius_data ? "a" : choice.abscissa == measure::Abscissa::kBaseDisplacement ? "z" : "delta";
    const bool abscissa = name == x;
    if (!abscissa && name != "F") {
      throw InputError("--sigma: '" + name + "' is not a column of these data (allowed: " + x + ", F)");
    }
    std::vector<double>& sigma = abscissa ? data.sigma_abscissa : data.sigma_force;
    if (!choice.reference[abscissa ? 2 : 3].empty()) {
      throw InputError("--sigma: " + name + " already has an uncertainty column (--columns)");
    }
    if (!sigma.empty()) throw InputError("--sigma: " + name + " is given twice");
    const std::vector<double>& values = abscissa ? data.abscissa : data.force;
    if (!value.empty() && value.back() == '%') {
      char* end = nullptr;
      const std::string number_text = value.substr(0, value.size() - 1);
      const double percent = std::strtod(number_text.c_str(), &end);
      if (end == number_text.c_str() || *end != '\0' || !(percent > 0.0) || !(percent < 100.0)) {
        throw InputError("--sigma " + name + ": '" + value + "' is not a percentage in (0, 100)");
      }
      for (double v : values) sigma.push_back(0.01 * percent * std::fabs(v));
    } else {
      const double absolute = parse_quantity(value, abscissa ? Quantity::kLength : Quantity::kForce, "--sigma " + name);
      if (!(absolute > 0.0)) throw InputError("--sigma " + name + ": must be > 0 (got '" + value + "')");
      sigma.assign(values.size(), absolute);
    }
  }
}

// Runs gnuplot on the embedded script (gnuplot/fit_plot.gp) with the tables in a private
// temporary folder; returns the picture (gnuplot writes it to stdout; the caller writes the
// file atomically). InputError when gnuplot is missing or fails.
std::string render_fit_plot(const std::string& table, const std::string& curve, const std::string& x_name,
                            const std::string& title, const std::string& fit_label, const std::string& term,
                            double lp_x, double lp_f, double dp_x, double dp_f, double spring_k) {
  const auto value = [](double v) { return std::isfinite(v) ? number(v) : std::string("NaN"); };
  return run_gnuplot({{"fit.tsv", table}, {"curve.tsv", curve}}, "fit_plot.gp", kFitPlotScript, [&](const std::string& dir) {
    return "fitfile=" + gnuplot_string(dir + "/fit.tsv") + "; curvefile=" + gnuplot_string(dir + "/curve.tsv") +
           "; xname='" + x_name + "'; term='" + term + "'; plottitle=" + gnuplot_string(title) +
           "; fitlabel=" + gnuplot_string(fit_label) + "; lp_x=" + value(lp_x) + "; lp_F=" + value(lp_f) +
           "; dp_x=" + value(dp_x) + "; dp_F=" + value(dp_f) + "; spring_k=" + value(spring_k);
  });
}

// Everything one `fit` run reads, fits and writes, filled in order by the steps below.
struct FitRun {
  FitRun(const Args& a, const Arguments& parsed) : args(a), arguments(parsed) {}
  const Args& args;
  const Arguments& arguments;
  std::string path, columns, x_name, output_path;
  measure::CurveColumns choice;
  bool base_data = false, radius_data = true, stack_given = false, hysteresis = false, md = false;
  fit::DataKind kind = fit::DataKind::kRadiusForce;
  fit::Problem problem;
  std::size_t layer_count = 1, parameter_count = 0, unload_index = 0;
  std::vector<std::string> free_items;
  std::vector<fit::ParameterInfo> parameters;
  std::vector<bool> free;
  std::vector<std::optional<double>> start;  // --start, in the order of the parameter vector
  std::optional<double> thickness, work;     // --thickness, --work
  fit::Branch branch = fit::Branch::kAll;
  LoadedData loaded;
  fit::Measurements all, data;  // the file's rows, and the selected branch
  std::string branch_source;
  std::vector<double> start_values;  // hints and fixed values, in the order of the parameter vector
  fit::Result result;
  std::vector<std::pair<std::string, std::string>> header;
  std::vector<std::string> out_columns;
  std::optional<std::string> curve_path, plot_path;
  std::ostringstream curve_text, table_text;
  std::string picture;
};


// The data kind, the indenter, the stack, the model (--model, --lambda, --spring) and the
// run options (--bootstrap, --seed, --plot).
void parse_model(FitRun& r) {
  // ---- columns ----
  r.columns = r.arguments.require("--columns");
  r.choice = measure::parse_curve_columns(r.columns);
  r.base_data = r.choice.abscissa == measure::Abscissa::kBaseDisplacement;
  r.kind = data_kind(r.choice);
  r.radius_data = r.kind == fit::DataKind::kRadiusForce;
  r.x_name = r.radius_data ? "a" : r.base_data ? "z" : "delta";

  // ---- physical parameters ----
  if (const auto text = r.arguments.get("--shape")) {
    if (r.arguments.has("--radius")) {
      throw InputError("--shape and --radius exclude each other (a sphere is --radius R or --shape sphere:R)");
    }
    if (r.arguments.has("--curve") || r.arguments.has("--plot")) {
      throw InputError("--shape: --curve and --plot draw the sphere's interpolated curve only; the fitted table "
                       "(--output) has the model at every data point");
    }
    std::string profile_end;
    r.problem.shape = parse_shape(*text, profile_end);
  } else {
    if (!r.arguments.has("--radius")) throw InputError("missing required option --radius R (or --shape SPEC) (see --help)");
    r.problem.sphere_radius = parse_quantity(r.arguments.require("--radius"), Quantity::kLength, "--radius");
  }
  // --film (one film of thickness t) or --layer, repeated (a stack whose layers carry their
  // thicknesses); parse_stack refuses both together and checks the constants.
  r.stack_given = r.arguments.has("--layer");
  {
    const Stack stack = parse_stack(r.arguments);
    if (r.stack_given) {
      if (r.arguments.has("--thickness")) {
        throw InputError("--thickness: cannot be combined with --layer (the layers carry their thicknesses; "
                         "fit one with --free h1..hN)");
      }
      r.problem.layers = stack.layers();
    } else {
      r.problem.film = stack.top();
    }
    r.problem.substrate = stack.substrate();
    r.problem.indenter = stack.indenter();
  }
  r.layer_count = r.stack_given ? r.problem.layers.size() : 1;
  // Loading and unloading with their own adhesion energy (JKR hysteresis): named in --free.
  r.free_items = split(r.arguments.get("--free").value_or("w"), ',');
  r.hysteresis = std::any_of(r.free_items.begin(), r.free_items.end(), [](const std::string& item) {
    return trim(item) == "w_load" || trim(item) == "w_unload";
  });
  // --model md: the Maugis-Dugdale zone (lambda last in the parameter vector; --lambda its value).
  r.md = false;
  if (const auto text = r.arguments.get("--model")) {
    if (*text == "md") {
      r.md = true;
    } else if (*text != "jkr") {
      throw InputError("--model: '" + *text + "' is not allowed (jkr, the default, or md: Maugis-Dugdale)");
    }
  }
  if (r.md) {
    r.problem.maugis_dugdale = true;
    if (!r.radius_data) throw InputError("--model md: fits a,F data only (--columns a,F)");
    if (r.problem.shape) throw InputError("--model md: the Maugis-Dugdale zone is fitted for the sphere only, not --shape");
    if (r.hysteresis) throw InputError("--model md: one adhesion energy only (not w_load,w_unload)");
    if (r.arguments.has("--spring")) throw InputError("--model md: no spring pull-off (leave out --spring)");
    if (const auto text = r.arguments.get("--lambda")) r.problem.lambda = parse_lambda(*text, "--lambda");
    r.problem.maugis_dugdale_direct = r.arguments.has("--md-direct");
  } else if (r.arguments.has("--lambda")) {
    throw InputError("--lambda: only with --model md");
  } else if (r.arguments.has("--md-direct")) {
    throw InputError("--md-direct: only with --model md (it selects the Maugis-Dugdale solve)");
  }
  r.parameters = fit::parameter_list(r.layer_count, r.hysteresis, r.base_data, r.md);
  r.parameter_count = r.parameters.size();
  r.unload_index = fit::unload_work_index(r.layer_count);
  r.problem.hysteresis = r.hysteresis;
  if (const auto text = r.arguments.get("--spring")) r.problem.spring_stiffness = parse_stiffness(*text);
  // z,F: the base (piezo) displacement z = delta + F/k; k is a parameter (--spring: its value).
  r.problem.base_displacement = r.base_data;
  if (r.base_data) {
    if (r.problem.shape) {
      throw InputError("--columns z,F: base-displacement data are fitted with the sphere only (--radius), not --shape");
    }
    if (!r.arguments.has("--spring")) {
      throw InputError("--columns z,F: give the spring stiffness with --spring k (its value when fixed, the start of "
                       "the search when --free names k)");
    }
  }
  if (const auto text = r.arguments.get("--bootstrap")) {
    char* end = nullptr;
    const long n = std::strtol(text->c_str(), &end, 10);
    if (end == text->c_str() || *end != '\0' || n < 10 || n > 100000) {
      throw InputError("--bootstrap: '" + *text + "' is not an integer in [10, 100000]");
    }
    r.problem.bootstrap = static_cast<int>(n);
  }
  if (const auto text = r.arguments.get("--seed")) {
    char* end = nullptr;
    const long long n = std::strtoll(text->c_str(), &end, 10);
    if (end == text->c_str() || *end != '\0' || n < 0 || n > 4000000000LL) {
      throw InputError("--seed: '" + *text + "' is not an integer in [0, 4e9]");
    }
    if (!r.arguments.get("--bootstrap")) throw InputError("--seed: only used with --bootstrap");
    r.problem.bootstrap_seed = static_cast<unsigned long>(n);
  }
  if (const auto text = r.arguments.get("--plot")) {
    const auto dot = text->rfind('.');
    const std::string extension = dot == std::string::npos ? "" : text->substr(dot + 1);
    if (extension != "png" && extension != "pdf") {
      throw InputError("--plot: '" + *text + "' must end in .png or .pdf (the format follows the extension)");
    }
  }
}

// --free, --start, --thickness, --work, --branch.
void parse_parameters(FitRun& r) {
  r.free.assign(r.parameter_count, false);
  for (const std::string& item : r.free_items) {
    const int which = parameter_index(trim(item), "--free", r.layer_count, r.stack_given, r.hysteresis, r.base_data, r.md);
    if (r.free[which]) throw InputError("--free: '" + trim(item) + "' is named twice");
    r.free[which] = true;
  }
  if (r.hysteresis && !(r.free[fit::kWork] && r.free[r.unload_index])) {
    throw InputError("--free: name both w_load and w_unload (the two branches' adhesion energies are fitted together)");
  }
  for (std::size_t which = 0; which < r.parameter_count; ++which) {
    if ((r.stack_given || r.hysteresis || r.base_data || r.md) && r.free[which]) r.problem.free_parameters.push_back(which);
    if (!r.stack_given && !r.hysteresis && !r.base_data && !r.md) r.problem.free[which] = r.free[which];
  }
  r.start.assign(r.parameter_count, std::nullopt);
  if (const auto text = r.arguments.get("--start")) {
    for (const std::string& item : split(*text, ',')) {
      const auto equals = item.find('=');
      if (equals == std::string::npos) {
        throw InputError("--start: '" + trim(item) + "' is not name=value (e.g. w=40mJ/m2,t=50um)");
      }
      const std::string name = trim(item.substr(0, equals));
      const int which = parameter_index(name, "--start", r.layer_count, r.stack_given, r.hysteresis, r.base_data, r.md);
      if (!r.free[which]) {
        throw InputError("--start: " + name + " is not free (add it to --free, or fix it with its own option)");
      }
      if (r.start[which]) throw InputError("--start: " + name + " is given twice");
      if (r.parameters[which].kind == fit::ParameterKind::kLambda) {
        r.start[which] = parse_lambda(item.substr(equals + 1), "--start lambda");
      } else if (r.parameters[which].kind == fit::ParameterKind::kSpring) {
        try {
          r.start[which] = parse_stiffness(item.substr(equals + 1));
        } catch (const InputError& error) {
          std::string message = error.what();
          if (message.rfind("--spring: ", 0) == 0) message = message.substr(10);
          throw InputError("--start k: " + message);
        }
      } else {
        r.start[which] = parse_quantity(item.substr(equals + 1), parameter_kind(r.parameters[which]), "--start " + name);
      }
    }
  }
  if (r.base_data && r.start[r.parameters.size() - 1]) r.problem.spring_stiffness = *r.start[r.parameters.size() - 1];
  if (r.md && r.start[r.parameters.size() - 1]) r.problem.lambda = *r.start[r.parameters.size() - 1];
  if (const auto text = r.arguments.get("--thickness")) r.thickness = parse_quantity(*text, Quantity::kLength, "--thickness");
  if (const auto text = r.arguments.get("--work")) r.work = parse_quantity(*text, Quantity::kEnergy, "--work");
  r.branch = fit::Branch::kAll;
  if (const auto text = r.arguments.get("--branch"); text && r.hysteresis && *text != "both") {
    throw InputError("--branch: '" + *text + "' keeps one branch, but w_load,w_unload need both (leave --branch out)");
  }
  if (r.choice.reference[4].size() > 0 && !r.hysteresis) {
    throw InputError("--columns: branch=" + r.choice.reference[4] +
                     " is read only when the branches have their own adhesion energies (--free w_load,w_unload)");
  }
  if (const auto text = r.arguments.get("--branch")) {
    if (*text == "load") {
      r.branch = fit::Branch::kLoading;
    } else if (*text == "unload") {
      r.branch = fit::Branch::kUnloading;
    } else if (*text != "both") {
      throw InputError("--branch: '" + *text + "' is not allowed (load, unload or both)");
    }
  }
}

// The data file through the measure floor, the checks that need --radius or --shape, --sigma,
// the branch of each row.
void read_data(FitRun& r) {
  // ---- data ----
  check_output_paths({{"--output", r.arguments.get("--output").value_or("")},
                      {"--curve", r.arguments.get("--curve").value_or("")},
                      {"--plot", r.arguments.get("--plot").value_or("")}});
  r.loaded = load_data(r.path, r.choice);
  r.all = r.loaded.data;
  for (std::size_t i = 0; i < r.all.size(); ++i) {
    if (r.radius_data && !(r.all.abscissa[i] > 0.0)) {
      throw InputError(short_name(r.path) + ":" + std::to_string(r.all.line_numbers[i]) +
                       ": contact radius must be > 0 (got " + short_number(r.all.abscissa[i]) +
                       "); points out of contact are not on the equilibrium curve, remove them");
    }
    // A contact radius at or above R is not a sphere contact: almost always forgotten units.
    if (!r.problem.shape && r.radius_data && r.all.abscissa[i] >= r.problem.sphere_radius) {
      throw InputError(short_name(r.path) + ":" + std::to_string(r.all.line_numbers[i]) + ": contact radius a = " +
                       short_number(r.all.abscissa[i]) + " m is not below the sphere radius --radius " +
                       short_number(r.problem.sphere_radius) + " m" +
                       (r.loaded.has_units ? std::string("")
                                         : "; the file declares no units, so its numbers were read as metres and "
                                           "newtons: add a line '# units: um mN' (or name the columns 'a (um)', 'F (mN)')"));
    }
  }
  if (r.problem.shape && r.radius_data) {
    for (std::size_t i = 0; i < r.all.size(); ++i) {
      if (r.all.abscissa[i] > r.problem.shape->max_contact_radius()) {
        throw InputError(short_name(r.path) + ":" + std::to_string(r.all.line_numbers[i]) + ": contact radius a = " +
                         short_number(r.all.abscissa[i]) + " m exceeds the largest radius of --shape (" +
                         r.problem.shape->description() + ")");
      }
    }
  }
  if (!r.problem.shape && !r.radius_data && !r.loaded.has_units) {
    double largest = 0.0;
    for (double d : r.all.abscissa) largest = std::max(largest, std::fabs(d));
    if (largest >= r.problem.sphere_radius) {
      throw InputError(short_name(r.path) + ": penetrations up to " + short_number(largest) + " m exceed the sphere radius --radius " +
                       short_number(r.problem.sphere_radius) + " m; the file declares no units, so its numbers were "
                       "read as metres and newtons: add a line '# units: um mN' (or name the columns 'delta (um)', 'F (mN)')");
    }
  }
  apply_sigma_option(r.arguments.get("--sigma"), r.all, r.choice);
  // The branch of each row: the branch column (1 loading, 0 unloading), else the row order.
  if (r.hysteresis) {
    if (!r.loaded.branch.empty()) {
      r.all.unloading.assign(r.all.size(), false);
      for (std::size_t i = 0; i < r.all.size(); ++i) {
        const double b = r.loaded.branch[i];
        if (b != 0.0 && b != 1.0) {
          throw InputError(short_name(r.path) + ":" + std::to_string(r.all.line_numbers[i]) + ": branch = " + short_number(b) +
                           " is not allowed (1 for a loading row, 0 for an unloading row)");
        }
        r.all.unloading[i] = b == 0.0;
      }
      r.branch_source = "the branch column (1 loading, 0 unloading)";
    } else {
      r.all.unloading = fit::unloading_by_order(r.all);
      r.branch_source = std::string("the row order (loading up to the largest ") + (r.radius_data ? "a" : "delta") +
                      ", unloading after it)";
    }
  }
  r.data = fit::select_branch(r.all, r.branch);
}

// The hint (free) or value (fixed) of every parameter; the library checks their ranges.
void set_start_values(FitRun& r) {
  // ---- start values / fixed values ----
  if (r.stack_given) {
    // The layers' given values are the hints of the free ones (or --start) and fix the others.
    for (std::size_t which = 0; which < r.parameter_count; ++which) {
      if (!r.start[which] || which == fit::kWork) continue;
      const fit::ParameterInfo& info = r.parameters[which];
      Layer& layer = r.problem.layers[info.layer];
      (info.kind == fit::ParameterKind::kThickness ? layer.thickness : layer.material.youngs_modulus) = *r.start[which];
    }
  } else if (r.free[fit::kThickness]) {
    // Without a hint the search needs none: t ~ the middle of the contact radii (a/t ~ 1).
    double middle = 0.0;
    for (double x : r.data.abscissa) middle = std::max(middle, std::fabs(x));
    if (!r.radius_data && !r.problem.shape) middle = std::sqrt(r.problem.sphere_radius * middle);
    r.problem.thickness = r.start[fit::kThickness].value_or(r.thickness.value_or(0.3 * middle));
  } else {
    if (!r.thickness) throw InputError("t is fixed: give it with --thickness (or add t to --free)");
    r.problem.thickness = *r.thickness;
  }
  if (r.free[fit::kWork]) {
    if (r.start[fit::kWork]) {
      r.problem.work = *r.start[fit::kWork];
    } else if (r.work) {
      r.problem.work = *r.work;
    } else {
      // A shape has no sphere radius for the JKR estimate: the search finds w on its own.
      r.problem.work = fit::start_work(r.data, r.problem);
    }
    if (r.hysteresis) {
      r.problem.unload_work = r.start[r.unload_index].value_or(
          r.work.value_or(fit::start_work(r.data, r.problem)));
    }
  } else {
    if (!r.work) throw InputError("w is fixed: give it with --work (or add w to --free)");
    r.problem.work = *r.work;
  }
  if (!r.stack_given && r.free[fit::kFilmModulus] && r.start[fit::kFilmModulus]) {
    r.problem.film.youngs_modulus = *r.start[fit::kFilmModulus];
  }
  // The hint (free) or fixed value of every parameter, in the order of the parameter vector.
  r.start_values = {r.problem.work};
  if (r.stack_given) {
    for (const Layer& layer : r.problem.layers) r.start_values.push_back(layer.thickness);
    for (const Layer& layer : r.problem.layers) r.start_values.push_back(layer.material.youngs_modulus);
  } else {
    r.start_values.push_back(r.problem.thickness);
    r.start_values.push_back(r.problem.film.youngs_modulus);
  }
  if (r.hysteresis) r.start_values.push_back(r.problem.unload_work);
  if (r.base_data) r.start_values.push_back(r.problem.spring_stiffness);  // k, last
  if (r.md) r.start_values.push_back(r.problem.lambda);                     // lambda, last
  const auto source_option = [&](std::size_t which) -> std::string {
    if (r.start[which]) return "--start " + r.parameters[which].name;
    return r.stack_given ? "--layer" : which == fit::kThickness ? "--thickness" : "--film";
  };
  check_fit_columns(r.choice.two_column ? r.columns : std::string("a,F"), r.loaded.declared_columns, r.loaded.declared_line, r.path);
  // The library's ranges of the start values; the message names the option that set each.
  try {
    fit::check_start(r.data, r.problem);
  } catch (const fit::StartError& error) {
    const std::size_t which = error.parameter();
    const bool estimated_work = which == fit::kWork && r.free[fit::kWork] && !r.start[fit::kWork] && !r.work;
    std::string option;
    if (which == fit::kWork) {
      option = !r.free[fit::kWork] ? "--work"
               : r.start[fit::kWork] ? "--start w"
               : r.work ? "--work"
                      : "--radius (with the data's most tensile force, the start value of w)";
    } else if (r.hysteresis && which == r.unload_index) {
      option = r.start[r.unload_index] ? "--start w_unload" : "--work";
    } else if (which == fit::thickness_index(0)) {
      option = r.layer_count == 1 ? source_option(fit::kThickness) : "--layer (their total thickness)";
    } else {
      option = source_option(which);
    }
    throw InputError(option + ": " + error.what() + (estimated_work ? "; give a start value with --start w=..." : "") +
                     (estimated_work && !r.loaded.has_units ? no_units_note(r.radius_data) : ""));
  }
}

// The one library call.
void run_library_fit(FitRun& r) {
  r.result = [&] {
    try {
      return fit::fit(r.data, r.problem);
    } catch (const NumericalError& error) {
      // An unweighted fit assumes an exact abscissa; scatter in a (or delta) near the steep
      // part of the curve then drags w to the edge of its range. Say so and how to fix it.
      const std::string what = error.what();
      const bool runaway = what.find("the data do not determine w") != std::string::npos;
      if (!runaway || !r.data.sigma_abscissa.empty() || !r.data.sigma_force.empty()) throw;
      throw NumericalError(what + ". No uncertainties were given: if " + r.x_name +
                           " is noisy, that noise may dominate an unweighted fit in force; give both, e.g. --sigma " +
                           r.x_name + "=2%,F=1uN (or sigma columns), to weight each point by its effective variance");
    }
  }();
}

// Pairs of free parameters correlated beyond |r| = kMaxCorrelation: the data hardly tell them
// apart (the fit converges, but the two move together along a valley of the cost), so their
// standard errors are large and their values depend on each other. One text per pair.
std::vector<std::string> correlation_warnings(const FitRun& r) {
  std::vector<std::string> out;
  for (std::size_t a = 0; a < r.parameter_count; ++a) {
    for (std::size_t b = a + 1; b < r.parameter_count; ++b) {
      if (!r.free[a] || !r.free[b]) continue;
      const double c = r.result.correlation[a][b];
      if (std::fabs(c) > kMaxCorrelation) {
        out.push_back("correlation " + r.parameters[a].name + ", " + r.parameters[b].name + " = " + short_number(c) +
                      " (|r| > " + short_number(kMaxCorrelation) + "): the data hardly separate " +
                      r.parameters[a].name + " and " + r.parameters[b].name +
                      "; fix one of them (its value from another measurement) or add data that tells them apart");
      }
    }
  }
  return out;
}

// The header's key of a parameter with its unit, as every command writes them: "w [J/m2]",
// "lambda" (dimensionless), "w, start of the search [J/m2]" with a `what`.
std::string parameter_key(const fit::ParameterInfo& info, const std::string& what = "") {
  const std::string unit = info.unit;
  return info.name + what + (unit.empty() ? std::string() : " [" + unit + "]");
}

// One line per parameter ("w [J/m2]: 0.0401 +- 0.0002", "E1 [Pa]: 1e+06 (fixed)", as `afm fit`
// and `kinetics --fit`), the start of the search of the free ones, their correlations and,
// with --bootstrap, their percentile intervals.
void add_parameter_lines(FitRun& r) {
  auto& h = r.header;
  for (std::size_t which = 0; which < r.parameter_count; ++which) {
    const fit::ParameterInfo& info = r.parameters[which];
    h.emplace_back(parameter_key(info), number(r.result.value[which]) +
                                            (r.free[which] ? " +- " + number(r.result.standard_error[which])
                                                           : std::string(" (fixed)")));
  }
  for (std::size_t which = 0; which < r.parameter_count; ++which) {
    if (r.free[which]) h.emplace_back(parameter_key(r.parameters[which], ", start of the search"), number(r.start_values[which]));
  }
  for (std::size_t a = 0; a < r.parameter_count; ++a) {
    for (std::size_t b = a + 1; b < r.parameter_count; ++b) {
      if (r.free[a] && r.free[b]) {
        h.emplace_back("correlation " + r.parameters[a].name + ", " + r.parameters[b].name,
                       number(r.result.correlation[a][b]));
      }
    }
  }
  for (const std::string& w : correlation_warnings(r)) h.emplace_back("warning", w);
  if (r.problem.bootstrap <= 0) return;
  for (std::size_t which = 0; which < r.parameter_count; ++which) {
    if (!r.free[which]) continue;
    h.emplace_back(parameter_key(r.parameters[which], ", bootstrap 68% interval"),
                   number(r.result.interval68_low[which]) + ", " + number(r.result.interval68_high[which]));
    h.emplace_back(parameter_key(r.parameters[which], ", bootstrap 95% interval"),
                   number(r.result.interval95_low[which]) + ", " + number(r.result.interval95_high[which]));
  }
  h.emplace_back("bootstrap", std::to_string(r.result.bootstrap_samples) + " of " + std::to_string(r.problem.bootstrap) +
                                  " residual resamples refitted (seed " + std::to_string(r.problem.bootstrap_seed) +
                                  "), percentile intervals");
}

// The pull-off of the fitted model under one control, keyed as `contact` keys it.
void add_pulloff_lines(FitRun& r, const std::string& control, double force, double radius, double penetration) {
  r.header.emplace_back("pull-off force, " + control + " control [N]", number(force));
  r.header.emplace_back("pull-off contact radius, " + control + " control [m]", number(radius));
  r.header.emplace_back("pull-off penetration, " + control + " control [m]", number(penetration));
}

// An elastic body as the material header of every command: "substrate: rigid", or
// "substrate E0 [Pa]" and "substrate nu0".
void add_body_lines(FitRun& r, const std::string& body, const std::string& index, bool rigid, const Material& m) {
  if (rigid) {
    r.header.emplace_back(body, "rigid");
    return;
  }
  r.header.emplace_back(body + " E" + index + " [Pa]", number(m.youngs_modulus));
  r.header.emplace_back(body + " nu" + index, number(m.poisson_ratio));
}

// The header of the table and the curve: keys in words with their units in brackets and values
// in the shortest text that reads back to the same double, as every command writes them.
void make_header(FitRun& r) {
  auto& h = r.header;
  std::string command = "coatcontact fit";
  for (const auto& a : r.args) command += " " + a;
  h.emplace_back("command", command);
  h.emplace_back("data file", r.path);
  h.emplace_back("columns in the file", r.columns);
  h.emplace_back("data units", r.loaded.units);
  h.emplace_back("branch", r.branch == fit::Branch::kAll ? "both" : r.branch == fit::Branch::kLoading ? "load" : "unload");
  if (r.hysteresis) {
    const auto unloading_rows = std::count(r.data.unloading.begin(), r.data.unloading.end(), true);
    h.emplace_back("branches", std::to_string(r.data.size() - static_cast<std::size_t>(unloading_rows)) + " loading rows (w_load), " +
                                   std::to_string(unloading_rows) + " unloading rows (w_unload), from " + r.branch_source +
                                   "; pull-offs predicted with w_unload");
  }
  h.emplace_back("points", std::to_string(r.result.points) + " (of " + std::to_string(r.all.size()) + " in the file)");
  if (r.problem.shape) {
    h.emplace_back("indenter shape", r.problem.shape->description());
  } else {
    h.emplace_back("sphere radius R [m]", number(r.problem.sphere_radius));
  }
  if (r.stack_given) {
    std::string layers_text;
    for (std::size_t i = 0; i < r.layer_count; ++i) {
      const Layer& layer = r.problem.layers[i];
      const std::string k = std::to_string(i + 1);
      layers_text += (i == 0 ? "" : "; ") + std::string("h") + k + " = " + number(layer.thickness) + " m" +
                     (r.free[fit::thickness_index(i)] ? " (free)" : "") + ", E" + k + " = " +
                     number(layer.material.youngs_modulus) + " Pa" +
                     (r.free[fit::modulus_index(i, r.layer_count)] ? " (free)" : "") + ", nu" + k + " = " +
                     number(layer.material.poisson_ratio) + (layer.slip_below ? ", slip below" : "");
    }
    h.emplace_back("layers", std::to_string(r.layer_count) + " (top first; given values, hints of the free ones): " +
                                 layers_text);
  } else {
    h.emplace_back("film nu1", number(r.problem.film.poisson_ratio));
  }
  add_body_lines(r, "substrate", "0", r.problem.substrate.rigid, r.problem.substrate.material);
  std::string free_names;
  for (std::size_t which = 0; which < r.parameter_count; ++which) {
    if (r.free[which]) free_names += (free_names.empty() ? "" : ",") + r.parameters[which].name;
  }
  h.emplace_back("free", free_names);
  add_parameter_lines(r);
  add_body_lines(r, "indenter", "2", r.problem.indenter.rigid, r.problem.indenter.material);
  if (r.result.weighted) {
    h.emplace_back("weights", "effective variance sigma_F^2 + (dF/d" + r.x_name + ")^2 sigma_" + r.x_name +
                                  "^2 (dF/d" + r.x_name + " along the fitted curve)");
    h.emplace_back("chi2", number(r.result.chi2));
    h.emplace_back("chi2/dof", number(r.result.chi2_per_dof));
    if (r.result.chi2_per_dof > 2.0 || r.result.chi2_per_dof < 0.5) {
      h.emplace_back("warning", "chi2/(n-p) = " + short_number(r.result.chi2_per_dof) +
                                    " is far from 1: the stated uncertainties do not match the scatter, and "
                                    "the standard errors (which trust them) are off by sqrt(chi2/(n-p))");
    }
  } else {
    h.emplace_back("weights", "none: residuals in F, noise level from the scatter; the errors assume exact " +
                                  r.x_name + " (give --sigma " + r.x_name + "=..,F=.. if " + r.x_name + " is measured)");
  }
  h.emplace_back("global search", std::to_string(r.result.search_evaluations) + " model evaluations over log-parameters, " +
                                      short_number(r.result.search_seconds) + " s");
  if (r.result.second_minimum) {
    std::string text;
    for (std::size_t which = 0; which < r.parameter_count; ++which) {
      if (!r.free[which]) continue;
      text += std::string(text.empty() ? "" : ", ") + r.parameters[which].name + " = " +
              short_number(r.result.second_value[which]) + " " + r.parameters[which].unit;
    }
    h.emplace_back("second minimum", text + " (cost " + short_number(r.result.second_cost_ratio) + " x the best)");
  }
  if (r.problem.spring_stiffness > 0.0) {
    if (r.result.has_spring_pulloff) {
      add_pulloff_lines(r, "spring", r.result.spring_pulloff_force, r.result.spring_pulloff_radius,
                        r.result.spring_pulloff_penetration);
    } else {
      h.emplace_back("pull-off, spring control", "not found inside the scanned range of the fitted model");
    }
  }
  if (r.result.has_load_pulloff) {
    add_pulloff_lines(r, "load", r.result.load_pulloff_force, r.result.load_pulloff_radius,
                      r.result.load_pulloff_penetration);
  }
  h.emplace_back("residual norm [N]", number(r.result.residual_norm));
  h.emplace_back("residual sigma [N]", number(r.result.residual_sigma));
  h.emplace_back("R^2", number(r.result.r_squared));
  h.emplace_back("iterations", std::to_string(r.result.iterations));
  h.emplace_back("converged", r.result.converged ? "yes (" + r.result.stop_reason + ")" : "no");
  h.emplace_back("interpolation error [N]", number(r.result.interpolation_error));
  h.emplace_back("interpolation error / residual sigma", number(r.result.interpolation_error / r.result.residual_sigma));
  h.emplace_back("solver tolerance", number(r.result.solver_tolerance));
  h.emplace_back("solver calls", std::to_string(r.result.solver_calls));
  h.emplace_back("run time (wall clock, this computation) [s]", short_number(r.result.seconds));
  if (r.result.displacement_pulloff_radius > 0.0) {
    add_pulloff_lines(r, "displacement", r.result.displacement_pulloff_force, r.result.displacement_pulloff_radius,
                      r.result.displacement_pulloff_penetration);
  }
  std::size_t clamped = 0;
  for (bool c : r.result.clamped) clamped += c ? 1 : 0;
  if (!r.radius_data) {
    h.emplace_back("model branch", "a >= a_c (first minimum of delta(a)); points with delta < delta(a_c): " +
                                       std::to_string(clamped) + " (taken at a_c)");
  }
  r.out_columns = 
      r.radius_data ? std::vector<std::string>{"line", "a_m", "F_data_N", "F_model_N", "residual_N", "sigma_eff_N"}
                  : std::vector<std::string>{"line", "delta_m", "F_data_N", "a_model_m", "F_model_N", "residual_N",
                                             "clamped", "sigma_eff_N"};
  if (r.hysteresis) r.out_columns.push_back("branch");  // 1 loading, 0 unloading
}

// The fitted curve (for --curve and --plot); every file is produced in memory first (the plot by
// gnuplot) so a failure leaves no half-written set of files.
// The fitted model at the data points against the validity limits of the library (limits.hpp,
// as every SI command): a header line and a line on stderr for each limit it exceeds.
void add_validity_warnings(FitRun& r) {
  std::vector<Layer> layers = r.problem.layers;
  if (r.stack_given) {
    for (std::size_t i = 0; i < r.layer_count; ++i) {
      layers[i].thickness = r.result.value[fit::thickness_index(i)];
      layers[i].material.youngs_modulus = r.result.value[fit::modulus_index(i, r.layer_count)];
    }
  } else {
    Material film = r.problem.film;
    film.youngs_modulus = r.result.value[fit::kFilmModulus];
    layers = {Layer{r.result.value[fit::kThickness], film, false}};
  }
  const Stack fitted(layers, r.problem.substrate, r.problem.indenter);
  ValidityLimits limits;
  for (const Layer& layer : layers) limits.thickness += layer.thickness;
  limits.modulus = fitted.reference_modulus();
  limits.sphere_radius = r.problem.shape ? 0.0 : r.problem.sphere_radius;
  limits.max_contact_radius = r.problem.shape ? r.problem.shape->max_contact_radius() : 0.0;
  for (const std::string& w :
       validity_warnings(r.result.model_radius, r.result.model_penetration, r.result.model_force, limits)) {
    r.header.emplace_back("warning", "fitted model: " + w);
    std::cerr << "coatcontact fit: warning: fitted model: " << w << "\n";
  }
}

void make_curve(FitRun& r) {
  // The curve (for --curve and --plot), then the table; every file is produced in memory
  // first (the plot by gnuplot) so a failure leaves no half-written set of files.
  r.curve_path = r.arguments.get("--curve");
  r.plot_path = r.arguments.get("--plot");
  const std::vector<std::string> curve_columns{"a_m", "delta_m", "F_N"};
  if (r.curve_path || r.plot_path) {
    fit::Problem fitted = r.problem;
    // With two adhesion energies the curve is the unloading one (the pull-offs' w).
    fitted.work = r.result.value[r.hysteresis ? r.unload_index : static_cast<std::size_t>(fit::kWork)];
    fitted.hysteresis = false;
    if (r.stack_given) {
      for (std::size_t i = 0; i < r.layer_count; ++i) {
        fitted.layers[i].thickness = r.result.value[fit::thickness_index(i)];
        fitted.layers[i].material.youngs_modulus = r.result.value[fit::modulus_index(i, r.layer_count)];
      }
    } else {
      fitted.thickness = r.result.value[fit::kThickness];
      fitted.film.youngs_modulus = r.result.value[fit::kFilmModulus];
    }
    double a_lo = *std::min_element(r.result.model_radius.begin(), r.result.model_radius.end());
    const double a_hi = 1.05 * *std::max_element(r.result.model_radius.begin(), r.result.model_radius.end());
    if (r.result.displacement_pulloff_radius > 0.0) a_lo = std::min(a_lo, r.result.displacement_pulloff_radius);
    if (r.result.has_load_pulloff) a_lo = std::min(a_lo, r.result.load_pulloff_radius);
    a_lo *= r.radius_data ? 0.9 : 0.3;
    const std::vector<fit::CurvePoint> curve = fit::model_curve(fitted, a_lo, a_hi, 200);
    auto curve_header = r.header;
    curve_header.emplace_back("curve", std::string("fitted model, 200 points log-spaced in a") + (r.hysteresis ? " (with w_unload)" : ""));
    write_header(r.curve_text, curve_header, curve_columns);
    for (const auto& p : curve) write_row(r.curve_text, {p.radius, p.penetration, p.force}, curve_columns);
  }
}

// The data table with the model at every point.
void make_table(FitRun& r) {
  write_header(r.table_text, r.header, r.out_columns);
  for (std::size_t i = 0; i < r.data.size(); ++i) {
    const double line = r.data.line_numbers.empty() ? static_cast<double>(i + 1) : r.data.line_numbers[i];
    // sigma_eff: the weight's sigma, or the residual standard deviation of an unweighted fit.
    const double sigma = r.result.weighted ? r.result.sigma_effective[i] : r.result.residual_sigma;
    std::vector<double> row =
        r.radius_data ? std::vector<double>{line, r.data.abscissa[i], r.data.force[i], r.result.model_force[i], r.result.residual[i], sigma}
                    : std::vector<double>{line, r.data.abscissa[i], r.data.force[i], r.result.model_radius[i], r.result.model_force[i],
                                          r.result.residual[i], r.result.clamped[i] ? 1.0 : 0.0, sigma};
    if (r.hysteresis) row.push_back(r.data.unloading[i] ? 0.0 : 1.0);
    write_row(r.table_text, row, r.out_columns);
  }
}

// --plot: gnuplot on the table and the curve.
void make_picture(FitRun& r) {
  if (r.plot_path) {
    const double nan = std::nan("");
    // z,F data are drawn against the base displacement z = delta + F/k (THEORY.md section 10):
    // the model curve and the pull-offs too.
    const double spring_k = r.base_data ? r.result.value[fit::spring_index(r.layer_count, r.hysteresis)] : nan;
    const auto abscissa = [&](double radius, double penetration, double force) {
      return r.radius_data ? radius : r.base_data ? penetration + force / spring_k : penetration;
    };
    const double lp_x = r.result.has_load_pulloff
                            ? abscissa(r.result.load_pulloff_radius, r.result.load_pulloff_penetration,
                                       r.result.load_pulloff_force)
                            : nan;
    const double dp_x = r.result.displacement_pulloff_radius > 0.0
                            ? abscissa(r.result.displacement_pulloff_radius, r.result.displacement_pulloff_penetration,
                                       r.result.displacement_pulloff_force)
                            : nan;
    std::string estimates;
    for (std::size_t which = 0; which < r.parameter_count; ++which) {
      if (!r.free[which]) continue;
      const std::string unit = r.parameters[which].kind == fit::ParameterKind::kWork ? "J/m^2" : r.parameters[which].unit;
      estimates += std::string(estimates.empty() ? "" : ",  ") + r.parameters[which].name + " = " +
                   si_text_with_error(r.result.value[which], r.result.standard_error[which], unit);
    }
    const std::string fit_label =
        "fit: " + estimates + "   (n = " + std::to_string(r.result.points) +
        (r.result.weighted ? ", χ^2/(n-p) = " + si_text(r.result.chi2_per_dof, "") : ", s = " + si_text(r.result.residual_sigma, "N")) +
        (r.result.has_load_pulloff ? ", pull-off " + si_text(r.result.load_pulloff_force, "N") : "") + ")";
    std::string substrate = r.problem.substrate.rigid ? std::string("rigid substrate")
                                                      : "E0 = " + si_text(r.problem.substrate.material.youngs_modulus, "Pa") +
                                                            ", ν0 = " + short_number(r.problem.substrate.material.poisson_ratio);
    const std::string name = r.path == "-" ? std::string("stdin") : r.path.substr(r.path.find_last_of('/') + 1);
    std::string coating;
    if (r.stack_given) {
      coating = std::to_string(r.layer_count) + " layers (";
      for (std::size_t i = 0; i < r.layer_count; ++i) {
        coating += (i == 0 ? "" : "; ") + si_text(r.result.value[fit::thickness_index(i)], "m") + ", " +
                   si_text(r.result.value[fit::modulus_index(i, r.layer_count)], "Pa");
      }
      coating += ")";
    } else {
      coating = "film E1 = " + si_text(r.result.value[fit::kFilmModulus], "Pa") + " (ν1 = " +
                short_number(r.problem.film.poisson_ratio) + "), t = " + si_text(r.result.value[fit::kThickness], "m");
    }
    const std::string title = name + ": R = " + si_text(r.problem.sphere_radius, "m") + ", " + coating + ", " + substrate;
    r.picture = render_fit_plot(r.table_text.str(), r.curve_text.str(), r.x_name, title, fit_label,
                              r.plot_path->substr(r.plot_path->rfind('.') + 1), lp_x, r.result.load_pulloff_force, dp_x,
                              r.result.displacement_pulloff_force, spring_k);
  }
}

// Every output, all or none.
void write_outputs(FitRun& r) {
  r.output_path = r.arguments.get("--output").value_or("");
  std::unique_ptr<Output> plot_output;
  if (r.plot_path) {
    plot_output = std::make_unique<Output>(*r.plot_path, "--plot");
    plot_output->stream().write(r.picture.data(), static_cast<std::streamsize>(r.picture.size()));
  }
  std::unique_ptr<Output> curve_output;
  if (r.curve_path) {
    curve_output = std::make_unique<Output>(*r.curve_path, "--curve");
    curve_output->stream() << r.curve_text.str();
  }
  Output output(r.output_path);
  output.stream() << r.table_text.str();
  if (plot_output) plot_output->commit();
  if (curve_output) curve_output->commit();
  output.commit();
}

// A short human-readable summary: on stdout when the table went to a file (--output), on stderr
// when the table is on stdout (so it stays a clean table).
void print_summary(FitRun& r) {
  {
    std::ostream& os = r.output_path.empty() ? std::cerr : std::cout;
    os << "coatcontact fit: " << r.result.points << " points (" << r.x_name << ",F), "
              << r.result.free_count << " free parameter" << (r.result.free_count == 1 ? "" : "s") << ", converged ("
              << r.result.stop_reason << ") after " << r.result.iterations << " iterations\n";
    std::size_t width = 0;
    for (const auto& info : r.parameters) width = std::max(width, info.name.size());
    for (std::size_t which = 0; which < r.parameter_count; ++which) {
      os << "  " << r.parameters[which].name << std::string(width - r.parameters[which].name.size(), ' ') << " = "
                << short_number(r.result.value[which]) << " " << r.parameters[which].unit;
      if (r.free[which]) {
        os << " +- " << short_number(r.result.standard_error[which]) << " (standard error)";
        if (r.problem.bootstrap > 0) {
          os << ", bootstrap 68 % [" << short_number(r.result.interval68_low[which]) << ", "
                    << short_number(r.result.interval68_high[which]) << "]";
        }
      } else {
        os << " (fixed)";
      }
      os << "\n";
    }
    os << "  residual norm " << short_number(r.result.residual_norm) << " N, sigma "
              << short_number(r.result.residual_sigma) << " N, R^2 " << short_number(r.result.r_squared)
              << ", interpolation error " << order_of_magnitude_bound(r.result.interpolation_error / r.result.residual_sigma)
              << " sigma\n";
    if (r.result.weighted) {
      os << "  weighted by sigma_F^2 + (dF/d" << r.x_name << ")^2 sigma_" << r.x_name
                << "^2: chi2/(n-p) = " << short_number(r.result.chi2_per_dof) << "\n";
    } else {
      os << "  unweighted: the errors assume exact " << r.x_name << " (give --sigma if it is measured)\n";
    }
    if (r.result.has_load_pulloff) {
      os << "  predicted pull-off: " << short_number(r.result.load_pulloff_force) << " N under load control";
      if (r.result.displacement_pulloff_radius > 0.0) {
        os << ", " << short_number(r.result.displacement_pulloff_force) << " N under displacement control";
      }
      os << "\n";
    }
    if (r.result.has_spring_pulloff) {
      os << "  predicted pull-off through the spring k = "
                << short_number(r.base_data ? r.result.value.back() : r.problem.spring_stiffness)
                << " N/m: " << short_number(r.result.spring_pulloff_force) << " N\n";
    }
    for (const std::string& w : correlation_warnings(r)) os << "  warning: " << w << "\n";
    if (r.result.second_minimum) {
      os << "  note: a second minimum at";
      for (std::size_t which = 0; which < r.parameter_count; ++which) {
        if (r.free[which]) os << " " << r.parameters[which].name << " = " << short_number(r.result.second_value[which]);
      }
      os << " (cost " << short_number(r.result.second_cost_ratio) << " x the best)\n";
    }
  }
}

int run_fit_body(const Args& args) {
  const auto& spec = fit_options();
  Arguments arguments(args, spec, 1);
  if (arguments.help()) {
    std::cout << usage(
        "fit",
        "DATA --columns a,F|delta,F|z,F (--radius R | --shape SPEC) (--film E1,nu1 | --layer h,E,nu[,slip] ...) --substrate E0,nu0|rigid "
        "[--free w[,t][,E1] | --free w,h1..hN,E1..EN] [--start w=..,t=..,E1=..] [--thickness t] [--work w] "
        "[--branch load|unload|both] [--sigma a=..,F=..] [--bootstrap N [--seed N]] [--indenter E2,nu2] "
        "[--output FILE] [--curve FILE] [--plot FILE.png|FILE.pdf]",
        "Fits the adhesion energy w (and optionally the film thickness t and modulus E1) to measured\n"
        "contact radius-force (a,F) or penetration-force (delta,F) data of a sphere on a coated\n"
        "substrate, by nonlinear least squares (GSL trust region in log-parameters) on the exact model\n"
        "of THEORY.md section 5. The coating may be a stack of layers (--layer h,E,nu[,slip], top\n"
        "first, h a length, THEORY.md section 12): then any of w, h1..hN, E1..EN may be free, the others\n"
        "keep their given values. --free w_load,w_unload gives the loading and the unloading rows their\n"
        "own adhesion energy (JKR hysteresis; pull-offs with w_unload). No start values are needed: a\n"
        "coarse global search over the physical ranges picks the start (--start only adds a hint).\n"
        "Residuals are in force; with --sigma (or sigma columns) each is weighted by the effective\n"
        "variance sigma_F^2 + (dF/da)^2 sigma_a^2 and chi2/(n-p) is reported; without, the noise is\n"
        "estimated from the scatter and the errors assume an exact a (or delta). For delta,F data the\n"
        "model is taken on the stable branch under displacement control. DATA: TSV/CSV or '-'\n"
        "(stdin), '#' comments, units from a '# units: um mN' line or column names like 'a (um)'; SI\n"
        "otherwise. F is compressive positive.\n"
        "--shape SPEC replaces the sphere by any indenter of 'contact --shape' (cone, pyramid, flat\n"
        "punch, power law, blunted cone, measured profile; THEORY.md section 11): the model is then\n"
        "solved directly at each data point (slower: seconds to minutes), the shape's own parameters\n"
        "stay fixed.\n"
        "--columns z,F: the abscissa is the base (piezo) displacement z = delta + F/k of a sphere on a\n"
        "spring k (cantilever, machine frame; --spring k): the model is taken on the branch stable under\n"
        "spring control, and k itself can be fitted (--free w,k): F and z together carry it.\n"
        "--model md: a Maugis-Dugdale cohesive zone instead of JKR (THEORY.md section 13), lambda fixed\n"
        "(--lambda) or free (--free w,lambda); a,F data of a rigid sphere, one solve per point and trial.\n"
        "Exit 2: bad input; exit 3: no convergence, parameters not determined, or no model fit.",
        spec);
    return kExitSuccess;
  }
  if (arguments.positionals().size() != 1) {
    throw InputError("give exactly one data file (coatcontact fit DATA --columns ...)");
  }
  FitRun r(args, arguments);
  r.path = arguments.positionals()[0];
  parse_model(r);
  parse_parameters(r);
  const auto notes = report_plausibility("fit", arguments);
  read_data(r);
  set_start_values(r);
  run_library_fit(r);
  make_header(r);
  r.header.insert(r.header.end(), notes.begin(), notes.end());
  add_validity_warnings(r);
  make_curve(r);
  make_table(r);
  make_picture(r);
  write_outputs(r);
  print_summary(r);
  return kExitSuccess;
}

}  // namespace

int run_fit(const Args& args) {
  return run_guarded("fit", [&] { return run_fit_body(args); });
}

}  // namespace coatcontact::cli
