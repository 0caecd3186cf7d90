/*
 * coatcontact: AFM force curves through the C interface (included by coatcontact.h): reading
 * (every registered reader: JPK, Asylum .ibw, AFM Workshop, NT-MDT), preprocessing, the one
 * fit of a curve (afm_fit_curve, THEORY.md section 15) and the batch of many curves
 * (afm_fit_batch). Implemented in cpp/capi/capi_afm.cpp (reading, preprocessing),
 * capi_afm_fit.cpp (request, fit, result) and capi_afm_batch.cpp over
 * coatcontact/afm_readers.hpp, afm_preprocess.hpp, afm_curve_fit.hpp and afm_batch.hpp.
 *
 * Status, errors, NULL handles as in coatcontact.h: every function but the destroyers returns
 * CC_OK, CC_INPUT_ERROR (the message names the function, the argument, the value and what is
 * allowed), CC_NUMERICAL_ERROR or CC_INTERNAL_ERROR; on failure nothing is written through the
 * output pointers. Strings and arrays returned by pointer are owned by the handle and valid
 * until it is destroyed. Arrays copied into the caller's buffer take a capacity and report the
 * length (a capacity below the length is CC_INPUT_ERROR, naming both); a NULL buffer with any
 * capacity asks for the length only.
 *
 * Thread safety: a file handle (its archive) is used by one thread at a time; curves, requests,
 * fit results and batch rows are read-only once made and may be shared.
 *
 * Units SI (N, m, Pa, s). Tip position z = height + F/k decreases toward the sample; force > 0
 * is repulsive (coatcontact/force_curve.hpp).
 */
#ifndef COATCONTACT_COATCONTACT_AFM_H
#define COATCONTACT_COATCONTACT_AFM_H

#include "coatcontact/cc_status.h"

