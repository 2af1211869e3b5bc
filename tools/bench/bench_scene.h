/* bench_scene.h - the steps the scene benchmarks share (bench_scene.c): timed renders, the
 * interleaved repetitions with their medians, the squared errors over a pixel mask. */
#ifndef ABRDF_BENCH_SCENE_H
#define ABRDF_BENCH_SCENE_H
#include <stddef.h>
#include <stdio.h>

#include "render.h"
#include "scene.h"

/* Wall-clock seconds (monotonic), for render timings that span threads. */
double bench_wall_seconds(void);

/* Renders s with ro into rgb; *seconds (may be NULL) receives the wall time of render_image.
 * Returns 0, or -1 with a message in err. */
int bench_render_timed(const scene *s, const render_options *ro, float *rgb, double *seconds,
                       char *err, size_t err_size);

/* Renders each of the count scenes sv[v] into img[v], reps + 1 times with the repetitions
 * interleaved (so that drift of the machine's load affects every scene alike; the first
 * round untimed); sec[v] receives the median time. Returns 0, or -1 with a message in err. */
int bench_render_medians(const scene *sv, int count, const render_options *ro, int reps,
                         float *const *img, double *sec, char *err, size_t err_size);

/* *num: the sum of the squared differences of img from ref, *den: the sum of ref's squares,
 * over the pixels (3 floats each) where mask > 0.5 (all pixels if mask is NULL). */
void bench_masked_sums(const float *img, const float *ref, const float *mask, size_t pixels,
                       double *num, double *den);

/* One material's JSON object {"material", "models", "nmse"} (a non-finite nmse as -1),
 * preceded by ", " unless it is the first (i == 0) of its array. */
void bench_material_json(FILE *out, int i, const char *name, const char *models, double nmse);

#endif
