// Tabled coated force laws (THEORY.md section 15, "Tabled coated force laws"; check "coated
// table against direct solves"):
//  - every value of the CoatedTable (reduced variables at (a/t, E_L) off its nodes) lies within
//    its error estimate of a direct solve (tolerance 1e-9, below the table's), at 240
//    random points over four material systems: a soft film, a stiff film, a film on a rigid
//    base with nu1 = 0.5, and a two-layer stack whose top layer's modulus is free; a/t in
//    [1e-3, 1e3] (to 1e2 for the stiff film and the rigid base: their solves at a/t ~ 1e3 do not
//    reach the tolerance 1e-8). The estimate means what it says: at most 10x the actual error (the actual
//    error floored at the nodes' and the reference's own error estimates, below which it cannot
//    be measured, and at 1e-10).
//  - the Hertz fit on a coating from the table equals the direct-solve fit (AfmCoating::direct)
//    within 1/100 of its standard errors: synthetic curves whose truth is known (film on an
//    elastic substrate, E1 free and t free; film on a rigid base, nu1 = 0.5, E1 free), and the
//    real spot3 approach as a film on a substrate; two threads fitting on one empty shared table
//    get the single fit's result bit for bit.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "check.hpp"
#include "coatcontact/afm_fit.hpp"
#include "coatcontact/afm_readers.hpp"
#include "coatcontact/coated_table.hpp"
#include "coatcontact/reduced.hpp"
#include "coatcontact/stack.hpp"

namespace fit = coatcontact::fit;
namespace afm = coatcontact::afm;
using coatcontact::CoatedTable;
using coatcontact::Layer;
using coatcontact::Material;
using coatcontact::Stack;
using coatcontact::Substrate;

