// make_synthetic_data: writes a synthetic adhesive sphere-contact data set (a,F or delta,F, a
// loading and an unloading branch) from known parameters, with Gaussian noise of a stated
// standard deviation on the force and, optionally, on the abscissa (GSL mt19937 generator,
// fixed seed: reproducible).
// The model is the library's (THEORY.md section 5): JkrLaw with the Maugis scales of Contact.
// Its reduced variables are solved directly at each contact radius through a SolverSource,
// not interpolated, so the data stay independent of the ReducedTable the fit uses.
// Used by scripts/make_example_data.sh (data/README.md). Links only the library: its few
// options are parsed here, not by the CLI's parsers.
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "coatcontact/adhesion.hpp"
#include "coatcontact/contact.hpp"
#include "coatcontact/detail/format.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/reduced.hpp"
#include "coatcontact/units.hpp"

namespace {

using namespace coatcontact;

// ---- options ------------------------------------------------------------------------------

struct Option {
  const char* name;
  const char* value;
  const char* help;
  const char* fallback;  // nullptr: required
};

const Option kOptions[] = {
    {"--kind", "a,F|delta,F", "data columns to write", nullptr},
    {"--radius", "R", "sphere radius", "5mm"},
    {"--film", "E1,nu1", "film modulus and Poisson ratio", "1MPa,0.49"},
    {"--substrate", "E0,nu0|rigid", "substrate", "70GPa,0.22"},
    {"--thickness", "t", "film thickness", "50um"},
    {"--layer", "h,E,nu[,slip]", "a layer, top first, repeated (instead of --film and --thickness)", ""},
    {"--work", "w", "adhesion energy", "40mJ/m2"},
    {"--work-unload", "w", "adhesion energy of the unloading rows (default: --work)", ""},
    {"--branch-column", "yes|no", "add a third column 'branch': 1 on loading rows, 0 on unloading rows", "no"},
    {"--noise", "sigma", "standard deviation of the Gaussian force noise", "10uN"},
    {"--noise-x", "sigma|p%", "Gaussian noise on a (or delta): absolute, or relative with %", "0"},
    {"--a-range", "a_min,a_max", "contact radii of both branches (default: from F = 0)", ""},
    {"--seed", "N", "seed of the GSL mt19937 generator", "1"},
    {"--points", "N", "points per branch", "40"},
    {"--max-over-pulloff", "f", "a_max / a at zero force on loading", "1.5"},
    {"--signal", "model|none", "none: F is pure noise (for tests of failing fits)", "model"},
    {"--output", "FILE", "output file (default stdout)", ""},
};

// A number with an optional unit of the library's table (units.hpp). The plain product
// number * factor (not to_si's division) keeps the files of data/ regenerating bit for bit.
double parse_value(const std::string& text, const std::string& option, bool with_unit) {
  const char* begin = text.c_str();
  char* end = nullptr;
  const double number = std::strtod(begin, &end);
  const std::string unit(end);
  if (end == begin || !std::isfinite(number)) throw InputError(option + ": '" + text + "' is not a number");
  if (unit.empty()) return number;
  const auto info = find_unit(unit);
  if (!with_unit || !info) throw InputError(option + ": unknown unit in '" + text + "'");
  return number * info->to_si;
}

Material parse_material(const std::string& text, const std::string& option) {
  const auto comma = text.find(',');
  if (comma == std::string::npos) throw InputError(option + ": '" + text + "' is not E,nu");
  Material m{parse_value(text.substr(0, comma), option, true),
             parse_value(text.substr(comma + 1), option, false)};
  validate(m, option.substr(2));
  return m;
}

class Arguments {
 public:
  explicit Arguments(const std::vector<std::string>& args) {
    for (std::size_t i = 0; i < args.size(); ++i) {
      if (args[i] == "--help" || args[i] == "-h") {
        help_ = true;
        continue;
      }
      bool known = false;
      for (const Option& o : kOptions) known = known || args[i] == o.name;
      if (!known) throw InputError("unknown option '" + args[i] + "' (see --help)");
      if (i + 1 >= args.size()) throw InputError(args[i] + " needs a value");
      values_[args[i]] = args[i + 1];
      all_[args[i]].push_back(args[i + 1]);
      ++i;
    }
  }
  bool help() const { return help_; }
  std::vector<std::string> get_all(const std::string& name) const {
    const auto it = all_.find(name);
    return it == all_.end() ? std::vector<std::string>{} : it->second;
  }
  std::string get(const std::string& name) const {
    const auto it = values_.find(name);
    if (it != values_.end()) return it->second;
    for (const Option& o : kOptions) {
      if (name == o.name && o.fallback != nullptr) return o.fallback;
    }
    throw InputError(name + " is required (see --help)");
  }

