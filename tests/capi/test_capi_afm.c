/* The AFM C API (cc_afm_* in coatcontact/coatcontact_afm.h, through coatcontact.h) used from C
 * on the real files of data/afm: channels bit for bit against the C++ reader, segments and
 * metadata against what the files state, the preprocessing, the spot3 fit (hertz and jkr)
 * against afm_fit_curve called directly (test_capi_afm_reference.cpp) to 1e-12, the map2x2
 * batch's rows against the one-curve fit, and the error paths (NULL handle, unknown model,
 * unknown parameter, curve index out of range, short buffer) with their status and message;
 * a two-layer stack's fit against the CLI's `afm fit --layer`.
 * Arguments: the data/afm folder, the coatcontact CLI. */
#define _POSIX_C_SOURCE 200809L /* popen */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h> /* getpid */

#include "coatcontact/coatcontact.h"

long ref_channel(const char *path, long index, const char *name, double *out, long capacity);
int ref_fit(const char *path, long index, const char *model, double radius, double out[10]);

static int failures = 0;

static void check(const char *what, int condition) {
  if (!condition) {
    ++failures;
    printf("FAIL %s (last error: %s)\n", what, cc_last_error_message());
  }
}

static int message_has(const char *fragment) { return strstr(cc_last_error_message(), fragment) != NULL; }

/* The same pipeline through two doors gives the same numbers: 1e-12 relative (the issue's
 * check; the tier for rounding amplified by a fit, although both doors run the same code). */
static void close_to(const char *what, double actual, double expected) {
  const double scale = fabs(expected) > 0.0 ? fabs(expected) : 1.0;
  if (!(fabs(actual - expected) <= 1e-12 * scale)) {
    ++failures;
    printf("FAIL %s: %.17g, expected %.17g\n", what, actual, expected);
  }
}

static cc_afm_curve *read_curve(const char *folder, const char *file, long index, char *path, size_t size) {
  snprintf(path, size, "%s/%s", folder, file);
  cc_afm_file *f = NULL;
  cc_afm_curve *curve = NULL;
  check("cc_afm_open", cc_afm_open(path, NULL, &f) == CC_OK);
  check("cc_afm_curve_read", cc_afm_curve_read(f, index, &curve) == CC_OK && curve != NULL);
  cc_afm_file_destroy(f);
  return curve;
}

static const char *metadata(const cc_afm_curve *curve, const char *wanted) {
  long count = 0;
  const char *key = NULL, *value = NULL;
  cc_afm_curve_metadata_count(curve, &count);
  for (long i = 0; i < count; ++i) {
    if (cc_afm_curve_metadata_entry(curve, i, &key, &value) == CC_OK && strcmp(key, wanted) == 0) return value;
  }
  return NULL;
}

