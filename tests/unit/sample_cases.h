/* sample_cases.h - the parameter sets and view directions the sampling suites run every
 * model on: the model's defaults, then one parameter at a time moved to the values of
 * sc_variations (those the model uses, inside its range). Built from the registry, so a
 * model added later is covered without editing the suites. */
#ifndef ABRDF_SAMPLE_CASES_H
#define ABRDF_SAMPLE_CASES_H
#include "abrdf.h"

#define SC_MAX_SETS 12

typedef struct sc_set {
    abrdf_params p;
    char label[64]; /* "defaults" or "NAME=VALUE" */
} sc_set;

/* The sets for `model`; returns their count (>= 1). */
int sc_param_sets(abrdf_model model, sc_set *out);

/* The local direction to centre a histogram on: the mirror direction of wo for the
 * specular samplers, the fibre T = +x for fibre and hair samplers, N = +z for the cosine;
 * *warp receives the ring spacing of the grid (sample_stats.h). */
void sc_pole(abrdf_model model, const double wo[3], double pole[3], double *warp);

#endif
