// Modulus against depth (coatcontact/afm_depth_profile.hpp; THEORY.md section 15, "Modulus
// against depth"). A synthetic approach of a sphere on a soft film bonded to a stiff substrate,
// made with the library's coated model plus Gaussian noise and given heights (so it goes through
// the whole one-curve pipeline): the half-space fit's apparent E rises with depth (the substrate
// shows through), while the coated fit's E1 stays within 2 standard errors of the truth at every
// depth. Then the default depth sequence (its documented ends) and the requests it refuses.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "check.hpp"
#include "coatcontact/afm_depth_profile.hpp"
#include "coatcontact/afm_fit.hpp"
#include "coatcontact/afm_preprocess.hpp"
#include "coatcontact/errors.hpp"

namespace fit = coatcontact::fit;
namespace afm = coatcontact::afm;

namespace {

constexpr double kFilm = 5e3, kSubstrate = 1e6, kThickness = 2e-6, kRadius = 10e-6, kNoise = 2e-12, kSpring = 0.05;

fit::AfmFitProblem truth() {
  fit::AfmFitProblem p;
  p.tip = fit::afm_paraboloid(kRadius);
  fit::AfmCoating c;
  c.film = {kFilm, 0.5};
  c.substrate.material = {kSubstrate, 0.3};
  c.thickness = kThickness;
  p.coating = c;
  p.poisson = 0.5;
  p.contact_point = 2e-6;
  p.baseline = 1e-10;
  return p;
}

// Tip positions 5 um -> 0 (indentations up to t), heights = z - F/k as an instrument records them.
afm::ForceCurve synthetic(unsigned seed) {
  const std::size_t n = 300;
  std::vector<double> z;
  for (std::size_t i = 0; i < n; ++i) z.push_back(5e-6 * (1.0 - static_cast<double>(i) / static_cast<double>(n - 1)));
  std::vector<double> f = fit::afm_model_force(truth(), z);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, kNoise);
  afm::ForceCurve c;
  for (std::size_t i = 0; i < n; ++i) {
    f[i] += noise(rng);
    c.force.push_back(f[i]);
    c.height_piezo.push_back(z[i] - f[i] / kSpring);
    c.segment.push_back(0);
  }
  afm::Segment s;
  s.kind = afm::SegmentKind::kApproach;
  s.begin = 0;
  s.end = n;
  c.segments.push_back(s);
  c.metadata.spring_constant = kSpring;
  c.metadata.spring_constant_source = afm::CalibrationSource::kUser;
  c.metadata.source_file = "synthetic coated";
  return c;
}

fit::AfmCurveRequest request() {
  fit::AfmCurveRequest r;
  r.problem = truth();
  r.problem.coating->film.youngs_modulus = 2e4;  // the start, 4x off
  r.problem.free = fit::AfmFree{};  // E1, contact point, baseline (t fixed)
  return r;
}

}  // namespace

int main() {
  const afm::ForceCurve curve = synthetic(3);
  const fit::AfmCurveRequest req = request();
  const fit::AfmDepthProfile profile = fit::afm_depth_profile(curve, req, {});
  // The documented sequence: kDepthProfileSteps depths, increasing, the last the deepest
  // indentation of the whole-range fit (computed here from its contact point and the data).
  std::vector<double> depths;
  for (const fit::AfmDepthStep& s : profile.steps) depths.push_back(s.depth);
  check::that(depths.size() == fit::kDepthProfileSteps, "depth sequence: kDepthProfileSteps depths");
  check::that(std::is_sorted(depths.begin(), depths.end()) && depths.front() < depths.back(), "depth sequence increases");
  double deepest = 0.0;
  for (double z : profile.reference.z_segment) deepest = std::max(deepest, profile.reference_contact_point - z);
  check::close(depths.back(), deepest, check::tier::kRounding, "depth sequence ends at the deepest indentation (the same arithmetic)");
  check::close(profile.steps.back().max_indentation, deepest, check::tier::kRounding, "the last depth is the whole range");
  check::that(profile.modulus_name == "E1" && profile.coated, "coating: the profile follows E1");
  double previous = 0.0;
  bool rising = true;
  for (const fit::AfmDepthStep& s : profile.steps) {
    std::printf("depth %.3e m: delta_max %.3e m, E1 %.5g +- %.3g Pa (%+.2f SE), apparent E %.5g +- %.3g Pa, beyond %d\n",
                s.depth, s.max_indentation, s.modulus, s.modulus_error, (s.modulus - kFilm) / s.modulus_error,
                s.apparent_modulus, s.apparent_modulus_error, s.beyond_thickness_fraction ? 1 : 0);
    check::that(s.flag == fit::AfmFlag::kFitted, "every depth fitted");
    // The coated model is the truth's: E1 within 2 standard errors at every depth.
    check::below(std::abs(s.modulus - kFilm), 2.0 * s.modulus_error, "coated fit: E1 within 2 SE of the truth");
    // The half-space fit absorbs the substrate: its E rises with depth (each step above the
    // previous, allowing 2 of its standard errors of noise).
    if (s.apparent_modulus < previous - 2.0 * s.apparent_modulus_error) rising = false;
    previous = s.apparent_modulus;
    check::that(s.beyond_thickness_fraction == (s.max_indentation > fit::kDepthProfileThicknessFraction * kThickness),
                "the thickness-fraction mark follows its definition");
  }
  check::that(rising, "half-space fit: apparent E rises with depth");
  const double first = profile.steps.front().apparent_modulus, last = profile.steps.back().apparent_modulus;
  // At delta = t on a substrate 200 times stiffer the apparent modulus is several times E1.
  check::that(last > 2.0 * first && last > 2.0 * kFilm, "half-space fit: apparent E at delta = t over twice its shallow value");
  check::that(!profile.warnings.empty(), "coating: the steps deeper than 0.1 t are warned about");

  // Requests the profile refuses.
  fit::AfmCurveRequest bad = req;
  bad.problem.free.thickness = true;
  check::throws<coatcontact::InputError>([&] { fit::afm_depth_profile(curve, bad, depths); }, {"t must be fixed"});
  bad = req;
  bad.problem.free.modulus = false;
  check::throws<coatcontact::InputError>([&] { fit::afm_depth_profile(curve, bad, depths); }, {"modulus must be free"});
  check::throws<coatcontact::InputError>([&] { fit::afm_depth_profile(curve, req, {1e-7, -1e-7}); }, {"depths must be > 0"});
  return check::exit_code();
}
