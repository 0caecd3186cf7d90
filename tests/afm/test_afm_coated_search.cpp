// The coated Hertz fit's search for E1 on an elastic base (THEORY.md section 15, "Tabled coated
// force laws", "The search"; check "profiled search = nested search"): the fixed point of the
// closed-form scale polished by Gauss-Newton (afm_fit_hertz's search) reaches the same least
// squares as the nested search (a contact-point search per trial E1, minimized over ln E1):
// E1, z_c and b within 1/100 of their standard errors, on the real spot3 approach as a film on
// 1 MPa, a synthetic soft film (E1/E0 = 0.005, the fixed point contracts fast) and a synthetic
// stiff film (E1/E0 = 3, it contracts slowly: the secant's case), each started 4x off. Both
// searches read the same tabled force law, so the difference is the search's alone.
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
