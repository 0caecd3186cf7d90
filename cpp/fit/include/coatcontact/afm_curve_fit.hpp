// The one AFM fit of a force curve (THEORY.md section 15): segment choice, the preprocessing
// steps (tip position, baseline, contact point; each recorded with its parameters), the
// baseline model (offset, or the preprocessing's tilt subtracted), the fit range, the model
// fit and the derived quantities (pull-off). The CLI's one-curve fit, the batch (one row per
// curve, afm_batch.hpp) and Python's coatcontact.afm.fit all call afm_fit_curve, so one curve
// gives the same estimates alone, as a row of its map and from Python.
#pragma once
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "coatcontact/afm_fit.hpp"
#include "coatcontact/afm_preprocess.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/force_curve.hpp"

namespace coatcontact::fit {

// Why a curve has no estimates (0: fitted). The numbers are part of the batch's output format.
enum class AfmFlag : int {
  kFitted = 0,
  kNoContact = 1,       // the approach never leaves its baseline, or the fit finds no contact
  kJumpIn = 2,          // the approach dips below its baseline (kJumpInSigmas, kJumpInFraction)
  kNoConvergence = 3,   // the fit did not give finite, identifiable estimates
  kEmptySegment = 4,    // a segment of the curve holds no points
  kMissingSegment = 5,  // the curve has no segment of the kind fitted (or no approach)
  kCalibration = 6,     // the curve lacks a spring constant or sensitivity its force needs
  kTooFewPoints = 7,    // the range options leave fewer than min_points
  kUnreadable = 8,      // the curve's entries are missing, truncated or corrupt
  kBadData = 9,         // the curve's values are not usable (not finite, one tip position)
  // Fitted, estimates kept, but not to be trusted (afm_fit_curve's checks after the fit):
  kUndetermined = 10,   // a free E, E1, t or w whose standard error exceeds its value
  kNoDetachment = 11,   // a retract fit whose retract ends off the free-cantilever level
};
constexpr int kAfmFlagCount = 12;
const char* afm_flag_name(AfmFlag flag);  // "fitted", "no_contact", "jump_in", ...
// True for the flags whose curve has estimates (fitted, undetermined, no_detachment).
bool afm_flag_keeps_estimates(AfmFlag flag);

// no_detachment: the mean force of the retract's last kDetachmentTailFraction of points (at
// least 3) differs from the approach's free-cantilever baseline (the preprocessing's line) by
// more than kDetachmentSigmas baseline sigmas and more than kDetachmentFraction of the
// approach's largest force above it (the second bound keeps the viscous-drag offset between
// approach and retract of a detached tip from flagging it, as kJumpInFraction does for jump-ins).
constexpr double kDetachmentTailFraction = 0.05;
constexpr double kDetachmentSigmas = 5.0;
constexpr double kDetachmentFraction = 0.05;

// The curve rating 0..10 (docs/afm.md, "Curve rating"): 10 s_fit s_signal s_contact s_flag,
// s_fit = min(1, noise / residual sigma), s_signal = log10(span / noise) / kRatingSignalDecades
// in [0, 1] (span: the range of the model force over the fitted points), s_contact =
// min(1, points in contact / kRatingContactPoints), s_flag = 1 (fitted), kRatingKeptFlag
// (undetermined, no_detachment), times kRatingWarning if the fit has warnings; 0 for a curve
// without estimates. Monotone: more noise, a worse fit, fewer contact points or a flag never
// raise it.
constexpr double kRatingSignalDecades = 3.0;
constexpr double kRatingContactPoints = 50.0;
constexpr double kRatingKeptFlag = 0.5;
constexpr double kRatingWarning = 0.8;
double afm_rating(AfmFlag flag, double residual_sigma, double noise_sigma, double model_span, std::size_t points_in_contact,
                  bool warnings);

// A per-curve failure of afm_fit_curve with its flag: bad input of the curve (exit 2 for a
// single fit) or a numerical failure (exit 3); the batch turns either into a flagged row.
class AfmCurveInputError : public InputError {
 public:
  AfmCurveInputError(AfmFlag flag, const std::string& message) : InputError(message), flag_(flag) {}
  AfmFlag flag() const { return flag_; }

 private:
  AfmFlag flag_;
};
class AfmCurveNumericalError : public NumericalError {
 public:
  AfmCurveNumericalError(AfmFlag flag, const std::string& message) : NumericalError(message), flag_(flag) {}
  AfmFlag flag() const { return flag_; }

