/* The crack-kinetics C API (cc_kinetics_* in coatcontact/coatcontact.h, THEORY.md section 14)
 * used from C, against the C++ library behind `coatcontact kinetics`: the README's run (sphere
 * R = 2 mm, 1 MPa film of 50 um on glass, spring 500 N/m) and a 70-degree cone on the same
 * stack. Arguments (run_test_capi_kinetics.sh, the CLI's header in round-trip digits): for the
 * sphere, then the cone: pull-off F, t, a, loss-of-contact t, and the number of states. Then
 * the units, the energy and the fit (scales_energy_and_fit). */
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

/* The same computation through two front ends: equal but for the last bits of the printed
 * digits (round trip). */
static int same(double value, double expected) { return fabs(value - expected) <= 1e-13 * fabs(expected); }

static cc_stack *coating(void) {
  cc_stack *stack = NULL;
  check("cc_stack_create", cc_stack_create(&stack) == CC_OK);
  check("cc_stack_add_layer", cc_stack_add_layer(stack, 50e-6, 1e6, 0.49, 0) == CC_OK);
  check("cc_stack_set_substrate", cc_stack_set_substrate(stack, 70e9, 0.22) == CC_OK);
  return stack;
}

static const cc_kinetics_segment readme_protocol[3] = {
    {CC_KINETICS_APPROACH, 1e-6, 0.0, 1e-3, 1}, {CC_KINETICS_DWELL, 0.0, 1.0, 0.0, 0},
    {CC_KINETICS_RETRACT, 1e-5, 0.0, 0.0, 0}};

static cc_kinetics_setup setup_of(int tip) {
  cc_kinetics_setup s;
  memset(&s, 0, sizeof s);
  s.tip = tip;
  s.radius = 2e-3;
  s.half_angle = 70.0 * 3.14159265358979323846 / 180.0;
  s.work = 0.04;
  s.v_star = 1e-6;
  s.n = 0.6;
  s.spring = 500.0;
  s.segment_count = 3;
  s.segments = readme_protocol;
  return s;
}

static void compare_with_cli(const char *name, int tip, char **expected) {
  char label[200];
  cc_stack *stack = coating();
  cc_kinetics_setup setup = setup_of(tip);
  cc_kinetics *run = NULL;
  double events[CC_KINETICS_EVENT_COLUMNS];
  int rows = -1, i, monotone = 1;
  double *states;
  snprintf(label, sizeof label, "%s: cc_kinetics_run", name);
  check(label, cc_kinetics_run(stack, &setup, &run) == CC_OK && run != NULL);
  check("cc_kinetics_size", cc_kinetics_size(run, &rows) == CC_OK);
  check("cc_kinetics_events", cc_kinetics_events(run, events) == CC_OK);
  printf("%s: pull-off %.17g N at %.17g s, a %.17g m; loss at %.17g s; %d states\n", name, events[0], events[1],
         events[2], events[4], rows);
  snprintf(label, sizeof label, "%s: pull-off force as the CLI", name);
  check(label, same(events[0], strtod(expected[0], NULL)));
  snprintf(label, sizeof label, "%s: pull-off time as the CLI", name);
  check(label, same(events[1], strtod(expected[1], NULL)));
  snprintf(label, sizeof label, "%s: pull-off radius as the CLI", name);
  check(label, same(events[2], strtod(expected[2], NULL)));
  snprintf(label, sizeof label, "%s: loss-of-contact time as the CLI", name);
  check(label, same(events[4], strtod(expected[3], NULL)));
  snprintf(label, sizeof label, "%s: number of states as the CLI", name);
  check(label, rows == atoi(expected[4]));
  states = (double *)malloc(sizeof(double) * (size_t)rows * CC_KINETICS_COLUMNS);
  check("cc_kinetics_states", states != NULL && cc_kinetics_states(run, rows, states) == CC_OK);
  for (i = 1; states != NULL && i < rows; ++i) {
    if (!(states[i * CC_KINETICS_COLUMNS] >= states[(i - 1) * CC_KINETICS_COLUMNS])) monotone = 0;
  }
  snprintf(label, sizeof label, "%s: times increase", name);
  check(label, monotone);
  /* The pull-off is the most tensile state of the table. */
  if (states != NULL) {
    double least = 0.0;
    for (i = 0; i < rows; ++i) {
      if (states[i * CC_KINETICS_COLUMNS + 4] < least) least = states[i * CC_KINETICS_COLUMNS + 4];
    }
    snprintf(label, sizeof label, "%s: pull-off is the least force of the states", name);
    check(label, least == events[0]);
  }
  /* A wrong row count is refused and writes nothing. */
  if (states != NULL) {
    states[0] = -7777.0;
    check("cc_kinetics_states: wrong rows refused", cc_kinetics_states(run, rows - 1, states) == CC_INPUT_ERROR);
    check("cc_kinetics_states: refused call writes nothing", states[0] == -7777.0);
  }
  free(states);
  cc_kinetics_destroy(run);
  cc_stack_destroy(stack);
}