/* Every channel of the spot3 curve equals the C++ reader's, bit for bit. */
static void reading(const char *folder) {
  char path[4096];
  cc_afm_curve *curve = read_curve(folder, "fmt-jpk-fd_spot3-0192.jpk-force", 0, path, sizeof path);
  long points = 0, length = -1, channels = 0, segments = 0;
  check("points", cc_afm_curve_points(curve, &points) == CC_OK && points > 100);
  check("length query", cc_afm_curve_channel(curve, "force", NULL, 0, &length) == CC_OK && length == points);
  double *values = malloc((size_t)points * sizeof(double));
  double *expected = malloc((size_t)points * sizeof(double));
  const char *names[] = {"force", "height_measured", "height_piezo", "time"};
  for (int k = 0; k < 4; ++k) {
    const long n = ref_channel(path, 0, names[k], expected, points);
    if (n <= 0) continue; /* the file has no such channel: the C API must not list it */
    check(names[k], cc_afm_curve_channel(curve, names[k], values, points, &length) == CC_OK && length == n &&
                        memcmp(values, expected, (size_t)n * sizeof(double)) == 0);
  }
  check("channel count", cc_afm_curve_channel_count(curve, &channels) == CC_OK && channels >= 3);
  const char *name = NULL;
  check("first channel force", cc_afm_curve_channel_name(curve, 0, &name) == CC_OK && strcmp(name, "force") == 0);
  check("tip_position", cc_afm_curve_channel(curve, "tip_position", values, points, &length) == CC_OK && length == points);
  /* A JPK single curve: extend then retract (the file's segments), covering every point. */
  check("segments", cc_afm_curve_segment_count(curve, &segments) == CC_OK && segments >= 2);
  cc_afm_segment first, last;
  check("segment 0", cc_afm_curve_segment(curve, 0, &first) == CC_OK && first.kind == CC_AFM_APPROACH && first.begin == 0);
  check("last segment", cc_afm_curve_segment(curve, segments - 1, &last) == CC_OK && last.kind == CC_AFM_RETRACT &&
                            last.end == points);
  const char *vendor = metadata(curve, "vendor");
  check("vendor JPK", vendor != NULL && strcmp(vendor, "JPK") == 0);
  const char *source = metadata(curve, "spring_constant_source");
  check("spring constant from the file", source != NULL && strcmp(source, "file") == 0);
  check("spring constant value", metadata(curve, "spring_constant") && atof(metadata(curve, "spring_constant")) > 0.0);
  /* Errors: short buffer, unknown channel, segment out of range, NULL handle. */
  check("short buffer", cc_afm_curve_channel(curve, "force", values, points - 1, &length) == CC_INPUT_ERROR &&
                            message_has("capacity") && message_has("force"));
  check("unknown channel", cc_afm_curve_channel(curve, "deflection", values, points, &length) == CC_INPUT_ERROR &&
                               message_has("'deflection'") && message_has("force"));
  check("segment out of range", cc_afm_curve_segment(curve, segments, &first) == CC_INPUT_ERROR && message_has("segment"));
  check("NULL curve", cc_afm_curve_points(NULL, &points) == CC_INPUT_ERROR && message_has("curve is NULL"));

  /* Preprocessing: defaults as the library's; the contact point lies on the approach. */
  cc_afm_preprocess_options options;
  cc_afm_preprocessed pre;
  check("defaults", cc_afm_preprocess_defaults(&options) == CC_OK && options.baseline_fraction == 0.5 &&
                        options.contact_method == CC_AFM_CONTACT_PIECEWISE_FIT);
  check("preprocess", cc_afm_preprocess(curve, &options, &pre, values, expected, points) == CC_OK &&
                          pre.contact_index > first.begin && pre.contact_index < first.end && pre.baseline_points > 10);
  check("corrected force", fabs(expected[0] - 0.0) < 10.0 * pre.baseline_sigma + fabs(pre.baseline_slope) * 1e-9);
  options.baseline_fraction = 1.5;
  check("bad fraction", cc_afm_preprocess(curve, &options, &pre, NULL, NULL, 0) == CC_INPUT_ERROR &&
                            message_has("baseline_fraction") && message_has("(0, 1)"));
  free(values);
  free(expected);
  cc_afm_curve_destroy(curve);

  /* A map: grid indices; a curve index out of range names the range. */
  cc_afm_file *map = NULL;
  long count = 0;
  snprintf(path, sizeof path, "%s/fmt-jpk-fd_map2x2_extracted.jpk-force-map", folder);
  check("open map", cc_afm_open(path, NULL, &map) == CC_OK);
  check("map count 4", cc_afm_file_count(map, &count) == CC_OK && count == 4);
  check("index out of range", cc_afm_curve_read(map, 4, &curve) == CC_INPUT_ERROR && message_has("index 4") &&
                                  message_has("0..3"));
  cc_afm_curve *c3 = NULL;
  cc_afm_grid grid;
  /* Curve 1 of the map (its header, as `afm show` lists it): grid index 9, 0 of a 10 x 10 grid. */
  check("map curve 1", cc_afm_curve_read(map, 1, &c3) == CC_OK);
  check("grid", cc_afm_curve_grid(c3, &grid) == CC_OK && grid.has_index && grid.index_x == 9 && grid.index_y == 0 &&
                    grid.has_shape && grid.shape_x == 10 && grid.shape_y == 10 && grid.has_position &&
                    fabs(grid.position_x - 0.0005718359375000001) < 1e-18);
  cc_afm_curve_destroy(c3);
  cc_afm_file_destroy(map);
  check("not a file", cc_afm_open("/nonexistent/x.jpk-force", NULL, &map) == CC_INPUT_ERROR);
}

static cc_afm_request *sphere_request(const char *model) {
  cc_afm_request *request = NULL;
  cc_stack *halfspace = NULL;
  check("request", cc_afm_request_create(&request) == CC_OK);
  check("model", cc_afm_request_set_model(request, model) == CC_OK);
  check("tip", cc_afm_request_set_tip(request, "sphere", 10e-6) == CC_OK);
  check("stack", cc_stack_create(&halfspace) == CC_OK && cc_stack_set_substrate(halfspace, 1000.0, 0.5) == CC_OK);
  check("sample", cc_afm_request_set_sample(request, halfspace) == CC_OK);
  cc_stack_destroy(halfspace);
  return request;
}

static void compare_fit(const char *folder, const char *model) {
  char path[4096], what[200];
  cc_afm_curve *curve = read_curve(folder, "fmt-jpk-fd_spot3-0192.jpk-force", 0, path, sizeof path);
  cc_afm_request *request = sphere_request(model);
  cc_afm_fit *fit = NULL;
  double expected[10];
  check("reference fit", ref_fit(path, 0, model, 10e-6, expected) == 0);
  check("cc_afm_fit_curve", cc_afm_fit_curve(curve, request, &fit) == CC_OK);
  const int jkr = strcmp(model, "jkr") == 0;
  const char *names[] = {"E", "contact_point", "baseline", "w", "tilt"};
  for (int k = 0; k < (jkr ? 5 : 3); ++k) {
    double value = 0.0, error = 0.0;
    snprintf(what, sizeof what, "%s %s", model, names[k]);
    check(what, cc_afm_fit_estimate(fit, names[k], &value, &error) == CC_OK);
    close_to(what, value, expected[2 * k]);
    close_to(what, error, expected[2 * k + 1]);
    printf("%s: C API %.17g +- %.3g, afm_fit_curve %.17g (difference %.3g)\n", what, value, error, expected[2 * k],
           value - expected[2 * k]);
  }
  long count = 0, length = 0;
  const char *name = NULL, *unit = NULL, *flag = NULL;
  check("parameter count", cc_afm_fit_parameter_count(fit, &count) == CC_OK && count == (jkr ? 5 : 3));
  check("first parameter E", cc_afm_fit_parameter_name(fit, 0, &name, &unit) == CC_OK && strcmp(name, "E") == 0 &&
                                 strcmp(unit, "Pa") == 0);
  check("flag", cc_afm_fit_flag(fit, &flag) == CC_OK && flag != NULL);
  cc_afm_fit_summary s;
  check("summary", cc_afm_fit_get_summary(fit, &s) == CC_OK && s.points > 10 && s.rating >= 0.0 && s.rating <= 10.0 &&
                       s.has_pulloff && s.pulloff_force < 0.0);
  /* Per-point arrays: residual = model - data at every fitted point. */
  double *model_force = malloc((size_t)s.points * sizeof(double));
  double *force = malloc((size_t)s.points * sizeof(double));
  double *residual = malloc((size_t)s.points * sizeof(double));
  check("model_force", cc_afm_fit_array(fit, "model_force", model_force, s.points, &length) == CC_OK && length == s.points);
  check("force", cc_afm_fit_array(fit, "force", force, s.points, &length) == CC_OK && length == s.points);
  check("residual", cc_afm_fit_array(fit, "residual", residual, s.points, &length) == CC_OK && length == s.points);
  double worst = 0.0;
  for (long i = 0; i < s.points; ++i) worst = fmax(worst, fabs(residual[i] - (model_force[i] - force[i])));
  snprintf(what, sizeof what, "%s residual = model - data", model);
  check(what, worst <= 1e-12 * s.residual_sigma * 1e6);
  check("unknown estimate", cc_afm_fit_estimate(fit, "E1", &worst, NULL) == CC_INPUT_ERROR && message_has("'E1'") &&
                                message_has("allowed"));
  check("unknown array", cc_afm_fit_array(fit, "stress", force, s.points, &length) == CC_INPUT_ERROR && message_has("stress"));
  check("steps", cc_afm_fit_step_count(fit, &count) == CC_OK && count >= 3);
  free(model_force);
  free(force);
  free(residual);
  cc_afm_fit_destroy(fit);
  cc_afm_request_destroy(request);
  cc_afm_curve_destroy(curve);
}

