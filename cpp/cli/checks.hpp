// Checks of the CLI that need the physics (solver, model): what the support layer cannot know.
// Each refuses with InputError naming the options at fault, before any long computation, or
// returns warnings for the header. Kept apart from the commands so the library below can
// move without touching them.
#pragma once
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "coatcontact/adhesion.hpp"
#include "coatcontact/contact.hpp"
#include "coatcontact/limits.hpp"
#include "coatcontact/maugis_dugdale.hpp"
#include "coatcontact/reduced.hpp"
#include "coatcontact/shape_contact.hpp"

namespace coatcontact::cli {

// CPU seconds of the calling thread. The plans time their sample solves with it, not with the
// wall clock, so a loaded machine (make -j, CI) does not inflate an estimate into a refusal.
double thread_cpu_seconds();

// Work estimate of a table of reduced variables over [a_over_t_min, a_over_t_max]: solves once
// at each end at `tolerance`. A tolerance the solver cannot reach there, or a run estimated
// above kMaxWorkSeconds, is refused naming `options` (e.g. "--tol 1e-13 with --eta 1e-06");
// otherwise the estimate (seconds) is given to the progress line and returned.
constexpr double kMaxWorkSeconds = 1800.0;
// With `points_may_fail` (an array whose points are delivered one by one, cli_support.hpp:
// report_not_delivered) one end the solver cannot serve is not refused (its points will be
// flagged, and its time counts in the estimate); both ends are, as without.
double plan_table_work(const ReducedSolver& solver, double tolerance, double a_over_t_min,
                       double a_over_t_max, const std::string& options, bool points_may_fail = false);

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

// Default contact radii of `contact` (log-spaced, `points` of them): [lo, hi] of the shape's
// default range, with hi lowered, as for `sphere`, to the largest radius at which the curve is
// still inside every validity limit (scanned at 16 points per decade; kept as given when even lo
// is outside: the warnings then say so), but never below `reach` (the pull-off's radius).
std::vector<double> contact_default_radii(const ShapeContact& contact, double lo, double hi, double reach,
                                          std::size_t points, double sphere_radius);

// The homogeneous JKR reference of a rigid sphere (THEORY.md section 5, the homogeneous
// solid: the film's half-space, reference modulus E*): a(F), delta(a) at `points` radii
// log-spaced over [a_min, a_max], and its pull-offs -3/2 pi w R (load control) and
// -5/6 pi w R (displacement control).
struct JkrReference {
  std::vector<double> a, delta, force;
  double pulloff_load = 0.0, pulloff_disp = 0.0;
};
JkrReference jkr_reference(double modulus, double radius, double work, double a_min, double a_max,
                           std::size_t points);
// The same over the range of `radii` (not empty).
JkrReference jkr_reference(double modulus, double radius, double work, const std::vector<double>& radii,
                           std::size_t points);
// Its header item, printed beside every coated sphere's pull-offs.
std::pair<std::string, std::string> jkr_reference_header(const JkrReference& jkr);

// `fit`: --columns against a "# columns:" line of the data file (the start values are checked by
// the fit library, fit::check_start).
void check_fit_columns(const std::string& columns, const std::vector<std::string>& declared, int declared_line,
                       const std::string& data_path);

// A pull-off scan's warning (in a_bar, as the normalized commands print it) in the units of an
// SI run: `eta=..: ` dropped (the header gives eta), "a_bar [lo, hi]" and "a_bar=v" as contact
// radii in m (a_bar = a/length) with the reduced value in parentheses (issue 40 item 8).
std::string si_pulloff_warning(const std::string& warning, double length);

}  // namespace coatcontact::cli