 private:
  bool help_ = false;
  std::map<std::string, std::string> values_;
  std::map<std::string, std::vector<std::string>> all_;
};

// "h,E,nu[,slip]" (h with a length unit).
Layer parse_layer(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) items.push_back(item);
  if (items.size() < 3 || items.size() > 4 || (items.size() == 4 && items[3] != "slip")) {
    throw InputError("--layer: '" + text + "' is not h,E,nu[,slip]");
  }
  Layer layer;
  layer.thickness = parse_value(items[0], "--layer", true);
  if (!(layer.thickness > 0.0)) throw InputError("--layer: the thickness must be > 0 (got '" + items[0] + "')");
  layer.material = parse_material(items[1] + "," + items[2], "--layer");
  layer.slip_below = items.size() == 4;
  return layer;
}

void print_help() {
  std::cout << "usage: make_synthetic_data --kind a,F|delta,F [options]\n"
               "Synthetic adhesive sphere-contact data with Gaussian force noise.\n";
  for (const Option& o : kOptions) {
    std::cout << "  " << o.name << " " << o.value << "\t" << o.help;
    if (o.fallback != nullptr && *o.fallback != '\0') std::cout << " (default " << o.fallback << ")";
    std::cout << "\n";
  }
}

// ---- the model ----------------------------------------------------------------------------

struct Point {
  double a, delta, force;
};

// The exact model at each contact radius: one solver sweep, then the JKR law of the adhesive
// model at a_bar = a/l, converted to SI with the contact's scales.
std::vector<Point> exact_points(const Contact& contact, const ReducedSolver& solver,
                                const std::vector<double>& radii, double thickness, double tolerance) {
  std::vector<double> a_over_t;
  for (double a : radii) a_over_t.push_back(a / thickness);
  const std::vector<ReducedVariables> v = SolverSource(solver, tolerance).evaluate(a_over_t);
  std::vector<Point> out;
  for (std::size_t i = 0; i < radii.size(); ++i) {
    ReducedPoint r;  // values only: P and D need no derivatives
    r.a_over_t = v[i].a_over_t;
    r.pi_s = v[i].pi_s;
    r.delta_s = v[i].delta_s;
    r.pi_c = v[i].pi_c;
    r.delta_c = v[i].delta_c;
    r.e_eq = v[i].e_eq;
    r.gamma1 = v[i].gamma1;
    const CurvePoint p =
        contact.model().law().point(r, contact.eta(), radii[i] / contact.length_scale());
    out.push_back({radii[i], p.penetration * contact.penetration_scale(), p.load * contact.force_scale()});
  }
  return out;
}

std::vector<double> linspace(double from, double to, int count) {
  std::vector<double> out;
  for (int i = 0; i < count; ++i) out.push_back(from + (to - from) * i / (count - 1));
  return out;
}

std::string text(const char* format, double value) {
  char line[64];
  std::snprintf(line, sizeof line, format, value);
  return line;
}

// The options, parsed and checked.
struct Settings {
  std::string kind;
  bool radius_data = true;
  double R = 0.0;
  std::vector<Layer> layers;
  Material film;
  Substrate substrate;
  double t = 0.0, w = 0.0, w_unload = 0.0;
  bool branch_column = false;
  double sigma = 0.0, max_factor = 0.0;
  bool noise_x_relative = false;
  double noise_x = 0.0, range_lo = 0.0, range_hi = 0.0;
  bool pure_noise = false;
  int points = 0;
  unsigned long seed = 0;
};