/* Bad requests: each setter's refusal, and the whole request's at the fit. */
static void bad_requests(const char *folder) {
  char path[4096];
  cc_afm_curve *curve = read_curve(folder, "fmt-jpk-fd_spot3-0192.jpk-force", 0, path, sizeof path);
  cc_afm_request *request = sphere_request("hertz");
  cc_afm_fit *fit = NULL;
  check("unknown model", cc_afm_request_set_model(request, "hertzian") == CC_INPUT_ERROR && message_has("'hertzian'") &&
                             message_has("hertz, jkr"));
  check("unknown free parameter", cc_afm_request_set_free(request, "E,Q") == CC_INPUT_ERROR && message_has("'Q'") &&
                                      message_has("contact_point"));
  check("unknown setting", cc_afm_request_set(request, "radius", 1.0) == CC_INPUT_ERROR && message_has("'radius'"));
  check("negative spring constant", cc_afm_request_set(request, "spring_constant", -1.0) == CC_INPUT_ERROR &&
                                        message_has("spring_constant -1") && message_has("> 0"));
  check("unknown tip", cc_afm_request_set_tip(request, "brick", 1.0) == CC_INPUT_ERROR && message_has("'brick'"));
  check("cone angle", cc_afm_request_set_tip(request, "cone", 2.0) == CC_INPUT_ERROR && message_has("(0, pi/2)"));
  check("segment", cc_afm_request_set_segment(request, "pause") == CC_INPUT_ERROR && message_has("approach or retract"));
  check("NULL request", cc_afm_request_set_model(NULL, "hertz") == CC_INPUT_ERROR && message_has("request is NULL"));
  check("NULL curve", cc_afm_fit_curve(NULL, request, &fit) == CC_INPUT_ERROR && message_has("curve is NULL"));
  /* The request is unchanged by the refusals: it still fits. */
  check("fits after refusals", cc_afm_fit_curve(curve, request, &fit) == CC_OK);
  cc_afm_fit_destroy(fit);
  fit = NULL;
  /* E1 on a half-space is not a parameter of the fit (checked at the fit). */
  check("E1 listed", cc_afm_request_set_free(request, "E1,contact_point") == CC_OK);
  check("E1 on a half-space", cc_afm_fit_curve(curve, request, &fit) == CC_INPUT_ERROR && message_has("'E1'") &&
                                  message_has("half-space") && fit == NULL);
  /* A fixed contact point needs its value. */
  check("E listed", cc_afm_request_set_free(request, "E,baseline") == CC_OK);
  check("fixed contact point", cc_afm_fit_curve(curve, request, &fit) == CC_INPUT_ERROR && message_has("contact_point"));
  /* JKR takes a sphere tip; MD on two layers is refused. */
  check("jkr", cc_afm_request_set_model(request, "jkr") == CC_OK && cc_afm_request_set_free(request, "E,w,contact_point") == CC_OK);
  check("cone", cc_afm_request_set_tip(request, "cone", 0.3) == CC_OK);
  check("jkr with a cone", cc_afm_fit_curve(curve, request, &fit) == CC_INPUT_ERROR && message_has("sphere tip"));
  cc_stack *two = NULL;
  cc_stack_create(&two);
  cc_stack_add_layer(two, 1e-6, 1e3, 0.5, 0);
  cc_stack_add_layer(two, 1e-6, 1e4, 0.5, 0);
  cc_stack_set_substrate(two, 1e5, 0.5);
  check("free layer outside the stack", cc_afm_request_set_sample_layer(request, two, 2) == CC_INPUT_ERROR &&
                                           message_has("free layer 2") && message_has("0..1"));
  check("two layers", cc_afm_request_set_sample_layer(request, two, 1) == CC_OK);
  check("sphere again", cc_afm_request_set_tip(request, "sphere", 10e-6) == CC_OK &&
                            cc_afm_request_set_free(request, "E1,w,contact_point") == CC_OK);
  /* (JKR and DMT take a stack, THEORY.md section 15; Maugis-Dugdale one film) */
  check("md", cc_afm_request_set_model(request, "md") == CC_OK);
  check("md on two layers", cc_afm_fit_curve(curve, request, &fit) == CC_INPUT_ERROR && message_has("takes one bonded film") &&
                                message_has("--model hertz, jkr or dmt"));
  cc_stack_destroy(two);
  cc_afm_request_destroy(request);
  /* A fit range outside the curve: the input code, its flag named. */
  request = sphere_request("hertz");
  check("fit range", cc_afm_request_set(request, "tip_min", 1.0) == CC_OK && cc_afm_request_set(request, "tip_max", 2.0) == CC_OK);
  check("too few points", cc_afm_fit_curve(curve, request, &fit) == CC_INPUT_ERROR &&
                              strcmp(cc_afm_last_flag(), "too_few_points") == 0);
  cc_afm_request_destroy(request);
  cc_afm_curve_destroy(curve);
}

