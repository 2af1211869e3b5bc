/* test_util.h - helpers shared by the Check suites: directions, relative comparison,
 * and a runner that prints Check's summary line. */
#ifndef ABRDF_TEST_UTIL_H
#define ABRDF_TEST_UTIL_H
#include <check.h>
#include "abrdf.h"

/* Unit direction from polar angle theta and azimuth phi (degrees), local frame. */
void tu_dir(double theta_deg, double phi_deg, double out[3]);
/* |a - b| <= rel * max(|a|, |b|) + abs_tol */
int tu_close(double a, double b, double rel, double abs_tol);
/* Evaluate model with params in the local frame; returns channel 0 and asserts OK. */
double tu_eval1(abrdf_model m, const abrdf_params *p, const double wi[3], const double wo[3]);
/* Evaluation counters of the stability grids. */
typedef struct tu_counts {
    long evals, nan, inf, neg;
} tu_counts;
/* Add f[0..2] to the counters (each value counts once: NaN, else Inf, else negative). */
void tu_count(tu_counts *k, const double f[3]);
/* Model `id`'s metadata if it is evaluated from parameters alone (every model but the
 * `measured` one, which needs a caller's table: test_measured.c runs the shared properties
 * on tables), else NULL; what the suites that loop over every model iterate. */
const abrdf_model_info *tu_param_model(int id);
/* Run one suite, print the summary, return the process exit status. */
int tu_run(Suite *s);
#endif