static void sweep_and_errors(void) {
  cc_stack *stack = coating();
  cc_kinetics_setup setup = setup_of(CC_KINETICS_SPHERE);
  const double speeds[2] = {1e-5, 1e-4};
  double rows[2 * CC_KINETICS_SWEEP_COLUMNS];
  cc_kinetics *run = NULL, *sentinel = (cc_kinetics *)&setup;
  cc_kinetics_segment bad[3];
  check("cc_kinetics_sweep", cc_kinetics_sweep(stack, &setup, 2, speeds, rows) == CC_OK);
  check("sweep: speeds echoed", rows[0] == 1e-5 && rows[CC_KINETICS_SWEEP_COLUMNS] == 1e-4);
  check("sweep: faster retract, more tensile pull-off", rows[CC_KINETICS_SWEEP_COLUMNS + 1] < rows[1]);
  check("sweep: reduced speed proportional",
        fabs(rows[CC_KINETICS_SWEEP_COLUMNS + 6] / rows[6] - 10.0) < 1e-12);
  /* n <= 0: CC_INPUT_ERROR naming n; the handle is not written. */
  setup.n = 0.0;
  run = sentinel;
  check("n = 0 refused", cc_kinetics_run(stack, &setup, &run) == CC_INPUT_ERROR);
  check("n = 0: message names n", strstr(cc_last_error_message(), "n = 0") != NULL);
  check("n = 0: handle untouched", run == sentinel);
  setup.n = 0.6;
  memcpy(bad, readme_protocol, sizeof bad);
  bad[1].kind = 9;
  setup.segments = bad;
  check("unknown segment kind refused", cc_kinetics_run(stack, &setup, &run) == CC_INPUT_ERROR);
  check("unknown kind: message names the segment", strstr(cc_last_error_message(), "segment 2") != NULL);
  setup.segments = readme_protocol;
  setup.tip = 7;
  check("unknown tip refused", cc_kinetics_run(stack, &setup, &run) == CC_INPUT_ERROR);
  setup.tip = CC_KINETICS_CONE;
  setup.half_angle = 2.0;
  check("cone half angle past pi/2 refused", cc_kinetics_run(stack, &setup, &run) == CC_INPUT_ERROR);
  check("NULL setup refused", cc_kinetics_run(stack, NULL, &run) == CC_INPUT_ERROR);
  check("handle still untouched", run == sentinel);
  cc_stack_destroy(stack);
}

/* cc_kinetics_scales against the cone's units written out (THEORY.md section 14, "The cone"),
 * cc_kinetics_energy of a run, and cc_kinetics_fit recovering the law from curves the C API
 * itself simulated (noise-free, every third state; as tests/kinetics/cli_kinetics_fit.sh). */
