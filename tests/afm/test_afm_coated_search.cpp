// The coated Hertz fit's search for E1 on an elastic base (THEORY.md section 15, "Tabled coated
// force laws", "The search"; check "profiled search = nested search"): the fixed point of the
// closed-form scale polished by Gauss-Newton (afm_fit_hertz's search) reaches the same least
// squares as the nested search (a contact-point search per trial E1, minimized over ln E1):
// E1, z_c and b within 1/100 of their standard errors, on the real spot3 approach as a film on
// 1 MPa, a synthetic soft film (E1/E0 = 0.005, the fixed point contracts fast) and a synthetic
// stiff film (E1/E0 = 3, it contracts slowly: the secant's case), each started 4x off. Both
// searches read the same tabled force law, so the difference is the search's alone.
// Also (THEORY.md section 15, "The force law per point", "Many moduli at one grid"): the fit's
// resampled force law (the cubic Hermite on a uniform grid) gives the model force of the spline
// it resamples within 1e-6 of the largest force, for a sphere (grid in sqrt(delta)) and a cone
// (grid in delta); and the table read through a fit's node cache equals the uncached read bit
// for bit, error estimates included.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "afm_internal.hpp"
#include "check.hpp"
#include "coatcontact/afm_fit.hpp"
#include "coatcontact/afm_models.hpp"
#include "coatcontact/afm_readers.hpp"
#include "coatcontact/coated_table.hpp"

namespace fit = coatcontact::fit;
namespace afm = coatcontact::afm;
using coatcontact::Substrate;

