// C interface of the reduced-variable solver (cpp/include/coatcontact/coatcontact.h), its own
// floor above the C++ libraries so that it can grow to cover adhesion and fit.
#include "coatcontact/coatcontact.h"

#include <exception>
#include <new>
#include <string>
#include <vector>

#include "coatcontact/errors.hpp"
#include "coatcontact/reduced.hpp"

struct cc_reduced_solver {
  coatcontact::ReducedSolver solver;
};

namespace {

thread_local std::string last_error;

// Runs `body`, mapping exceptions to status codes and the thread's last error message.
template <typename Body>
int guarded(Body&& body) {
  try {
    last_error.clear();
    body();
    return CC_REDUCED_OK;
  } catch (const coatcontact::InputError& e) {
    last_error = e.what();
    return CC_REDUCED_INPUT_ERROR;
  } catch (const coatcontact::NumericalError& e) {
    last_error = e.what();
    return CC_REDUCED_NUMERICAL_ERROR;
  } catch (const std::bad_alloc&) {
    last_error = "out of memory";
    return CC_REDUCED_INTERNAL_ERROR;
  } catch (const std::exception& e) {
    last_error = e.what();
    return CC_REDUCED_INTERNAL_ERROR;
  } catch (...) {
    last_error = "unknown failure";
    return CC_REDUCED_INTERNAL_ERROR;
  }
}

coatcontact::Material material(double e, double nu) {
  coatcontact::Material m;
  m.youngs_modulus = e;
  m.poisson_ratio = nu;
  return m;
}

coatcontact::Stack film_stack(double e1, double nu1, double e0, double nu0, int rigid) {
  coatcontact::Substrate s;
  s.rigid = rigid != 0;
  s.material = material(e0, nu0);
  return coatcontact::Stack::film_on(material(e1, nu1), s);
}

double tolerance_or_default(double tolerance) {
  return tolerance == 0.0 ? coatcontact::kDefaultTolerance : tolerance;
}

void write_row(const coatcontact::ReducedVariables& v, double* out) {
  out[0] = v.a_over_t;
  out[1] = v.pi_s;
  out[2] = v.delta_s;
  out[3] = v.pi_c;
  out[4] = v.delta_c;
  out[5] = v.e_eq;
  out[6] = v.gamma1;
  out[7] = v.error_estimate;
}

void sweep_into(const coatcontact::ReducedSolver& solver, int n, const double* a_over_t,
                double tolerance, double* out) {
  if (n < 0) throw coatcontact::InputError("number of contact radii " + std::to_string(n) + " is negative");
  if (n > 0 && (a_over_t == nullptr || out == nullptr)) {
    throw coatcontact::InputError("null a_over_t or out array");
  }
  const std::vector<double> radii(a_over_t, a_over_t + n);
  const auto rows = solver.sweep(radii, tolerance_or_default(tolerance));
  for (int i = 0; i < n; ++i) write_row(rows[static_cast<std::size_t>(i)], out + CC_REDUCED_COLUMNS * i);
}

}  // namespace

extern "C" {

const char* cc_last_error_message(void) { return last_error.c_str(); }

int cc_reduced_solver_create(double e1, double nu1, double e0, double nu0, int substrate_rigid,
                             cc_reduced_solver** solver) {
  return guarded([&] {
    if (solver == nullptr) throw coatcontact::InputError("null solver pointer");
    *solver = nullptr;
    *solver = new cc_reduced_solver{
        coatcontact::ReducedSolver(film_stack(e1, nu1, e0, nu0, substrate_rigid))};
  });
}

void cc_reduced_solver_destroy(cc_reduced_solver* solver) { delete solver; }

int cc_reduced_solver_solve(const cc_reduced_solver* solver, double a_over_t, double tolerance,
                            double out[CC_REDUCED_COLUMNS]) {
  return guarded([&] {
    if (solver == nullptr || out == nullptr) throw coatcontact::InputError("null solver or out pointer");
    write_row(solver->solver.solve(a_over_t, tolerance_or_default(tolerance)), out);
  });
}

int cc_reduced_solver_sweep(const cc_reduced_solver* solver, int n, const double* a_over_t,
                            double tolerance, double* out) {
  return guarded([&] {
    if (solver == nullptr) throw coatcontact::InputError("null solver pointer");
    sweep_into(solver->solver, n, a_over_t, tolerance, out);
  });
}

int cc_reduced_solve(double e1, double nu1, double e0, double nu0, int substrate_rigid,
                     double a_over_t, double tolerance, double out[CC_REDUCED_COLUMNS]) {
  return guarded([&] {
    if (out == nullptr) throw coatcontact::InputError("null out pointer");
    const coatcontact::ReducedSolver solver(film_stack(e1, nu1, e0, nu0, substrate_rigid));
    write_row(solver.solve(a_over_t, tolerance_or_default(tolerance)), out);
  });
}

int cc_reduced_sweep(double e1, double nu1, double e0, double nu0, int substrate_rigid, int n,
                     const double* a_over_t, double tolerance, double* out) {
  return guarded([&] {
    const coatcontact::ReducedSolver solver(film_stack(e1, nu1, e0, nu0, substrate_rigid));
    sweep_into(solver, n, a_over_t, tolerance, out);
  });
}

}  // extern "C"
