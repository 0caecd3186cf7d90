// Fit of the crack-kinetics law (THEORY.md section 14, fitting) to force-time curves measured at
// several retract speeds: the adhesion energy w, the receding law's v* and n, and optionally
// the film thickness t and the film's Young modulus E1, from F(t) of each curve and the protocol (segments, spring) that drove
// it. The model of each curve is the kinetics simulation (simulate_kinetics_si) of its
// protocol; the residual is F_model(t_i) - F_i at the measured times (t = 0 at first contact),
// minimised over ln p (gsl_multifit_nlinear), Jacobian by central differences in ln p.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "coatcontact/crack_kinetics.hpp"
#include "coatcontact/fit.hpp"
#include "coatcontact/stack.hpp"

namespace coatcontact::fit {

// One measured curve and the protocol that produced it.
struct KineticsCurve {
  std::vector<KineticsSegmentSI> protocol;  // approach / dwell / retract (SI, as simulate_kinetics_si)
  double spring = 0.0;                      // N/m; 0 load control, +inf displacement control
  std::vector<double> time;                 // s since first contact, increasing
  std::vector<double> force;                // N, compressive positive
  std::vector<double> sigma_force;          // N per point, or empty (unweighted fit)
};

// Parameter order of the fit: w, v_star, n, t, E1 (the top layer's Young modulus).
enum KineticsParameter : int {
  kKinWork = 0,
  kKinSpeed = 1,
  kKinExponent = 2,
  kKinThickness = 3,
  kKinFilmModulus = 4
};
constexpr int kKineticsParameterCount = 5;
const char* kinetics_parameter_name(int parameter);  // "w", "v_star", "n", "t", "E1"

struct KineticsFitProblem {
  double radius = 0.0;     // R [m]
  double thickness = 0.0;  // t [m] (hint if free)
  double work = 0.0;       // w [J/m2] (hint if free)
  double v_star = 0.0;     // m/s (hint if free)
  double n = 0.0;          // receding exponent (hint if free)
  // E1 [Pa] of the top layer (hint if free); <= 0: the stack's. Each value of E1 has a JKR table
  // of its own (built per trial value; the current one and the Jacobian's neighbours are kept).
  double film_modulus = 0.0;
  // The advancing law: <= 0 follows the receding value (then it moves with the fitted v*, n).
  double v_star_adv = 0.0, n_adv = 0.0;
  std::array<bool, kKineticsParameterCount> free{{true, true, true, false, false}};
  double solver_tolerance = kDefaultAdhesiveTolerance;  // of the JKR table
  KineticsOptions options;                              // of the ODE integration
  int max_iterations = 100;
};

// Fitted values, standard errors, correlations, R^2, chi2 (Result's fields; parameters are the
// five of KineticsParameter). The residual is each curve's points up to its measured pull-off
// (its most tensile force); model_force and residual are given for every point of the curves in
// order, and `clamped` marks the points after a pull-off, which are not in the residual;
// `points` counts the fitted ones, solver_calls the kinetics simulations.
// InputError: a bad curve or protocol (named by its index), fewer points than free parameters,
// v_star and n both free with one retract speed only (one speed determines only the rate
// factor (v/v*)^n of that speed, section 14, fitting). NumericalError: no convergence, or parameters
// the data do not determine.
Result fit_kinetics(const Stack& stack, const std::vector<KineticsCurve>& curves, const KineticsFitProblem& problem);
// The same on the JKR table of an existing model of the stack (its solver tolerance is the
// model's; the table, built lazily, is kept for the next fit). With E1 free, every other value
// of E1 gets a model of its own at the same tolerance.
Result fit_kinetics(const AdhesiveModel& model, const std::vector<KineticsCurve>& curves,
                    const KineticsFitProblem& problem);

}  // namespace coatcontact::fit
