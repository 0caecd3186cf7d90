// coatcontact fit: least-squares fit of measured a,F or delta,F data to the coated-substrate
// JKR model (THEORY.md section 5; the model, branch choice and error policy are in fit.hpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <cstdio>
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
#include "checks.hpp"
#include "commands.hpp"

namespace coatcontact::cli {
namespace {

const std::vector<OptionSpec>& fit_options() {
  static const std::vector<OptionSpec> spec = {
      {"--columns", "a,F|delta,F", "what the two data columns are (F,a and F,delta: reversed order)", true},
      {"--radius", "R", "sphere radius (length, e.g. 5mm)", true},
      {"--film", "E1,nu1", "film Young's modulus and Poisson ratio (E1 is the start value if fitted)", true},
      {"--substrate", "E0,nu0|rigid", "substrate Young's modulus and Poisson ratio, or rigid", true},
      {"--free", "w[,t][,E1]", "parameters to fit (default w); the others are fixed"},
      {"--start", "w=..,t=..,E1=..", "start values of free parameters (with units)"},
      {"--thickness", "t", "film thickness (required when t is fixed; start value when free)"},
      {"--work", "w", "adhesion energy (required when w is fixed; start value when free)"},
      {"--branch", "load|unload|both", "fit only the loading or unloading rows (default both)"},
      {"--output", "FILE", "write the fitted data table here (default stdout)"},
      {"--curve", "FILE", "also write the fitted model curve (a, delta, F; 200 points) here"},
  };
  return spec;
}

std::string number(double value) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

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

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> items;
  std::string item;
  std::istringstream stream(text);
  while (std::getline(stream, item, separator)) items.push_back(item);
  if (!text.empty() && text.back() == separator) items.emplace_back();
  return items;
}

std::string trim(const std::string& text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t") - first + 1);
}

int parameter_index(const std::string& name, const std::string& option) {
  if (name == "w") return fit::kWork;
  if (name == "t") return fit::kThickness;
  if (name == "E1") return fit::kFilmModulus;
  throw InputError(option + ": '" + name + "' is not a parameter (allowed: w, t, E1)");
}

Quantity parameter_kind(int which) {
  return which == fit::kWork ? Quantity::kEnergy
                             : which == fit::kThickness ? Quantity::kLength : Quantity::kPressure;
}

const char* parameter_unit(int which) {
  return which == fit::kWork ? "J/m2" : which == fit::kThickness ? "m" : "Pa";
}

// The unit as spelled in header keys ("w_stderr_J_per_m2").
const char* key_unit(int which) {
  return which == fit::kWork ? "J_per_m2" : which == fit::kThickness ? "m" : "Pa";
}

int run_fit_body(const Args& args) {
  const auto& spec = fit_options();
  Arguments arguments(args, spec, 1);
  if (arguments.help()) {
    std::cout << usage(
        "fit",
        "DATA --columns a,F|delta,F --radius R --film E1,nu1 --substrate E0,nu0|rigid "
        "[--free w[,t][,E1]] [--start w=..,t=..,E1=..] [--thickness t] [--work w] "
        "[--branch load|unload|both] [--output FILE] [--curve FILE]",
        "Fits the adhesion energy w (and optionally the film thickness t and modulus E1) to measured\n"
        "contact radius-force (a,F) or penetration-force (delta,F) data of a rigid sphere on a coated\n"
        "substrate, by nonlinear least squares (GSL trust region) on the exact model of THEORY.md\n"
        "section 5. Residuals are in force; for delta,F data the model is taken on the stable branch\n"
        "under displacement control (a beyond the minimum of delta). Reports each estimate with its\n"
        "standard error (s^2 = RSS/(n-p), covariance s^2 (J^T J)^-1). DATA: TSV/CSV, '#' comments,\n"
        "optional '# units: um mN' line; SI otherwise. F is compressive positive (tension negative),\n"
        "delta may be negative, a must be > 0. Exit 2: bad input (also n <= free parameters);\n"
        "exit 3: no convergence, parameters not determined, or the model does not describe the data.",
        spec);
    return kExitSuccess;
  }
  if (arguments.positionals().size() != 1) {
    throw InputError("give exactly one data file (coatcontact fit DATA --columns ...)");
  }
  const std::string path = arguments.positionals()[0];

  // ---- columns ----
  const std::string columns = arguments.require("--columns");
  fit::DataKind kind;
  bool reversed = false;
  if (columns == "a,F" || columns == "F,a") {
    kind = fit::DataKind::kRadiusForce;
    reversed = columns == "F,a";
  } else if (columns == "delta,F" || columns == "F,delta") {
    kind = fit::DataKind::kPenetrationForce;
    reversed = columns == "F,delta";
  } else {
    throw InputError("--columns: '" + columns + "' is not allowed (a,F, delta,F, F,a or F,delta)");
  }
  const bool radius_data = kind == fit::DataKind::kRadiusForce;
  const std::string x_name = radius_data ? "a" : "delta";

  // ---- physical parameters ----
  fit::Problem problem;
  problem.sphere_radius = parse_quantity(arguments.require("--radius"), Quantity::kLength, "--radius");
  problem.film = parse_material(arguments.require("--film"), "--film");
  problem.substrate = parse_substrate(arguments.require("--substrate"), "--substrate");
  std::array<bool, fit::kParameterCount> free{{false, false, false}};
  for (const std::string& item : split(arguments.get("--free").value_or("w"), ',')) {
    const int which = parameter_index(trim(item), "--free");
    if (free[which]) throw InputError("--free: '" + trim(item) + "' is named twice");
    free[which] = true;
  }
  problem.free = free;
  std::array<std::optional<double>, fit::kParameterCount> start;
  if (const auto text = arguments.get("--start")) {
    for (const std::string& item : split(*text, ',')) {
      const auto equals = item.find('=');
      if (equals == std::string::npos) {
        throw InputError("--start: '" + trim(item) + "' is not name=value (e.g. w=40mJ/m2,t=50um)");
      }
      const std::string name = trim(item.substr(0, equals));
      const int which = parameter_index(name, "--start");
      if (!free[which]) {
        throw InputError("--start: " + name + " is not free (add it to --free, or fix it with its own option)");
      }
      if (start[which]) throw InputError("--start: " + name + " is given twice");
      start[which] = parse_quantity(item.substr(equals + 1), parameter_kind(which), "--start " + name);
    }
  }
  std::optional<double> thickness;
  std::optional<double> work;
  if (const auto text = arguments.get("--thickness")) thickness = parse_quantity(*text, Quantity::kLength, "--thickness");
  if (const auto text = arguments.get("--work")) work = parse_quantity(*text, Quantity::kEnergy, "--work");
  fit::Branch branch = fit::Branch::kAll;
  if (const auto text = arguments.get("--branch")) {
    if (*text == "load") {
      branch = fit::Branch::kLoading;
    } else if (*text == "unload") {
      branch = fit::Branch::kUnloading;
    } else if (*text != "both") {
      throw InputError("--branch: '" + *text + "' is not allowed (load, unload or both)");
    }
  }

  // ---- data: a >= 0 enforced by the reader (and a > 0 by the fit); F and delta any sign ----
  const std::vector<bool> nonnegative = radius_data ? (reversed ? std::vector<bool>{false, true}
                                                                : std::vector<bool>{true, false})
                                                    : std::vector<bool>{false, false};
  const std::vector<std::optional<Quantity>> kinds =
      reversed ? std::vector<std::optional<Quantity>>{Quantity::kForce, Quantity::kLength}
               : std::vector<std::optional<Quantity>>{Quantity::kLength, Quantity::kForce};
  const DataTable table = read_data_file(path, 2, nonnegative, kinds);
  // Refuse a bad --output/--curve now (a device, the data file, each other), not after the fit.
  check_output_paths({{"--output", arguments.get("--output").value_or("")},
                      {"--curve", arguments.get("--curve").value_or("")}});
  fit::Measurements all;
  all.kind = kind;
  all.abscissa = table.columns[reversed ? 1 : 0];
  all.force = table.columns[reversed ? 0 : 1];
  all.line_numbers = table.line_numbers;
  if (radius_data) {
    for (std::size_t i = 0; i < all.size(); ++i) {
      if (!(all.abscissa[i] > 0.0)) {
        throw InputError(path + ":" + std::to_string(all.line_numbers[i]) +
                         ": contact radius must be > 0 (got " + short_number(all.abscissa[i]) +
                         "); points out of contact are not on the equilibrium curve, remove them");
      }
    }
  }
  const fit::Measurements data = fit::select_branch(all, branch);

  // ---- start values / fixed values ----
  if (free[fit::kThickness]) {
    if (!start[fit::kThickness] && !thickness) {
      throw InputError("t is free: give its start value with --start t=... (or --thickness)");
    }
    problem.thickness = start[fit::kThickness].value_or(thickness.value_or(0.0));
  } else {
    if (!thickness) throw InputError("t is fixed: give it with --thickness (or add t to --free)");
    problem.thickness = *thickness;
  }
  if (free[fit::kWork]) {
    if (start[fit::kWork]) {
      problem.work = *start[fit::kWork];
    } else if (work) {
      problem.work = *work;
    } else {
      problem.work = fit::jkr_work_estimate(data, problem.sphere_radius);
    }
  } else {
    if (!work) throw InputError("w is fixed: give it with --work (or add w to --free)");
    problem.work = *work;
  }
  if (free[fit::kFilmModulus] && start[fit::kFilmModulus]) {
    problem.film.youngs_modulus = *start[fit::kFilmModulus];
  }
  const double start_values[3] = {problem.work, problem.thickness, problem.film.youngs_modulus};
  check_fit_start({columns, table.declared_columns, table.declared_columns_line, path, radius_data, data.abscissa,
                   problem.work, problem.thickness, problem.film.youngs_modulus,
                   free[fit::kWork] ? (start[fit::kWork] ? "--start w" : work ? "--work" : "--radius (with the data's most tensile force, the start value of w)") : "--work",
                   free[fit::kThickness] && start[fit::kThickness] ? "--start t" : "--thickness",
                   free[fit::kFilmModulus] && start[fit::kFilmModulus] ? "--start E1" : "--film"});

  const fit::Result result = fit::fit(data, problem);

  // ---- output ----
  std::vector<std::pair<std::string, std::string>> header;
  std::string command = "coatcontact fit";
  for (const auto& a : args) command += " " + a;
  header.emplace_back("command", command);
  header.emplace_back("data", path);
  header.emplace_back("columns_in_file", columns);
  header.emplace_back("branch", branch == fit::Branch::kAll ? "both" : branch == fit::Branch::kLoading ? "load" : "unload");
  header.emplace_back("points", std::to_string(result.points) + " (of " + std::to_string(all.size()) + " in the file)");
  header.emplace_back("sphere_radius_m", number(problem.sphere_radius));
  header.emplace_back("film_nu1", number(problem.film.poisson_ratio));
  header.emplace_back("substrate", problem.substrate.rigid ? std::string("rigid")
                                                           : "E0 = " + number(problem.substrate.material.youngs_modulus) +
                                                                 " Pa, nu0 = " + number(problem.substrate.material.poisson_ratio));
  std::string free_names;
  for (int which = 0; which < fit::kParameterCount; ++which) {
    if (!free[which]) continue;
    free_names += (free_names.empty() ? "" : ",") + std::string(fit::parameter_name(which));
  }
  header.emplace_back("free", free_names);
  const char* keys[3] = {"w_J_per_m2", "t_m", "E1_Pa"};
  for (int which = 0; which < fit::kParameterCount; ++which) {
    header.emplace_back(keys[which], number(result.value[which]));
    if (free[which]) {
      header.emplace_back(std::string(fit::parameter_name(which)) + "_stderr_" + key_unit(which),
                          number(result.standard_error[which]));
      header.emplace_back(std::string(fit::parameter_name(which)) + "_start_" + key_unit(which),
                          number(start_values[which]));
    } else {
      header.emplace_back(std::string(fit::parameter_name(which)) + "_status", "fixed");
    }
  }
  for (int a = 0; a < fit::kParameterCount; ++a) {
    for (int b = a + 1; b < fit::kParameterCount; ++b) {
      if (free[a] && free[b]) {
        header.emplace_back(std::string("correlation_") + fit::parameter_name(a) + "_" + fit::parameter_name(b),
                            number(result.correlation[a][b]));
      }
    }
  }
  header.emplace_back("residual_norm_N", number(result.residual_norm));
  header.emplace_back("residual_sigma_N", number(result.residual_sigma));
  header.emplace_back("r_squared", number(result.r_squared));
  header.emplace_back("iterations", std::to_string(result.iterations));
  header.emplace_back("converged", result.converged ? "yes (" + result.stop_reason + ")" : "no");
  header.emplace_back("interpolation_error_N", number(result.interpolation_error));
  header.emplace_back("interpolation_error_over_sigma", number(result.interpolation_error / result.residual_sigma));
  header.emplace_back("solver_tolerance", number(result.solver_tolerance));
  header.emplace_back("solver_calls", std::to_string(result.solver_calls));
  header.emplace_back("fit_seconds", short_number(result.seconds));
  if (result.displacement_pulloff_radius > 0.0) {
    header.emplace_back("displacement_pulloff_a_m", number(result.displacement_pulloff_radius));
    header.emplace_back("displacement_pulloff_delta_m", number(result.displacement_pulloff_penetration));
    header.emplace_back("displacement_pulloff_F_N", number(result.displacement_pulloff_force));
  }
  std::size_t clamped = 0;
  for (bool c : result.clamped) clamped += c ? 1 : 0;
  if (!radius_data) {
    header.emplace_back("model_branch", "a >= a_c (first minimum of delta(a)); points with delta < delta(a_c): "
                                        + std::to_string(clamped) + " (taken at a_c)");
  }
  const std::vector<std::string> out_columns =
      radius_data ? std::vector<std::string>{"line", "a_m", "F_data_N", "F_model_N", "residual_N"}
                  : std::vector<std::string>{"line", "delta_m", "F_data_N", "a_model_m", "F_model_N", "residual_N",
                                             "clamped"};

  // The curve (written first so a failure leaves no half-written pair of files).
  std::unique_ptr<Output> curve_output;
  if (const auto curve_path = arguments.get("--curve")) {
    fit::Problem fitted = problem;
    fitted.work = result.value[fit::kWork];
    fitted.thickness = result.value[fit::kThickness];
    fitted.film.youngs_modulus = result.value[fit::kFilmModulus];
    double a_lo = *std::min_element(result.model_radius.begin(), result.model_radius.end());
    const double a_hi = 1.05 * *std::max_element(result.model_radius.begin(), result.model_radius.end());
    if (result.displacement_pulloff_radius > 0.0) a_lo = std::min(a_lo, result.displacement_pulloff_radius);
    a_lo *= radius_data ? 0.9 : 0.3;
    const std::vector<fit::CurvePoint> curve = fit::model_curve(fitted, a_lo, a_hi, 200);
    curve_output = std::make_unique<Output>(*curve_path, "--curve");
    auto curve_header = header;
    curve_header.emplace_back("curve", "fitted model, 200 points log-spaced in a");
    const std::vector<std::string> curve_columns{"a_m", "delta_m", "F_N"};
    write_header(curve_output->stream(), curve_header, curve_columns);
    for (const auto& p : curve) write_row(curve_output->stream(), {p.radius, p.penetration, p.force}, curve_columns);
  }

  const std::string output_path = arguments.get("--output").value_or("");
  Output output(output_path);
  write_header(output.stream(), header, out_columns);
  for (std::size_t i = 0; i < data.size(); ++i) {
    const double line = data.line_numbers.empty() ? static_cast<double>(i + 1) : data.line_numbers[i];
    if (radius_data) {
      write_row(output.stream(), {line, data.abscissa[i], data.force[i], result.model_force[i], result.residual[i]},
                out_columns);
    } else {
      write_row(output.stream(),
                {line, data.abscissa[i], data.force[i], result.model_radius[i], result.model_force[i],
                 result.residual[i], result.clamped[i] ? 1.0 : 0.0},
                out_columns);
    }
  }
  if (curve_output) curve_output->commit();
  output.commit();

  if (!output_path.empty()) {
    // The table went to a file: a short human-readable summary on stdout.
    std::cout << "coatcontact fit: " << result.points << " points (" << x_name << ",F), "
              << result.free_count << " free parameter" << (result.free_count == 1 ? "" : "s") << ", converged ("
              << result.stop_reason << ") after " << result.iterations << " iterations\n";
    for (int which = 0; which < fit::kParameterCount; ++which) {
      std::cout << "  " << fit::parameter_name(which) << (which == fit::kFilmModulus ? " = " : "  = ")
                << short_number(result.value[which]) << " " << parameter_unit(which);
      if (free[which]) {
        std::cout << " +- " << short_number(result.standard_error[which]) << " (standard error)";
      } else {
        std::cout << " (fixed)";
      }
      std::cout << "\n";
    }
    std::cout << "  residual norm " << short_number(result.residual_norm) << " N, sigma "
              << short_number(result.residual_sigma) << " N, R^2 " << short_number(result.r_squared)
              << ", interpolation error " << order_of_magnitude_bound(result.interpolation_error / result.residual_sigma)
              << " sigma\n";
  }
  return kExitSuccess;
}

}  // namespace

int run_fit(const Args& args) {
  return run_guarded("fit", [&] { return run_fit_body(args); });
}

}  // namespace coatcontact::cli
