// Adhesionless fit of one AFM force-curve segment (THEORY.md section 15): the Hertz/Sneddon
// force of a rigid axisymmetric tip on a homogeneous half-space, with the contact point z_c on
// the tip-position axis and a force baseline b,
//   F(z) = b + E* g(delta),   delta = max(0, z_c - z),   E* = E/(1 - nu^2),
// g(delta) = F/E* of the tip at penetration delta (§11: 2[a delta0(a) - int_0^a delta0]).
// The tip-position axis decreases toward the sample (coatcontact/force_curve.hpp), so the tip
// indents the sample where z < z_c.
// At fixed z_c the model is linear in (b, E*): both are solved in closed form, and z_c is
// found by profiling that residual sum over the whole fitted range (a grid, then Brent on
// the bracket of each of the best grid minima), so the result is the global optimum, not the
// nearest local one. The data arrays are plain SI numbers (the fit floor does not read files).
#pragma once
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "coatcontact/indenter_shape.hpp"
#include "coatcontact/stack.hpp"

namespace coatcontact::fit {

// The tip: closed forms for the paraboloid (radius R) and the cone (half angle beta), and any
// IndenterShape through a table of g(delta) (Sneddon's integral, monotone interpolation).
struct AfmTip {
  enum class Kind { kParaboloid, kCone, kShape, kSneddonSphere };
  Kind kind = Kind::kParaboloid;
  double radius = 0.0;  // R [m] (paraboloid, Sneddon's sphere)
  double angle = 0.0;   // beta [rad], half included angle (cone)
  std::shared_ptr<const IndenterShape> shape;  // kShape
  std::string description;                     // one line for headers
};
AfmTip afm_paraboloid(double radius);
AfmTip afm_cone(double half_angle);
// Four-sided pyramid of face half angle theta (between face and axis) as the cone of equal
// cross-section area: pi (delta tan beta)^2 = 4 (delta tan theta)^2, tan beta = 2 tan theta/sqrt(pi).
AfmTip afm_pyramid(double face_half_angle);
// Three-sided pyramid of face angle theta with nanite's hertz_pyr3s law (Bilodeau 1992),
// F = 0.8887 tan(theta) E* delta^2: the cone with tan beta = (pi/2) 0.8887 tan theta.
AfmTip afm_pyramid3(double face_angle);
// The exact sphere of radius R (Sneddon 1965; nanite's sneddon_spher), through the contact
// radius a < R: delta = (a/2) ln((R+a)/(R-a)), F = E* [(R^2+a^2)/2 ln((R+a)/(R-a)) - a R];
// dF/d delta = 2 a E*. Past a = (1 - 1e-8) R (delta ~ 9.5 R) the sphere's equator: a punch of radius R.
AfmTip afm_sneddon_sphere(double radius);
AfmTip afm_shape(std::shared_ptr<const IndenterShape> shape);

// Which of E (the half-space's, or the film's E1), t (a coating's thickness), z_c and b are free
// (the others keep the values of AfmFitProblem).
struct AfmFree {
  bool modulus = true, contact_point = true, baseline = true;
  bool thickness = false;
  bool work = false;  // w of the adhesive (JKR) model
  bool tilt = false;  // a baseline slope m (either model): F += m (z - z_c)
};

// The tip force: adhesionless Hertz/Sneddon, or JKR (a sphere on the half-space or the coating)
// on the branch stable under the cantilever's spring k, zero past its jump-off (THEORY.md
// section 15, "Adhesive retract"): at contact radius a,
//   delta = delta_H(a) - sqrt(2 pi a w/E1*)/Gamma1,  F = F_H(a) - 2 a E1* E_eq sqrt(2 pi a w/E1*)/Gamma1
// for a >= a_s, the minimum of delta + F/k; below delta(a_s) the tip is off the sample. Or
// Maugis-Dugdale (kMd): the same through the cohesive-zone table, sigma0 = w/h0 with
// h0 = kDugdaleRangeOverZ0 z0 (surface_force_range), so lambda follows w and E1; the jump-off
// may be the curve's end a -> 0 (THEORY.md section 15). Or DMT (kDmt): the adhesionless
// contact less 2 pi w R while in contact, delta = delta_H(a), F = F_H(a) - 2 pi w R; through
// any spring the jump-off is the curve's end (delta, F) = (0, -2 pi w R).
// The model is named (coatcontact/afm_models.hpp: its parameter table, fit and force, one file
// each, listed in the registry); AfmModel is that name. kHertz ... kDmt name the built-in ones.
struct AfmModelInfo;
class AfmModel {
 public:
  constexpr AfmModel() = default;  // Hertz/Sneddon
  // `name`: a string that outlives the AfmModel (a literal, or AfmModelInfo::name).
  constexpr explicit AfmModel(const char* name) : name_(name) {}
  static const AfmModel kHertz, kJkr, kMd, kDmt;
  const char* name() const { return name_; }
  // The registry's entry (afm_model_by_name); InputError for a name it does not hold.
  const AfmModelInfo& info() const;
  friend bool operator==(AfmModel a, AfmModel b) { return std::string_view(a.name_) == std::string_view(b.name_); }
  friend bool operator!=(AfmModel a, AfmModel b) { return !(a == b); }

