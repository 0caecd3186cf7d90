// Regression of issue 36 ("Undetermined results pass as fitted"): a retract that never detaches
// and an estimate whose standard error exceeds its value were rows flagged 0 (fitted). Now:
//  - a Hertz fit of a retract whose end stays off the approach's free-cantilever level is
//    flagged no_detachment, the same curve with a retract back at the baseline is fitted;
//  - a Hertz fit whose contact signal is buried in noise has E_error > E: undetermined;
//  - a JKR fit (w free) of a retract without any adhesive dip: undetermined, with w named;
//  - the estimates are kept (the batch row has them), the reasons are warnings, the rating
//    (docs/afm.md, "Curve rating") of the clean curve is above that of the same curve with
//    10x noise, and the rating formula is monotone and 0 for curves without estimates.
// THEORY.md section 15 (the AFM fit); the synthetic force is Hertz's paraboloid, written here.
#include <cmath>
#include <random>
#include <string>

#include "check.hpp"
#include "coatcontact/afm_batch.hpp"
#include "coatcontact/afm_curve_fit.hpp"

namespace afm = coatcontact::afm;
namespace fit = coatcontact::fit;

namespace {

constexpr double kE = 1e4, kNu = 0.5, kR = 10e-6, kK = 0.05, kContact = 1e-6;

// Hertz's paraboloid: F = 4/3 E/(1 - nu^2) sqrt(R) d^1.5 (THEORY.md section 15).
double hertz(double d) { return d > 0.0 ? 4.0 / 3.0 * kE / (1.0 - kNu * kNu) * std::sqrt(kR) * std::pow(d, 1.5) : 0.0; }

// Approach (tip 3 um -> 0.5 um) and retract back, `n` points each; the retract's force past
// the contact point is `stuck` (0: the free cantilever) plus noise of `sigma`, less `dip` over
// the first 20 nm past it (a small adhesive dip).
afm::ForceCurve curve(double sigma, double stuck, unsigned seed, std::size_t n = 1000, double dip = 0.0) {
  afm::ForceCurve c;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  for (int s = 0; s < 2; ++s) {
    afm::Segment segment;
    segment.kind = s == 0 ? afm::SegmentKind::kApproach : afm::SegmentKind::kRetract;
    segment.begin = c.force.size();
    for (std::size_t i = 0; i < n; ++i) {
      const double u = static_cast<double>(i) / static_cast<double>(n - 1);
      const double z = s == 0 ? 3e-6 - 2.5e-6 * u : 0.5e-6 + 2.5e-6 * u;
      const double d = kContact - z;
      double f = (d > 0.0 ? hertz(d) : (s == 1 ? stuck : 0.0)) + noise(rng);
      if (s == 1 && d <= 0.0 && d > -20e-9) f -= dip;
      c.force.push_back(f);
      c.height_piezo.push_back(z - f / kK);  // height + F/k is the designed tip position
      c.segment.push_back(s);
    }
    segment.end = c.force.size();
    c.segments.push_back(segment);
  }
  c.metadata.spring_constant = kK;
  c.metadata.spring_constant_source = afm::CalibrationSource::kUser;
  c.metadata.source_file = "synthetic";
  return c;
}

fit::AfmBatchSettings hertz_request(afm::SegmentKind segment) {
  fit::AfmBatchSettings request;
  request.problem.tip = fit::afm_paraboloid(kR);
  request.problem.modulus = kE;
  request.problem.poisson = kNu;
  request.segment = segment;
  return request;
}

bool mentions(const std::vector<std::string>& lines, const std::string& word) {
  for (const std::string& line : lines) {
    if (line.find(word) != std::string::npos) return true;
  }
  return false;
}

}  // namespace

