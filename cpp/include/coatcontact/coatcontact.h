/*
 * coatcontact: C interface to the reduced-variable solver (THEORY.md section 5).
 *
 * For a film (e1, nu1) bonded to a substrate (e0, nu0, or rigid when substrate_rigid != 0)
 * and a contact radius over film thickness a/t, the solver returns, in this order,
 *   out[0] a_over_t  out[1] Pi_s  out[2] Delta_s  out[3] Pi_c  out[4] Delta_c
 *   out[5] E_eq      out[6] Gamma1  out[7] error_estimate
 * (the same columns as `coatcontact reduced`). The error estimate is the solver's bound on the
 * largest relative error of the six values; it is <= tolerance whenever the status is
 * CC_REDUCED_OK. Tolerance 0 means the default 1e-8; otherwise it must be in [1e-13, 1e-1].
 *
 * Every function returns a status code; on failure nothing is written to `out` except that
 * a sweep may have filled rows before the failing one, and cc_last_error_message() describes
 * the failure (per thread). Implemented in cpp/capi/capi.cpp.
 */
#ifndef COATCONTACT_COATCONTACT_H
#define COATCONTACT_COATCONTACT_H

#ifdef __cplusplus
extern "C" {
#endif

enum cc_reduced_status {
  CC_REDUCED_OK = 0,
  CC_REDUCED_INPUT_ERROR = 2,      /* bad material constant, a/t, tolerance, length or pointer */
  CC_REDUCED_NUMERICAL_ERROR = 3,  /* the tolerance could not be met (never wrong numbers) */
  CC_REDUCED_INTERNAL_ERROR = 4    /* out of memory or another unexpected failure */
};

/* Number of doubles written per contact radius. */
#define CC_REDUCED_COLUMNS 8

/* Message of the last failure in the calling thread ("" if none); valid until the next call. */
const char *cc_last_error_message(void);

/* One contact radius (builds the kernel table of the material pair each call: a few ms). */
int cc_reduced_solve(double e1, double nu1, double e0, double nu0, int substrate_rigid,
                     double a_over_t, double tolerance, double out[CC_REDUCED_COLUMNS]);

/* n contact radii; out has n * CC_REDUCED_COLUMNS doubles, row by row. */
int cc_reduced_sweep(double e1, double nu1, double e0, double nu0, int substrate_rigid,
                     int n, const double *a_over_t, double tolerance, double *out);

/* A solver kept for many calls (the kernel table is built once). Thread-safe to use from
 * several threads once created. */
typedef struct cc_reduced_solver cc_reduced_solver;

int cc_reduced_solver_create(double e1, double nu1, double e0, double nu0, int substrate_rigid,
                             cc_reduced_solver **solver);
void cc_reduced_solver_destroy(cc_reduced_solver *solver);
int cc_reduced_solver_solve(const cc_reduced_solver *solver, double a_over_t, double tolerance,
                            double out[CC_REDUCED_COLUMNS]);
int cc_reduced_solver_sweep(const cc_reduced_solver *solver, int n, const double *a_over_t,
                            double tolerance, double *out);

#ifdef __cplusplus
}
#endif
#endif
