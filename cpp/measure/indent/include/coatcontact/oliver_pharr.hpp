// Oliver–Pharr analysis of one indentation test (THEORY.md section 16): stiffness (CSM channel
// or a power-law fit of the upper unloading), frame compliance, contact depth h_c = h - eps P/S,
// the tip's area function, reduced and sample modulus, hardness, averages over a depth range;
// and the calibration of the area function and the frame stiffness on a reference sample.
// Everything in SI; the area function's coefficients keep the vendors' nm units.
#pragma once
#include <cstddef>
#include <vector>

#include "coatcontact/indentation.hpp"
#include "coatcontact/stack.hpp"

namespace coatcontact::indent {

// A(h_c) [m^2] at contact depth h_c [m] from the vendors' form (indentation.hpp). A contact depth
// <= 0 gives 0. InputError when the function has no coefficients.
double contact_area(const AreaFunction& area, double contact_depth);

// The diamond tip of every vendor's default: E = 1141 GPa, nu = 0.07.
inline Material diamond() { return Material{1141e9, 0.07}; }

enum class StiffnessSource { kAuto, kCsm, kUnloading };  // kAuto: CSM when the test has a channel

struct OliverPharrOptions {
  AreaFunction area;                 // empty: the test's own calibration
  bool area_from_hardness = false;   // A = P/H from the vendor's hardness column instead
  double poisson = kNotGiven;        // the sample's nu; NaN: the test's calibration
  Indenter indenter{false, diamond()};
  double beta = 1.0;                 // E_r = sqrt(pi) S / (2 beta sqrt(A))
  double epsilon = 0.75;             // h_c = h - epsilon P/S
  double frame_stiffness = kNotGiven;  // [N/m] series compliance removed from h and S; NaN: none
  double depth_min = kNotGiven;      // averaging range [m]; NaN: the test's range, else all
  double depth_max = kNotGiven;
  StiffnessSource stiffness = StiffnessSource::kAuto;
  double unload_lower = 0.5;         // quasi-static: fit P in [lower, upper] P_max of the unloading
  double unload_upper = 0.95;
};

// P = alpha (h - h_f)^m over the upper unloading; S = m alpha (h_max - h_f)^(m-1).
struct UnloadingFit {
  double alpha = 0.0, final_depth = 0.0, exponent = 0.0;  // alpha in N/m^m, h_f [m]
  double max_depth = 0.0, max_load = 0.0, stiffness = 0.0;
  double rms_relative = 0.0;  // RMS of (P - fit)/P over the fitted points
  std::size_t points = 0;
};

struct OliverPharrResult {
  bool csm = false;
  // Per analysed point (CSM: the loading points with P, S > 0; quasi-static: the start of the
  // unloading), SI units.
  std::vector<double> depth, load, stiffness, contact_depth, area, contact_radius;
  std::vector<double> reduced_modulus, modulus, hardness;
  std::vector<char> in_range;  // depth within [range_min, range_max]
  double range_min = 0.0, range_max = 0.0;
  std::size_t range_points = 0;
  double modulus_mean = 0.0, modulus_sd = 0.0, hardness_mean = 0.0, hardness_sd = 0.0;
  double poisson = 0.0;
  std::size_t dropped = 0;  // points without a positive h_c, area or sample modulus (first contact)
  UnloadingFit unloading;   // quasi-static only
};

// InputError for a missing Poisson ratio or area function, a bad option (named), or no point
// to analyse; NumericalError when the unloading fit fails. Points with h_c <= 0, A <= 0 or an
// E_r above the indenter's E* (the first contact) are dropped and counted.
OliverPharrResult oliver_pharr(const IndentTest& test, const OliverPharrOptions& options = {});

// The pieces, for callers that hold plain arrays.
UnloadingFit fit_unloading(const std::vector<double>& depth, const std::vector<double>& load,
                           double lower = 0.5, double upper = 0.95);
double reduced_modulus(double stiffness, double area, double beta);
// E from E_r: 1/E_r = (1 - nu^2)/E + (1 - nu_i^2)/E_i; NumericalError if E_r is not below the
// indenter's modulus (the sample would be stiffer than infinitely stiff).
double sample_modulus(double reduced, double poisson, const Indenter& indenter);
double reduced_of_sample(double modulus, double poisson, const Indenter& indenter);

// ---- calibration on a reference sample ---------------------------------------------------

struct CalibrationOptions {
  Material reference{72e9, 0.17};    // fused silica
  Indenter indenter{false, diamond()};
  double beta = 1.0, epsilon = 0.75;
  std::size_t terms = 5;             // C0 .. C(terms-1)
  double fixed_c0 = kNotGiven;       // e.g. 24.5 to hold C0; NaN: fitted
  double depth_min = kNotGiven, depth_max = kNotGiven;  // [m]; NaN: every point
};

struct AreaCalibration {
  AreaFunction area;
  std::vector<double> errors;        // standard errors of the coefficients (0 for a held C0)
  double rms_relative = 0.0;         // RMS of (A_i - A(h_c,i))/A_i
  std::size_t points = 0;
};

// A_i = pi S_i^2 / (4 beta^2 E_r^2) from the reference's known modulus, fitted linearly in the
// coefficients with weights 1/A_i^2 (GSL gsl_multifit_wlinear).
AreaCalibration calibrate_area(const std::vector<IndentTest>& tests, const CalibrationOptions& options);

struct FrameCalibration {
  double compliance = 0.0, compliance_error = 0.0;  // 1/K_f [m/N] and its standard error
  double slope = 0.0;                               // of 1/S against 1/sqrt(P)
  double frame_stiffness = 0.0;                     // 1/compliance (infinite if compliance <= 0)
  std::size_t points = 0;
};

// 1/S = 1/K_f + slope/sqrt(P) (constant hardness), fitted over the CSM points in range (or one
// point per quasi-static test).
FrameCalibration calibrate_frame(const std::vector<IndentTest>& tests, const CalibrationOptions& options);

}  // namespace coatcontact::indent