/* Fetches channel `name` of `curve` into a new array (NULL when the curve has none). */
static double *channel_copy(const cc_afm_curve *curve, const char *name, long points) {
  long length = 0;
  if (cc_afm_curve_channel(curve, name, NULL, 0, &length) != CC_OK || length != points) return NULL;
  double *values = malloc((size_t)points * sizeof(double));
  cc_afm_curve_channel(curve, name, values, points, &length);
  return values;
}

/* The spot3 curve rebuilt from its arrays (a binding's plain arrays) fits as the file's; the
 * measured pull-off on the retract's arrays is the fit's. */
static void arrays(const char *folder) {
  char path[4096];
  cc_afm_curve *file_curve = read_curve(folder, "fmt-jpk-fd_spot3-0192.jpk-force", 0, path, sizeof path);
  long points = 0, count = 0;
  cc_afm_curve_points(file_curve, &points);
  cc_afm_curve_segment_count(file_curve, &count);
  cc_afm_segment segments[8];
  for (long k = 0; k < count && k < 8; ++k) cc_afm_curve_segment(file_curve, k, &segments[k]);
  double *force = channel_copy(file_curve, "force", points), *piezo = channel_copy(file_curve, "height_piezo", points),
         *measured = channel_copy(file_curve, "height_measured", points), *time = channel_copy(file_curve, "time", points),
         *tip = channel_copy(file_curve, "tip_position", points);
  const double k = atof(metadata(file_curve, "spring_constant")); /* 17 digits: the same double */
  cc_afm_curve *curve = NULL;
  check("cc_afm_curve_create", cc_afm_curve_create(points, force, piezo, measured, time, count, segments, k, "spot3 arrays",
                                                   &curve) == CC_OK);
  cc_afm_request *request = sphere_request("hertz");
  cc_afm_fit *from_file = NULL, *from_arrays = NULL;
  check("fit file", cc_afm_fit_curve(file_curve, request, &from_file) == CC_OK);
  check("fit arrays", cc_afm_fit_curve(curve, request, &from_arrays) == CC_OK);
  const char *names[] = {"E", "contact_point", "baseline"};
  for (int i = 0; i < 3; ++i) {
    double a = 0.0, b = 0.0;
    cc_afm_fit_estimate(from_file, names[i], &a, NULL);
    cc_afm_fit_estimate(from_arrays, names[i], &b, NULL);
    close_to(names[i], b, a);
  }
  cc_afm_fit_summary s;
  cc_afm_pulloff pulloff;
  cc_afm_fit_get_summary(from_file, &s);
  const cc_afm_segment *retract = &segments[count - 1];
  check("measured pull-off", cc_afm_measured_pulloff(retract->end - retract->begin, tip + retract->begin,
                                                     force + retract->begin, 0.5, &pulloff) == CC_OK && pulloff.found);
  close_to("pull-off force as the fit's", pulloff.force, s.pulloff_force);
  close_to("pull-off position as the fit's", pulloff.tip_position, s.pulloff_position);
  check("pull-off fraction", cc_afm_measured_pulloff(10, tip, force, 1.0, &pulloff) == CC_INPUT_ERROR && message_has("fraction 1"));
  /* Segments that leave a gap are refused, naming the segment. */
  cc_afm_curve *bad = NULL;
  segments[1].begin += 1;
  check("gap between segments", cc_afm_curve_create(points, force, piezo, measured, time, count, segments, k, NULL, &bad) ==
                                    CC_INPUT_ERROR && message_has("segments[1]") && bad == NULL);
  check("no height", cc_afm_curve_create(points, force, NULL, NULL, NULL, count, segments, k, NULL, &bad) == CC_INPUT_ERROR &&
                         message_has("height"));
  cc_afm_fit_destroy(from_file);
  cc_afm_fit_destroy(from_arrays);
  cc_afm_request_destroy(request);
  cc_afm_curve_destroy(curve);
  cc_afm_curve_destroy(file_curve);
  free(force);
  free(piezo);
  free(measured);
  free(time);
  free(tip);
}

/* The batch of the 2x2 map: one row per curve, each equal to the one-curve fit of its curve
 * (the same pipeline), on 1 and 2 threads. */
