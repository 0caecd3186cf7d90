/*
 * coatcontact: the C interface of the library (stack, reduced solver, adhesive sphere,
 * contact in SI units, fit). Language bindings bind to this header. Implemented in
 * cpp/capi/capi.cpp (library coatcontact_capi).
 *
 * Objects are opaque handles, created by cc_*_create and released by cc_*_destroy (NULL is
 * accepted). A handle keeps alive what it was made from: a solver, model or contact may be
 * destroyed in any order, and a stack may be destroyed once a solver was created from it.
 *
 * Status and errors. Every function except the destroyers returns a status: CC_OK,
 * CC_INPUT_ERROR (a value outside its allowed range, a NULL pointer, an unsupported feature),
 * CC_NUMERICAL_ERROR (the requested accuracy could not be met: never silently wrong numbers)
 * or CC_INTERNAL_ERROR (out of memory, unexpected failure). On failure nothing is written
 * through any output pointer (handles, arrays, structs keep their previous contents), and
 * cc_last_error_message() says what went wrong; on success that message is "". No C++
 * exception crosses this interface.
 *
 * Thread safety. The error message is per thread. A stack or a reduced solver may be used
 * from several threads at once once created (they are read-only). An adhesive model and the
 * contacts made from it fill an interpolation cache lazily: use a model, and every contact
 * made from it, from one thread at a time. cc_fit builds everything it needs per call.
 *
 * Units and normalization (THEORY.md sections 1 and 5). Moduli in Pa (or any consistent
 * unit), lengths in m, forces in N, compressive positive. The reference modulus E* of every
 * normalization is the top layer's plane-strain modulus E/(1 - nu^2). With the sphere
 * radius R, work of adhesion w and coating thickness t, the Maugis scales are
 *   l = (pi w R^2/E*)^(1/3),  a = a_bar l,  t = eta l,  delta = D l^2/R,  F = P pi w R.
 */
#ifndef COATCONTACT_COATCONTACT_H
#define COATCONTACT_COATCONTACT_H

#include "coatcontact/cc_status.h"
#include "coatcontact/coatcontact_indent.h" /* nanoindentation files: cc_indent_* */
#include "coatcontact/coatcontact_indent_analysis.h" /* Oliver-Pharr and the film: cc_indent_analyse, cc_indent_film */
#include "coatcontact/coatcontact_afm.h" /* AFM force curves: reading, preprocessing, fit, batch (cc_afm_*) */

