/*
 * coatcontact: C interface to the Fortran layered-substrate kernel.
 *
 * Physics: THEORY.md section 3 (surface compliance C(q) of a film of thickness t
 * bonded to a substrate, q = k t) and section 4 (H(u) = int_0^inf [C(q)-1] cos(qu) dq).
 * Implemented by fortran/cc_kernel_capi.f90 (bind(C) shim over the Fortran modules).
 *
 * Conventions: every function returns a status code of cc_status.h (CC_OK = 0 on success);
 * scalars are passed by value, arrays with an explicit length (the pointers must be valid for
 * that many doubles; NULL only where a comment allows it); nothing prints or stops.
 * A substrate is rigid when substrate_rigid != 0 (then e0 and nu0 are ignored).
 */
#ifndef COATCONTACT_CC_KERNEL_H
#define COATCONTACT_CC_KERNEL_H

#include "coatcontact/cc_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* C(q) at n points q[i] >= 0 (THEORY.md section 3). */
int cc_compliance(double e1, double nu1, double e0, double nu0, int substrate_rigid,
                  int n, const double *q, double *c);

/* C(q) - 1 at n points, computed without cancellation where C is close to 1. */
int cc_compliance_minus_one(double e1, double nu1, double e0, double nu0, int substrate_rigid,
                            int n, const double *q, double *c_minus_one);

/* Taylor coefficients f_k = f^(k)(0)/k!, k = 0..order, of f(q) = C(q) - 1 at q = 0
 * (order <= 15). f_0 = C(0) - 1 = E1* / E0* - 1. */
int cc_compliance_taylor(double e1, double nu1, double e0, double nu0, int substrate_rigid,
                         int order, double *coefficients);

/* Surface compliance of a stack (THEORY.md section 12): n_layers layers, top first
 * (1 <= n_layers <= 1000), thickness[i] > 0 (any unit: only ratios matter), youngs[i] > 0,
 * poisson[i] in (-1, 0.5]; slip_below[i] != 0 makes the interface BELOW layer i frictionless
 * (below the last layer on a rigid base: a frictionless rigid base, u_z = 0 and s_rz = 0;
 * every pattern of flags is accepted). The base is rigid when base_rigid != 0 (then e_base and
 * nu_base are ignored), else an elastic half-space. Normalization: q = k T with T the total
 * thickness, and u(k) = 2 C(kT) p(k) / (E_top* k) with E_top* the top layer's plane-strain
 * modulus, so C(inf) = 1 and C(0) = E_top* / E_base* (0 on a rigid base). One bonded layer gives
 * exactly cc_compliance(youngs[0], poisson[0], e_base, nu_base, base_rigid, ...).
 * A bad layer reports CC_ERR_THICKNESS, CC_ERR_FILM_MODULUS or CC_ERR_FILM_POISSON, the base
 * CC_ERR_SUBSTRATE_MODULUS or CC_ERR_SUBSTRATE_POISSON. */
int cc_stack_compliance(int n_layers, const double *thickness, const double *youngs,
                        const double *poisson, const int *slip_below, int base_rigid,
                        double e_base, double nu_base, int n, const double *q, double *c);

/* (added) C(q) - 1 of a stack, without cancellation where C is close to 1 (large q). */
int cc_stack_compliance_minus_one(int n_layers, const double *thickness, const double *youngs,
                                  const double *poisson, const int *slip_below, int base_rigid,
                                  double e_base, double nu_base, int n, const double *q,
                                  double *c_minus_one);

/* Opaque table of H(u) and of its antiderivative H1(u) = int_0^u H(v) dv for one material
 * pair, built once (FFTW real-even/odd transforms with end corrections) and reused for
 * every contact radius. Read-only after creation: safe to evaluate from several threads. */
typedef struct cc_kernel_table cc_kernel_table;

/* Safe to call from several threads (FFTW planning is serialized inside the library).
 * On failure *table is set to NULL. Takes a few ms. */
int cc_kernel_table_create(double e1, double nu1, double e0, double nu0, int substrate_rigid,
                           cc_kernel_table **table);
void cc_kernel_table_destroy(cc_kernel_table *table);

/* The same table built on an independent grid: grid_variant 0 is
 * cc_kernel_table_create's grid; 1 .. cc_kernel_grid_variants()-1 use other q-steps, periods,
 * u-steps, ranges and interpolation stencils, so that their numerical errors (interpolation,
 * FFT rounding, aliasing) differ from variant 0's. Solving with two variants and comparing
 * measures the effect of the table's errors on a result (docs/solver.md). Each variant meets
 * the same accuracy target. CC_ERR_ARGUMENT for a variant out of range. */