int main() {
  const double f_max = hertz(kContact - 0.5e-6);  // ~20 nN at the deepest point
  const double sigma = 1e-11;

  // A retract that ends 0.3 F_max below the free level (the tip held by the sample): no_detachment.
  const fit::AfmBatchSettings retract = hertz_request(afm::SegmentKind::kRetract);
  const fit::AfmCurveFit stuck = fit::afm_fit_curve(curve(sigma, -0.3 * f_max, 1), retract);
  check::that(stuck.flag == fit::AfmFlag::kNoDetachment, std::string("stuck retract flagged no_detachment, got ") +
                                                              fit::afm_flag_name(stuck.flag));
  check::that(mentions(stuck.flag_warnings, "no_detachment"), "the warning names no_detachment");
  const fit::AfmCurveRow stuck_row = fit::afm_fit_curve_row(curve(sigma, -0.3 * f_max, 1), retract);
  check::that(stuck_row.flag == fit::AfmFlag::kNoDetachment && stuck_row.estimates.size() == 3,
              "the batch row is flagged no_detachment and keeps its 3 estimates");
  check::that(stuck_row.warnings.find("never detached") != std::string::npos, "the row's warnings say why");
  check::that(!stuck_row.tabor_mu && !stuck_row.maugis_lambda, "Hertz rows have no mu or lambda");
  check::that(stuck_row.rating > 0.0, "a row with kept estimates has a rating");

  // The same curve whose retract returns to the free level: fitted, E within 1 % (sigma 1e-11 N on 5 nN).
  const fit::AfmCurveFit detached = fit::afm_fit_curve(curve(sigma, 0.0, 1), retract);
  check::that(detached.flag == fit::AfmFlag::kFitted, std::string("detached retract fitted, got ") + fit::afm_flag_name(detached.flag));
  check::below(std::abs(detached.result.modulus - kE), 4.0 * detached.result.modulus_error, "E of the detached retract within 4 errors");

  // E from the first 5 nm of indentation (a few points, ~1 noise sigma of force): the error
  // exceeds E, flag undetermined; a draw whose E_error <= E stays fitted.
  const fit::AfmBatchSettings approach = hertz_request(afm::SegmentKind::kApproach);
  fit::AfmBatchSettings shallow = approach;
  shallow.range.indentation_max = 5e-9;
  bool seen = false;
  for (unsigned seed = 1; seed <= 5; ++seed) {
    try {
      const fit::AfmCurveFit noisy = fit::afm_fit_curve(curve(sigma, 0.0, seed), shallow);
      if (noisy.result.modulus_error > std::abs(noisy.result.modulus)) {
        check::that(noisy.flag == fit::AfmFlag::kUndetermined, "E_error > E is flagged undetermined");
        check::that(mentions(noisy.flag_warnings, "undetermined: E"), "the warning names E");
        seen = true;
      } else {
        check::that(noisy.flag == fit::AfmFlag::kFitted, "E_error <= E stays fitted");
      }
    } catch (const fit::AfmCurveInputError&) {  // no contact in so few points: flagged otherwise
    } catch (const fit::AfmCurveNumericalError&) {
    }
  }
  check::that(seen, "a fit with E_error > E among 5 noise draws");

  // JKR with w and the tilt free on a retract whose adhesive dip is 4 noise sigmas (the issue's
  // 1-D map: w ~ 1e-13 +- 1e-8 J/m2, flag 0): w is not determined.
  fit::AfmBatchSettings jkr = retract;
  jkr.problem.model = fit::AfmModel::kJkr;
  jkr.problem.free.work = true;
  jkr.problem.free.tilt = true;
  jkr.problem.spring_constant = kK;
  const fit::AfmCurveFit no_dip = fit::afm_fit_curve(curve(sigma, 0.0, 2, 1000, 4.0 * sigma), jkr);
  check::that(no_dip.flag == fit::AfmFlag::kUndetermined,
              std::string("JKR without a dip flagged undetermined, got ") + fit::afm_flag_name(no_dip.flag) +
                  " (w = " + std::to_string(no_dip.result.work) + " +- " + std::to_string(no_dip.result.work_error) + ")");
  check::that(mentions(no_dip.flag_warnings, "undetermined: w"), "the warning names w");
  const fit::AfmCurveRow jkr_row = fit::afm_fit_curve_row(curve(sigma, 0.0, 2, 1000, 4.0 * sigma), jkr);
  check::that(jkr_row.tabor_mu && jkr_row.maugis_lambda && std::isfinite(*jkr_row.maugis_lambda), "JKR rows carry mu and lambda");

  // Rating: the clean approach above the same curve with 10x noise.
  const fit::AfmCurveFit clean = fit::afm_fit_curve(curve(2e-11, 0.0, 3), approach);
  const fit::AfmCurveFit loud = fit::afm_fit_curve(curve(2e-10, 0.0, 3), approach);
  check::that(clean.flag == fit::AfmFlag::kFitted && loud.flag == fit::AfmFlag::kFitted, "both rating curves fitted");
  check::that(clean.rating > loud.rating && clean.rating <= 10.0 && loud.rating > 0.0,
              "clean rating " + std::to_string(clean.rating) + " > 10x noise rating " + std::to_string(loud.rating));
  // The formula itself: each factor as docs/afm.md states, monotone, 0 without estimates.
  check::close(fit::afm_rating(fit::AfmFlag::kFitted, 1.0, 1.0, 100.0, 25, false), 10.0 * (2.0 / 3.0) * 0.5, check::tier::kMachine,
               "rating = 10 s_fit s_signal s_contact (a few roundings: machine tier)");
  check::that(fit::afm_rating(fit::AfmFlag::kFitted, 2.0, 1.0, 100.0, 50, false) <
                  fit::afm_rating(fit::AfmFlag::kFitted, 1.0, 1.0, 100.0, 50, false),
              "a larger residual lowers the rating");
  check::that(fit::afm_rating(fit::AfmFlag::kUndetermined, 1.0, 1.0, 100.0, 50, false) <
                  fit::afm_rating(fit::AfmFlag::kFitted, 1.0, 1.0, 100.0, 50, false),
              "a kept-estimate flag lowers the rating");
  check::that(fit::afm_rating(fit::AfmFlag::kFitted, 1.0, 1.0, 100.0, 50, true) <
                  fit::afm_rating(fit::AfmFlag::kFitted, 1.0, 1.0, 100.0, 50, false),
              "a warning lowers the rating");
  check::that(fit::afm_rating(fit::AfmFlag::kNoContact, 1.0, 1.0, 100.0, 50, false) == 0.0, "no estimates: rating 0");
  return check::exit_code();
}