#ifdef __cplusplus
extern "C" {
#endif

/* Message of the last failure in the calling thread ("" after a success); valid until the
 * thread's next call into this interface. */
const char *cc_last_error_message(void);

/* Progress and interruption of long calls (sweeps of radii, curves, pull-offs): `hook`, if
 * not NULL, is called by the calling thread's later calls, on that thread, between units of
 * work (one radius, one pull-off) with the units done and the total of the current sweep
 * (a call may run several sweeps). A non-zero return stops the call: it returns
 * CC_INTERRUPTED. Set per thread; NULL removes it. In a process forked from the one that
 * loaded the library, sweeps run serially (an OpenMP runtime does not survive fork). */
typedef int (*cc_progress_hook)(void *user, long done, long total);
void cc_set_progress_hook(cc_progress_hook hook, void *user);

/* ---- stack: the elastic system (THEORY.md sections 1, 9, 12) ----------------------------
 *
 * Layers are added top first; thicknesses are in any unit, only their ratios enter (the
 * contact and the fit take the coating's total thickness T in m). 1 to 1000 layers, each
 * bonded (slip_below = 0) or sliding without friction on what lies below (section 12), and a
 * rigid or elastic indenter. Normalization (section 12): lengths by the TOTAL thickness T
 * (q = k T, a/T, eta), moduli by the TOP layer's E*. Each setter checks its
 * values at once with the library's rules and leaves the stack unchanged on failure; the
 * whole stack is checked again when used (a layer and a substrate are required). A new
 * stack has no layer, no substrate and a rigid indenter. */
typedef struct cc_stack cc_stack;

int cc_stack_create(cc_stack **stack);
void cc_stack_destroy(cc_stack *stack);
/* slip_below != 0: the interface below this layer slides without friction (below the last
 * layer on a rigid base: a frictionless rigid base, u_z = 0 and s_rz = 0). */
int cc_stack_add_layer(cc_stack *stack, double thickness, double youngs_modulus,
                       double poisson_ratio, int slip_below);
int cc_stack_set_substrate(cc_stack *stack, double youngs_modulus, double poisson_ratio);
int cc_stack_set_rigid_substrate(cc_stack *stack);
/* An elastic indenter (THEORY.md section 9): the reference modulus becomes E_r,
 * 1/E_r = 1/E1* + 1/E2*, and every normalized result uses it. */
int cc_stack_set_indenter(cc_stack *stack, double youngs_modulus, double poisson_ratio);
int cc_stack_set_rigid_indenter(cc_stack *stack);
/* E* of the normalizations: the top layer's E/(1 - nu^2), or E_r with an elastic indenter. */
int cc_stack_reference_modulus(const cc_stack *stack, double *reference_modulus);

/* ---- reduced solver (THEORY.md sections 4-5) --------------------------------------------
 *
 * For a contact radius over coating thickness a/t in (0, 1e8], one row of
 * CC_REDUCED_COLUMNS doubles, the columns of `coatcontact reduced`:
 *   0 a_over_t  1 Pi_s  2 Delta_s  3 Pi_c  4 Delta_c  5 E_eq  6 Gamma1  7 error_estimate
 * The error estimate bounds the largest relative error of columns 1-6; it is <= tolerance
 * whenever the status is CC_OK. Tolerance 0 means the default 1e-8; otherwise it must lie
 * in [1e-13, 1e-1]. Creating a solver builds the stack's kernel table (a few ms). */
#define CC_REDUCED_COLUMNS 8
typedef struct cc_reduced_solver cc_reduced_solver;

int cc_reduced_solver_create(const cc_stack *stack, cc_reduced_solver **solver);
void cc_reduced_solver_destroy(cc_reduced_solver *solver);
int cc_reduced_solver_solve(const cc_reduced_solver *solver, double a_over_t, double tolerance,
                            double out[CC_REDUCED_COLUMNS]);
/* n radii (may run in parallel); out has n * CC_REDUCED_COLUMNS doubles, row by row. */
int cc_reduced_solver_sweep(const cc_reduced_solver *solver, int n, const double *a_over_t,
                            double tolerance, double *out);

/* ---- adhesive sphere, normalized (THEORY.md section 5, [EqSolNormF, EqSolNormD]) ---------
 *
 * JKR contact of a rigid sphere: the reduced variables are solved at `tolerance` (0: the
 * default 1e-8; else [1e-13, 1e-1]) on Chebyshev nodes and interpolated. eta and a_bar must
 * lie in [1e-6, 1e6]. Not thread-safe (lazy cache, see above). */
typedef struct cc_adhesive_model cc_adhesive_model;

#define CC_CURVE_COLUMNS 4 /* a_bar, a_over_t = a_bar/eta, P, D */

int cc_adhesive_model_create(const cc_reduced_solver *solver, double tolerance,
                             cc_adhesive_model **model);
void cc_adhesive_model_destroy(cc_adhesive_model *model);
/* The default a_bar range of a curve, both JKR limits included:
 * [0.01 min(1, r), 10 max(1, r)], r = (E* / E_base*)^(1/3) (1 for a rigid base). */
int cc_adhesive_default_range(const cc_adhesive_model *model, double range[2]);
/* n >= 1 points; out has n * CC_CURVE_COLUMNS doubles, row by row. */
int cc_adhesive_curve(cc_adhesive_model *model, double eta, int n, const double *a_bar,
                      double *out);

/* Pull-off: the minimum of P over a_bar (load control) and of D (displacement control),
 * searched over [1e-3 min(1, r), 10 max(1, r)]. Homogeneous limit: P = -3/2 and -5/6.
 * out: 0 P_load  1 a_bar_load  2 D_load  3 P_disp  4 a_bar_disp  5 D_disp.
 * flags (may be NULL) receives a bitmask of the warnings below, 0 when both minima are
 * single and interior. */
#define CC_PULLOFF_COLUMNS 6
#define CC_PULLOFF_LOAD_SEVERAL_MINIMA 1 /* the lowest local minimum is reported */
#define CC_PULLOFF_LOAD_NO_MINIMUM 2     /* no interior minimum: a range end is reported */
#define CC_PULLOFF_DISP_SEVERAL_MINIMA 4
#define CC_PULLOFF_DISP_NO_MINIMUM 8
#define CC_PULLOFF_SCAN_TRUNCATED 16 /* solver failed at large a/t; a lower minimum may lie above */

int cc_pulloff(cc_adhesive_model *model, double eta, double out[CC_PULLOFF_COLUMNS], int *flags);
/* Before the cc_pulloff calls of a list of n etas (as `coatcontact pulloff --eta LIST`): for
 * n >= 2 builds one verified table over the a/t they scan, which cc_pulloff then reads for every
 * eta in [min, max] of the list, until the next cc_pulloff_prepare (THEORY.md section 5,
 * "Pull-off sweeps"); n < 2, or a table the solver cannot build: cc_pulloff stays on the model's
 * own table. */
int cc_pulloff_prepare(cc_adhesive_model *model, int n, const double *eta);

/* ---- contact in SI units (THEORY.md section 5) -------------------------------------------
 *
 * A sphere of radius R [m] on a coating of total thickness t [m] with work of adhesion
 * w [J/m^2], all finite and > 0, with eta = t/l in [1e-6, 1e6]. A contact uses its model's
 * cache: the model's thread rule applies to it. */
typedef struct cc_contact cc_contact;

#define CC_CONTACT_COLUMNS 3 /* a [m], delta [m], F [N] */

int cc_contact_create(cc_adhesive_model *model, double sphere_radius, double thickness,
                      double work_of_adhesion, cc_contact **contact);
void cc_contact_destroy(cc_contact *contact);
/* 0 l [m]  1 l^2/R [m]  2 pi w R [N]  3 eta */
int cc_contact_scales(const cc_contact *contact, double out[4]);
/* n >= 1 points log-spaced over the model's default a_bar range (the last one exactly at its
 * end); out has n * CC_CONTACT_COLUMNS doubles, row by row. */
int cc_contact_curve(cc_contact *contact, int n, double *out);
/* The same columns at n given contact radii a [m]. */
int cc_contact_at(cc_contact *contact, int n, const double *a, double *out);
/* out: 0 F_load [N]  1 a_load [m]  2 delta_load [m]  3 F_disp  4 a_disp  5 delta_disp;
 * flags as for cc_pulloff (may be NULL). */
int cc_contact_pulloff(cc_contact *contact, double out[CC_PULLOFF_COLUMNS], int *flags);
/* The validity limits of the library (coatcontact/limits.hpp: a > 0.1 R, a past R, delta > t,
 * mean pressure > 0.1 E*) against n rows of a curve (CC_CONTACT_COLUMNS each, as cc_contact_at
 * gives). *warnings is set to a per-thread text with one message per line, "" when the curve
 * stays inside every limit; it stays valid until the next call of this function in the thread. */
int cc_contact_validity(const cc_contact *contact, int n, const double *rows, const char **warnings);

/* ---- fit of measured data (coatcontact/fit.hpp) -------------------------------------------
 *
 * Least squares of (a, F) or (delta, F) data against the model of the stack's top layer on
 * its base; residuals in force. Free parameters: a non-empty mask of CC_FIT_FREE_*; the others
 * are fixed at their start value (E1 is the stack's top-layer modulus). The solver tolerance
 * of the fit's lattice is 1e-8. CC_NUMERICAL_ERROR when the fit does not converge, the
 * parameters are not identifiable, or the model does not describe the data (R^2 < 0.5). */
enum cc_fit_kind { CC_FIT_RADIUS_FORCE = 0, CC_FIT_PENETRATION_FORCE = 1 };
enum cc_fit_parameter { CC_FIT_WORK = 0, CC_FIT_THICKNESS = 1, CC_FIT_FILM_MODULUS = 2 };
#define CC_FIT_FREE_WORK (1u << CC_FIT_WORK)
#define CC_FIT_FREE_THICKNESS (1u << CC_FIT_THICKNESS)
#define CC_FIT_FREE_FILM_MODULUS (1u << CC_FIT_FILM_MODULUS)

typedef struct cc_fit_result {
  double value[3];          /* w [J/m^2], t [m], E1 [Pa], indexed by cc_fit_parameter */
  double standard_error[3]; /* 0 for fixed parameters */
  double correlation[9];    /* row-major 3 x 3; 1 on the diagonal, 0 for fixed parameters */
  unsigned free_mask;
  int points;
  double residual_norm;  /* sqrt(RSS) [N] */
  double residual_sigma; /* sqrt(RSS/(n - free parameters)) [N] */
  double r_squared;
  int iterations;
  int converged;
  /* The displacement-controlled pull-off of the fitted model: a_c [m], delta_c [m], F_c [N]. */
  double displacement_pulloff[3];
} cc_fit_result;

/* x: a [m] (> 0) for CC_FIT_RADIUS_FORCE, delta [m] for CC_FIT_PENETRATION_FORCE; force [N].
 * One film: a stack of more than one layer is refused (CC_INPUT_ERROR; see cc_fit_stack). */
int cc_fit(const cc_stack *stack, int kind, int n, const double *x, const double *force,
           double sphere_radius, double thickness_start, double work_start, unsigned free_mask,
           cc_fit_result *out);

/* The same fit on every layer of a stack. The stack's layer thicknesses are lengths [m]; they
 * and the layers' moduli are the fixed values, or the hints of the free ones. free_names:
 * comma-separated, from w, h1..hN, E1..EN (layers top first; one layer: t or h1).
 * values, standard_errors: parameter_count = 1 + 2N entries in the order w, h1..hN, E1..EN
 * (standard error 0 for a fixed parameter); residual_sigma (may be NULL): sqrt(RSS/(n-p)) [N]. */
int cc_fit_stack(const cc_stack *stack, int kind, int n, const double *x, const double *force,
                 double sphere_radius, double work_start, const char *free_names, int parameter_count,
                 double *values, double *standard_errors, double *residual_sigma);

/* ---- spring control (THEORY.md section 10) ---------------------------------------------
 * Pull-off through a spring of normalized stiffness k_bar = k (pi^2 w^2 R/E*^2)^(1/3)/(pi w R):
 * the minimum of Z = D + P/k_bar. k_bar = 0 is load control, INFINITY displacement control.
 * out: P, a_bar, D at the jump; flags: CC_PULLOFF_LOAD_SEVERAL_MINIMA or _NO_MINIMUM bits. */
int cc_pulloff_spring(cc_adhesive_model *model, double eta, double k_bar, double out[3], int *flags);

/* ---- Maugis-Dugdale cohesive zone (THEORY.md section 13) -------------------------------
 * lambda = 2 sigma0 (R/(pi w K^2))^(1/3), K = (4/3) E*, > 0; the sphere, a rigid indenter.
 * cc_md_model_create: values from the reduced table of the cohesive zone (THEORY.md section 13,
 * "The cohesive zone as a table"), its tiles built on first use and kept by the model, each
 * value within its error estimate of the direct solve; outside the table (a/t beyond
 * [1e-4, 1e2] or c/t > 1e4) the direct solve. cc_md_model_create_direct: the direct
 * per-radius solve everywhere (the reference, the command line's --md-direct; no cache).
 * Either model may be shared across threads. */
typedef struct cc_md_model cc_md_model;
#define CC_MD_CURVE_COLUMNS 5   /* a_bar, a_over_t, m = c/a, P, D */
#define CC_MD_PULLOFF_COLUMNS 8 /* P_load, a_bar_load, D_load, m_load, P_disp, a_bar_disp, D_disp, m_disp */
#define CC_MD_PULLOFF_ERROR_COLUMNS 2 /* P_load_err, D_disp_err: error estimates of the two minima */
/* The error estimate of each of the CC_MD_PULLOFF_COLUMNS values, in their order (0 for m at
 * the end of the curve, where it is infinite). */
#define CC_MD_PULLOFF_ALL_ERROR_COLUMNS 8
int cc_md_model_create(const cc_stack *stack, cc_md_model **model);
int cc_md_model_create_direct(const cc_stack *stack, cc_md_model **model);
void cc_md_model_destroy(cc_md_model *model);
/* a_bar >= 0 (0: the end of the curve, a -> 0, where m is INFINITY). */
int cc_md_curve(const cc_md_model *model, double eta, double lambda, int n, const double *a_bar,
                double *out);
/* flags bit 1: the displacement-controlled pull-off is the end of the curve (a -> 0). */
int cc_md_pulloff(const cc_md_model *model, double eta, double lambda,
                  double out[CC_MD_PULLOFF_COLUMNS], int *flags);
/* cc_md_pulloff plus the error estimates of P_load and D_disp (the table's, or the direct
 * solve's own ~1e-11 relative); errors may be NULL. */
int cc_md_pulloff_errors(const cc_md_model *model, double eta, double lambda,
                         double out[CC_MD_PULLOFF_COLUMNS], double errors[CC_MD_PULLOFF_ERROR_COLUMNS],
                         int *flags);
/* cc_md_pulloff plus the error estimate of every value (THEORY.md section 13, the pull-off's
 * location included); errors may be NULL. */
int cc_md_pulloff_all_errors(const cc_md_model *model, double eta, double lambda,
                             double out[CC_MD_PULLOFF_COLUMNS], double errors[CC_MD_PULLOFF_ALL_ERROR_COLUMNS],
                             int *flags);

/* ---- indenters of any axisymmetric shape, SI units (THEORY.md section 11) --------------
 * Lengths in m, angles (half included angle beta) in radians, in (0, pi/2). */
typedef struct cc_shape cc_shape;
int cc_shape_paraboloid(double radius, cc_shape **shape);
int cc_shape_cone(double beta, cc_shape **shape);
/* Four-sided pyramid of face half angle theta (the CLI's pyramid:THETA), as the cone of equal
 * area, tan(beta) = 2 tan(theta)/sqrt(pi) (THEORY.md section 11). */
int cc_shape_pyramid(double theta, cc_shape **shape);
int cc_shape_flat_punch(double radius, cc_shape **shape);
/* z = r^n / (n R^(n-1)), n > 0. */
int cc_shape_power_law(double n, double radius, cc_shape **shape);
/* Spherical cap of radius R tangent to the cone of half angle beta. */
int cc_shape_blunted_cone(double radius, double beta, cc_shape **shape);
/* Measured profile z(r): n points, r[0] = 0, r increasing, z non-decreasing. */
int cc_shape_profile(int n, const double *r, const double *z, cc_shape **shape);
void cc_shape_destroy(cc_shape *shape);

typedef struct cc_shape_contact cc_shape_contact;
#define CC_SHAPE_CURVE_COLUMNS 5    /* a, delta, F, delta_H, F_H ([m], [m], [N], [m], [N]) */
#define CC_SHAPE_PULLOFF_COLUMNS 9  /* F, a, delta under load, displacement, spring control */
/* Film (coating) thickness [m] and work of adhesion [J/m^2]; tolerance 0: default. */
int cc_shape_contact_create(const cc_stack *stack, const cc_shape *shape, double thickness,
                            double work_of_adhesion, double tolerance, cc_shape_contact **contact);
void cc_shape_contact_destroy(cc_shape_contact *contact);
/* range[0..1]: contact radii [m] holding both JKR pull-offs (film and base modulus). */
int cc_shape_contact_default_range(const cc_shape_contact *contact, double range[2]);
int cc_shape_contact_curve(const cc_shape_contact *contact, int n, const double *a, double *out);
/* The validity limits (as cc_contact_validity; a paraboloid's are a sphere's of its radius) against
 * n rows of cc_shape_contact_curve (CC_SHAPE_CURVE_COLUMNS each). *warnings: per-thread text, one
 * message per line, "" inside every limit, valid until the next call of this function. */
int cc_shape_contact_validity(const cc_shape_contact *contact, int n, const double *rows, const char **warnings);
/* spring_stiffness k [N/m] (0: none; the spring columns are then 0). */
int cc_shape_contact_pulloff(const cc_shape_contact *contact, double spring_stiffness,
                             double out[CC_SHAPE_PULLOFF_COLUMNS]);

/* ---- arrays point by point -------------------------------------------------------------
 * The _each variants of the array calls return every point they can instead of failing the
 * whole array (the calls above stop at the first point that fails). status (n ints) receives,
 * per point, CC_OK (delivered) or CC_NUMERICAL_ERROR (its tolerance cannot be met; its row
 * holds its input coordinates and zeros, never NaN), and cc_point_reasons() the reasons: n
 * lines, one per point in order, empty for a delivered point (per-thread text, valid until
 * the thread's next _each call). The call returns CC_OK when every point was processed and at
 * least one delivered, CC_NUMERICAL_ERROR (nothing written; the message is the first
 * point's reason) when none was; bad input fails the whole call as in the strict calls. */
int cc_reduced_solver_sweep_each(const cc_reduced_solver *solver, int n, const double *a_over_t,
                                 double tolerance, double *out, int *status);
int cc_adhesive_curve_each(cc_adhesive_model *model, double eta, int n, const double *a_bar,
                           double *out, int *status);
int cc_contact_at_each(cc_contact *contact, int n, const double *a, double *out, int *status);
int cc_shape_contact_curve_each(const cc_shape_contact *contact, int n, const double *a, double *out,
                                int *status);
const char *cc_point_reasons(void);

/* ---- the fit with every model of `coatcontact fit` (coatcontact/fit.hpp) -----------------
 * Data: (a, F), (delta, F), or (z, F) with z = delta + F/k the base displacement of a sphere on
 * a spring k. Models: JKR on the sphere, any shape (cc_shape), Maugis-Dugdale (lambda), the
 * loading and unloading branches with their own w (free_names with w_load,w_unload). The
 * stack's layer thicknesses are lengths [m]; they and the moduli are the fixed values or the
 * hints of the free ones. Everything zero or NULL that is not needed. */
#define CC_FIT_BASE_FORCE 2 /* kind: (z, F), z = delta + F/k through the spring of spring_stiffness */
enum cc_fit_model { CC_FIT_JKR = 0, CC_FIT_MAUGIS_DUGDALE = 1 };
typedef struct cc_fit_request {
  int kind;                  /* CC_FIT_RADIUS_FORCE, CC_FIT_PENETRATION_FORCE or CC_FIT_BASE_FORCE */
  int n;                     /* data points */
  const double *x;           /* a, delta or z [m] */
  const double *force;       /* F [N], compressive positive */
  const double *sigma_x;     /* standard uncertainty of each x [m], or NULL */
  const double *sigma_force; /* of each F [N], or NULL (neither: an unweighted fit) */
  const int *unloading;      /* per point 1 on the unloading branch, 0 loading; NULL: the rows after
                                the largest x (read only with w_load,w_unload free) */
  double sphere_radius;      /* R [m] (unused with a shape) */
  const cc_shape *shape;     /* NULL: the sphere */
  const char *free_names;    /* comma-separated, from cc_fit_parameter_names ("w", "w,t,E1",
                                "w_load,w_unload", "w,k", "w,lambda", "w,h2,E1", ...) */
  double work;               /* w [J/m^2]: fixed, or hint; 0: the library's start value */
  double unload_work;        /* w_unload hint; 0: as work */
  double spring_stiffness;   /* k [N/m]: the spring of (z, F) data (hint if k is free); for other
                                data > 0 reports the pull-off through it; 0: none */
  int model;                 /* CC_FIT_JKR or CC_FIT_MAUGIS_DUGDALE */
  double lambda;             /* Maugis's lambda: fixed, or hint; 0: 1 */
  int bootstrap;             /* residual-bootstrap refits (0: none) */
  unsigned long seed;        /* of the bootstrap resampling (0: 1) */
} cc_fit_request;

typedef struct cc_fit_summary {
  int parameter_count;
  int points;
  int iterations;
  int weighted;              /* sigmas were given: chi2_per_dof is meaningful */
  double residual_norm;      /* sqrt(RSS) [N] */
  double residual_sigma;     /* sqrt(RSS/(n - free parameters)) [N] */
  double r_squared;
  double chi2_per_dof;
  int has_load_pulloff;      /* the pull-offs of the fitted model: F [N], a [m], delta [m] */
  double load_pulloff[3];
  int has_displacement_pulloff;
  double displacement_pulloff[3];
  int has_spring_pulloff;
  double spring_pulloff[3];
  int bootstrap_samples;     /* refits that converged */
} cc_fit_summary;

/* The parameters of `request` on `stack`, comma-separated in the order of cc_fit_run's arrays,
 * into names (size bytes with the final NUL); count (may be NULL): how many. */
int cc_fit_parameter_names(const cc_stack *stack, const cc_fit_request *request, char *names, int size,
                           int *count);
/* values, standard_errors, start (hints and fixed values; may be NULL): parameter_count doubles;
 * correlation (may be NULL): parameter_count^2, row-major; interval68, interval95 (may be NULL):
 * 2 parameter_count doubles, low and high of each (bootstrap); model_force, model_x (may be
 * NULL): n doubles, the model's F and contact radius a [m] at each point. */
int cc_fit_run(const cc_stack *stack, const cc_fit_request *request, int parameter_count, double *values,
               double *standard_errors, double *start, double *correlation, double *interval68,
               double *interval95, double *model_force, double *model_x, cc_fit_summary *summary);

/* ---- measured force curves (coatcontact/measured_curve.hpp) -------------------------------
 * A data file (TSV/CSV, '#' comments, "# units:" or units in column names) read into SI. columns
 * as the CLI's --columns: "a,F", "delta,F", "z,F" or "a=2,F=5,sigma_F=6,branch=7". */
typedef struct cc_curve cc_curve;
enum cc_curve_column { CC_CURVE_X = 0, CC_CURVE_F = 1, CC_CURVE_SIGMA_X = 2, CC_CURVE_SIGMA_F = 3,
                       CC_CURVE_BRANCH = 4, CC_CURVE_LINE = 5 };
int cc_curve_read(const char *path, const char *columns, cc_curve **curve);
void cc_curve_destroy(cc_curve *curve);
/* Rows; the kind (CC_FIT_RADIUS_FORCE, CC_FIT_PENETRATION_FORCE or CC_FIT_BASE_FORCE). */
int cc_curve_size(const cc_curve *curve, int *rows, int *kind);
/* The column's values (rows doubles); CC_INPUT_ERROR when the file has no such column. */
int cc_curve_column(const cc_curve *curve, int column, double *out);
/* The units as read ("a um, F mN (from the '# units:' line)"), into text (size bytes). */
int cc_curve_units(const cc_curve *curve, char *text, int size);

/* ---- crack kinetics at the JKR edge (THEORY.md section 14; coatcontact/crack_kinetics.hpp) ----
 *
 * A sphere (radius R) or a cone (half included angle beta) on the stack, whose total thickness
 * is the coating's; the edge obeys G - w = w (|v|/v*)^n receding, w - G = w (v/v_a*)^n_adv
 * advancing; the base moves through a spring (F = k (z - delta); k = 0 load control, then
 * speeds are force rates in N/s; k = HUGE_VAL displacement control) along the segments, from
 * first contact; the last segment is a retract until contact is lost. */
enum cc_kinetics_tip { CC_KINETICS_SPHERE = 0, CC_KINETICS_CONE = 1 };
enum cc_kinetics_segment_kind { CC_KINETICS_APPROACH = 0, CC_KINETICS_DWELL = 1, CC_KINETICS_RETRACT = 2 };
typedef struct cc_kinetics_segment {
  int kind;            /* cc_kinetics_segment_kind */
  double speed;        /* approach, retract: m/s (N/s under load control) */
  double duration;     /* dwell: s */
  double target_force; /* approach: N to reach; retract: N to reach if has_target */
  int has_target;      /* retract: 0 runs until contact is lost */
} cc_kinetics_segment;
typedef struct cc_kinetics_setup {
  int tip;                 /* cc_kinetics_tip */
  double radius;           /* sphere: R [m] */
  double half_angle;       /* cone: beta [rad] in (0, pi/2) */
  double work;             /* w [J/m2] */
  double v_star, n;        /* receding law: v* [m/s], n > 0 */
  double v_star_adv, n_adv;/* advancing law; <= 0: the receding values */
  double spring;           /* k [N/m] >= 0, or HUGE_VAL */
  int segment_count;
  const cc_kinetics_segment *segments;
  double tolerance;        /* of the JKR table's solves; 0: the default */
} cc_kinetics_setup;

typedef struct cc_kinetics cc_kinetics; /* one finished run */
#define CC_KINETICS_COLUMNS 6           /* t [s], z [m], delta [m], a [m], F [N], G [J/m2] */
#define CC_KINETICS_EVENT_COLUMNS 6     /* pull-off F [N], t [s], a [m]; loss of contact F, t, a */
#define CC_KINETICS_SWEEP_COLUMNS 8     /* V, pull-off F, t, a, loss F, t, reduced V, reduced P */

int cc_kinetics_run(const cc_stack *stack, const cc_kinetics_setup *setup, cc_kinetics **run);
void cc_kinetics_destroy(cc_kinetics *run);
/* The number of states (rows) of the run. */
int cc_kinetics_size(const cc_kinetics *run, int *rows);
/* rows (as cc_kinetics_size gives) * CC_KINETICS_COLUMNS doubles, row by row. */
int cc_kinetics_states(const cc_kinetics *run, int rows, double *out);
int cc_kinetics_events(const cc_kinetics *run, double out[CC_KINETICS_EVENT_COLUMNS]);
/* One run per retract speed of the last segment (the part before it is simulated once); out has
 * n * CC_KINETICS_SWEEP_COLUMNS doubles, row by row. */
int cc_kinetics_sweep(const cc_stack *stack, const cc_kinetics_setup *setup, int n, const double *retract_speeds,
                      double *out);

/* The units of a setup, as the runs use them: L_a [m], L_D [m], F_s [N], t_s = L_a/v* [s], eta,
 * k_bar and the reduced drive rate per SI speed (per m/s; per N/s under load control). The
 * cone's L_a, L_D, F_s are its own (THEORY.md section 14, "The cone"). */
#define CC_KINETICS_SCALE_COLUMNS 7
int cc_kinetics_scales(const cc_stack *stack, const cc_kinetics_setup *setup,
                       double out[CC_KINETICS_SCALE_COLUMNS]);
/* The run's drive work and dissipation (reduced: in units of pi w L_a^2) and its accepted ODE steps. */
#define CC_KINETICS_ENERGY_COLUMNS 3
int cc_kinetics_energy(const cc_kinetics *run, double out[CC_KINETICS_ENERGY_COLUMNS]);

/* ---- fit of the kinetics law to force-time curves (THEORY.md section 14, fitting;
 * coatcontact/kinetics_fit.hpp) ----
 * Parameters in the order w [J/m2], v_star [m/s], n, t [m], E1 [Pa]; t starts at the stack's total
 * thickness, E1 at its top layer's modulus. The residual is each curve's points up to its
 * measured pull-off; model_force and residual are given for every point of every curve. */
#define CC_KINETICS_FIT_PARAMETERS 5
typedef struct cc_kinetics_curve {
  int segment_count;                  /* from first contact, ending with the retract */
  const cc_kinetics_segment *segments;
  double spring;                      /* k [N/m]; 0 load control, HUGE_VAL displacement control */
  int n;                              /* points */
  const double *time;                 /* s since first contact, increasing */
  const double *force;                /* N, compressive positive */
  const double *sigma_force;          /* N per point, or NULL: unweighted (all curves or none) */
} cc_kinetics_curve;
typedef struct cc_kinetics_fit_request {
  double radius;                      /* sphere R [m] */
  double work, v_star, n;             /* start values of the free ones, values of the fixed */
  double v_star_adv, n_adv;           /* advancing law; <= 0: the receding values */
  int free[CC_KINETICS_FIT_PARAMETERS]; /* non-zero: fitted */
  int curve_count;
  const cc_kinetics_curve *curves;
  double tolerance;                   /* of the JKR table's solves; 0: the default */
} cc_kinetics_fit_request;
typedef struct cc_kinetics_fit_summary {
  int points;                         /* fitted points (up to the pull-offs) */
  int iterations;
  long simulations;                   /* kinetics runs (one per curve and evaluation) */
  int weighted;                       /* sigma_force given: chi2_per_dof is meaningful */
  double r_squared, chi2_per_dof, residual_sigma;
  double seconds;                     /* wall time of the fit */
} cc_kinetics_fit_summary;
/* values, standard_errors: CC_KINETICS_FIT_PARAMETERS doubles (errors 0 for fixed ones);
 * correlation (may be NULL): CC_KINETICS_FIT_PARAMETERS^2, row-major; model_force, residual (may
 * be NULL): the sum of the curves' n doubles each. */
int cc_kinetics_fit(const cc_stack *stack, const cc_kinetics_fit_request *request, double *values,
                    double *standard_errors, double *correlation, double *model_force, double *residual,
                    cc_kinetics_fit_summary *summary);

#ifdef __cplusplus
}
#endif
#endif