int cc_kernel_table_create_ex(double e1, double nu1, double e0, double nu0, int substrate_rigid,
                              int grid_variant, cc_kernel_table **table);
/* (added) The table of a stack (THEORY.md section 12; arguments and validation as
 * cc_stack_compliance), in the stack's normalization: u = r/T with T the total thickness,
 * H(u) = int_0^inf [C(q) - 1] cos(qu) dq with C normalized by the top layer's E*. One bonded
 * layer gives cc_kernel_table_create_ex's table bit for bit. Otherwise the grid is refined by
 * a power of 2 >= T/h_top (C - 1 decays like exp(-2 q h_top/T)): the table costs about
 * T/h_top times one film's, and a top layer thinner than T/32 reports CC_ERR_ACCURACY. The
 * end correction and asymptotic series use Taylor coefficients from a power-series run of
 * the stack recursion (exact propagators, so they are accurate to rounding). */
int cc_kernel_table_create_stack(int n_layers, const double *thickness, const double *youngs,
                                 const double *poisson, const int *slip_below, int base_rigid,
                                 double e_base, double nu_base, int grid_variant,
                                 cc_kernel_table **table);

/* (added) Variant 0's table on a compact grid (same step, stencil and q range; shorter period)
 * that tabulates at least [0, u_range] (u_range > 0; at least [0, 40], at most variant 0's
 * range), for callers that never need H beyond u_range (the solver: |x +- y| <= 2 a/t); the
 * asymptotic series is used beyond, as for every table. Up to 64x less FFT work than the full
 * grid, and H only: cc_kernel_table_eval with a non-NULL h1 returns CC_ERR_ARGUMENT. Fails
 * with CC_ERR_ACCURACY where the short period or range misses the accuracy target (then use a
 * larger u_range or the full grid). The _stack form takes cc_kernel_table_create_stack's
 * arguments (u in units of the total thickness); one bonded layer gives the film's table. */
int cc_kernel_table_create_range(double e1, double nu1, double e0, double nu0,
                                 int substrate_rigid, double u_range, cc_kernel_table **table);
int cc_kernel_table_create_stack_range(int n_layers, const double *thickness,
                                       const double *youngs, const double *poisson,
                                       const int *slip_below, int base_rigid, double e_base,
                                       double nu_base, double u_range, cc_kernel_table **table);

/* (added) The tables of cc_kernel_table_create_ex and cc_kernel_table_create_stack without
 * H1, for callers that evaluate H alone (the solver): H, the info and the accuracy are those
 * tables' bit for bit, at the cost of the DCT alone (the DST-I of H1 and its FFTW planning are
 * skipped); cc_kernel_table_eval with a non-NULL h1 returns CC_ERR_ARGUMENT. */
int cc_kernel_table_create_h(double e1, double nu1, double e0, double nu0, int substrate_rigid,
                             int grid_variant, cc_kernel_table **table);
int cc_kernel_table_create_stack_h(int n_layers, const double *thickness, const double *youngs,
                                   const double *poisson, const int *slip_below, int base_rigid,
                                   double e_base, double nu_base, int grid_variant,
                                   cc_kernel_table **table);

/* Number of grid variants (4). */
int cc_kernel_grid_variants(void);

/* Largest refinement of a stack's table grid (32): a stack table needs a top layer of at
 * least T / cc_kernel_stack_max_refinement() (thinner ones report CC_ERR_ACCURACY). */
int cc_kernel_stack_max_refinement(void);

/* H(u[i]) and H1(u[i]) for any real u (H even, H1 odd); h1 may be NULL (then H alone is
 * evaluated; a compact table, cc_kernel_table_create_range, requires NULL).
 * Beyond the tabulated range the asymptotic expansion in 1/u^2 is used. */
int cc_kernel_table_eval(const cc_kernel_table *table, int n, const double *u,
                         double *h, double *h1);

/* Facts about a table: the tabulated range [0, u_max], grid step du, C(0), the sum-rule
 * value int_0^inf H du = (pi/2)(C(0)-1), and the estimated absolute accuracy of H. */
int cc_kernel_table_info(const cc_kernel_table *table, double *u_max, double *du,
                         double *c_zero, double *half_integral, double *abs_accuracy);

/* Scale of the table: max |H| over the tabulated range, and the decay rate b of the
 * subtracted analytic part s(q) = exp(-bq)(c0 + c1 q + c3 q^3 + c5 q^5) (diagnostic).
 * Null output pointers are skipped (also in cc_kernel_table_info). */
int cc_kernel_table_scale(const cc_kernel_table *table, double *max_abs_h, double *decay_rate);

#ifdef __cplusplus
}
#endif
#endif
