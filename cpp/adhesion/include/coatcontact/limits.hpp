// The physical scales and limits of the adhesive contact in SI units, in one place for every
// user (CLI, C API, Python): the Maugis scales (THEORY.md sections 5, 13), the allowed range of
// the Maugis-Dugdale lambda, and the validity limits of a curve (small strain, the paraboloid
// approximation of a sphere, a film the indenter does not pass through). Bad values throw
// InputError naming the quantity, its value and what is allowed; callers prefix their option
// names.
#pragma once
#include <limits>
#include <string>
#include <vector>

namespace coatcontact {

// ---- Maugis scales -----------------------------------------------------------------

// Rigid sphere of radius R on a coating of thickness t, work of adhesion w, reference modulus
// E* (THEORY.md section 5): length l = (pi w R^2/E*)^(1/3), penetration l^2/R, force pi w R,
// eta = t/l. With a Dugdale zone (section 13): sigma0, h0 = w/sigma0 and
// lambda = 2 sigma0 (R/(pi w K^2))^(1/3), K = 4E*/3.
struct MaugisScales {
  double radius = 0.0, thickness = 0.0, work = 0.0, modulus = 0.0;  // R [m], t [m], w [J/m2], E* [Pa]
  double length = 0.0;       // l [m]
  double penetration = 0.0;  // l^2/R [m]
  double force = 0.0;        // pi w R [N]
  double eta = 0.0;          // t/l
  double cohesive_stress = 0.0;                            // sigma0 [Pa] (0: JKR)
  double lambda = std::numeric_limits<double>::infinity();  // inf: JKR
};

// InputError unless R, t, w, E* are finite and > 0, l is a finite positive number and eta lies
// in [kMinimumScaled, kMaximumScaled] of adhesion.hpp ([1e-6, 1e6]).
MaugisScales maugis_scales(double radius, double thickness, double work, double modulus);

// The same with a Dugdale zone of adhesive stress sigma0 [Pa]: sets cohesive_stress and lambda.
// InputError (as check_cohesive_range and check_lambda) for a range h0 = w/sigma0 above
// kMaximumRangeOverThickness t or a lambda outside the allowed range.
MaugisScales maugis_scales(double radius, double thickness, double work, double modulus, double cohesive_stress);

// a_bar = a/l of each contact radius a [m]; InputError unless every a_bar lies in
// [kMinimumScaled, kMaximumScaled] (the range of the normalized curves).
std::vector<double> scaled_contact_radii(const std::vector<double>& a, const MaugisScales& scales);

// lambda from sigma0 [Pa] and back (InputError unless sigma0, resp. lambda, is finite and > 0).
double maugis_lambda(const MaugisScales& scales, double cohesive_stress);
double maugis_cohesive_stress(const MaugisScales& scales, double lambda);

// Allowed Maugis-Dugdale lambda (inf, JKR, is allowed besides). Below 1e-3 the DMT limit holds
// to ~1e-3 in P and the zone reaches ~1e3 contact radii; above 1e4 the curve differs from JKR
// by ~1/lambda^2 < 1e-8, the default tolerance of the reduced variables, so JKR (lambda = inf)
// is the same answer at a fraction of the cost (THEORY.md section 13).
inline constexpr double kMinimumLambda = 1e-3;
inline constexpr double kMaximumLambda = 1e4;
// "[0.001, 10000] or inf"
std::string lambda_range_text();
// InputError "lambda = ... not allowed (need [0.001, 10000] or inf)" unless lambda is in the
// range or +inf. `source` (may be empty) says where the value came from, e.g. "from sigma0 = 5e6 Pa".
void check_lambda(double lambda, const std::string& source = "");

// Largest range h0 = w/sigma0 accepted, in coating thicknesses: beyond it the zone would reach
// 1e6 film thicknesses and the film is irrelevant. InputError naming h0 otherwise.
inline constexpr double kMaximumRangeOverThickness = 1e6;
void check_cohesive_range(double range, double thickness);

// ---- validity limits of a curve in SI units ----------------------------------------

// A curve is linear elastic contact of the given indenter on the film while
//  - the mean pressure F/(pi a^2) stays below kMaxPressureOverModulus E* (small strain),
//  - the penetration delta stays below the coating thickness t (the indenter stays in the film),
//  - for a sphere of radius R (a paraboloid): a <= kMaxContactRadiusOverR R (the paraboloid
//    approximation of the sphere), and a <= R (past R no sphere has that contact radius),
//  - a stays within the shape's own largest radius (a punch, a measured profile).
inline constexpr double kMaxContactRadiusOverR = 0.1;
inline constexpr double kMaxPressureOverModulus = 0.1;

struct ValidityLimits {
  double thickness = 0.0;           // t [m]
  double modulus = 0.0;             // E* [Pa] of the reference (top layer)
  double sphere_radius = 0.0;       // R [m] of a spherical tip (0: not a sphere)
  double max_contact_radius = 0.0;  // the shape's largest radius [m] (0 or inf: none)
};

// Whether one point (a [m], delta [m], F [N]) is inside every limit.
bool within_validity(double a, double delta, double force, const ValidityLimits& limits);

// One message per limit that the curve exceeds (empty when it stays inside), each naming the
// largest value reached and the limit, e.g. "contact radius reaches 0.003 m, above 0.1 R = ...".
std::vector<std::string> validity_warnings(const std::vector<double>& a, const std::vector<double>& delta,
                                           const std::vector<double>& force, const ValidityLimits& limits);

// Contact radii [m] asked of a sphere of radius R so far past R (a > kMaxContactRadiusOverSphere R)
// that the request describes no sphere, nor a paraboloid anyone means: InputError naming the
// largest a and R, before any solve (between 0.1 R and this limit the curve is computed and
// validity_warnings says what it is).
inline constexpr double kMaxContactRadiusOverSphere = 10.0;
void check_sphere_contact_radii(const std::vector<double>& a, double sphere_radius);

}  // namespace coatcontact
