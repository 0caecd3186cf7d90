/*
 * coatcontact: nanoindentation files through the C interface (included by coatcontact.h).
 * Implemented in cpp/capi/capi_indent.cpp over coatcontact/indentation.hpp.
 *
 * cc_indent_read reads every test of a vendor file (NanoSuite .xls, Hysitron .txt and .hld,
 * Micromaterials .zip, FischerScope .txt; the format from the content and the extension) into
 * one handle. Tests are indexed 0..count-1; status, errors and thread safety as in
 * coatcontact.h (the handle is read-only once made). Strings returned are owned by the handle
 * and valid until it is destroyed.
 *
 * Channels in SI: "depth" [m], "load" [N], "time" [s], "stiffness" [N/m] (CSM harmonic
 * contact stiffness), "hardness" and "modulus" [Pa] (the vendor's own columns), "segment" (the
 * vendor's segment number, as doubles), then the file's other channels by their names with
 * the SI unit in brackets ("Depth [V]", "LoadCell [m]"). A test holds only the channels its
 * file has; all have the test's point count. NaN marks a value the vendor wrote as missing
 * (NanoSuite's 1.797e308 before contact or during unloading).
 */
#ifndef COATCONTACT_COATCONTACT_INDENT_H
#define COATCONTACT_COATCONTACT_INDENT_H

#include "coatcontact/cc_status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct cc_indent_tests cc_indent_tests;

/* The tests of the file at `path`. CC_INPUT_ERROR names the file, sheet or archive entry and
 * line of what is wrong. */
int cc_indent_read(const char *path, cc_indent_tests **tests);
void cc_indent_tests_destroy(cc_indent_tests *tests);

int cc_indent_count(const cc_indent_tests *tests, long *count);
/* The vendor's test name ("Test 001", the entry's stem, "Block 1 Value 2"). */
int cc_indent_name(const cc_indent_tests *tests, long index, const char **name);
int cc_indent_points(const cc_indent_tests *tests, long index, long *points);

/* The channels test `index` has, in the order above. */
int cc_indent_channel_count(const cc_indent_tests *tests, long index, long *count);
int cc_indent_channel_name(const cc_indent_tests *tests, long index, long channel, const char **name);
/* Copies channel `name` into values[0..capacity); *length: the point count. CC_INPUT_ERROR if
 * the test has no such channel or capacity < the point count. */
int cc_indent_channel(const cc_indent_tests *tests, long index, const char *name, double *values,
                      long capacity, long *length);

/* Everything else the file states, as text: key/value pairs in key order. */
int cc_indent_metadata_count(const cc_indent_tests *tests, long index, long *count);
int cc_indent_metadata_entry(const cc_indent_tests *tests, long index, long entry, const char **key,
                             const char **value);
/* The vendor's own results in SI ("E_mean", "H_mean" [Pa] of NanoSuite's Results sheet;
 * "HM" [Pa] of FischerScope), in key order. */
int cc_indent_result_count(const cc_indent_tests *tests, long index, long *count);
int cc_indent_result_entry(const cc_indent_tests *tests, long index, long entry, const char **key,
                           double *value);

/* The calibration the file states; NaN (and area_count 0, "" strings) where it is silent.
 * Area function: A [nm^2] = C0 h^2 + C1 h + C2 h^(1/2) + C3 h^(1/4) + ..., h_c in nm. */
typedef struct cc_indent_calibration {
  const double *area_coefficients; /* C0, C1, ... (owned by the handle) */
  long area_count;
  double frame_stiffness; /* N/m */
  double poisson;         /* the sample's */
  double beta;
  double eps;
  double range_min; /* m: the vendor's averaging range */
  double range_max;
  const char *tip;
  const char *source;
} cc_indent_calibration;
int cc_indent_calibration_get(const cc_indent_tests *tests, long index, cc_indent_calibration *calibration);

#ifdef __cplusplus
}
#endif

#endif /* COATCONTACT_COATCONTACT_INDENT_H */