static void batch(const char *folder) {
  char path[4096];
  snprintf(path, sizeof path, "%s/fmt-jpk-fd_map2x2_extracted.jpk-force-map", folder);
  const char *files[] = {path};
  cc_afm_request *request = sphere_request("hertz");
  for (unsigned jobs = 1; jobs <= 2; ++jobs) {
    cc_afm_rows *rows = NULL;
    cc_afm_batch_options options = {0};
    options.jobs = jobs;
    long count = 0, parameters = 0;
    check("batch", cc_afm_fit_batch(files, 1, NULL, request, &options, &rows) == CC_OK);
    check("4 rows", cc_afm_rows_count(rows, &count) == CC_OK && count == 4);
    check("3 columns", cc_afm_rows_parameter_count(rows, &parameters) == CC_OK && parameters == 3);
    cc_afm_file *map = NULL;
    cc_afm_open(path, NULL, &map);
    for (long i = 0; i < count; ++i) {
      cc_afm_row row;
      cc_afm_curve *curve = NULL;
      cc_afm_fit *fit = NULL;
      check("row", cc_afm_rows_get(rows, i, &row) == CC_OK && row.curve == i);
      cc_afm_curve_read(map, i, &curve);
      const int fitted = cc_afm_fit_curve(curve, request, &fit) == CC_OK;
      check("row flag as the one-curve fit", row.has_estimates == fitted);
      if (fitted && row.has_estimates) {
        double e = 0.0;
        cc_afm_fit_estimate(fit, "E", &e, NULL);
        close_to("batch row E", row.estimates[0], e);
      }
      cc_afm_fit_destroy(fit);
      cc_afm_curve_destroy(curve);
    }
    cc_afm_file_destroy(map);
    cc_afm_rows_destroy(rows);
  }
  /* A share of the run: curves 1 and 2 only, the rows of the whole run's. */
  cc_afm_rows *rows = NULL;
  cc_afm_batch_options share = {0};
  share.jobs = 1;
  share.skip = 1;
  share.count = 2;
  long count = 0;
  check("share", cc_afm_fit_batch(files, 1, NULL, request, &share, &rows) == CC_OK && cc_afm_rows_count(rows, &count) == CC_OK &&
                     count == 2);
  cc_afm_row row;
  check("share starts at curve 1", cc_afm_rows_get(rows, 0, &row) == CC_OK && row.curve == 1);
  check("row out of range", cc_afm_rows_get(rows, 2, &row) == CC_INPUT_ERROR && message_has("row 2"));
  cc_afm_rows_destroy(rows);
  rows = NULL;
  check("batch of no file", cc_afm_fit_batch(files, 0, NULL, request, NULL, &rows) == CC_INPUT_ERROR &&
                                message_has("file_count 0"));
  const char *missing[] = {"/nonexistent.jpk-force"};
  check("batch of a missing file", cc_afm_fit_batch(missing, 1, NULL, request, NULL, &rows) == CC_INPUT_ERROR &&
                                       rows == NULL);
  cc_afm_request_destroy(request);
}

/* The header value (and its error) of `key` in the CLI's output. */
static int header_pair(const char *text, const char *key, double *value, double *error) {
  char pattern[128];
  snprintf(pattern, sizeof pattern, "# %s: ", key);
  const char *line = strstr(text, pattern);
  return line && sscanf(line + strlen(pattern), "%lf +- %lf", value, error) == 2;
}

/* A two-layer stack (cell on gel on glass) on spot3 through the C API equals `afm fit --layer`
 * (run here) to 1e-12: z_c and b free, the layers' moduli fixed (one modulus: a cheap table). */
static void stack_fit(const char *folder, const char *cli) {
  char path[4096], command[8192];
  cc_afm_curve *curve = read_curve(folder, "fmt-jpk-fd_spot3-0192.jpk-force", 0, path, sizeof path);
  cc_afm_request *request = NULL;
  cc_stack *stack = NULL;
  check("request", cc_afm_request_create(&request) == CC_OK && cc_afm_request_set_tip(request, "sphere", 10e-6) == CC_OK);
  check("stack", cc_stack_create(&stack) == CC_OK && cc_stack_add_layer(stack, 1e-6, 5e3, 0.5, 0) == CC_OK &&
                     cc_stack_add_layer(stack, 4e-6, 2e4, 0.5, 0) == CC_OK && cc_stack_set_rigid_substrate(stack) == CC_OK);
  check("stack sample", cc_afm_request_set_sample(request, stack) == CC_OK);
  check("free", cc_afm_request_set_free(request, "contact_point,baseline") == CC_OK);
  cc_stack_destroy(stack);
  cc_afm_fit *fit = NULL;
  check("stack fit", cc_afm_fit_curve(curve, request, &fit) == CC_OK);
  snprintf(command, sizeof command,
           "'%s' afm fit '%s' --radius 10um --layer 1um,5kPa,0.5 --layer 4um,20kPa,0.5 --substrate rigid "
           "--free contact_point,baseline 2>/dev/null | grep '^#'", cli, path);
  FILE *pipe = popen(command, "r");
  static char text[1 << 16];
  size_t length = pipe ? fread(text, 1, sizeof text - 1, pipe) : 0;
  text[length] = '\0';
  check("the CLI ran", pipe != NULL && pclose(pipe) == 0);
  const char *names[] = {"contact_point", "baseline"}, *keys[] = {"contact point [m]", "baseline [N]"};
  for (int k = 0; k < 2 && fit; ++k) {
    double value = 0.0, error = 0.0, cli_value = 0.0, cli_error = 0.0;
    check(names[k], cc_afm_fit_estimate(fit, names[k], &value, &error) == CC_OK);
    check(keys[k], header_pair(text, keys[k], &cli_value, &cli_error));
    close_to(names[k], value, cli_value);
    close_to(names[k], error, cli_error);
    printf("stack %s: C API %.17g +- %.3g, CLI %.17g\n", names[k], value, error, cli_value);
  }
  cc_afm_fit_destroy(fit);
  cc_afm_request_destroy(request);
  cc_afm_curve_destroy(curve);
}

