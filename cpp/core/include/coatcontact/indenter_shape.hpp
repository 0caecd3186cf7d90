// Axisymmetric indenters in physical units (THEORY.md sections 2 and 11): each is its
// δ0(r) = r ∫_0^r z'(s) ds / sqrt(r² - s²) [EqDelta0], the adhesionless right-hand side
// θ = -δ0(r) of the integral equation. The solver (coatcontact/shape_solver.hpp) turns one
// into E_eq, Γ(1), Π, Δ at a contact radius; coatcontact/shape_contact.hpp adds adhesion.
#pragma once
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace coatcontact {

class IndenterShape {
 public:
  virtual ~IndenterShape() = default;
  // δ0(r) [m] for 0 <= r <= max_contact_radius().
  virtual double delta0(double r) const = 0;
  // θ extends evenly and smoothly through r = 0 (paraboloid, even integer powers, spherical
  // cap); else only reciprocity is used at the apex (section 11).
  virtual bool smooth_at_apex() const = 0;
  // Radii > 0 where δ0 is not smooth (the blunted cone's tangent point, a profile's knots).
  virtual std::vector<double> kinks() const { return {}; }
  // Graded halvings toward each kink in the solver's product integrals.
  virtual int kink_grading_levels() const { return 48; }
  // A flat punch (δ0 = 0): the contact radius is fixed to max_contact_radius().
  virtual bool flat() const { return false; }
  virtual double max_contact_radius() const { return std::numeric_limits<double>::infinity(); }
  // Relative interpolation error estimate of δ0 (a measured profile), 0 for closed forms.
  virtual double interpolation_error() const { return 0.0; }
  // One line for output headers, e.g. "power law z = r^3/(3 R^2), R = 1e-05 m".
  virtual std::string description() const = 0;
};

// Each factory throws InputError naming the parameter and its allowed range.
// Paraboloid z = r²/(2R): δ0 = r²/R.
std::shared_ptr<const IndenterShape> make_paraboloid(double radius);
// Cone of half included angle beta (radians, in (0, π/2)): δ0 = (π/2) r cot(beta).
std::shared_ptr<const IndenterShape> make_cone(double beta);
// Four-sided pyramid of face half angle theta (radians, in (0, π/2)) as the cone of equal area,
// tan(beta) = 2 tan(theta)/√π.
std::shared_ptr<const IndenterShape> make_pyramid(double face_half_angle);
// Flat punch of radius `radius`.
std::shared_ptr<const IndenterShape> make_flat_punch(double radius);
// Power law z = r^n/(n R^(n-1)), n > 0: δ0 = c_n r^n/R^(n-1), c_n = (√π/2) Γ(n/2)/Γ((n+1)/2).
std::shared_ptr<const IndenterShape> make_power_law(double n, double radius);
// Spherical cap of radius R tangent to a cone of half included angle beta at b = R cos(beta).
std::shared_ptr<const IndenterShape> make_blunted_cone(double radius, double beta);
// Measured profile z(r): r strictly increasing from r = 0, z non-decreasing, >= 5 points.
// Interpolated by a cubic spline clamped with z'(0) = 0 (and z' at the end from the cubic
// through the last four points), δ0 integrated exactly piece by piece; the error estimate
// compares with the spline of every other point (error ≈ difference/7; measured on a sphere
// cap: O(h³) relative to δ0(r_max), O(h²) pointwise near the apex, where δ0 ~ r²).
// `source` and `lines` (1-based line of each point, may be empty) name bad points in messages.
std::shared_ptr<const IndenterShape> make_measured_profile(const std::vector<double>& r,
                                                           const std::vector<double>& z,
                                                           const std::string& source,
                                                           const std::vector<int>& lines = {});

// Homogeneous half-space closed forms (Sneddon; THEORY.md section 11), for checks:
// c_n of the power law, and F/E* of the blunted cone at contact radius a.
double power_law_coefficient(double n);
double blunted_cone_force_over_modulus(double radius, double beta, double a);

}  // namespace coatcontact
