// Preprocessing of a force curve: tip position, baseline offset and tilt, contact point
// (coatcontact/afm_preprocess.hpp). The baseline line is GSL's linear least squares.
#include "coatcontact/afm_preprocess.hpp"

#include <gsl/gsl_fit.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "coatcontact/errors.hpp"

namespace coatcontact::afm {

const char* contact_point_method_name(ContactPointMethod method) {
  switch (method) {
    case ContactPointMethod::kDeviation: return "deviation";
    case ContactPointMethod::kPiecewiseFit: return "piecewise-fit";
  }
  return "unknown";
}

namespace {

constexpr std::size_t kMinBaselinePoints = 10;

// Sum of squares of the piecewise model with contact at approach index c (points [first, end)):
// zero before c, A (z_c - z)^p from c on, A by linear least squares (> 0, else +inf).
double piecewise_cost(const std::vector<double>& z, const std::vector<double>& f, std::size_t first, std::size_t end,
                      std::size_t c, double p) {
  double before = 0.0, fg = 0.0, gg = 0.0, ff = 0.0;
  for (std::size_t i = first; i < c; ++i) before += f[i] * f[i];
  for (std::size_t i = c; i < end; ++i) {
    const double d = z[c] - z[i];
    const double g = d > 0.0 ? (p == 1.5 ? d * std::sqrt(d) : std::pow(d, p)) : 0.0;
    fg += f[i] * g;
    gg += g * g;
    ff += f[i] * f[i];
  }
  if (!(gg > 0.0) || !(fg > 0.0)) return std::numeric_limits<double>::infinity();
  return before + ff - fg * fg / gg;
}

}  // namespace

PreprocessedCurve preprocess(const ForceCurve& curve, const PreprocessOptions& options) {
  const std::string& file = curve.metadata.source_file;
  if (!(options.baseline_fraction > 0.0 && options.baseline_fraction < 1.0)) {
    throw InputError("baseline fraction " + std::to_string(options.baseline_fraction) + " is not allowed; it must be in (0, 1)");
  }
  if (!(options.deviation_sigmas > 0.0) || !(options.piecewise_exponent >= 1.0 && options.piecewise_exponent <= 3.0)) {
    throw InputError("contact point options: deviation sigmas must be > 0 and the exponent in [1, 3]");
  }
  const Segment* approach = curve.find_segment(SegmentKind::kApproach);
  if (approach == nullptr) throw InputError(file + ": no approach segment to preprocess");
  PreprocessedCurve out;
  out.tip_position = curve.tip_position();  // step 1 (InputError without a spring constant)

  // Step 2: baseline on the leading part of the approach.
  const std::size_t first = approach->begin;
  const std::size_t end = approach->end;
  const std::size_t n_base = static_cast<std::size_t>(options.baseline_fraction * static_cast<double>(end - first));
  if (n_base < kMinBaselinePoints || end - first - n_base < kMinBaselinePoints) {
    throw InputError(file + ": the approach has " + std::to_string(end - first) +
                     " points, too few for a baseline and a contact region of 10 points each");
  }
  double c0 = 0.0, c1 = 0.0, cov00 = 0.0, cov01 = 0.0, cov11 = 0.0, sumsq = 0.0;
  gsl_fit_linear(out.tip_position.data() + first, 1, curve.force.data() + first, 1, n_base, &c0, &c1, &cov00, &cov01,
                 &cov11, &sumsq);
  out.baseline_offset = c0;
  out.baseline_slope = c1;
  out.baseline_points = n_base;
  out.baseline_sigma = std::sqrt(sumsq / static_cast<double>(n_base - 2));
  out.baseline_offset_error = std::sqrt(cov00);
  out.baseline_slope_error = std::sqrt(cov11);
  if (!std::isfinite(c0) || !std::isfinite(c1)) throw NumericalError(file + ": the baseline fit did not give finite values");
  out.force_corrected.resize(curve.force.size());
  for (std::size_t i = 0; i < curve.force.size(); ++i) {
    out.force_corrected[i] = curve.force[i] - (c0 + c1 * out.tip_position[i]);
  }

  // Step 3: contact point among the approach points after the baseline.
  const auto& z = out.tip_position;
  const auto& f = out.force_corrected;
  const std::size_t lo = first + n_base;
  out.contact_method = options.contact_method;
  if (options.contact_method == ContactPointMethod::kDeviation) {
    const double threshold = options.deviation_sigmas * out.baseline_sigma;
    std::size_t c = end;
    while (c > lo && f[c - 1] > threshold) --c;
    if (c == end || c == lo) {
      throw InputError(file + ": no contact found in the approach: the corrected force " +
                       std::string(c == end ? "does not end above " : "is above ") + "the deviation threshold (" +
                       std::to_string(options.deviation_sigmas) + " baseline sigmas)");
    }
    out.contact_index = c;
  } else {
    // Coarse scan, then every index around the best coarse candidate.
    const std::size_t last = end - 3;
    const std::size_t stride = std::max<std::size_t>(1, (last - lo) / 200);
    std::size_t best = lo;
    double best_cost = std::numeric_limits<double>::infinity();
    for (std::size_t c = lo; c <= last; c += stride) {
      const double cost = piecewise_cost(z, f, lo, end, c, options.piecewise_exponent);
      if (cost < best_cost) best_cost = cost, best = c;
    }
    const std::size_t from = best > lo + stride ? best - stride : lo;
    const std::size_t to = std::min(last, best + stride);
    for (std::size_t c = from; c <= to; ++c) {
      const double cost = piecewise_cost(z, f, lo, end, c, options.piecewise_exponent);
      if (cost < best_cost) best_cost = cost, best = c;
    }
    // A contact must raise the force above the noise: the corrected force at the end of the
    // approach beyond the deviation threshold (otherwise the best fit is of noise alone).
    if (!std::isfinite(best_cost) || !(f[end - 1] > options.deviation_sigmas * out.baseline_sigma)) {
      throw InputError(file + ": no contact found in the approach: the corrected force does not end above " +
                       std::to_string(options.deviation_sigmas) + " baseline sigmas");
    }
    out.contact_index = best;
  }
  out.contact_point = z[out.contact_index];
  return out;
}

}  // namespace coatcontact::afm
