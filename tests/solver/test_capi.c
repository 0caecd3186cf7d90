/* The C interface of the solver (cpp/include/coatcontact/coatcontact.h), used from C. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "coatcontact/coatcontact.h"

static int failures = 0;

static void check(const char *what, int condition) {
  if (!condition) {
    ++failures;
    printf("FAIL %s (last error: %s)\n", what, cc_last_error_message());
  }
}

/* THEORY.md section 6, homogeneous substrate: 8/3, 1, 2, 1, 1, 1 (to the 1e-10). */
static void check_homogeneous_row(const char *what, const double *row, double a_over_t) {
  const double expected[7] = {a_over_t, 8.0 / 3.0, 1.0, 2.0, 1.0, 1.0, 1.0};
  int i;
  for (i = 0; i < 7; ++i) check(what, fabs(row[i] - expected[i]) <= 1e-10 * expected[i]);
  check(what, row[7] >= 0.0 && row[7] <= 1e-8);
}

int main(void) {
  double out[CC_REDUCED_COLUMNS];
  double table[3 * CC_REDUCED_COLUMNS];
  const double radii[3] = {0.01, 1.0, 100.0};
  cc_reduced_solver *solver = NULL;
  int status, i;

  status = cc_reduced_solve(2.0, 0.3, 2.0, 0.3, 0, 5.0, 0.0, out);
  check("cc_reduced_solve homogeneous: status", status == CC_REDUCED_OK);
  check_homogeneous_row("cc_reduced_solve homogeneous: values", out, 5.0);

  status = cc_reduced_sweep(2.0, 0.3, 2.0, 0.3, 0, 3, radii, 1e-8, table);
  check("cc_reduced_sweep homogeneous: status", status == CC_REDUCED_OK);
  for (i = 0; i < 3; ++i) check_homogeneous_row("cc_reduced_sweep homogeneous: row", table + 8 * i, radii[i]);

  /* Handle API gives the same numbers as the one-shot calls (same algorithm, deterministic). */
  status = cc_reduced_solver_create(0.1, 0.25, 1.0, 0.25, 0, &solver);
  check("cc_reduced_solver_create: status", status == CC_REDUCED_OK && solver != NULL);
  status = cc_reduced_solver_sweep(solver, 3, radii, 0.0, table);
  check("cc_reduced_solver_sweep: status", status == CC_REDUCED_OK);
  status = cc_reduced_solve(0.1, 0.25, 1.0, 0.25, 0, 1.0, 0.0, out);
  check("cc_reduced_solve soft film: status", status == CC_REDUCED_OK);
  for (i = 0; i < CC_REDUCED_COLUMNS; ++i) check("sweep row equals single solve", table[8 + i] == out[i]);
  /* FE reference (data/fe_flat_punch.tsv): E1/E0 = 0.1, a/t = 1: E_eq = 2.073515864 +- 5.6e-7. */
  check("E_eq against the finite-element reference", fabs(out[5] - 2.073515864) <= 5.6e-7);

  /* Errors: status codes and a message naming the problem; nothing silently wrong. */
  status = cc_reduced_solver_solve(solver, -1.0, 0.0, out);
  check("negative a/t is an input error", status == CC_REDUCED_INPUT_ERROR);
  check("message names a/t", strstr(cc_last_error_message(), "a/t") != NULL);
  status = cc_reduced_solver_solve(solver, 1.0, 1e-20, out);
  check("tolerance below 1e-13 is an input error", status == CC_REDUCED_INPUT_ERROR);
  status = cc_reduced_solve(-1.0, 0.3, 1.0, 0.3, 0, 1.0, 0.0, out);
  check("negative film modulus is an input error", status == CC_REDUCED_INPUT_ERROR);
  status = cc_reduced_solve(1.0, 0.7, 1.0, 0.3, 0, 1.0, 0.0, out);
  check("film Poisson ratio 0.7 is an input error", status == CC_REDUCED_INPUT_ERROR);
  status = cc_reduced_sweep(1.0, 0.3, 1.0, 0.3, 0, 2, NULL, 0.0, table);
  check("null radii is an input error", status == CC_REDUCED_INPUT_ERROR);
  /* Incompressible film on a rigid base at a/t = 1000: condition ~ (a/t)^3, the tolerance
   * cannot be met; the solver must say so. */
  status = cc_reduced_solve(1.0, 0.5, 1.0, 0.0, 1, 1000.0, 1e-8, out);
  check("unreachable tolerance is a numerical error", status == CC_REDUCED_NUMERICAL_ERROR);
  check("numerical error message names the tolerance", strstr(cc_last_error_message(), "tolerance") != NULL);
  status = cc_reduced_solver_solve(solver, 2.0, 0.0, out);
  check("error state cleared by a successful call", status == CC_REDUCED_OK && cc_last_error_message()[0] == '\0');

  cc_reduced_solver_destroy(solver);
  cc_reduced_solver_destroy(NULL);
  if (failures == 0) {
    printf("test_capi: all checks passed\n");
    return 0;
  }
  printf("test_capi: %d check(s) failed\n", failures);
  return 1;
}