static void scales_energy_and_fit(void) {
  cc_stack *stack = coating();
  cc_kinetics_setup setup = setup_of(CC_KINETICS_CONE);
  const double e_star = 1e6 / (1.0 - 0.49 * 0.49), tb = tan(setup.half_angle);
  const double l_a = 4.0 * 0.04 * tb * tb / (3.14159265358979323846 * e_star), l_d = 2.0 * 0.04 * tb / e_star;
  double scales[CC_KINETICS_SCALE_COLUMNS], energy[CC_KINETICS_ENERGY_COLUMNS];
  static const double speeds[3] = {1e-6, 1e-5, 1e-4};
  cc_kinetics_segment protocols[3][3];
  cc_kinetics_curve curves[3];
  double *time[3], *force[3], values[CC_KINETICS_FIT_PARAMETERS], errors[CC_KINETICS_FIT_PARAMETERS];
  double correlation[CC_KINETICS_FIT_PARAMETERS * CC_KINETICS_FIT_PARAMETERS], *model, *residual;
  cc_kinetics_fit_request request;
  cc_kinetics_fit_summary summary;
  cc_kinetics *run = NULL;
  int c, i, total = 0;
  check("cc_kinetics_scales", cc_kinetics_scales(stack, &setup, scales) == CC_OK);
  check("cone L_a", same(scales[0], l_a));
  check("cone L_D", same(scales[1], l_d));
  check("cone F_s = E* L_a L_D", same(scales[2], e_star * l_a * l_d));
  check("t_s = L_a / v*", same(scales[3], l_a / 1e-6));
  check("eta = t / L_a", same(scales[4], 50e-6 / l_a));
  check("k_bar = k L_D / F_s", same(scales[5], 500.0 * l_d / (e_star * l_a * l_d)));
  check("scales: NULL out refused", cc_kinetics_scales(stack, &setup, NULL) == CC_INPUT_ERROR);

  setup = setup_of(CC_KINETICS_SPHERE);
  for (c = 0; c < 3; ++c) {
    int rows = 0, n = 0;
    double *states;
    memcpy(protocols[c], readme_protocol, sizeof protocols[c]);
    protocols[c][2].speed = speeds[c];
    setup.segments = protocols[c];
    check("fit data: cc_kinetics_run", cc_kinetics_run(stack, &setup, &run) == CC_OK);
    check("fit data: cc_kinetics_size", cc_kinetics_size(run, &rows) == CC_OK && rows > 9);
    if (c == 0) {
      check("cc_kinetics_energy", cc_kinetics_energy(run, energy) == CC_OK);
      check("energy: the receding edge dissipates", energy[1] > 0.0);
      check("energy: a whole number of steps", energy[2] >= 1.0 && energy[2] == floor(energy[2]));
    }
    states = malloc(sizeof(double) * rows * CC_KINETICS_COLUMNS);
    time[c] = malloc(sizeof(double) * rows);
    force[c] = malloc(sizeof(double) * rows);
    check("fit data: cc_kinetics_states", cc_kinetics_states(run, rows, states) == CC_OK);
    for (i = 2; i < rows; i += 3, ++n) {
      time[c][n] = states[i * CC_KINETICS_COLUMNS];
      force[c][n] = states[i * CC_KINETICS_COLUMNS + 4];
    }
    free(states);
    cc_kinetics_destroy(run);
    memset(&curves[c], 0, sizeof curves[c]);
    curves[c].segment_count = 3;
    curves[c].segments = protocols[c];
    curves[c].spring = 500.0;
    curves[c].n = n;
    curves[c].time = time[c];
    curves[c].force = force[c];
    total += n;
  }
  memset(&request, 0, sizeof request);
  request.radius = 2e-3;
  request.work = 0.06;
  request.v_star = 3e-6;
  request.n = 0.45;
  request.free[0] = request.free[1] = request.free[2] = 1;
  request.curve_count = 3;
  request.curves = curves;
  model = malloc(sizeof(double) * total);
  residual = malloc(sizeof(double) * total);
  check("cc_kinetics_fit", cc_kinetics_fit(stack, &request, values, errors, correlation, model, residual, &summary) ==
                               CC_OK);
  /* Noise-free data on the true run's states: 1e-3 (the bound of cli_kinetics_fit.sh). */
  check("fit: w", fabs(values[0] / 0.04 - 1.0) <= 1e-3);
  check("fit: v_star", fabs(values[1] / 1e-6 - 1.0) <= 1e-3);
  check("fit: n", fabs(values[2] / 0.6 - 1.0) <= 1e-3);
  check("fit: t and E1 fixed at the stack's", values[3] == 50e-6 && values[4] == 1e6 && errors[3] == 0.0);
  check("fit: unweighted, R^2 ~ 1", summary.weighted == 0 && summary.r_squared > 0.999999);
  check("fit: correlation diagonal", correlation[0] == 1.0 && correlation[6] == 1.0);
  check("fit: model + residual = data", fabs(model[total - 1] - residual[total - 1] - force[2][curves[2].n - 1]) <=
                                            1e-12 * fabs(force[2][curves[2].n - 1]));
  request.curve_count = 1;
  check("fit: one retract speed with v_star and n free refused",
        cc_kinetics_fit(stack, &request, values, errors, NULL, NULL, NULL, &summary) == CC_INPUT_ERROR);
  check("fit: NULL request refused",
        cc_kinetics_fit(stack, NULL, values, errors, NULL, NULL, NULL, &summary) == CC_INPUT_ERROR);
  for (c = 0; c < 3; ++c) {
    free(time[c]);
    free(force[c]);
  }
  free(model);
  free(residual);
  cc_stack_destroy(stack);
}

int main(int argc, char **argv) {
  if (argc != 11) {
    printf("usage: test_capi_kinetics F t a t_loss states (sphere) F t a t_loss states (cone)\n");
    return 2;
  }
  compare_with_cli("sphere", CC_KINETICS_SPHERE, argv + 1);
  compare_with_cli("cone", CC_KINETICS_CONE, argv + 6);
  sweep_and_errors();
  scales_energy_and_fit();
  if (failures != 0) {
    printf("%d failure(s)\n", failures);
    return 1;
  }
  printf("all checks passed\n");
  return 0;
}
