/* The nanoindentation C API (cc_indent_* in coatcontact/coatcontact_indent.h, through
 * coatcontact.h) used from C on the real NanoSuite and Hysitron files: counts, names, channel
 * copies against values the sheets and lines state, metadata and calibration, and every error
 * path (NULL, index out of range, unknown channel, short buffer, bad file) with its status and
 * message. Argument: the data/indentation folder. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "coatcontact/coatcontact.h"

static int failures = 0;

static void check(const char *what, int condition) {
  if (!condition) {
    ++failures;
    printf("FAIL %s (last error: %s)\n", what, cc_last_error_message());
  }
}

static int message_has(const char *fragment) { return strstr(cc_last_error_message(), fragment) != NULL; }

static void nanosuite(const char *folder) {
  char path[4096];
  snprintf(path, sizeof path, "%s/FS_Calibration.xls", folder);
  cc_indent_tests *tests = NULL;
  check("cc_indent_read xls", cc_indent_read(path, &tests) == CC_OK && tests != NULL);
  long count = 0, points = 0, channels = 0;
  check("count 16", cc_indent_count(tests, &count) == CC_OK && count == 16);
  const char *name = NULL;
  check("name of test 15", cc_indent_name(tests, 15, &name) == CC_OK && strcmp(name, "Test 016") == 0);
  check("points", cc_indent_points(tests, 15, &points) == CC_OK && points > 1000);
  check("channel count 7", cc_indent_channel_count(tests, 15, &channels) == CC_OK && channels == 7);
  check("channel 4 is stiffness", cc_indent_channel_name(tests, 15, 3, &name) == CC_OK && strcmp(name, "stiffness") == 0);
  double *values = malloc((size_t)points * sizeof(double));
  long length = 0;
  /* Sheet "Test 016", row 3: stiffness 162.59360575619806 N/m; row 5: depth 0.56980673226926037 nm. */
  check("stiffness", cc_indent_channel(tests, 15, "stiffness", values, points, &length) == CC_OK && length == points &&
                         values[0] == 162.59360575619806);
  check("depth", cc_indent_channel(tests, 15, "depth", values, points, &length) == CC_OK && values[2] == 0.56980673226926037 / 1e9);
  check("hardness NaN before contact", cc_indent_channel(tests, 15, "hardness", values, points, &length) == CC_OK && isnan(values[0]));
  check("segment as doubles", cc_indent_channel(tests, 15, "segment", values, points, &length) == CC_OK && values[0] == 1.0);
  cc_indent_calibration c;
  check("calibration", cc_indent_calibration_get(tests, 0, &c) == CC_OK && c.area_count == 3 &&
                           c.area_coefficients[0] == 27.3136 && c.poisson == 0.18 && isnan(c.frame_stiffness) &&
                           strcmp(c.tip, "Berk40_20210907_MarilaineSP") == 0 && c.range_max == 200e-9);
  long results = 0;
  const char *key = NULL;
  double value = 0.0;
  check("results", cc_indent_result_count(tests, 0, &results) == CC_OK && results == 2);
  check("E_mean", cc_indent_result_entry(tests, 0, 0, &key, &value) == CC_OK && strcmp(key, "E_mean") == 0 && value == 76.318e9);
  long entries = 0;
  const char *text = NULL;
  check("metadata", cc_indent_metadata_count(tests, 0, &entries) == CC_OK && entries > 20);
  int found = 0;
  for (long e = 0; e < entries; ++e) {
    check("metadata entry", cc_indent_metadata_entry(tests, 0, e, &key, &text) == CC_OK);
    if (strcmp(key, "test") == 0) found = strcmp(text, "Test 001") == 0;
  }
  check("metadata test", found);
  /* Error paths: status and message, outputs untouched. */
  long untouched = -7;
  check("index out of range", cc_indent_points(tests, 16, &untouched) == CC_INPUT_ERROR && untouched == -7 &&
                                  message_has("out of range 0..15"));
  check("unknown channel", cc_indent_channel(tests, 0, "force", values, points, &length) == CC_INPUT_ERROR && message_has("no channel 'force'"));
  check("short buffer", cc_indent_channel(tests, 0, "depth", values, 10, &length) == CC_INPUT_ERROR && message_has("capacity 10"));
  check("NULL handle", cc_indent_count(NULL, &count) == CC_INPUT_ERROR && message_has("tests is NULL"));
  check("entry out of range", cc_indent_result_entry(tests, 0, 2, &key, &value) == CC_INPUT_ERROR);
  check("success clears the message", cc_indent_count(tests, &count) == CC_OK && cc_last_error_message()[0] == '\0');
  free(values);
  cc_indent_tests_destroy(tests);
  cc_indent_tests_destroy(NULL);
}

static void hysitron_and_bad_files(const char *folder) {
  char path[4096];
  snprintf(path, sizeof path, "%s/RobinSteel0000LC.txt", folder);
  cc_indent_tests *tests = NULL;
  check("cc_indent_read txt", cc_indent_read(path, &tests) == CC_OK);
  double load[5304];
  long length = 0;
  /* line 5: "0.814723  1.836146  0.000000 ..." (nm, µN, s) */
  check("load", cc_indent_channel(tests, 0, "load", load, 5304, &length) == CC_OK && length == 5304 && load[0] == 1.836146 / 1e6);
  check("extra channel", cc_indent_channel(tests, 0, "Load [V]", load, 5304, &length) == CC_OK && load[0] == 0.481918);
  cc_indent_tests_destroy(tests);
  cc_indent_tests *none = NULL;
  snprintf(path, sizeof path, "%s/README.md", folder);
  check("bad file", cc_indent_read(path, &none) == CC_INPUT_ERROR && none == NULL && message_has("README.md") &&
                        message_has("unknown indentation file format"));
  check("NULL path", cc_indent_read(NULL, &none) == CC_INPUT_ERROR && message_has("path is NULL"));
}

int main(int argc, char **argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: test_capi_indent DATA_DIR\n");
    return 2;
  }
  nanosuite(argv[1]);
  hysitron_and_bad_files(argv[1]);
  if (failures == 0) printf("capi indent: all checks passed\n");
  return failures == 0 ? 0 : 1;
}
