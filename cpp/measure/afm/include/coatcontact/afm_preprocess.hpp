// Preprocessing of an AFM force curve, named steps in a fixed order (each result keeps its
// parameters so that an output header can record them):
//  1. tip position: height (measured, else piezo) + F/k ("vertical tip position");
//  2. baseline: offset and tilt, F = offset + slope * tip, fitted by least squares on the
//     non-contact part of the approach (its first `baseline_fraction` of points in time);
//     every force is corrected by it;
//  3. contact point on the tip-position axis, by one of
//     - deviation: the first approach point after which the corrected force stays above
//       `deviation_sigmas` times the baseline's residual sigma (simple; late by the threshold);
//     - piecewise-fit: least squares of F = 0 before and F = A (z_c - z)^p after the contact
//       point over every approach point past the baseline, z_c scanned over the approach
//       points (robust to noise: it uses all the points, not the first one above a threshold).
//  Either method needs the corrected force to end the approach above the deviation threshold.
#pragma once
#include <cstddef>
#include <vector>

#include "coatcontact/force_curve.hpp"

namespace coatcontact::afm {

enum class ContactPointMethod { kDeviation, kPiecewiseFit };
const char* contact_point_method_name(ContactPointMethod method);  // "deviation", "piecewise-fit"

struct PreprocessOptions {
  double baseline_fraction = 0.5;  // (0, 1): leading part of the approach taken as non-contact
  ContactPointMethod contact_method = ContactPointMethod::kPiecewiseFit;
  double deviation_sigmas = 5.0;    // threshold in residual sigmas of the baseline (both methods)
  double piecewise_exponent = 1.5;  // piecewise-fit: F ~ (z_c - z)^p (1.5: paraboloid, 2: cone)
};

struct PreprocessedCurve {
  std::vector<double> tip_position;     // [m], every point
  std::vector<double> force_corrected;  // [N], force - (offset + slope * tip), every point
  // Step 2.
  double baseline_offset = 0.0;        // [N]
  double baseline_slope = 0.0;         // [N/m]
  double baseline_offset_error = 0.0;  // standard errors from the residuals
  double baseline_slope_error = 0.0;
  double baseline_sigma = 0.0;         // [N], residual standard deviation
  std::size_t baseline_points = 0;
  // Step 3.
  ContactPointMethod contact_method = ContactPointMethod::kPiecewiseFit;
  double contact_point = 0.0;     // [m], tip position
  std::size_t contact_index = 0;  // point index in the curve
};

// InputError (naming the curve's file) when the curve has no approach segment, too few points
// for a baseline, no spring constant, or no contact in its approach.
PreprocessedCurve preprocess(const ForceCurve& curve, const PreprocessOptions& options = {});

}  // namespace coatcontact::afm