#ifdef __cplusplus
extern "C" {
#endif

struct cc_stack; /* coatcontact.h */
struct cc_shape; /* coatcontact.h */

/* ---- reading ------------------------------------------------------------------------------ */

/* The user's calibration: each value > 0 overrides the file's (and is marked "user"); 0: the
 * file's. allow_missing != 0 reads a curve whose file lacks the calibration its force needs,
 * without the force channel (for listing); 0 makes that CC_INPUT_ERROR. */
typedef struct cc_afm_calibration {
  double spring_constant; /* [N/m] */
  double sensitivity;     /* [m/V] */
  int allow_missing;
} cc_afm_calibration;

typedef struct cc_afm_file cc_afm_file;
typedef struct cc_afm_curve cc_afm_curve;

/* Opens a force-curve file (format from content and extension); calibration may be NULL. A
 * JPK archive keeps its directory open and reads each curve on demand. */
int cc_afm_open(const char *path, const cc_afm_calibration *calibration, cc_afm_file **file);
void cc_afm_file_destroy(cc_afm_file *file);
int cc_afm_file_count(const cc_afm_file *file, long *count);
/* "JPK", "Igor binary wave", ... (coatcontact::afm::file_format_name). */
int cc_afm_file_format(const cc_afm_file *file, const char **name);
/* Reads curve `index` (0..count-1) into its own handle (independent of the file's lifetime). */
int cc_afm_curve_read(const cc_afm_file *file, long index, cc_afm_curve **curve);
void cc_afm_curve_destroy(cc_afm_curve *curve);

enum cc_afm_segment_kind { CC_AFM_APPROACH = 0, CC_AFM_PAUSE = 1, CC_AFM_RETRACT = 2 };
typedef struct cc_afm_segment {
  int kind;         /* cc_afm_segment_kind */
  long begin, end;  /* point range [begin, end) in the curve's channels */
  const char *name; /* the file's own name ("extend-spm"), may be "" */
  double duration;  /* [s]; 0 when the file does not say */
} cc_afm_segment;

/* A curve from arrays (a binding's mappings and plain arrays), fitted as a file's: n points;
 * force [N]; height_piezo, height_measured [m] (at least one) and time [s] may be NULL; the
 * segments cover 0..n in order, contiguous (names may be NULL); spring_constant [N/m] > 0
 * (marked "user"), or 0 for none (the curve then has no tip position, and a fit fails with
 * flag calibration). source names the curve in messages (NULL: "arrays"). Arrays are copied. */
int cc_afm_curve_create(long n, const double *force, const double *height_piezo, const double *height_measured,
                        const double *time, long segment_count, const cc_afm_segment *segments, double spring_constant,
                        const char *source, cc_afm_curve **curve);

int cc_afm_curve_points(const cc_afm_curve *curve, long *points);
int cc_afm_curve_segment_count(const cc_afm_curve *curve, long *count);
int cc_afm_curve_segment(const cc_afm_curve *curve, long segment, cc_afm_segment *out);

/* Channels, each of the curve's point count, in this order where present: "force" [N],
 * "height_piezo" [m], "height_measured" [m], "time" [s], "segment" (segment index per point),
 * "tip_position" [m] (height + F/k; present when the curve has a force and a spring constant). */
int cc_afm_curve_channel_count(const cc_afm_curve *curve, long *count);
int cc_afm_curve_channel_name(const cc_afm_curve *curve, long channel, const char **name);
int cc_afm_curve_channel(const cc_afm_curve *curve, const char *name, double *values, long capacity, long *length);

/* Metadata as text, in this order: vendor, format, instrument, date, time, source_file, entry,
 * curve_index, curve_count, spring_constant [N/m] and spring_constant_source, sensitivity [m/V]
 * and sensitivity_source (none, file, user; numbers with 17 digits, "" when the source is none),
 * then the vendor's details in file order (keys may repeat). */
int cc_afm_curve_metadata_count(const cc_afm_curve *curve, long *count);
int cc_afm_curve_metadata_entry(const cc_afm_curve *curve, long entry, const char **key, const char **value);

/* The place of a map or QI curve; has_* 0 where the file does not say. */
typedef struct cc_afm_grid {
  int has_index;
  long index_x, index_y;
  int has_shape;
  long shape_x, shape_y;
  int has_position;
  double position_x, position_y; /* [m] */
} cc_afm_grid;
int cc_afm_curve_grid(const cc_afm_curve *curve, cc_afm_grid *grid);
/* Sets the place of a curve made by cc_afm_curve_create (a binding's curve of a map):
 * curve_index >= 0 and, from grid (may be NULL), the index (has_index) and the position
 * (has_position); the shape is ignored. Call before the curve is shared. */
int cc_afm_curve_set_place(cc_afm_curve *curve, long curve_index, const cc_afm_grid *grid);

/* ---- preprocessing (coatcontact/afm_preprocess.hpp; the CLI's --contact-point,
 * --baseline-fraction) ------------------------------------------------------------------ */

enum cc_afm_contact_method { CC_AFM_CONTACT_DEVIATION = 0, CC_AFM_CONTACT_PIECEWISE_FIT = 1 };
typedef struct cc_afm_preprocess_options {
  double baseline_fraction;  /* (0, 1): leading part of the approach fitted as baseline */
  int contact_method;        /* cc_afm_contact_method */
  double deviation_sigmas;   /* > 0: threshold in baseline sigmas */
  double piecewise_exponent; /* > 0: F ~ (z_c - z)^p of the piecewise fit */
} cc_afm_preprocess_options;
/* The library's defaults (those of the CLI and of every fit). */
int cc_afm_preprocess_defaults(cc_afm_preprocess_options *options);

typedef struct cc_afm_preprocessed {
  double baseline_offset, baseline_slope;             /* [N], [N/m]: F = offset + slope z */
  double baseline_offset_error, baseline_slope_error; /* standard errors */
  double baseline_sigma;                              /* [N] residual sigma of the baseline */
  long baseline_points;
  int contact_method;   /* as applied */
  double contact_point; /* [m] tip position */
  long contact_index;   /* point index in the curve */
} cc_afm_preprocessed;
/* options NULL: the defaults. tip_position, force_corrected (may be NULL): capacity >= the
 * curve's points. */
int cc_afm_preprocess(const cc_afm_curve *curve, const cc_afm_preprocess_options *options, cc_afm_preprocessed *out,
                      double *tip_position, double *force_corrected, long capacity);

/* The measured pull-off of a retract, the same for every model (afm_measured_pulloff): the
 * most tensile force against the free-cantilever line fitted on the last `fraction` (0, 1) of
 * the n points; found 0 with fewer than 3 baseline points or one tip position. */
typedef struct cc_afm_pulloff {
  int found;
  double force, tip_position; /* [N] (negative when adhesive), [m] */
  long index;                 /* in the arrays */
  double baseline_offset, baseline_slope; /* [N], [N/m] */
  long baseline_points;
} cc_afm_pulloff;
int cc_afm_measured_pulloff(long n, const double *tip_position, const double *force, double fraction, cc_afm_pulloff *out);

/* ---- one fit (coatcontact/afm_curve_fit.hpp: afm_fit_curve) --------------------------------
 * A request is built by setters; each checks its value at once (CC_INPUT_ERROR, the request
 * unchanged) and cc_afm_fit checks the whole (a free w without an adhesive model, E1 on a
 * half-space, ...). A new request: model hertz, no tip, no sample, free "E,contact_point,
 * baseline" (adhesive models: "E,w,contact_point,baseline,tilt"; E1 on a coating), the model's
 * segment (hertz approach, adhesive retract), baseline model tilt, the default preprocessing,
 * the file's spring constant. */
typedef struct cc_afm_request cc_afm_request;
int cc_afm_request_create(cc_afm_request **request);
void cc_afm_request_destroy(cc_afm_request *request);
/* "hertz", "jkr", "md" (or "maugis-dugdale"), "dmt". */
int cc_afm_request_set_model(cc_afm_request *request, const char *model);
/* kind "sphere" (a paraboloid of radius value [m]), "sneddon-sphere" (the exact sphere),
 * "cone" (half included angle [rad]), "pyramid" (face half angle [rad]), "pyramid3" (face angle). */
int cc_afm_request_set_tip(cc_afm_request *request, const char *kind, double value);
/* Any axisymmetric tip (coatcontact.h's cc_shape; copied). */
int cc_afm_request_set_tip_shape(cc_afm_request *request, const struct cc_shape *shape);
/* The sample as a stack (copied): no layer and an elastic substrate (E, nu) is the homogeneous
 * half-space; one layer (thickness t [m], E1, nu1) on a substrate (elastic or rigid) is a
 * coating. E, E1 and t are the values if fixed, else the centres of their searches. An
 * elastic indenter: CC_INPUT_ERROR. More layers: the top one's modulus free (as _layer, 0). */
int cc_afm_request_set_sample(cc_afm_request *request, const struct cc_stack *stack);
/* A stack of any number of layers (thicknesses [m], top first; bonded or sliding) whose layer
 * free_layer (0-based) has the free modulus, set free as E1 (cc_afm_request_set_free) and
 * named E<free_layer + 1> in the results (cc_afm_fit_parameter_name, cc_afm_fit_estimate, the
 * rows' columns; "E1" is read too); its value in the stack the fixed value or the centre of its
 * search. More than one layer: model hertz,
 * t fixed (CC_INPUT_ERROR at the fit otherwise). free_layer outside the layers: CC_INPUT_ERROR. */
int cc_afm_request_set_sample_layer(cc_afm_request *request, const struct cc_stack *stack, long free_layer);
/* Comma-separated names of the free parameters, the CLI's --free: E (half-space) or E1 and t
 * (coating), w (adhesive models), tilt, contact_point, baseline. */
int cc_afm_request_set_free(cc_afm_request *request, const char *names);
/* "approach" or "retract". */
int cc_afm_request_set_segment(cc_afm_request *request, const char *segment);
/* "tilt" (the preprocessing's slope subtracted) or "offset" (the forces as measured). */
int cc_afm_request_set_baseline_model(cc_afm_request *request, const char *model);
int cc_afm_request_set_preprocess(cc_afm_request *request, const cc_afm_preprocess_options *options);
/* The other settings by name (the CLI's options):
 *   contact_point [m], baseline [N], tilt [N/m]: the values of fixed parameters (one set for a
 *   free parameter is CC_INPUT_ERROR at the fit); w [J/m2]: the value if fixed, else the centre
 *   of its search (adhesive models; 0: from the data),
 *   spring_constant [N/m] (> 0; else the curve's), surface_force_range z0 [m] (> 0),
 *   weight_cp [m] (>= 0, hertz on a half-space), noise_sigma [N] (>= 0; 0: the baseline's),
 *   min_points (>= 1, default 5), check_jump_in (0 or 1; approach fits; default 0 for one
 *   curve, 1 in a batch, as the CLI),
 *   tip_min, tip_max [m], indentation_min, indentation_max [m], max_force [N] (the fit range;
 *   NaN removes a bound). */
int cc_afm_request_set(cc_afm_request *request, const char *name, double value);

typedef struct cc_afm_fit cc_afm_fit;
/* Fits curve with request. A curve that cannot be fitted returns CC_INPUT_ERROR (no contact,
 * missing segment or calibration, too few points) or CC_NUMERICAL_ERROR (no convergence) with
 * the message; cc_afm_last_flag() then names its flag. */
int cc_afm_fit_curve(const cc_afm_curve *curve, const cc_afm_request *request, cc_afm_fit **fit);
void cc_afm_fit_destroy(cc_afm_fit *fit);
/* The flag of the calling thread's last failed cc_afm_fit_curve ("" after a success or another
 * failure): no_contact, jump_in, no_convergence, empty_segment, missing_segment, calibration,
 * too_few_points, unreadable, bad_data. */
const char *cc_afm_last_flag(void);

/* The free parameters, in the batch's column order (E or E1, t, contact_point, baseline, w, tilt). */
int cc_afm_fit_parameter_count(const cc_afm_fit *fit, long *count);
int cc_afm_fit_parameter_name(const cc_afm_fit *fit, long parameter, const char **name, const char **unit);
/* Any parameter by name, free (its standard error) or fixed (error 0): E/E1, t, w, tilt,
 * contact_point, baseline. */
int cc_afm_fit_estimate(const cc_afm_fit *fit, const char *name, double *value, double *error);
/* "fitted", or "undetermined" / "no_detachment" (estimates kept, warnings say why). */
int cc_afm_fit_flag(const cc_afm_fit *fit, const char **flag);
/* The model's warnings, then the flag's. */
int cc_afm_fit_warning_count(const cc_afm_fit *fit, long *count);
int cc_afm_fit_warning(const cc_afm_fit *fit, long warning, const char **text);
/* The recorded steps (tip position, baseline, contact point, baseline model): name, parameters. */
int cc_afm_fit_step_count(const cc_afm_fit *fit, long *count);
int cc_afm_fit_step(const cc_afm_fit *fit, long step, const char **name, const char **parameters);

typedef struct cc_afm_fit_summary {
  long points, points_in_contact; /* fitted */
  int free_count;
  double rss, residual_sigma, chi2, chi2_per_dof, r_squared; /* [N^2], [N] */
  double reduced_modulus;  /* E* [Pa] (the film's on a coating) */
  double max_indentation;  /* [m] */
  double rating;           /* 0..10 */
  double spring_constant;  /* [N/m] as used (adhesive models), else the request's or 0 */
  double noise_sigma;      /* [N] chi2's noise */
  double tabor_mu, maugis_lambda;                    /* adhesive models, else 0 */
  double jump_off_indentation, jump_off_force;       /* the model's jump-off [m], [N] */
  int has_pulloff;         /* the measured pull-off of the retract (model-independent) */
  double pulloff_force, pulloff_position;            /* [N], [m] */
  double subtracted_tilt;  /* [N/m] the tilt step's slope (0: offset) */
  double reference_contact, reference_baseline;      /* [m], [N] the preprocessing's */
  long segment_begin, segment_end;                   /* the fitted segment's point range */
} cc_afm_fit_summary;
int cc_afm_fit_get_summary(const cc_afm_fit *fit, cc_afm_fit_summary *summary);

/* Arrays over the fitted points (summary.points): "tip_position" [m], "force" [N] (less the
 * subtracted tilt), "model_force" [N], "residual" [N] (model - data), "indentation" [m],
 * "index" (the point's index in the curve). */
int cc_afm_fit_array(const cc_afm_fit *fit, const char *name, double *values, long capacity, long *length);

/* The fit of (tip_position, force) arrays as given: no segment choice and no preprocessing
 * (the forces as measured), the request's range relative to reference_contact [m] and
 * reference_baseline [N] (afm_select), then the model (afm_fit). The request's segment,
 * baseline model and preprocessing are not used; a depth profile is CC_INPUT_ERROR. n >= 1. */
int cc_afm_fit_arrays(long n, const double *tip_position, const double *force, const cc_afm_request *request,
                      double reference_contact, double reference_baseline, cc_afm_fit **fit);

/* What a binding reports beside the summary. */
typedef struct cc_afm_fit_details {
  const char *model;          /* the registry's name: "hertz", "jkr", ... */
  const char *tip;            /* the tip in words ("paraboloid R = 1e-05 m") */
  const char *baseline_model; /* "tilt" or "offset", as applied */
  double surface_force_range; /* z0 [m] of tabor_mu and maugis_lambda */
  long profile_evaluations, solver_calls, model_evaluations;
  double seconds;             /* the fit's time */
  long model_warnings;        /* the first this many of cc_afm_fit_warning are the model's */
  double pulloff_baseline_offset, pulloff_baseline_slope; /* [N], [N/m] the pull-off's line */
  int coated;                 /* the sample has a layer */
  long free_layer;            /* the layer (0-based) whose modulus is free; 0 on a half-space */
} cc_afm_fit_details;
int cc_afm_fit_get_details(const cc_afm_fit *fit, cc_afm_fit_details *details);

/* The depth profile (afm fit --depth-profile): cc_afm_request_set(request, "depth_profile", 1)
 * makes cc_afm_fit_curve fit the curve at increasing maximum indentations too; the fit is then
 * the whole-range one. steps 0 without a profile. */
typedef struct cc_afm_depth_profile_info {
  long steps;
  int coated;
  const char *modulus_name;  /* "E", or "E1" on a coating (a stack's E<K>) */
  double thickness_fraction; /* over_thickness_fraction marks depths beyond this fraction of t */
  long warning_count;
} cc_afm_depth_profile_info;
int cc_afm_fit_depth_profile(const cc_afm_fit *fit, cc_afm_depth_profile_info *info);
/* Arrays of steps values: "depth", "max_indentation" [m], "modulus", "modulus_error",
 * "apparent_modulus", "apparent_modulus_error" [Pa], "points_in_contact",
 * "over_thickness_fraction" (0 or 1). NaN where a depth has no estimate. */
int cc_afm_fit_depth_profile_array(const cc_afm_fit *fit, const char *name, double *values, long capacity, long *length);
int cc_afm_fit_depth_profile_flag(const cc_afm_fit *fit, long step, const char **flag);
int cc_afm_fit_depth_profile_warning(const cc_afm_fit *fit, long warning, const char **text);

/* ---- the model registry (coatcontact/afm_models.hpp) ---------------------------------- */
typedef struct cc_afm_model_info {
  const char *name, *title;
  const char *aliases;              /* comma-separated, "" for none */
  const char *segment;              /* default segment: "approach" or "retract" */
  int needs_spring;                 /* fitted through the cantilever's spring constant */
  const char *default_free;         /* half-space, comma-separated */
  const char *coating_default_free; /* coating */
} cc_afm_model_info;
int cc_afm_model_count(long *count);
int cc_afm_model_get(long model, cc_afm_model_info *info);
/* The parameters of model `model` on a half-space (coated 0) or a coating (coated 1). */
int cc_afm_model_parameter_count(long model, int coated, long *count);
int cc_afm_model_parameter(long model, int coated, long parameter, const char **name, const char **unit, int *free_by_default);

/* ---- many curves (coatcontact/afm_batch.hpp: afm_fit_batch) --------------------------------
 * Every curve of the files, fitted by the request's pipeline on `jobs` threads (0: the
 * machine's cores; the rows do not depend on it). A curve that cannot be fitted is a row with
 * its flag and reason; a file that cannot be opened is CC_INPUT_ERROR, or with
 * unreadable_file_rows != 0 one flagged row. options may be NULL (every curve, all cores). The thread's progress hook (coatcontact.h) sees
 * the curves done and may interrupt (CC_INTERRUPTED). */
typedef struct cc_afm_rows cc_afm_rows;
/* What a run knows of one file (afm_survey_files): its curves (-1: not surveyed), or why it
 * cannot be read at all with its one row's flag (6 calibration, 8 unreadable). */
typedef struct cc_afm_file_survey {
  const char *path;
  long curves;
  const char *unreadable; /* "" when readable */
  int flag;
} cc_afm_file_survey;
/* Rows of each chunk of a run, in curve order, on the calling thread; the chunk handle is
 * valid during the call only. A non-zero return stops the run (CC_INTERRUPTED). */
typedef int (*cc_afm_rows_sink)(void *user, const cc_afm_rows *chunk);
typedef struct cc_afm_batch_options {
  unsigned jobs;
  int unreadable_file_rows;
  long skip;  /* the first `skip` curves of the run (over all files) are not fitted (a share of a run, a resume) */
  long count; /* at most this many curves after them; 0: all */
  /* The files' survey when the caller has it (cc_afm_survey_files; a share of a run: only the
   * files of the share are opened); survey_count 0: surveyed here, else one per file (paths unused). */
  long survey_count;
  const cc_afm_file_survey *survey;
  int keep_traces; /* each row keeps its control-plot trace (cc_afm_rows_trace) */
  /* With a sink the rows go to it chunk by chunk and the returned handle holds none. */
  cc_afm_rows_sink sink;
  void *sink_user;
} cc_afm_batch_options;
int cc_afm_fit_batch(const char *const *files, long file_count, const cc_afm_calibration *calibration,
                     const cc_afm_request *request, const cc_afm_batch_options *options, cc_afm_rows **rows);
/* The given curves (cc_afm_curve_create with cc_afm_curve_set_place, or read), each a row as a
 * curve of a file (afm_fit_curve_row), one after another on the calling thread; the progress
 * hook sees each curve. options: keep_traces, sink (jobs, skip, count, survey unused). */
int cc_afm_fit_curves(const cc_afm_curve *const *curves, long count, const cc_afm_request *request,
                      const cc_afm_batch_options *options, cc_afm_rows **rows);
void cc_afm_rows_destroy(cc_afm_rows *rows);
int cc_afm_rows_count(const cc_afm_rows *rows, long *count);
/* The estimate columns: the request's free parameters (as cc_afm_fit_parameter_name). */
int cc_afm_rows_parameter_count(const cc_afm_rows *rows, long *count);
int cc_afm_rows_parameter_name(const cc_afm_rows *rows, long parameter, const char **name, const char **unit);

typedef struct cc_afm_row {
  const char *file;
  long curve;
  int has_grid;
  long grid_x, grid_y;
  int has_position;
  double position_x, position_y; /* [m] */
  int flag;                      /* 0 fitted, ... (the batch table's numbers) */
  const char *flag_name;         /* "fitted", "no_contact", ... */
  const char *message;           /* why ("" for a fitted curve) */
  int has_estimates;             /* fitted, undetermined, no_detachment */
  double rating;
  double chi2, chi2_per_dof, residual_sigma;
  double contact_point;          /* [m] fitted or fixed */
  long points;
  int has_pulloff;
  double pulloff_force, pulloff_position;
  int has_adhesion;              /* adhesive models: tabor_mu, maugis_lambda */
  double tabor_mu, maugis_lambda;
  const char *warnings;          /* "; "-separated, "" for none */
  const double *estimates, *errors; /* parameter_count each (NULL without estimates) */
  /* Each part of the place as known (has_grid, has_position: both parts), else -1 and NaN. */
  long grid_x_or_none, grid_y_or_none;
  double position_x_or_nan, position_y_or_nan;
  int has_model_jump_off;        /* adhesive models: the model's own jump-off through the spring */
  double model_jump_off_force, model_jump_off_indentation; /* [N] above the baseline, [m] */
  int has_trace;                 /* keep_traces and a curve with data */
  double trace_contact_point;    /* [m]; NaN without estimates */
} cc_afm_row;
int cc_afm_rows_get(const cc_afm_rows *rows, long row, cc_afm_row *out);
/* A row's control-plot trace (keep_traces): "z" [m], "force" [N], "segment" (0 approach, 1
 * retract), "model" [N] (NaN off the fitted segment), "fitted" (1 fitted point, else 0). */
int cc_afm_rows_trace(const cc_afm_rows *rows, long row, const char *name, double *values, long capacity, long *length);
/* The rows of a run over files (cc_afm_fit_batch without a sink) as the CLI's `afm fit FILES
 * --output FILE` table (coatcontact/afm_batch_table.hpp: the same header, flagged count and
 * row lines, without the "# command:" line), written atomically to path. */
int cc_afm_rows_write_table(const cc_afm_rows *rows, const char *path);

/* ---- files of a run ------------------------------------------------------------------------ */
typedef struct cc_afm_file_list cc_afm_file_list;
/* The files of paths: each file, and each folder's AFM files by extension, sorted (curves -1). */
int cc_afm_expand_paths(const char *const *paths, long count, cc_afm_file_list **files);
/* Opens each file once to count its curves (afm_survey_files). A file that cannot be opened:
 * CC_INPUT_ERROR, or with tolerate != 0 an entry with its reason (a path that does not exist
 * stays CC_INPUT_ERROR). */
int cc_afm_survey_files(const char *const *files, long count, const cc_afm_calibration *calibration, int tolerate,
                        cc_afm_file_list **survey);
void cc_afm_file_list_destroy(cc_afm_file_list *files);
int cc_afm_file_list_count(const cc_afm_file_list *files, long *count);
int cc_afm_file_list_get(const cc_afm_file_list *files, long file, cc_afm_file_survey *out);

#ifdef __cplusplus
}
#endif

#endif /* COATCONTACT_COATCONTACT_AFM_H */
