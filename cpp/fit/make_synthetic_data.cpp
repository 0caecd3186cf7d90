// make_synthetic_data: writes a synthetic adhesive sphere-contact data set (a,F or delta,F, a
// loading and an unloading branch) from known parameters, with Gaussian noise of a stated
// standard deviation on the force only (GSL mt19937 generator, fixed seed: reproducible).
// The model values are computed directly from the ReducedSolver at each contact radius
// (THEORY.md section 5, [selfconsistenceInhom], [EqPenetrationCS], [EqForceCS]), with no
// interpolation, independently of the fit library's lattice. Used by scripts/make_example_data.sh.
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "coatcontact/cli_support.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/reduced.hpp"

namespace {

using namespace coatcontact;
using namespace coatcontact::cli;

struct Point {
  double a, delta, force;
};

// Exact model at each contact radius (one solver sweep).
std::vector<Point> exact_points(const ReducedSolver& solver, const std::vector<double>& radii, double R,
                                double t, double w, double tolerance) {
  std::vector<double> a_over_t;
  for (double a : radii) a_over_t.push_back(a / t);
  const std::vector<ReducedVariables> v = solver.sweep(a_over_t, tolerance);
  const double E = solver.stack().reference_modulus();
  std::vector<Point> out;
  for (std::size_t i = 0; i < radii.size(); ++i) {
    const double a = radii[i];
    const double delta_fp = -std::sqrt(2.0 * M_PI * a * w / E) / v[i].gamma1;
    const double force = a * a * a * E / (2.0 * R) * v[i].pi_s + 2.0 * a * E * v[i].e_eq * delta_fp;
    const double delta = a * a / R * v[i].delta_s + delta_fp;
    out.push_back({a, delta, force});
  }
  return out;
}

std::vector<double> linspace(double from, double to, int count) {
  std::vector<double> out;
  for (int i = 0; i < count; ++i) out.push_back(from + (to - from) * i / (count - 1));
  return out;
}

int run(const std::vector<std::string>& args) {
  const std::vector<OptionSpec> spec = {
      {"--kind", "a,F|delta,F", "data columns to write", true},
      {"--radius", "R", "sphere radius (default 5mm)"},
      {"--film", "E1,nu1", "film modulus and Poisson ratio (default 1MPa,0.49)"},
      {"--substrate", "E0,nu0|rigid", "substrate (default 70GPa,0.22)"},
      {"--thickness", "t", "film thickness (default 50um)"},
      {"--work", "w", "adhesion energy (default 40mJ/m2)"},
      {"--noise", "sigma", "standard deviation of the Gaussian force noise (default 10uN)"},
      {"--seed", "N", "seed of the GSL mt19937 generator (default 1)"},
      {"--points", "N", "points per branch (default 40)"},
      {"--max-over-pulloff", "f", "a_max / a at zero force on loading (default 1.5)"},
      {"--signal", "model|none", "none: F is pure noise (for tests of failing fits; default model)"},
      {"--output", "FILE", "output file (default stdout)"},
  };
  Arguments arguments(args, spec);
  if (arguments.help()) {
    std::cout << usage("make_synthetic_data", "make_synthetic_data --kind a,F|delta,F [options]",
                       "Synthetic adhesive sphere-contact data with Gaussian force noise.", spec);
    return 0;
  }
  const std::string kind = arguments.require("--kind");
  if (kind != "a,F" && kind != "delta,F") {
    throw InputError("--kind: '" + kind + "' is not allowed (a,F or delta,F)");
  }
  const bool radius_data = kind == "a,F";
  const double R = parse_quantity(arguments.get("--radius").value_or("5mm"), Quantity::kLength, "--radius");
  const Material film = parse_material(arguments.get("--film").value_or("1MPa,0.49"), "--film");
  const Substrate substrate =
      parse_substrate(arguments.get("--substrate").value_or("70GPa,0.22"), "--substrate");
  const double t = parse_quantity(arguments.get("--thickness").value_or("50um"), Quantity::kLength, "--thickness");
  const double w = parse_quantity(arguments.get("--work").value_or("40mJ/m2"), Quantity::kEnergy, "--work");
  const double sigma = parse_quantity(arguments.get("--noise").value_or("10uN"), Quantity::kForce, "--noise");
  const double seed_value = parse_number(arguments.get("--seed").value_or("1"), "--seed");
  const double points_value = parse_number(arguments.get("--points").value_or("40"), "--points");
  const double max_factor = parse_number(arguments.get("--max-over-pulloff").value_or("1.5"), "--max-over-pulloff");
  if (seed_value < 0 || seed_value != std::floor(seed_value) || seed_value > 4e9) {
    throw InputError("--seed: must be an integer in [0, 4e9]");
  }
  if (points_value < 3 || points_value != std::floor(points_value) || points_value > 100000) {
    throw InputError("--points: must be an integer in [3, 100000]");
  }
  if (!(max_factor > 1.0 && max_factor < 100.0)) throw InputError("--max-over-pulloff: must be in (1, 100)");
  const std::string signal = arguments.get("--signal").value_or("model");
  if (signal != "model" && signal != "none") throw InputError("--signal: '" + signal + "' is not allowed (model or none)");
  const bool pure_noise = signal == "none";
  const int points = static_cast<int>(points_value);
  const unsigned long seed = static_cast<unsigned long>(seed_value);
  const double tolerance = 1e-9;  // the kernel table limits the solver to ~1e-10

  const ReducedSolver solver(Stack::film_on(film, substrate));
  const double E = film.reduced_modulus();
  // Locate the turning points on a dense exact curve (they only set the sampled range):
  // a0 where F = 0 on the stable branch (jump into contact), the load-controlled pull-off
  // (minimum of F) and the displacement-controlled pull-off (minimum of delta).
  const double length = std::cbrt(M_PI * w * R * R / E);  // Maugis length with E1*
  std::vector<double> dense;
  for (int i = 0; i <= 400; ++i) dense.push_back(1e-3 * length * std::pow(1e4, i / 400.0));
  const std::vector<Point> curve = exact_points(solver, dense, R, t, w, 1e-8);
  std::size_t i_fmin = 0;
  std::size_t i_dmin = 0;
  for (std::size_t i = 0; i < curve.size(); ++i) {
    if (curve[i].force < curve[i_fmin].force) i_fmin = i;
    if (curve[i].delta < curve[i_dmin].delta) i_dmin = i;
  }
  std::size_t i_zero = i_fmin;
  while (i_zero < curve.size() && curve[i_zero].force < 0.0) ++i_zero;
  if (i_fmin == 0 || i_dmin == 0 || i_zero >= curve.size()) {
    throw NumericalError("could not locate the pull-off points on the model curve");
  }
  const double a_zero = curve[i_zero].a;
  const double a_max = max_factor * a_zero;
  // Loading from the jump-in radius to a_max; unloading back to just above the pull-off
  // (load control for a,F, displacement control for delta,F), on a grid offset by half a
  // step so the two branches sample different radii.
  const double a_end = 1.02 * (radius_data ? curve[i_fmin].a : curve[i_dmin].a);
  std::vector<double> radii = linspace(a_zero, a_max, points);
  const double step = (a_max - a_end) / (points - 0.5);
  for (int i = 0; i < points; ++i) radii.push_back(a_max - (i + 0.5) * step);
  const std::vector<Point> data = exact_points(solver, radii, R, t, w, tolerance);

  std::unique_ptr<gsl_rng, void (*)(gsl_rng*)> rng(gsl_rng_alloc(gsl_rng_mt19937), gsl_rng_free);
  gsl_rng_set(rng.get(), seed);

  Output output(arguments.get("--output").value_or(""));
  std::ostream& out = output.stream();
  std::string command = "make_synthetic_data";
  for (const auto& a : args) command += " " + a;
  out << "# Synthetic adhesive sphere-contact data (coatcontact, issue 6; see data/README.md)\n"
      << "# generated by: " << command << "\n"
      << "# model: exact coated-substrate JKR curve (THEORY.md section 5), reduced variables solved\n"
      << "#   directly at each a/t by ReducedSolver (tolerance " << tolerance << "), no interpolation\n";
  char line[256];
  std::snprintf(line, sizeof line, "# sphere radius R = %.15g m\n", R);
  out << line;
  std::snprintf(line, sizeof line, "# film: t = %.15g m, E1 = %.15g Pa, nu1 = %.15g\n", t,
                film.youngs_modulus, film.poisson_ratio);
  out << line;
  if (substrate.rigid) {
    out << "# substrate: rigid\n";
  } else {
    std::snprintf(line, sizeof line, "# substrate: E0 = %.15g Pa, nu0 = %.15g\n",
                  substrate.material.youngs_modulus, substrate.material.poisson_ratio);
    out << line;
  }
  std::snprintf(line, sizeof line, "# adhesion energy w = %.15g J/m2\n", w);
  out << line;
  std::snprintf(line, sizeof line,
                "# noise: Gaussian, standard deviation %.15g N, added to F only (%s exact); "
                "GSL gsl_rng_mt19937, seed %lu, gsl_ran_gaussian, one draw per row in file order\n",
                sigma, radius_data ? "a" : "delta", seed);
  out << line;
  std::snprintf(line, sizeof line,
                "# rows: %d loading (a increasing from F = 0 to a_max = %.6g m), then %d unloading "
                "(a decreasing to 1.02 x the %s pull-off radius)\n",
                points, a_max, points, radius_data ? "load-controlled" : "displacement-controlled");
  out << line;
  if (pure_noise) out << "# signal: none -- F is pure noise (the model force is NOT added)\n";
  out << (radius_data ? "# columns: a\tF\n# units: um mN\n" : "# columns: delta\tF\n# units: um mN\n");
  for (const Point& p : data) {
    const double noisy = (pure_noise ? 0.0 : p.force) + gsl_ran_gaussian(rng.get(), sigma);
    out << format_value((radius_data ? p.a : p.delta) * 1e6, "x") << "\t" << format_value(noisy * 1e3, "F")
        << "\n";
  }
  output.commit();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  return run_guarded("make_synthetic_data", [&] { return run(args); });
}
