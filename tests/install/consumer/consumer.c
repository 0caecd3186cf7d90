/* Consumer of the installed package, in C: prints E_eq of one case (see run_install_test.sh). */
#include <stdio.h>

#include "coatcontact/coatcontact.h"

/* ---- the only call into the library's C API ---- */
/* Film E1 = 0.1, nu1 = 0.25 on substrate E0 = 1, nu0 = 0.25, a/t = 1, default tolerance. */
static int solve_e_eq(double *e_eq) {
  double out[CC_REDUCED_COLUMNS];
  const int status = cc_reduced_solve(0.1, 0.25, 1.0, 0.25, 0, 1.0, 0.0, out);
  if (status == CC_REDUCED_OK) *e_eq = out[5]; /* out[5] is E_eq (coatcontact.h) */
  return status;
}

int main(void) {
  double e_eq = 0.0;
  if (solve_e_eq(&e_eq) != CC_REDUCED_OK) {
    fprintf(stderr, "consumer_c: %s\n", cc_last_error_message());
    return 1;
  }
  printf("%.17g\n", e_eq);
  return 0;
}
