/* measure.h - timing of model evaluation on this machine: ns per evaluation on the float
 * batch path over random front-facing direction pairs (abrdf calibrate, abrdf tables 4). */
#ifndef ABRDF_MEASURE_H
#define ABRDF_MEASURE_H
#include <stddef.h>
#include "abrdf_select.h"

typedef struct measure_opts {
    int reps;                 /* timed repetitions; the median is reported */
    size_t pairs;             /* direction pairs per batch (structure of arrays, warm in cache) */
    double rep_seconds;       /* each repetition repeats the batch until it lasts this long */
    size_t integrating_pairs; /* pairs for models that integrate numerically (slow) */
} measure_opts;

/* Defaults: 7 repetitions of 4096 pairs, 20 ms each (quick: 3 repetitions of 5 ms). */
void measure_defaults(measure_opts *o, int quick);

typedef struct measure_set measure_set;

/* Fixed-seed random unit directions on the upper hemisphere; NULL if out of memory. */
measure_set *measure_set_new(size_t pairs);
void measure_set_free(measure_set *s);

/* Median ns/eval of `model` (its default parameters) via abrdf_eval_batch. Models that
 * integrate numerically use at most o->integrating_pairs of the pairs. The measured model
 * evaluates a table of MERL's grid written from an analytic material (measure.c,
 * bench_table), prepared once. Returns < 0 on error. */
double measure_model_ns(measure_set *s, abrdf_model model, const measure_opts *o);
/* The same for parameters p, on the float batch path (double_path 0), the double scalar
 * reference path abrdf_eval in the local frame (double_path 1, one call per pair), or the
 * same prepared once per batch (double_path 2, abrdf_eval_prepared per pair; double_path 3,
 * abrdf_eval_prepared_unit per pair; double_path 4, the float per-sample call
 * abrdf_eval_prepared_float per pair; double_path 5, abrdf_inline.h's abrdf_ggx_float_eval
 * per pair, disney_specular only: < 0 for another model). */
double measure_model_params_ns(measure_set *s, abrdf_model model, const abrdf_params *p,
                               int double_path, const measure_opts *o);
/* Median ns per pair of `model` (parameters p) on the float batch path when the pairs come
 * in runs of `lights` pairs that share one view wo, as a renderer hands a shading point's
 * lights over (huang builds the view's paths once per run): the cost per light. The views
 * and lights are those of groups of `group` >= lights fresh pairs (the seed of
 * measure_set_new), so that runs of 1 and of `group` lights are timed on the same views;
 * < 0 on error. */
double measure_shared_view_ns(abrdf_model model, const abrdf_params *p, int lights, int group,
                              const measure_opts *o);
/* Median ns/eval of the unit: a bare loop H = normalise(wi + wo), powf(H.z, n), n = 100. */
double measure_unit_ns(measure_set *s, const measure_opts *o);

/* Measure `models` (count of them; NULL = every registered model) into out (unit
 * COSTS_UNIT; the others < 0) and the unit into *unit_ns. progress (may be NULL) is called
 * with each name before it is timed. Returns 0, or -1 if out of memory. */
int measure_models(const measure_opts *o, const abrdf_model *models, int count, abrdf_costs *out,
                   double *unit_ns, void (*progress)(const char *name));

#endif