 private:
  const char* name_ = "hertz";
};
inline constexpr AfmModel AfmModel::kHertz{"hertz"};
inline constexpr AfmModel AfmModel::kJkr{"jkr"};
inline constexpr AfmModel AfmModel::kMd{"md"};
inline constexpr AfmModel AfmModel::kDmt{"dmt"};

// A coating instead of the half-space: film (E1 the value if fixed, else the centre of its
// search; nu1 fixed) of thickness t on a fixed substrate, adhesionless (THEORY.md sections 5
// and 14): the sphere's F_H = (a^3 E1*/(2R)) Pi_s(a/t), delta_H = (a^2/R) Delta_s(a/t), the
// cone's likewise with Pi_c, Delta_c, from the reduced solver swept over a/t in
// [kCoatingAOverT] (kCoatingPerDecade points per decade) and interpolated in log-log; below
// the sweep the film's own power law, past it (trial contact points of the search only) the
// power law of its last two nodes; the final fit must lie inside the sweep. Tips: paraboloid, cone, pyramid.
// A multi-layer sample (a cell on a gel on glass; THEORY.md sections 12 and 15): `layers`, top
// first, each with its thickness [m], material and bonding; layer `free_layer` is the one whose
// modulus the fit may free, and its material and thickness are `film` and `thickness` (its
// entry in `layers` only gives its bonding). Empty `layers`: the one film of thickness t. The
// Hertz model reads a multi-layer stack from the tabled force law of that layer's modulus
// (CoatedTable); the length of a/t is then the stack's total thickness T and the force's scale
// the top layer's E*. The thickness is free on one film only, the adhesive models take one film.
struct AfmCoating {
  Material film;           // the free layer's material (the film's with one layer)
  Substrate substrate;
  double thickness = 0.0;  // t [m] of the free layer (value if fixed, else the centre of its search)
  std::vector<Layer> layers;
  std::size_t free_layer = 0;
  bool multilayer() const { return layers.size() > 1; }
  // The free modulus as --free, the columns and the messages name it: E<free_layer + 1> (one film: E1).
  std::string free_modulus_name() const { return "E" + std::to_string(free_layer + 1); }
  // The sample with the free layer's modulus E and thickness t (one film: Stack::film_on).
  Stack stack_with(double modulus, double t) const;
  Stack stack() const { return stack_with(film.youngs_modulus, thickness); }
  // The length of a/t: T with the free layer's thickness t (one film: t itself).
  double total_thickness(double t) const;
  // The top layer's E* with the free layer's modulus E: the scale of the reduced force.
  double reference_modulus(double modulus) const;
  double solver_tolerance = 1e-8;
  // false: the Hertz model reads every trial E1 from the process's shared tabled force law
  // (THEORY.md section 15, "Tabled coated force laws"); true: a reduced-solver sweep per trial
  // E1 (the direct path, kept for comparison). The JKR model likewise: false, E1 between its
  // nodes interpolated; true, a sweep at every trial E1.
  bool direct = false;
};
// The sample `stack` with layer `free_layer`'s modulus (the fit's E<free_layer + 1>) free;
// InputError naming the allowed layers when free_layer is out of range. One layer: film, t.
// A stack's solves ask kStackSolverTolerance (its kernel tables are not good to 1e-8 near a/T = 1e2).
AfmCoating afm_coating(const Stack& stack, std::size_t free_layer);
constexpr double kStackSolverTolerance = 1e-7;
constexpr double kCoatingAOverT[2] = {1e-2, 1e2};
constexpr double kCoatingPerDecade = 16.0;
// Free E1 and t are searched on a log grid within this factor of their given values
// (kSearchPointsPerDecade per decade), then Brent.
constexpr double kCoatingSearchFactor = 10.0;
constexpr double kCoatingSearchPointsPerDecade = 4.0;

struct AfmFitProblem {
  AfmTip tip;
  double modulus = 0.0;         // E [Pa] of the half-space (value if fixed; unused if free)
  double poisson = 0.5;         // nu
  double contact_point = 0.0;   // z_c [m] (value if fixed)
  double baseline = 0.0;        // b [N] (value if fixed)
  AfmFree free;
  std::optional<AfmCoating> coating;  // none: the homogeneous half-space (modulus, poisson)
  AfmModel model = AfmModel::kHertz;
  // JKR: w [J/m2] (the value if fixed; if free, the centre of its search, 0: from the data's
  // most tensile force), the cantilever's spring constant k [N/m] (> 0), the surface-force
  // range z0 [m] of Tabor's/Maugis's lambda, the baseline slope m [N/m] (value if fixed).
  double work = 0.0;
  double spring_constant = 0.0;
  double surface_force_range = 0.3e-9;
  double tilt = 0.0;
  // Grid of the contact-point profile over [z_min, z_max + kContactBeyond (z_max - z_min)]
  // of the fitted points (z_c may lie beyond the last point out of contact).
  std::size_t profile_points = 400;
  // Noise of one force value [N] (e.g. the baseline's residual sigma): chi2 = rss/noise^2.
  // 0: no chi2 (the fit is unweighted either way).
  double noise_sigma = 0.0;
  // Contact-point weighting with nanite's definition (weight.weight_cp): every residual times
  // w = min(|z - z_c|/D, 1) at the trial z_c, D = weight_cp [m] (0: none). Adhesionless
  // half-space fits without a free tilt only; the errors use the weighted Jacobian and residuals.
  double weight_cp = 0.0;
};
constexpr double kContactBeyond = 0.25;
// JKR fits search on at most this many points (equal-count bins of a denser curve), then
// polish on every point (THEORY.md section 15).
constexpr std::size_t kAdhesiveSearchPoints = 300;
// Maugis's lambda below which JKR is outside its range (Johnson & Greenwood's map: the
// Maugis-Dugdale model is needed below ~5; a warning).
constexpr double kJkrMinimumLambda = 5.0;
// DMT's range: Maugis's lambda below this (Johnson and Greenwood's adhesion map); above, a warning.
constexpr double kDmtMaximumLambda = 0.1;
// The Dugdale range h0 = w/sigma0 of a surface-force range z0 (Lennard-Jones law matched by
// Johnson & Greenwood 1997): h0 = 0.97 z0. Maugis's lambda of every adhesive fit uses it.
constexpr double kDugdaleRangeOverZ0 = 0.97;
// JKR on a coating with E1 free: reduced-solver sweeps on nodes of E1 this many per decade,
// interpolated (cubic in ln E1) between them.
constexpr double kModulusNodesPerDecade = 8.0;

struct AfmFitResult {
  double modulus = 0.0, contact_point = 0.0, baseline = 0.0;  // estimates (or fixed values)
  double modulus_error = 0.0, contact_point_error = 0.0, baseline_error = 0.0;  // 0 if fixed
  double thickness = 0.0, thickness_error = 0.0;  // t [m] of a coating (0 on a half-space)
  double reduced_modulus = 0.0;  // E* [Pa] (of the film on a coating)
  long solver_calls = 0;         // reduced-variable solves (coating)
  // Adhesive (JKR) fits: w, the baseline slope m [N/m] (about z_ref = tilt_origin), Tabor's
  // mu = (R w^2/(E1*^2 z0^3))^(1/3) and Maugis's lambda (Dugdale stress w/(0.97 z0)) from the
  // estimates, the model's jump-off through the spring (indentation [m], force above the
  // baseline [N]), and warnings (lambda outside JKR's range, a fit at a search bound).
  double work = 0.0, work_error = 0.0;
  double tilt = 0.0, tilt_error = 0.0, tilt_origin = 0.0;
  double tabor_mu = 0.0, maugis_lambda = 0.0;
  double jump_off_indentation = 0.0, jump_off_force = 0.0;
  std::vector<std::string> warnings;
  int model_evaluations = 0;  // adhesive: branch tables built
  std::size_t points = 0, points_in_contact = 0;
  int free_count = 0;
  double rss = 0.0;             // sum of squared residuals [N^2]
  double residual_sigma = 0.0;  // sqrt(rss/(n - p)) [N]
  double chi2 = 0.0;            // rss / residual_sigma^2 = n - p (unweighted: sigma from the residuals)
  double chi2_per_dof = 0.0;
  double r_squared = 0.0;
  double max_indentation = 0.0;  // [m] largest delta of the fitted points
  std::vector<double> model_force, residual, indentation;  // per point (residual = model - data)
  int profile_evaluations = 0;
  double seconds = 0.0;
};

// g(delta) = F/E* of the tip on a half-space at each penetration delta >= 0 [N/Pa].
std::vector<double> afm_force_per_modulus(const AfmTip& tip, const std::vector<double>& penetration);

// JKR on a coating keeps the reduced-solver sweeps of its E1 nodes for the fits that follow
// (the curves of a map share them; results do not depend on it). This drops them (benchmarks of
// a first fit, memory).
void afm_clear_shared_sweeps();

// The model force at tip positions z for E (E1 and t of a coating), z_c, b and the tilt m of `problem`.
std::vector<double> afm_model_force(const AfmFitProblem& problem, const std::vector<double>& tip_position);

// Fits force[i] at tip_position[i]. InputError: fewer points than free parameters + 1,
// non-finite values, bad tip or moduli; NumericalError: no contact in the fitted range
// (E* <= 0 everywhere on the profile) or a singular fit.
AfmFitResult afm_fit(const std::vector<double>& tip_position, const std::vector<double>& force,
                     const AfmFitProblem& problem);

// Fit ranges as the AFM field uses them, combined (a point must pass each one given): tip
// positions [m]; indentation relative to a reference contact point (delta_ref = z_ref - z,
// e.g. [-1e-6, 2e-6], or up to a maximum indentation); forces above a reference baseline up to
// a maximum [N]. The reference contact point and baseline are estimates made before the fit
// (the preprocessing's), so the fitted points do not move with the fitted z_c.
struct AfmRange {
  std::optional<double> tip_min, tip_max;
  std::optional<double> indentation_min, indentation_max;
  std::optional<double> max_force;
  bool any() const { return tip_min || tip_max || indentation_min || indentation_max || max_force; }
};
// Indices of the points inside `range`, in order.
std::vector<std::size_t> afm_select(const std::vector<double>& tip_position, const std::vector<double>& force,
                                    const AfmRange& range, double reference_contact, double reference_baseline);

// The measured pull-off of a retract is the same for every model: afm_measured_pulloff
// (coatcontact/afm_curve_fit.hpp), against the retract's free-cantilever baseline.

}  // namespace coatcontact::fit
