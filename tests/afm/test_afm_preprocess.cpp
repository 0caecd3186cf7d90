// Preprocessing of a force curve (coatcontact/afm_preprocess.hpp) on synthetic curves with a
// known answer: a tilted, offset baseline plus F = A (z_c - z)^1.5 past a contact point z_c,
// plus Gaussian noise. The baseline's offset and slope come back within 4 of their standard
// errors; the piecewise-fit contact point within the distance the model rises by 2 noise
// sigmas; the deviation method lies past the truth, by less than its threshold's distance
// (5 sigmas) plus one point. Then the real JPK curves: a contact point inside the approach.
// Usage: test_afm_preprocess DATA_DIR
#include <cmath>
#include <random>
#include <string>

#include "check.hpp"
#include "coatcontact/afm_preprocess.hpp"
#include "coatcontact/afm_readers.hpp"
#include "coatcontact/errors.hpp"

namespace afm = coatcontact::afm;

namespace {

struct Truth {
  double offset = 3e-10, slope = 2e-4, contact = 1e-6, amplitude = 5e-9 / std::pow(0.5e-6, 1.5), sigma = 2e-11;
};

afm::ForceCurve synthetic(const Truth& t, unsigned seed) {
  afm::ForceCurve c;
  const std::size_t n = 2000;
  const double k = 0.05;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, t.sigma);
  for (std::size_t i = 0; i < n; ++i) {
    const double z = 5e-6 - 4.5e-6 * static_cast<double>(i) / static_cast<double>(n - 1);  // tip position, 5 um -> 0.5 um
    const double d = t.contact - z;
    const double f = t.offset + t.slope * z + (d > 0 ? t.amplitude * std::pow(d, 1.5) : 0.0) + noise(rng);
    c.force.push_back(f);
    c.height_piezo.push_back(z - f / k);  // so that height + F/k is the designed tip position
    c.segment.push_back(0);
  }
  afm::Segment s;
  s.kind = afm::SegmentKind::kApproach;
  s.begin = 0;
  s.end = n;
  c.segments.push_back(s);
  c.metadata.spring_constant = k;
  c.metadata.spring_constant_source = afm::CalibrationSource::kUser;
  c.metadata.source_file = "synthetic";
  return c;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string data_dir = argc > 1 ? argv[1] : "data/afm";
  const Truth t;
  // Rise of the model by s noise sigmas: A d^1.5 = s sigma.
  const auto rise = [&](double sigmas) { return std::pow(sigmas * t.sigma / t.amplitude, 2.0 / 3.0); };
  const double spacing = 4.5e-6 / 1999.0;
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const afm::ForceCurve curve = synthetic(t, seed);
    const afm::PreprocessedCurve p = afm::preprocess(curve);
    check::below(std::fabs(p.baseline_offset - t.offset), 4 * p.baseline_offset_error, "baseline offset within 4 standard errors");
    check::below(std::fabs(p.baseline_slope - t.slope), 4 * p.baseline_slope_error, "baseline slope within 4 standard errors");
    check::close(p.baseline_sigma, t.sigma, 0.1, "baseline residual sigma = noise sigma (1000 points: 10 %)");
    check::below(std::fabs(p.contact_point - t.contact), rise(2.0) + spacing, "piecewise-fit contact point within the 2-sigma rise");
    afm::PreprocessOptions deviation;
    deviation.contact_method = afm::ContactPointMethod::kDeviation;
    const afm::PreprocessedCurve q = afm::preprocess(curve, deviation);
    check::that(q.contact_point <= t.contact + spacing, "deviation contact point past the truth (threshold is late)");
    check::below(t.contact - q.contact_point, rise(5.0 + 4.0) + spacing, "deviation late by at most its threshold's rise");
    // The corrected force before the contact is the noise alone.
    double mean = 0.0;
    for (std::size_t i = 0; i < p.baseline_points; ++i) mean += p.force_corrected[i];
    mean /= static_cast<double>(p.baseline_points);
    check::below(std::fabs(mean), 4 * t.sigma / std::sqrt(static_cast<double>(p.baseline_points)), "corrected baseline mean ~ 0");
  }
  // A curve without contact.
  Truth flat = t;
  flat.contact = -1.0;
  check::throws<coatcontact::InputError>([&] { afm::preprocess(synthetic(flat, 7)); }, {"synthetic", "no contact"});

  // Real curves: a contact point inside the approach, past the baseline part.
  for (const char* name : {"fmt-jpk-fd_spot3-0192.jpk-force", "fmt-jpk-cc_pr14-polymergel-2021.06.30.jpk-force",
                           "fmt-jpk-fd_flipsign_2015.05.22-15.31.49.352.jpk-force", "fmt-igor-fd_U3_3_p10004.ibw"}) {
    const auto curve = afm::read_force_curves(data_dir + "/" + name).at(0);
    const auto p = afm::preprocess(curve);
    const afm::Segment& a = *curve.find_segment(afm::SegmentKind::kApproach);
    check::that(p.contact_index >= a.begin + p.baseline_points && p.contact_index < a.end, std::string("contact inside the approach: ") + name);
    check::that(p.force_corrected[a.end - 1] > 10 * p.baseline_sigma, std::string("force at the end of the approach far above the noise: ") + name);
  }
  return check::exit_code();
}
