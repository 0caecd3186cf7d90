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
#include "coatcontact/limits.hpp"
#include "coatcontact/maugis_dugdale.hpp"
#include "coatcontact/reduced.hpp"

namespace coatcontact::cli {

// Work estimate of a table of reduced variables over [a_over_t_min, a_over_t_max]: solves once
// at each end at `tolerance`. A tolerance the solver cannot reach there, or a run estimated
// above kMaxWorkSeconds, is refused naming `options` (e.g. "--tol 1e-13 with --eta 1e-06");
// otherwise the estimate (seconds) is given to the progress line and returned.
constexpr double kMaxWorkSeconds = 1800.0;
double plan_table_work(const ReducedSolver& solver, double tolerance, double a_over_t_min,
                       double a_over_t_max, const std::string& options);

// Work estimate of Maugis-Dugdale solves (one per contact radius): times one point at
// (eta, lambda, a_bar) and refuses, naming `options`, `evaluations` such points estimated
// above kMaxWorkSeconds (divided among the threads when they run in parallel).
void plan_md_work(const MaugisDugdaleModel& md, double eta, double lambda, double a_bar, double evaluations,
                  bool parallel, const std::string& options);
// Point evaluations of one Maugis-Dugdale pull-off (the log scan and the refinement of its minima).
constexpr double kMdPulloffEvaluations = 100.0;

// Default contact radii of `sphere` (a_bar, log-spaced, `points` of them): [lo, hi], with hi
// lowered to the largest a_bar at which the curve is still inside every validity limit
// (limits.hpp; kept as given when even lo is outside: the warnings then say so), but never
// below `reach` (the pull-off's a_bar, so the curve reaches the pull-off it reports).
std::vector<double> sphere_default_a_bar(const AdhesiveModel& model, const Contact& sphere, double lo, double hi,
                                         double reach, std::size_t points);

// `fit` start values against the fit's own parameter ranges (w in [1e-9, 1e4] J/m2, E1 in
// [1e-2, 1e13] Pa, a/t of a,F data in [1e-5, 1e5]: the bounds of cpp/fit/fit.cpp), and
// --columns against a "# columns:" line of the data file. `*_option` names where each value
// came from ("--start w", "--work", ...).
struct FitStart {
  std::string columns;                      // --columns as given
  std::vector<std::string> declared_columns;
  int declared_line = 0;
  std::string data_path;
  bool radius_data = true;
  std::vector<double> radii;                // a [m] of a,F data
  double work = 0.0, thickness = 0.0, film_modulus = 0.0;
  std::string work_option, thickness_option, modulus_option;
};
void check_fit_start(const FitStart& start);

}  // namespace coatcontact::cli