namespace {

struct System {
  const char* name;
  Stack stack;
  double centre;  // the free modulus's centre [Pa]; points within a quarter decade of it
  double a_over_t_max;
};

double largest_relative(const coatcontact::ReducedValues& a, const coatcontact::ReducedValues& b) {
  const double x[6] = {a.pi_s, a.delta_s, a.pi_c, a.delta_c, a.e_eq, a.gamma1};
  const double y[6] = {b.pi_s, b.delta_s, b.pi_c, b.delta_c, b.e_eq, b.gamma1};
  double worst = 0.0;
  for (int j = 0; j < 6; ++j) worst = std::max(worst, std::abs(x[j] / y[j] - 1.0));
  return worst;
}

void check_table_against_direct() {
  Substrate elastic;
  elastic.material = {1e6, 0.3};
  Substrate rigid;
  rigid.rigid = true;
  const std::vector<Layer> two = {{0.5, {2e5, 0.45}, false}, {0.5, {5e6, 0.3}, false}};
  const std::vector<System> systems = {
      {"soft film (E1/E0 ~ 0.05)", Stack::film_on({5e4, 0.5}, elastic), 5e4, 1e3},
      {"stiff film (E1/E0 ~ 20)", Stack::film_on({2e7, 0.25}, elastic), 2e7, 1e2},
      {"film on a rigid base, nu1 = 0.5", Stack::film_on({1e5, 0.5}, rigid), 1e5, 1e2},
      {"two layers, top free", Stack(two, elastic), 2e5, 1e3},
  };
  std::vector<double> ratios, raw;
  double worst_excess = 0.0, worst_actual = 0.0;
  std::size_t solves = 0, points = 0;
  for (const System& s : systems) {
    coatcontact::CoatedTableOptions options;
    options.a_over_t_min = 1e-3;
    options.a_over_t_max = s.a_over_t_max;
    const CoatedTable table(s.stack, 0, options);
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int i = 0; i < 60; ++i, ++points) {
      const double modulus = s.centre * std::pow(10.0, 0.5 * unit(rng) - 0.25);
      const double a_over_t = 1e-3 * std::pow(s.a_over_t_max / 1e-3, unit(rng));
      const coatcontact::CoatedValues v = table.at(modulus, a_over_t);
      std::vector<Layer> layers = s.stack.layers();
      layers[0].material.youngs_modulus = modulus;
      const coatcontact::ReducedSolver solver(Stack(layers, s.stack.substrate()));
      const coatcontact::ReducedVariables direct = solver.solve(a_over_t, 1e-9);
      const double actual = largest_relative(v.point, direct);
      worst_actual = std::max(worst_actual, actual);
      worst_excess = std::max(worst_excess, actual / (v.error_estimate + direct.error_estimate));
      // The estimate against the actual error where that is measurable: above the nodes' own
      // error (the solver's estimate at its tolerance) and the reference's, and above 1e-10
      // (check::tier::kInterpolation, below what is asked of any table here).
      const bool measurable = actual > std::max(v.node_error + direct.error_estimate, check::tier::kInterpolation);
      if (measurable) ratios.push_back(v.error_estimate / actual);
      raw.push_back(v.error_estimate / std::max(actual, direct.error_estimate));
      if (measurable && ratios.back() > 10.0) {
        std::printf("  %s: E = %.6g, a/t = %.6g: estimate %.3e (cross %.2e, nodes' own %.2e) for an actual %.3e\n", s.name,
                    modulus, a_over_t, v.error_estimate, v.cross_error, v.node_error, actual);
      }
      if (!(actual <= v.error_estimate + direct.error_estimate)) {
        std::printf("  %s: E = %.6g, a/t = %.6g: actual %.3e > estimate %.3e (cross %.2e, nodes' own %.2e; reference %.1e)\n",
                    s.name, modulus, a_over_t, actual, v.error_estimate, v.cross_error, v.node_error, direct.error_estimate);
      }
    }
    solves += table.source_solves();
    std::printf("%s: %zu nodes, %zu solves\n", s.name, table.nodes(), table.source_solves());
  }
  std::sort(ratios.begin(), ratios.end());
  const auto quantile = [&](double q) { return ratios[static_cast<std::size_t>(q * (ratios.size() - 1))]; };
  std::sort(raw.begin(), raw.end());
  std::printf("estimate / actual without the nodes' floor: median %.3g, 90%% %.3g, max %.3g\n", raw[raw.size() / 2],
              raw[raw.size() * 9 / 10], raw.back());
  std::printf("table vs direct at %zu points: largest actual error %.3e, largest actual/(estimate+reference) %.3f\n",
              points, worst_actual, worst_excess);
  std::printf("estimate / actual at the %zu points of measurable error: min %.3g, 10%% %.3g, median %.3g, 90%% %.3g, "
              "max %.3g (%zu solves)\n",
              ratios.size(), quantile(0.0), quantile(0.1), quantile(0.5), quantile(0.9), quantile(1.0), solves);
  check::below(worst_excess, 1.0, "coated table: every value within its estimate of the direct solve");
  check::below(quantile(1.0), 10.0, "coated table: the estimate at most 10x the actual error");
  check::that(points >= 200 && ratios.size() >= 150, "coated table: at least 200 points, 150 of measurable error");
}

struct Curve {
  std::vector<double> z, f;
};

// The table's fit and the direct path's on the same points: every estimate within 1/100 of
// its standard error.
void check_same_fit(const Curve& c, fit::AfmFitProblem p, const std::string& name) {
  p.coating->direct = false;
  const fit::AfmFitResult tabled = fit::afm_fit(c.z, c.f, p);
  p.coating->direct = true;
  const fit::AfmFitResult direct = fit::afm_fit(c.z, c.f, p);
  std::printf("%s: E1 %.8g (table) %.8g (direct) +- %.3g; t %.8g %.8g +- %.3g; z_c %.10g %.10g +- %.3g; %.3f s vs %.3f s\n",
              name.c_str(), tabled.modulus, direct.modulus, direct.modulus_error, tabled.thickness, direct.thickness,
              direct.thickness_error, tabled.contact_point, direct.contact_point, direct.contact_point_error, tabled.seconds,
              direct.seconds);
  const auto same = [&](double a, double b, double se, const char* what) {
    check::below(std::abs(a - b), se / 100.0, name + ": " + what + " from the table = the direct fit's within SE/100");
  };
  if (p.free.modulus) same(tabled.modulus, direct.modulus, direct.modulus_error, "E1");
  if (p.free.thickness) same(tabled.thickness, direct.thickness, direct.thickness_error, "t");
  same(tabled.contact_point, direct.contact_point, direct.contact_point_error, "z_c");
  same(tabled.baseline, direct.baseline, direct.baseline_error, "b");
  check::close(tabled.modulus_error, direct.modulus_error, 0.01, name + ": the standard errors agree");
}