Settings parse_settings(const Arguments& arguments) {
  Settings s;
  s.kind = arguments.get("--kind");
  if (s.kind != "a,F" && s.kind != "delta,F") {
    throw InputError("--kind: '" + s.kind + "' is not allowed (a,F or delta,F)");
  }
  s.radius_data = s.kind == "a,F";
  s.R = parse_value(arguments.get("--radius"), "--radius", true);
  for (const std::string& text : arguments.get_all("--layer")) s.layers.push_back(parse_layer(text));
  s.film = parse_material(arguments.get("--film"), "--film");
  if (arguments.get("--substrate") == "rigid") {
    s.substrate.rigid = true;
  } else {
    s.substrate.material = parse_material(arguments.get("--substrate"), "--substrate");
  }
  s.t = parse_value(arguments.get("--thickness"), "--thickness", true);
  if (!s.layers.empty()) {
    s.t = 0.0;  // the layers carry the lengths; T = sum h is the unit
    for (const Layer& layer : s.layers) s.t += layer.thickness;
  }
  s.w = parse_value(arguments.get("--work"), "--work", true);
  const std::string unload_text = arguments.get("--work-unload");
  s.w_unload = unload_text.empty() ? s.w : parse_value(unload_text, "--work-unload", true);
  const std::string branch_text = arguments.get("--branch-column");
  if (branch_text != "yes" && branch_text != "no") throw InputError("--branch-column: '" + branch_text + "' is not yes or no");
  s.branch_column = branch_text == "yes";
  s.sigma = parse_value(arguments.get("--noise"), "--noise", true);
  const double seed_value = parse_value(arguments.get("--seed"), "--seed", false);
  const double points_value = parse_value(arguments.get("--points"), "--points", false);
  s.max_factor = parse_value(arguments.get("--max-over-pulloff"), "--max-over-pulloff", false);
  if (!(s.sigma >= 0.0)) throw InputError("--noise: must be >= 0");
  if (seed_value < 0 || seed_value != std::floor(seed_value) || seed_value > 4e9) {
    throw InputError("--seed: must be an integer in [0, 4e9]");
  }
  if (points_value < 3 || points_value != std::floor(points_value) || points_value > 100000) {
    throw InputError("--points: must be an integer in [3, 100000]");
  }
  if (!(s.max_factor > 1.0 && s.max_factor < 100.0)) throw InputError("--max-over-pulloff: must be in (1, 100)");
  // Noise on the abscissa: relative ("0.3%") or absolute (with a unit).
  const std::string noise_x_text = arguments.get("--noise-x");
  s.noise_x_relative = !noise_x_text.empty() && noise_x_text.back() == '%';
  s.noise_x =
      s.noise_x_relative ? 0.01 * parse_value(noise_x_text.substr(0, noise_x_text.size() - 1), "--noise-x", false)
                       : parse_value(noise_x_text, "--noise-x", true);
  if (!(s.noise_x >= 0.0)) throw InputError("--noise-x: must be >= 0");
  if (const std::string range = arguments.get("--a-range"); !range.empty()) {
    const auto comma = range.find(',');
    if (comma == std::string::npos) throw InputError("--a-range: '" + range + "' is not a_min,a_max");
    s.range_lo = parse_value(range.substr(0, comma), "--a-range", true);
    s.range_hi = parse_value(range.substr(comma + 1), "--a-range", true);
    if (!(s.range_lo > 0.0 && s.range_hi > s.range_lo)) throw InputError("--a-range: need 0 < a_min < a_max");
  }
  const std::string signal = arguments.get("--signal");
  if (signal != "model" && signal != "none") throw InputError("--signal: '" + signal + "' is not allowed (model or none)");
  s.pure_noise = signal == "none";
  s.points = static_cast<int>(points_value);
  s.seed = static_cast<unsigned long>(seed_value);
  return s;
}

