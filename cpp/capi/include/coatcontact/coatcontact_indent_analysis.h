/*
 * coatcontact: Oliver–Pharr and the film's modulus through the C interface (included by
 * coatcontact.h). Implemented in cpp/capi/capi_indent_analysis.cpp over oliver_pharr.hpp and
 * indent_film.hpp (THEORY.md section 16). Works on plain arrays (a test as read by
 * cc_indent_read, or any other), so that a binding need not keep the file's handle.
 *
 * A result is a table: named columns of equal length ("depth" [m], "modulus" [Pa], ...) and
 * named scalars ("E_mean" [Pa], ...); names and units are listed in docs/indentation.md and
 * by cc_indent_result_column_name. Status, errors and thread safety as in coatcontact.h.
 */
#ifndef COATCONTACT_COATCONTACT_INDENT_ANALYSIS_H
#define COATCONTACT_COATCONTACT_INDENT_ANALYSIS_H

#include "coatcontact/cc_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* One test in SI: depth [m], load [N] (required), stiffness [N/m] (CSM; NULL if none),
 * hardness [Pa] (the vendor's; NULL if none), each of `points` values; the file's area
 * function (C0.. of A [nm^2] in h_c [nm]), the sample's Poisson ratio and averaging range [m]
 * (NaN where not stated). */
typedef struct cc_indent_data {
  const double *depth, *load, *stiffness, *hardness;
  long points;
  const double *area_coefficients;
  long area_count;
  double poisson, range_min, range_max;
} cc_indent_data;

/* Oliver–Pharr options; cc_indent_options_default fills the defaults (the data's area and
 * Poisson ratio, diamond 1141 GPa / 0.07, beta 1, epsilon 0.75, no frame correction, the
 * data's range, stiffness from CSM when present, unloading fit 0.5–0.95 P_max). */
typedef struct cc_indent_options {
  const double *area_coefficients; /* NULL / 0: the data's */
  long area_count;
  int area_from_hardness; /* A = P/H */
  int rigid_indenter;
  double indenter_modulus, indenter_poisson;
  double poisson; /* NaN: the data's */
  double beta, epsilon;
  double frame_stiffness; /* N/m; NaN: none */
  double depth_min, depth_max; /* m; NaN: the data's range, else all */
  int stiffness; /* 0 auto, 1 CSM, 2 unloading */
  double unload_lower, unload_upper;
} cc_indent_options;
void cc_indent_options_default(cc_indent_options *options);

/* The sample of the film analysis: layers top first as (thickness [m], E [Pa], nu) triples;
 * the top is the film, whose modulus (or thickness) is the unknown (its given value unused). */
typedef struct cc_indent_film_options {
  const double *layers;
  long layer_count;
  int substrate_rigid;
  double substrate_modulus, substrate_poisson;
  int solve_thickness;  /* 0: the film's modulus; 1: its thickness (modulus given) */
  const char *model;    /* "exact" (default) or an empirical model's name */
  double alpha;         /* NaN: fitted over the range */
  int coated_contact_depth;
  long max_points;      /* default 200 */
  double tolerance;     /* of the reduced variables, default 1e-8 */
} cc_indent_film_options;
void cc_indent_film_options_default(cc_indent_film_options *options);

typedef struct cc_indent_result cc_indent_result;

/* Columns: depth, load, stiffness, contact_depth, area, contact_radius, reduced_modulus,
 * modulus, hardness, in_range (1/0). Scalars: E_mean, E_sd, H_mean, H_sd [Pa], range_points,
 * range_min, range_max [m] (range_max inf: to the end), poisson, dropped, csm (1/0); unloading:
 * unload_alpha, unload_final_depth, unload_exponent, unload_stiffness. */
int cc_indent_analyse(const cc_indent_data *data, const cc_indent_options *options, cc_indent_result **result);

/* Columns: depth, load, stiffness, contact_depth, contact_radius, a_over_t, E_apparent (the
 * composite's Oliver–Pharr E), value (E_film [Pa] or thickness [m]), value_error, in_range,
 * delivered (1/0; value 0 where not). Scalars: mean, mean_error, points, rms_relative, alpha
 * (NaN unless an empirical alpha), range_min, range_max. */
int cc_indent_film(const cc_indent_data *data, const cc_indent_options *options,
                   const cc_indent_film_options *film, cc_indent_result **result);

void cc_indent_result_destroy(cc_indent_result *result);
int cc_indent_result_rows(const cc_indent_result *result, long *rows);
int cc_indent_result_column_count(const cc_indent_result *result, long *count);
int cc_indent_result_column_name(const cc_indent_result *result, long column, const char **name);
/* Copies column `name` into values[0..capacity); *length: the row count. */
int cc_indent_result_column(const cc_indent_result *result, const char *name, double *values, long capacity,
                            long *length);
int cc_indent_result_scalar_count(const cc_indent_result *result, long *count);
int cc_indent_result_scalar(const cc_indent_result *result, long entry, const char **name, double *value);

#ifdef __cplusplus
}
#endif

#endif /* COATCONTACT_COATCONTACT_INDENT_ANALYSIS_H */
