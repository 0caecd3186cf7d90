/* Consumer of the installed package, in C: prints E_eq of one case (see run_install_test.sh). */
#include <stdio.h>

#include "coatcontact/coatcontact.h"
#include "coatcontact/coatcontact_afm.h" /* installed beside it (also included by coatcontact.h) */

/* ---- the only calls into the library's C API ---- */
/* Film E1 = 0.1, nu1 = 0.25 on substrate E0 = 1, nu0 = 0.25, a/t = 1, default tolerance. */
static int solve_e_eq(double *e_eq) {
  cc_stack *stack = NULL;
  cc_reduced_solver *solver = NULL;
  double out[CC_REDUCED_COLUMNS];
  int status = cc_stack_create(&stack);
  if (status == CC_OK) status = cc_stack_add_layer(stack, 1.0, 0.1, 0.25, 0);
  if (status == CC_OK) status = cc_stack_set_substrate(stack, 1.0, 0.25);
  if (status == CC_OK) status = cc_reduced_solver_create(stack, &solver);
  if (status == CC_OK) status = cc_reduced_solver_solve(solver, 1.0, 0.0, out);
  if (status == CC_OK) *e_eq = out[5]; /* out[5] is E_eq (coatcontact.h) */
  cc_reduced_solver_destroy(solver);
  cc_stack_destroy(stack);
  return status;
}

/* The AFM part of the C API links and answers: the preprocessing defaults (baseline on the
 * approach's first half). */
static int afm_defaults_ok(void) {
  cc_afm_preprocess_options options;
  return cc_afm_preprocess_defaults(&options) == CC_OK && options.baseline_fraction == 0.5;
}

int main(void) {
  double e_eq = 0.0;
  if (!afm_defaults_ok()) {
    fprintf(stderr, "consumer_c: cc_afm_preprocess_defaults: %s\n", cc_last_error_message());
    return 1;
  }
  if (solve_e_eq(&e_eq) != CC_OK) {
    fprintf(stderr, "consumer_c: %s\n", cc_last_error_message());
    return 1;
  }
  printf("%.17g\n", e_eq);
  return 0;
}
