// Checks of the CLI that need the physics (solver, model): what the support layer cannot know.
// Each refuses with InputError naming the options at fault, before any long computation, or
// returns warnings for the header. Kept apart from the commands so the library below can
// move without touching them.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "coatcontact/adhesion.hpp"
#include "coatcontact/contact.hpp"
#include "coatcontact/reduced.hpp"

namespace coatcontact::cli {

// Work estimate of a table of reduced variables over [a_over_t_min, a_over_t_max]: solves once
// at each end at `tolerance`. A tolerance the solver cannot reach there, or a run estimated
// above kMaxWorkSeconds, is refused naming `options` (e.g. "--tol 1e-13 with --eta 1e-06");
// otherwise the estimate (seconds) is given to the progress line and returned.
constexpr double kMaxWorkSeconds = 1800.0;
double plan_table_work(const ReducedSolver& solver, double tolerance, double a_over_t_min,
                       double a_over_t_max, const std::string& options);

// `sphere`: the limits of the model in physical units.
struct SphereLimits {
  double radius = 0.0;                 // R [m]: paraboloid approximation needs a <= 0.1 R
  double thickness = 0.0;              // t [m]: penetration beyond t leaves the film
  double film_reduced_modulus = 0.0;   // E1* [Pa]: mean pressure near E1* is not linear elastic
};
constexpr double kMaxContactRadiusOverR = 0.1;
constexpr double kMaxPressureOverModulus = 0.1;

// Default contact radii of `sphere` (a_bar, log-spaced, `points` of them): [lo, hi], with hi
// lowered to the largest a_bar at which the curve is still inside every SphereLimits limit
// (kept as given when even lo is outside; the warnings then say so).
std::vector<double> sphere_default_a_bar(const AdhesiveModel& model, const Contact& sphere,
                                         const SphereLimits& limits, double lo, double hi,
                                         std::size_t points);

// One message per limit that the curve (SI: a [m], delta [m], F [N]) exceeds.
std::vector<std::string> sphere_physics_warnings(const std::vector<double>& a, const std::vector<double>& delta,
                                                 const std::vector<double>& force, const SphereLimits& limits);

// `fit`: --columns against a "# columns:" line of the data file (the start values are checked by
// the fit library, fit::check_start).
void check_fit_columns(const std::string& columns, const std::vector<std::string>& declared, int declared_line,
                       const std::string& data_path);

}  // namespace coatcontact::cli
