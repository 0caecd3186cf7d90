// Elastic indenter (THEORY.md section 9): each test names the section-9 check it makes.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "materials.hpp"
#include "check.hpp"
#include "coatcontact/adhesion.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/kernel.hpp"
#include "coatcontact/reduced.hpp"

using namespace coatcontact;
using coatcontact::test::elastic;
using coatcontact::test::material;
using coatcontact::test::rigid;

// C' = (C + rho)/(1 + rho) and H/(1 + rho): one add and one divide on top of the same table.
constexpr double kScalingTier = 1e-14;
// Pull-off values from the interpolated curve at solver tolerance 1e-9 and location 1e-12.
constexpr double kPulloffTier = 1e-9;

namespace {

Indenter elastic_indenter(double e, double nu) { return Indenter{false, material(e, nu)}; }

std::string str(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%g", value);
  return buffer;
}

// Check "E2 -> infinity gives back section 5 exactly": a very stiff indenter reproduces the
// rigid reduced variables, kernel and pull-off to 1e-12.
void test_stiff_limit() {
  const Material film = material(0.1, 0.25);
  const Substrate base = elastic(1.0, 0.25);
  const ReducedSolver rigid_solver(Stack::film_on(film, base));
  const ReducedSolver stiff_solver(Stack::film_on(film, base, elastic_indenter(1e13, 0.3)));
  check::close(stiff_solver.stack().reference_modulus(), film.reduced_modulus(), check::tier::kAmplified, "E_r -> E1* as E2 -> inf");
  for (double a : {0.05, 1.0, 20.0}) {
    const ReducedVariables r = rigid_solver.solve(a, 1e-10);
    const ReducedVariables s = stiff_solver.solve(a, 1e-10);
    const double rv[6] = {r.pi_s, r.delta_s, r.pi_c, r.delta_c, r.e_eq, r.gamma1};
    const double sv[6] = {s.pi_s, s.delta_s, s.pi_c, s.delta_c, s.e_eq, s.gamma1};
    for (int i = 0; i < 6; ++i) {
      check::close(sv[i], rv[i], check::tier::kAmplified, "E2 -> inf: reduced value " + std::to_string(i) + " at a/t " + str(a));
    }
  }
  const AdhesiveModel rigid_model(rigid_solver, 1e-10);
  const AdhesiveModel stiff_model(stiff_solver, 1e-10);
  const Pulloff pr = rigid_model.pulloff(1.0);
  const Pulloff ps = stiff_model.pulloff(1.0);
  check::close(ps.load_control.load, pr.load_control.load, check::tier::kAmplified, "E2 -> inf: pull-off P (load)");
  check::close(ps.displacement_control.load, pr.displacement_control.load, check::tier::kAmplified, "E2 -> inf: pull-off P (displacement)");
  std::printf("E2 -> inf: P_load %.15f (rigid %.15f)\n", ps.load_control.load, pr.load_control.load);
}

// The kernel of an elastic indenter: C' = (C + rho)/(1 + rho), H' = H/(1 + rho).
void test_kernel() {
  const Material film = material(0.1, 0.25);
  const Substrate base = elastic(1.0, 0.25);
  const Stack rigid_stack = Stack::film_on(film, base);
  const Stack soft = Stack::film_on(film, base, elastic_indenter(0.1, 0.25));  // rho = 1
  check::close(soft.indenter_ratio(), 1.0, check::tier::kRounding, "rho = E1*/E2*");
  check::close(soft.reference_modulus(), film.reduced_modulus() / 2, check::tier::kRounding, "E_r = E1*/2");
  const std::vector<double> q = {0.0, 0.1, 1.0, 10.0};
  const auto c = compliance(rigid_stack, q);
  const auto cp = compliance(soft, q);
  for (std::size_t i = 0; i < q.size(); ++i) {
    check::close(cp[i], (c[i] + 1.0) / 2.0, kScalingTier, "C' at q " + str(q[i]));
  }
  const KernelTable t(rigid_stack), tp(soft);
  for (double u : {0.0, 0.5, 3.0, 100.0}) {
    check::close(tp.h(u), t.h(u) / 2.0, kScalingTier, "H' = H/(1 + rho) at u " + str(u), 1e-300);
  }
  check::close(tp.info().abs_accuracy, t.info().abs_accuracy / 2.0, kScalingTier, "accuracy estimate scales");
  check::close(tp.info().c_zero, (t.info().c_zero + 1.0) / 2.0, kScalingTier, "C'(0) in the table info");
}

// Check "film = substrate gives JKR with E_r (P = -3/2 and -5/6 for any E2)".
void test_homogeneous_jkr() {
  for (double e2 : {0.01, 1.0, 100.0}) {
    const ReducedSolver solver(Stack::film_on(material(1.0, 0.3), elastic(1.0, 0.3), elastic_indenter(e2, 0.2)));
    const ReducedVariables v = solver.solve(2.0, 1e-10);
    check::close(v.pi_s, 8.0 / 3.0, check::tier::kInterpolation, "homogeneous Pi_s with E_r, E2 " + str(e2));
    check::close(v.e_eq, 1.0, check::tier::kInterpolation, "homogeneous E_eq with E_r, E2 " + str(e2));
    check::close(v.gamma1, 1.0, check::tier::kInterpolation, "homogeneous Gamma1 with E_r, E2 " + str(e2));
    const AdhesiveModel model(solver, 1e-10);
    for (double eta : {0.1, 1.0, 10.0}) {
      const Pulloff p = model.pulloff(eta);
      check::close(p.load_control.load, -1.5, kPulloffTier, "JKR with E_r: P load, E2 " + str(e2) + " eta " + str(eta));
      check::close(p.displacement_control.load, -5.0 / 6.0, kPulloffTier, "JKR with E_r: P displacement, E2 " + str(e2) + " eta " + str(eta));
    }
  }
}

// Check "the identity Gamma(1)^2 = d(a E_eq)/da holds with E_r" (6th-order central difference
// in ln a, as in the solver's identity test).
void test_identity() {
  const double step = 0.05;
  const double coefficient[3] = {3.0 / 4.0, -3.0 / 20.0, 1.0 / 60.0};
  for (double e2 : {0.03, 0.1, 1.0}) {
    const ReducedSolver solver(Stack::film_on(material(0.1, 0.25), elastic(1.0, 0.25), elastic_indenter(e2, 0.3)));
    for (double a : {0.1, 1.0, 10.0}) {
      std::vector<double> radii;
      for (int k = -3; k <= 3; ++k) radii.push_back(a * std::exp(k * step));
      const auto rows = solver.sweep(radii, 1e-9);
      auto f = [&](int k) { return rows[static_cast<std::size_t>(k + 3)].a_over_t * rows[static_cast<std::size_t>(k + 3)].e_eq; };
      double ds = 0.0;
      for (int k = 1; k <= 3; ++k) ds += coefficient[k - 1] * (f(k) - f(-k)) / step;
      check::close(rows[3].gamma1, std::sqrt(ds / a), check::tier::kIdentityByDifferences, "identity Gamma1^2 = d(a E_eq)/da with E_r, E2 " + str(e2) + ", a/t " + str(a));
    }
  }
}

void test_bad_input() {
  bool threw = false;
  try {
    Stack::film_on(material(1.0, 0.3), rigid(), elastic_indenter(1.0, 0.7));
  } catch (const InputError& e) {
    threw = std::string(e.what()).find("indenter") != std::string::npos;
  }
  check::that(threw, "indenter nu2 = 0.7 rejected, naming the indenter");
  threw = false;
  try {
    Stack::film_on(material(1.0, 0.3), rigid(), elastic_indenter(-1.0, 0.3));
  } catch (const InputError&) {
    threw = true;
  }
  check::that(threw, "indenter E2 < 0 rejected");
}

}  // namespace

int main() {
  test_kernel();
  test_stiff_limit();
  test_homogeneous_jkr();
  test_identity();
  test_bad_input();
  return check::exit_code();
}