int run(const std::vector<std::string>& args) {
  const Arguments arguments(args);
  if (arguments.help()) {
    print_help();
    return 0;
  }
  const Settings settings = parse_settings(arguments);
  const auto& [kind, radius_data, R, layers, film, substrate, t, w, w_unload, branch_column, sigma, max_factor,
               noise_x_relative, noise_x, range_lo, range_hi, pure_noise, points, seed] = settings;
  const double tolerance = 1e-9;  // the kernel table limits the solver to ~1e-10

  const ReducedSolver solver(layers.empty() ? Stack::film_on(film, substrate) : Stack(layers, substrate));
  const AdhesiveModel model(solver);
  const Contact contact(model, R, t, w);  // checks R, t, w and owns the Maugis scales
  const Contact unload_contact(model, R, t, w_unload);
  // Locate the turning points on a dense exact curve (they only set the sampled range):
  // a0 where F = 0 on the stable branch (jump into contact), the load-controlled pull-off
  // (minimum of F) and the displacement-controlled pull-off (minimum of delta).
  const double length = contact.length_scale();
  std::vector<double> dense;
  for (int i = 0; i <= 400; ++i) dense.push_back(1e-3 * length * std::pow(1e4, i / 400.0));
  const std::vector<Point> curve = exact_points(contact, solver, dense, t, kDefaultTolerance);
  std::size_t i_fmin = 0;
  std::size_t i_dmin = 0;
  for (std::size_t i = 0; i < curve.size(); ++i) {
    if (curve[i].force < curve[i_fmin].force) i_fmin = i;
    if (curve[i].delta < curve[i_dmin].delta) i_dmin = i;
  }
  // The unloading rows end above the pull-off of their own adhesion energy.
  const std::vector<Point> unload_curve = w_unload == w ? curve : exact_points(unload_contact, solver, dense, t, kDefaultTolerance);
  std::size_t u_fmin = 0;
  std::size_t u_dmin = 0;
  for (std::size_t i = 0; i < unload_curve.size(); ++i) {
    if (unload_curve[i].force < unload_curve[u_fmin].force) u_fmin = i;
    if (unload_curve[i].delta < unload_curve[u_dmin].delta) u_dmin = i;
  }
  std::size_t i_zero = i_fmin;
  while (i_zero < curve.size() && curve[i_zero].force < 0.0) ++i_zero;
  if (i_fmin == 0 || i_dmin == 0 || i_zero >= curve.size()) {
    throw NumericalError("could not locate the pull-off points on the model curve");
  }
  const double a_zero = curve[i_zero].a;
  double a_max = max_factor * a_zero;
  // Loading from the jump-in radius to a_max; unloading back to just above the pull-off
  // (load control for a,F, displacement control for delta,F), on a grid offset by half a
  // step so the two branches sample different radii.
  double a_end = 1.02 * (radius_data ? unload_curve[u_fmin].a : unload_curve[u_dmin].a);
  double a_start = a_zero;
  if (range_hi > 0.0) {
    a_start = range_lo;
    a_max = range_hi;
    a_end = range_lo;
  }
  std::vector<double> radii = linspace(a_start, a_max, points);
  const double step = (a_max - a_end) / (points - 0.5);
  std::vector<double> unload_radii;
  for (int i = 0; i < points; ++i) unload_radii.push_back(a_max - (i + 0.5) * step);
  std::vector<Point> data;
  if (w_unload == w) {
    radii.insert(radii.end(), unload_radii.begin(), unload_radii.end());
    data = exact_points(contact, solver, radii, t, tolerance);
  } else {
    data = exact_points(contact, solver, radii, t, tolerance);
    const std::vector<Point> unloading = exact_points(unload_contact, solver, unload_radii, t, tolerance);
    data.insert(data.end(), unloading.begin(), unloading.end());
  }

  std::unique_ptr<gsl_rng, void (*)(gsl_rng*)> rng(gsl_rng_alloc(gsl_rng_mt19937), gsl_rng_free);
  gsl_rng_set(rng.get(), seed);

  std::ostringstream out;
  std::string command = "make_synthetic_data";
  for (const auto& a : args) command += " " + a;
  out << "# Synthetic adhesive sphere-contact data (coatcontact, issue 6; see data/README.md)\n"
      << "# generated by: " << command << "\n"
      << "# model: exact coated-substrate JKR curve (THEORY.md section 5), reduced variables solved\n"
      << "#   directly at each a/t by ReducedSolver (tolerance " << tolerance << "), no interpolation\n"
      << "# sphere radius R = " << text("%.15g", R) << " m\n";
  if (layers.empty()) {
    out << "# film: t = " << text("%.15g", t) << " m, E1 = " << text("%.15g", film.youngs_modulus)
        << " Pa, nu1 = " << text("%.15g", film.poisson_ratio) << "\n";
  } else {
    for (std::size_t i = 0; i < layers.size(); ++i) {
      out << "# layer " << i + 1 << ": h = " << text("%.15g", layers[i].thickness) << " m, E = "
          << text("%.15g", layers[i].material.youngs_modulus) << " Pa, nu = "
          << text("%.15g", layers[i].material.poisson_ratio) << (layers[i].slip_below ? ", slip below" : "") << "\n";
    }
  }
  if (substrate.rigid) {
    out << "# substrate: rigid\n";
  } else {
    out << "# substrate: E0 = " << text("%.15g", substrate.material.youngs_modulus)
        << " Pa, nu0 = " << text("%.15g", substrate.material.poisson_ratio) << "\n";
  }
  out << "# adhesion energy w = " << text("%.15g", w) << " J/m2"
      << (w_unload == w ? std::string() : " on loading, " + text("%.15g", w_unload) + " J/m2 on unloading") << "\n"
      << "# noise: Gaussian, standard deviation " << text("%.15g", sigma) << " N, added to F"
      << (noise_x > 0.0 ? std::string(" (") + (radius_data ? "a" : "delta") + " noisy too, see below)"
                        : std::string(" only (") + (radius_data ? "a" : "delta") + " exact)")
      << "; GSL gsl_rng_mt19937, seed " << seed
      << ", gsl_ran_gaussian, one draw per row in file order\n";
  if (noise_x > 0.0) {
    out << "# noise on " << (radius_data ? "a" : "delta") << ": Gaussian, "
        << (noise_x_relative ? "relative " + text("%.6g", 100.0 * noise_x) + " %" : text("%.6g", noise_x) + " m")
        << ", a second draw per row after the force's\n";
  }
  if (range_hi > 0.0) {
    out << "# rows: " << points << " loading (a from " << text("%.6g", range_lo) << " to " << text("%.6g", range_hi)
        << " m), then " << points << " unloading (back to " << text("%.6g", range_lo) << " m, half a step offset)\n";
  } else {
    out << "# rows: " << points << " loading (a increasing from F = 0 to a_max = " << text("%.6g", a_max)
        << " m), then " << points << " unloading (a decreasing to 1.02 x the "
        << (radius_data ? "load-controlled" : "displacement-controlled") << " pull-off radius)\n";
  }
  if (pure_noise) out << "# signal: none -- F is pure noise (the model force is NOT added)\n";
  if (branch_column) {
    out << (radius_data ? "# columns: a\tF\tbranch\n# units: um mN 1\n" : "# columns: delta\tF\tbranch\n# units: um mN 1\n");
  } else {
    out << (radius_data ? "# columns: a\tF\n# units: um mN\n" : "# columns: delta\tF\n# units: um mN\n");
  }
  for (std::size_t row = 0; row < data.size(); ++row) {
    const Point& p = data[row];
    const double noisy = (pure_noise ? 0.0 : p.force) + gsl_ran_gaussian(rng.get(), sigma);
    double x = radius_data ? p.a : p.delta;
    if (noise_x > 0.0) {
      const double e = gsl_ran_gaussian(rng.get(), 1.0);
      x += noise_x_relative ? noise_x * std::fabs(x) * e : noise_x * e;
    }
    x *= 1e6;
    if (!std::isfinite(x) || !std::isfinite(noisy)) throw NumericalError("model value not finite");
    out << detail::full_precision(x) << "\t" << detail::full_precision(noisy * 1e3);
    if (branch_column) out << "\t" << (row < static_cast<std::size_t>(points) ? 1 : 0);
    out << "\n";
  }

  const std::string path = arguments.get("--output");
  if (path.empty()) {
    std::cout << out.str();
    return 0;
  }
  std::ofstream file(path);
  file << out.str();
  file.close();
  if (!file) throw InputError("cannot write " + path);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(std::vector<std::string>(argv + 1, argv + argc));
  } catch (const InputError& error) {
    std::cerr << "make_synthetic_data: error: " << error.what() << "\n";
    return kExitUsage;
  } catch (const std::exception& error) {
    std::cerr << "make_synthetic_data: numerical failure: " << error.what() << "\n";
    return kExitNumerical;
  }
}