/* The whole text of a file (NULL if it cannot be read); the caller frees it. */
static char *file_text(const char *path) {
  FILE *in = fopen(path, "rb");
  if (!in) return NULL;
  static const size_t limit = 1 << 20;
  char *text = malloc(limit);
  size_t length = fread(text, 1, limit - 1, in);
  text[length] = '\0';
  fclose(in);
  return text;
}

/* The map2x2 batch's table through the C API is the CLI's `afm fit --output` table byte for
 * byte (one writer in the fit floor), the CLI's "# command:" line aside. */
static void batch_table(const char *folder, const char *cli) {
  char path[4096], c_table[4200], cli_table[4200], command[16384];
  snprintf(path, sizeof path, "%s/fmt-jpk-fd_map2x2_extracted.jpk-force-map", folder);
  const char *tmp = getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp";
  snprintf(c_table, sizeof c_table, "%s/capi_afm_table_%ld.tsv", tmp, (long)getpid());
  snprintf(cli_table, sizeof cli_table, "%s/capi_afm_table_cli_%ld.tsv", tmp, (long)getpid());
  const char *files[] = {path};
  cc_afm_request *request = sphere_request("hertz");
  cc_afm_rows *rows = NULL;
  cc_afm_batch_options options = {0};
  options.jobs = 1;
  check("batch for the table", cc_afm_fit_batch(files, 1, NULL, request, &options, &rows) == CC_OK);
  check("write table", cc_afm_rows_write_table(rows, c_table) == CC_OK);
  check("write table NULL path", cc_afm_rows_write_table(rows, NULL) == CC_INPUT_ERROR && message_has("path is NULL"));
  check("write table NULL rows", cc_afm_rows_write_table(NULL, c_table) == CC_INPUT_ERROR && message_has("rows is NULL"));
  check("write table to a folder", cc_afm_rows_write_table(rows, "/nonexistent-folder/x.tsv") == CC_INPUT_ERROR &&
                                      message_has("cannot write"));
  cc_afm_rows *curves_rows = NULL;
  check("rows of curves", cc_afm_fit_curves(NULL, 0, request, NULL, &curves_rows) == CC_OK);
  check("rows of curves have no table", cc_afm_rows_write_table(curves_rows, c_table) == CC_INPUT_ERROR &&
                                            message_has("not a run over files"));
  cc_afm_rows_destroy(curves_rows);
  snprintf(command, sizeof command, "'%s' afm fit '%s' --radius 10um --halfspace 1000,0.5 --jobs 1 --output '%s' 2>/dev/null",
           cli, path, cli_table);
  check("the CLI wrote its table", system(command) == 0);
  char *a = file_text(c_table), *b = file_text(cli_table);
  const char *b_rest = b ? strchr(b, '\n') : NULL; /* past "# command: ..." */
  check("the CLI's table starts with its command", b && strncmp(b, "# command: ", 11) == 0);
  check("C API table = CLI table", a && b_rest && strcmp(a, b_rest + 1) == 0);
  if (a && b_rest && strcmp(a, b_rest + 1) != 0) printf("C API table:\n%s\nCLI table:\n%s\n", a, b_rest + 1);
  free(a);
  free(b);
  remove(c_table);
  remove(cli_table);
  cc_afm_rows_destroy(rows);
  cc_afm_request_destroy(request);
}

/* The sink of python_needs: counts the chunks' rows and keeps the first row's E and trace length. */
struct sink_state {
  long rows, trace_points;
  double first_e;
  int stop;
};
static int count_rows(void *user, const cc_afm_rows *chunk) {
  struct sink_state *s = (struct sink_state *)user;
  long n = 0;
  cc_afm_rows_count(chunk, &n);
  for (long i = 0; i < n; ++i) {
    cc_afm_row row;
    cc_afm_rows_get(chunk, i, &row);
    if (s->rows == 0 && row.has_estimates) s->first_e = row.estimates[0];
    long length = 0;
    if (s->rows == 0 && row.has_trace) cc_afm_rows_trace(chunk, i, "z", NULL, 0, &length);
    if (s->rows == 0) s->trace_points = length;
    ++s->rows;
  }
  return s->stop;
}

/* What a binding needs beyond one fit (issue 35: Python on the C API only): the registry, a fit
 * of given arrays, the fit's details, the depth profile, given curves as rows (equal to the
 * file's batch rows), a sink with traces, folder expansion and the survey; each with its
 * input errors. */