fit::AfmFitProblem coated(double e1, const Substrate& substrate, double nu1, double thickness) {
  fit::AfmFitProblem p;
  p.tip = fit::afm_paraboloid(10e-6);
  fit::AfmCoating c;
  c.film = {e1, nu1};
  c.substrate = substrate;
  c.thickness = thickness;
  p.coating = c;
  p.contact_point = 2e-6;
  p.baseline = 1e-10;
  return p;
}

Curve synthetic(const fit::AfmFitProblem& truth, double noise, unsigned seed) {
  Curve c;
  for (int i = 0; i < 300; ++i) c.z.push_back(4e-6 * (1.0 - i / 299.0));
  fit::AfmFitProblem t = truth;
  t.coating->direct = true;  // the truth from direct solves
  c.f = fit::afm_model_force(t, c.z);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gauss(0.0, noise);
  for (double& v : c.f) v += gauss(rng);
  return c;
}

void check_fits() {
  Substrate elastic;
  elastic.material = {1e6, 0.3};
  Substrate rigid;
  rigid.rigid = true;
  {
    const fit::AfmFitProblem truth = coated(5e3, elastic, 0.5, 2e-6);
    const Curve c = synthetic(truth, 1e-9, 1);
    fit::AfmFitProblem p = truth;
    p.coating->film.youngs_modulus = 2e4;  // a start 4x off
    check_same_fit(c, p, "film 5 kPa on 1 MPa, E1 free");
    p = truth;
    p.free.modulus = false;
    p.free.thickness = true;
    p.coating->thickness = 5e-6;
    check_same_fit(c, p, "film 5 kPa on 1 MPa, t free");
  }
  {
    const fit::AfmFitProblem truth = coated(5e3, rigid, 0.5, 2e-6);
    const Curve c = synthetic(truth, 1e-9, 2);
    fit::AfmFitProblem p = truth;
    p.coating->film.youngs_modulus = 2e4;
    check_same_fit(c, p, "film 5 kPa on a rigid base, nu1 = 0.5, E1 free");
    const fit::AfmFitResult r = fit::afm_fit(c.z, c.f, p);
    check::below(std::abs(r.modulus - 5e3) / r.modulus_error, 3.0, "rigid base: E1 within 3 SE of the truth");
  }
}

void check_spot3(const std::string& dir) {
  const auto curves = afm::read_force_curves(dir + "/fmt-jpk-fd_spot3-0192.jpk-force");
  const afm::ForceCurve& curve = curves.at(0);
  const afm::Segment* seg = curve.find_segment(afm::SegmentKind::kApproach);
  if (!check::that(seg != nullptr, "spot3: approach segment")) return;
  const std::vector<double> tip = curve.tip_position();
  Curve c{{tip.begin() + seg->begin, tip.begin() + seg->end}, {curve.force.begin() + seg->begin, curve.force.begin() + seg->end}};
  Substrate elastic;
  elastic.material = {1e6, 0.3};
  Substrate rigid;
  rigid.rigid = true;
  check_same_fit(c, coated(1e4, elastic, 0.5, 2e-6), "spot3, film on 1 MPa, E1 free");
  // One table shared by two threads that build its nodes concurrently from empty: both fits
  // equal the one of a table built by a single fit, bit for bit (a value does not depend on
  // which nodes exist or who built them).
  {
    const fit::AfmFitProblem p = coated(1e4, elastic, 0.5, 2e-6);
    const double alone = fit::afm_fit(c.z, c.f, p).modulus;
    fit::afm_clear_shared_sweeps();
    double both[2] = {0.0, 0.0};
    std::thread other([&] { both[1] = fit::afm_fit(c.z, c.f, p).modulus; });
    both[0] = fit::afm_fit(c.z, c.f, p).modulus;
    other.join();
    std::printf("spot3 on 1 MPa, two threads on one empty table: E1 %.17g, %.17g (alone %.17g)\n", both[0], both[1], alone);
    check::that(both[0] == alone && both[1] == alone, "a table shared by two threads gives the single fit's E1 bit for bit");
  }
  check_same_fit(c, coated(1e4, rigid, 0.5, 2e-6), "spot3, film on a rigid base, nu1 = 0.5, E1 free");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: test_afm_coated_table DATA_DIR\n");
    return 2;
  }
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  check_table_against_direct();
  check_fits();
  check_spot3(argv[1]);
  return check::exit_code();
}