namespace {

struct Curve {
  std::vector<double> z, f;
};

fit::AfmFitProblem coated(double e1, double e0, double thickness) {
  fit::AfmFitProblem p;
  p.tip = fit::afm_paraboloid(10e-6);
  fit::AfmCoating c;
  c.film = {e1, 0.5};
  c.substrate.material = {e0, 0.3};
  c.thickness = thickness;
  p.coating = c;
  p.contact_point = 2e-6;
  p.baseline = 1e-10;
  return p;
}

void check_same(const Curve& c, const fit::AfmFitProblem& p, const std::string& name) {
  const int free_count = fit::afm_free_count(p.model.info(), p.free);
  using fit::internal::CoatedE1Search;
  const fit::AfmFitResult a = fit::internal::afm_fit_hertz(c.z, c.f, p, free_count, CoatedE1Search::kProfiled);
  const fit::AfmFitResult b = fit::internal::afm_fit_hertz(c.z, c.f, p, free_count, CoatedE1Search::kNested);
  std::printf("%s: E1 %.9g (profiled) %.9g (nested) +- %.3g; z_c %.10g %.10g +- %.3g; b %.6g %.6g +- %.3g; "
              "%d vs %d profile evaluations, %.3f s vs %.3f s\n",
              name.c_str(), a.modulus, b.modulus, b.modulus_error, a.contact_point, b.contact_point, b.contact_point_error,
              a.baseline, b.baseline, b.baseline_error, a.profile_evaluations, b.profile_evaluations, a.seconds, b.seconds);
  // SE/100: the rule for a faster path of the same least squares.
  check::below(std::abs(a.modulus - b.modulus), b.modulus_error / 100.0, name + ": E1 profiled = nested within SE/100");
  check::below(std::abs(a.contact_point - b.contact_point), b.contact_point_error / 100.0,
               name + ": z_c profiled = nested within SE/100");
  check::below(std::abs(a.baseline - b.baseline), b.baseline_error / 100.0, name + ": b profiled = nested within SE/100");
  // Fewer profile evaluations is the point of the search (a count, not a timing).
  check::below(a.profile_evaluations, b.profile_evaluations, name + ": the profiled search evaluates fewer profiles");
}

// The fitted model force (the fit's resampled table) against afm_model_force at the fitted
// parameters (the log-log spline itself, not resampled).
void check_resampled_force(const Curve& c, const fit::AfmFitProblem& p, const std::string& name) {
  const fit::AfmFitResult r = fit::afm_fit(c.z, c.f, p);
  fit::AfmFitProblem at = p;
  at.coating->film.youngs_modulus = r.modulus;
  at.coating->thickness = r.thickness;
  at.contact_point = r.contact_point;
  at.baseline = r.baseline;
  at.tilt = r.tilt;
  const std::vector<double> spline = fit::afm_model_force(at, c.z);
  double largest = 0.0, worst = 0.0;
  for (std::size_t i = 0; i < c.z.size(); ++i) {
    largest = std::max(largest, std::abs(spline[i] - r.baseline));
    worst = std::max(worst, std::abs(r.model_force[i] - spline[i]));
  }
  std::printf("%s: fitted model force - spline's: largest %.3g of the largest force %.3g N\n", name.c_str(), worst / largest, largest);
  check::that(largest > 0.0, name + ": the fit is in contact");
  // The grid's tolerance is 1e-10 of the force at the far end of the contact-point search, which
  // for spot3 (a long approach) is ~5 000x the largest force in contact: 1e-6 here.
  check::below(worst, 1e-6 * largest, name + ": the resampled force law = the spline's within 1e-6 of the largest force");
}

// CoatedTable::at through a node cache (a fit's reads) = the uncached read, bit for bit.
void check_node_cache(const fit::AfmFitProblem& p) {
  const auto table = fit::internal::afm_coated_table(*p.coating);
  const std::vector<double> grid = {0.01, 0.13, 0.9, 2.2, 7.5}, other = {0.05, 1.7};
  coatcontact::CoatedSweepCache cache;
  bool same = true;
  for (const double e : {4.6e3, 4.55e3, 4.61e3, 5.2e3}) {
    for (const auto* at : {&grid, &other, &grid}) {
      const auto cached = table->at(e, *at, cache), plain = table->at(e, *at);
      for (std::size_t i = 0; i < at->size(); ++i) {
        const auto& a = cached[i];
        const auto& b = plain[i];
        same = same && a.point.pi_s == b.point.pi_s && a.point.delta_s == b.point.delta_s && a.point.pi_c == b.point.pi_c &&
               a.point.delta_c == b.point.delta_c && a.point.e_eq == b.point.e_eq && a.point.gamma1 == b.point.gamma1 &&
               a.point.dlog_pi_s == b.point.dlog_pi_s && a.point.dlog_delta_c == b.point.dlog_delta_c &&
               a.error_estimate == b.error_estimate && a.cross_error == b.cross_error && a.node_error == b.node_error;
      }
    }
  }
  check::that(same, "coated table: the cached read = the uncached one bit for bit (values, derivatives, estimates)");
  check::that(cache.nodes() > 0, "coated table: the cache holds the nodes it read");
}

Curve synthetic(const fit::AfmFitProblem& truth, double noise, unsigned seed) {
  Curve c;
  for (int i = 0; i < 300; ++i) c.z.push_back(4e-6 * (1.0 - i / 299.0));
  c.f = fit::afm_model_force(truth, c.z);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gauss(0.0, noise);
  for (double& v : c.f) v += gauss(rng);
  return c;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: test_afm_coated_search DATA_DIR\n");
    return 2;
  }
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  {
    const auto curves = afm::read_force_curves(std::string(argv[1]) + "/fmt-jpk-fd_spot3-0192.jpk-force");
    const afm::ForceCurve& curve = curves.at(0);
    const afm::Segment* seg = curve.find_segment(afm::SegmentKind::kApproach);
    if (!check::that(seg != nullptr, "spot3: approach segment")) return check::exit_code();
    const std::vector<double> tip = curve.tip_position();
    const Curve c{{tip.begin() + seg->begin, tip.begin() + seg->end},
                  {curve.force.begin() + seg->begin, curve.force.begin() + seg->end}};
    check_same(c, coated(1e4, 1e6, 2e-6), "spot3, film on 1 MPa, E1 free");
    check_resampled_force(c, coated(1e4, 1e6, 2e-6), "spot3, sphere, film on 1 MPa");
    check_node_cache(coated(1e4, 1e6, 2e-6));
  }
  {
    fit::AfmFitProblem truth = coated(5e3, 1e6, 2e-6);
    truth.tip = fit::afm_cone(35.0 * 3.14159265358979323846 / 180.0);
    fit::AfmFitProblem p = truth;
    p.coating->film.youngs_modulus = 1e4;
    check_resampled_force(synthetic(truth, 1e-9, 4), p, "cone 35 deg, film 5 kPa on 1 MPa");
  }
  {
    const fit::AfmFitProblem truth = coated(5e3, 1e6, 2e-6);
    fit::AfmFitProblem p = truth;
    p.coating->film.youngs_modulus = 2e4;
    check_same(synthetic(truth, 1e-9, 1), p, "soft film 5 kPa on 1 MPa");
  }
  {
    fit::AfmFitProblem truth = coated(3e6, 1e6, 1e-6);
    fit::AfmFitProblem p = truth;
    p.coating->film.youngs_modulus = 0.75e6;
    check_same(synthetic(truth, 1e-8, 3), p, "stiff film 3 MPa on 1 MPa");
  }
  return check::exit_code();
}