static void python_needs(const char *folder) {
  long models = 0, parameters = 0;
  cc_afm_model_info info;
  check("model count", cc_afm_model_count(&models) == CC_OK && models >= 4);
  check("model 0 is hertz", cc_afm_model_get(0, &info) == CC_OK && strcmp(info.name, "hertz") == 0 && !info.needs_spring &&
                                strcmp(info.segment, "approach") == 0);
  check("model out of range", cc_afm_model_get(models, &info) == CC_INPUT_ERROR && message_has("model"));
  check("hertz parameters", cc_afm_model_parameter_count(0, 0, &parameters) == CC_OK && parameters >= 3);
  const char *name = NULL, *unit = NULL;
  int free_by_default = 0;
  check("hertz E", cc_afm_model_parameter(0, 0, 0, &name, &unit, &free_by_default) == CC_OK && strcmp(name, "E") == 0 &&
                       strcmp(unit, "Pa") == 0 && free_by_default);
  check("coated 2", cc_afm_model_parameter_count(0, 2, &parameters) == CC_INPUT_ERROR && message_has("coated 2"));
  check("parameter NULL name", cc_afm_model_parameter(0, 0, 0, NULL, NULL, NULL) == CC_INPUT_ERROR);

  /* The fit of the file's curve's fitted points as arrays: the same E as the one-curve fit
   * with the offset baseline model (no tilt subtracted). */
  char path[4096];
  cc_afm_curve *curve = read_curve(folder, "fmt-jpk-fd_spot3-0192.jpk-force", 0, path, sizeof path);
  cc_afm_request *request = sphere_request("hertz");
  cc_afm_request_set_baseline_model(request, "offset");
  cc_afm_fit *fit = NULL, *again = NULL;
  check("fit curve", cc_afm_fit_curve(curve, request, &fit) == CC_OK);
  cc_afm_fit_summary summary;
  cc_afm_fit_get_summary(fit, &summary);
  long n = 0;
  cc_afm_fit_array(fit, "tip_position", NULL, 0, &n);
  double *z = malloc((size_t)n * sizeof(double)), *f = malloc((size_t)n * sizeof(double));
  cc_afm_fit_array(fit, "tip_position", z, n, &n);
  cc_afm_fit_array(fit, "force", f, n, &n);
  check("fit arrays", cc_afm_fit_arrays(n, z, f, request, summary.reference_contact, summary.reference_baseline, &again) == CC_OK);
  double e1 = 0.0, e2 = 0.0;
  cc_afm_fit_estimate(fit, "E", &e1, NULL);
  cc_afm_fit_estimate(again, "E", &e2, NULL);
  close_to("arrays E = curve E", e2, e1);
  cc_afm_fit_details details;
  check("details", cc_afm_fit_get_details(fit, &details) == CC_OK && strcmp(details.model, "hertz") == 0 &&
                       strcmp(details.baseline_model, "offset") == 0 && !details.coated && details.profile_evaluations > 0);
  check("details NULL", cc_afm_fit_get_details(NULL, &details) == CC_INPUT_ERROR && message_has("fit is NULL"));
  cc_afm_fit *bad = NULL;
  check("arrays n 0", cc_afm_fit_arrays(0, z, f, request, 0.0, 0.0, &bad) == CC_INPUT_ERROR && message_has("n 0") && !bad);
  check("arrays NULL force", cc_afm_fit_arrays(n, z, NULL, request, 0.0, 0.0, &bad) == CC_INPUT_ERROR && !bad);
  cc_afm_depth_profile_info profile;
  check("no profile", cc_afm_fit_depth_profile(fit, &profile) == CC_OK && profile.steps == 0);
  check("no profile array", cc_afm_fit_depth_profile_array(fit, "depth", NULL, 0, &n) == CC_INPUT_ERROR &&
                                message_has("no depth profile"));
  cc_afm_fit_destroy(again);
  again = NULL;
  check("depth_profile 2", cc_afm_request_set(request, "depth_profile", 2.0) == CC_INPUT_ERROR && message_has("0 or 1"));
  check("depth_profile", cc_afm_request_set(request, "depth_profile", 1.0) == CC_OK &&
                             cc_afm_fit_curve(curve, request, &again) == CC_OK);
  check("profile", cc_afm_fit_depth_profile(again, &profile) == CC_OK && profile.steps > 0 &&
                       strcmp(profile.modulus_name, "E") == 0 && !profile.coated);
  double e3 = 0.0;
  cc_afm_fit_estimate(again, "E", &e3, NULL);
  close_to("profile's reference = the fit", e3, e1);
  const char *flag = NULL;
  check("profile flag", cc_afm_fit_depth_profile_flag(again, 0, &flag) == CC_OK && flag != NULL);
  check("profile flag out of range", cc_afm_fit_depth_profile_flag(again, profile.steps, &flag) == CC_INPUT_ERROR);
  check("profile unknown array", cc_afm_fit_depth_profile_array(again, "E", NULL, 0, &n) == CC_INPUT_ERROR && message_has("allowed"));
  check("batch refuses a profile", cc_afm_fit_curves(NULL, 0, request, NULL, &(cc_afm_rows *){NULL}) == CC_INPUT_ERROR &&
                                       message_has("depth profile"));
  cc_afm_fit_destroy(again);
  cc_afm_fit_destroy(fit);
  cc_afm_request_destroy(request);
  cc_afm_curve_destroy(curve);
  free(z);
  free(f);

  /* The map's curves given as handles: the rows of the file's batch; a sink sees them with traces. */
  snprintf(path, sizeof path, "%s/fmt-jpk-fd_map2x2_extracted.jpk-force-map", folder);
  const char *files[] = {path};
  request = sphere_request("hertz");
  cc_afm_file *map = NULL;
  cc_afm_curve *curves[4] = {NULL, NULL, NULL, NULL};
  cc_afm_open(path, NULL, &map);
  for (long i = 0; i < 4; ++i) cc_afm_curve_read(map, i, &curves[i]);
  cc_afm_file_destroy(map);
  cc_afm_rows *from_file = NULL, *from_curves = NULL, *sunk = NULL;
  check("batch", cc_afm_fit_batch(files, 1, NULL, request, NULL, &from_file) == CC_OK);
  check("curves", cc_afm_fit_curves((const cc_afm_curve *const *)curves, 4, request, NULL, &from_curves) == CC_OK);
  for (long i = 0; i < 4; ++i) {
    cc_afm_row a, b;
    cc_afm_rows_get(from_file, i, &a);
    cc_afm_rows_get(from_curves, i, &b);
    check("curve row flag = file row flag", a.flag == b.flag && a.curve == b.curve && a.grid_x_or_none == b.grid_x_or_none);
    if (a.has_estimates && b.has_estimates) close_to("curve row E = file row E", b.estimates[0], a.estimates[0]);
  }
  struct sink_state state = {0, 0, 0.0, 0};
  cc_afm_batch_options options = {0};
  options.keep_traces = 1;
  options.sink = count_rows;
  options.sink_user = &state;
  long kept = -1;
  check("sink", cc_afm_fit_batch(files, 1, NULL, request, &options, &sunk) == CC_OK && cc_afm_rows_count(sunk, &kept) == CC_OK &&
                    kept == 0 && state.rows == 4 && state.trace_points > 0);
  cc_afm_row first;
  cc_afm_rows_get(from_file, 0, &first);
  if (first.has_estimates) close_to("sink row E", state.first_e, first.estimates[0]);
  check("no trace kept", cc_afm_rows_trace(from_file, 0, "z", NULL, 0, &kept) == CC_INPUT_ERROR && message_has("no trace"));
  cc_afm_rows_destroy(sunk);
  sunk = NULL;
  state.rows = 0;
  state.stop = 1;
  check("a sink stops the run", cc_afm_fit_batch(files, 1, NULL, request, &options, &sunk) == CC_INTERRUPTED && !sunk);
  cc_afm_file_survey wrong = {"", -1, "", 0};
  options.sink = NULL;
  options.survey_count = 1;
  options.survey = &wrong;
  check("survey curves -1", cc_afm_fit_batch(files, 1, NULL, request, &options, &sunk) == CC_INPUT_ERROR &&
                               message_has("survey[0]"));
  options.survey_count = 2;
  check("survey count", cc_afm_fit_batch(files, 1, NULL, request, &options, &sunk) == CC_INPUT_ERROR &&
                            message_has("survey_count 2"));
  check("NULL curve", cc_afm_fit_curves((const cc_afm_curve *const *)(const cc_afm_curve *[]){NULL}, 1, request, NULL, &sunk) ==
                          CC_INPUT_ERROR && message_has("curves[0]"));
  check("negative place", cc_afm_curve_set_place(curves[0], -1, NULL) == CC_INPUT_ERROR && message_has("curve_index -1"));
  cc_afm_grid place = {1, 7, 3, 0, 0, 0, 1, 1e-6, 2e-6};
  cc_afm_grid back;
  check("place", cc_afm_curve_set_place(curves[0], 9, &place) == CC_OK && cc_afm_curve_grid(curves[0], &back) == CC_OK &&
                     back.index_x == 7 && back.index_y == 3 && back.position_y == 2e-6 && strcmp(metadata(curves[0], "curve_index"), "9") == 0);
  for (long i = 0; i < 4; ++i) cc_afm_curve_destroy(curves[i]);
  cc_afm_rows_destroy(from_file);
  cc_afm_rows_destroy(from_curves);
  cc_afm_request_destroy(request);

  /* The folder: its AFM files, each surveyed; a file that cannot be read is an entry when tolerated. */
  const char *folders[] = {folder};
  cc_afm_file_list *list = NULL, *survey = NULL;
  long count = 0, map_curves = 0;
  check("expand", cc_afm_expand_paths(folders, 1, &list) == CC_OK && cc_afm_file_list_count(list, &count) == CC_OK && count > 5);
  const char **paths = malloc((size_t)count * sizeof(char *));
  for (long i = 0; i < count; ++i) {
    cc_afm_file_survey entry;
    cc_afm_file_list_get(list, i, &entry);
    paths[i] = entry.path;
    check("expanded: not surveyed", entry.curves == -1);
  }
  check("survey", cc_afm_survey_files(paths, count, NULL, 1, &survey) == CC_OK);
  for (long i = 0; i < count; ++i) {
    cc_afm_file_survey entry;
    cc_afm_file_list_get(survey, i, &entry);
    check("surveyed", entry.curves >= 1 && (entry.unreadable[0] == '\0' || entry.flag == 6 || entry.flag == 8));
    if (strstr(entry.path, "map2x2")) map_curves = entry.curves;
  }
  check("map2x2 has 4 curves", map_curves == 4);
  cc_afm_file_survey entry;
  check("entry out of range", cc_afm_file_list_get(survey, count, &entry) == CC_INPUT_ERROR && message_has("out of range"));
  cc_afm_file_list *none = NULL;
  check("expand none", cc_afm_expand_paths(folders, 0, &none) == CC_INPUT_ERROR && message_has("count 0") && !none);
  check("survey NULL", cc_afm_survey_files(NULL, 1, NULL, 0, &none) == CC_INPUT_ERROR && !none);
  const char *missing[] = {"/nonexistent.jpk-force"};
  check("survey missing", cc_afm_survey_files(missing, 1, NULL, 1, &none) == CC_INPUT_ERROR && !none);
  free(paths);
  cc_afm_file_list_destroy(survey);
  cc_afm_file_list_destroy(list);
}

int main(int argc, char **argv) {
  if (argc != 3) {
    fprintf(stderr, "usage: test_capi_afm DATA_AFM_FOLDER COATCONTACT_CLI\n");
    return 2;
  }
  stack_fit(argv[1], argv[2]);
  reading(argv[1]);
  compare_fit(argv[1], "hertz");
  compare_fit(argv[1], "jkr");
  bad_requests(argv[1]);
  arrays(argv[1]);
  batch(argv[1]);
  python_needs(argv[1]);
  batch_table(argv[1], argv[2]);
  if (failures) {
    printf("%d failures\n", failures);
    return 1;
  }
  printf("all AFM C API checks passed\n");
  return 0;
}