 private:
  AfmFlag flag_;
};

// A jump-in: the baseline-corrected approach force below -kJumpInSigmas x the baseline's
// residual sigma and deeper than kJumpInFraction of the approach's largest force. Gaussian
// noise of n <= 1e6 points stays above -5.3 sigma (two-sided tail 1e-7); the fraction keeps a
// shallow attractive dip before contact, significant only against a very quiet baseline, from
// costing the curve (real AFM Workshop curves: 15 sigma but 4 % of the force).
constexpr double kJumpInSigmas = 8.0;
constexpr double kJumpInFraction = 0.1;

// The baseline step: `kTilt` subtracts the preprocessing's baseline slope s (z - z_ref) from
// the fitted forces (and the retract's), so the model's constant b is the baseline at the
// reference contact point z_ref; `kOffset` leaves the forces as measured (b alone). A model
// with a free tilt fits the slope itself: the step is then the offset (THEORY.md section 15).
enum class AfmBaselineModel { kTilt, kOffset };
const char* afm_baseline_model_name(AfmBaselineModel model);  // "tilt", "offset"
constexpr AfmBaselineModel kAfmDefaultBaseline = AfmBaselineModel::kTilt;

struct AfmCurveRequest {
  // As for afm_fit. noise_sigma > 0 is the caller's, else the curve's baseline sigma; spring_constant > 0 is
  // the user's, else the curve's (the adhesive models need one: else kCalibration).
  AfmFitProblem problem;
  afm::SegmentKind segment = afm::SegmentKind::kApproach;
  AfmRange range;  // relative to the preprocessing's contact point and baseline
  afm::PreprocessOptions preprocess;
  AfmBaselineModel baseline = kAfmDefaultBaseline;
  std::size_t min_points = 5;
  bool check_jump_in = false;  // approach fits only: a jump-in is kJumpIn
};

// The measured pull-off of a retract (THEORY.md section 15), the same for every model: the
// free-cantilever baseline is the least-squares line F = offset + slope z on the retract's last
// `fraction` of points (the tip far from the sample), and the pull-off the retract's most
// tensile force against it, with its tip position. Not found: fewer than 3 baseline points or
// one tip position.
struct AfmMeasuredPulloff {
  bool found = false;
  double force = 0.0;         // [N], negative when adhesive
  double tip_position = 0.0;  // [m]
  std::size_t index = 0;      // in the arrays given (afm_fit_curve: in the curve)
  double baseline_offset = 0.0, baseline_slope = 0.0;  // [N], [N/m]
  std::size_t baseline_points = 0;
};
AfmMeasuredPulloff afm_measured_pulloff(const std::vector<double>& tip_position, const std::vector<double>& force,
                                        double fraction);

// One recorded step: its name and its parameters in words (for headers and Python).
struct AfmStep {
  std::string name, parameters;
};

struct AfmCurveFit {
  AfmFitProblem problem;             // as fitted (noise sigma, spring constant)
  afm::PreprocessedCurve preprocessed;
  std::vector<AfmStep> steps;        // tip position, baseline, contact point, baseline model
  AfmBaselineModel baseline = kAfmDefaultBaseline;  // as applied (offset when the tilt is free)
  double subtracted_tilt = 0.0;      // [N/m] s of the tilt step (0 for offset)
  double reference_contact = 0.0;    // [m] the preprocessing's contact point z_ref
  double reference_baseline = 0.0;   // [N] the preprocessing's baseline at z_ref
  afm::Segment segment;              // the segment fitted (point range in the curve)
  std::vector<double> z_segment, f_segment;  // its tip positions and forces (less the subtracted tilt)
  std::vector<std::size_t> kept;     // indices into the segment of the fitted points
  AfmFitResult result;
  AfmFitProblem fitted;              // the problem at the estimates (for afm_model_force)
  AfmMeasuredPulloff pulloff;        // of the retract (model-independent; the model's jump-off: result)
  // kFitted, or kUndetermined / kNoDetachment with the estimates kept; flag_warnings say why
  // (one line each; result.warnings are the model's own, e.g. lambda out of its range).
  AfmFlag flag = AfmFlag::kFitted;
  std::vector<std::string> flag_warnings;
  double rating = 0.0;               // afm_rating of the fit
};

// Fits one curve. Per-curve failures are AfmCurveInputError / AfmCurveNumericalError with
// their flag and a message naming the file; other InputErrors only for a bad request.
AfmCurveFit afm_fit_curve(const afm::ForceCurve& curve, const AfmCurveRequest& request);

}  // namespace coatcontact::fit
