/* bench_scene.c - the steps the scene benchmarks share (bench_scene.h). */
#define _POSIX_C_SOURCE 200809L
#include "bench_scene.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "cli_args.h"

double bench_wall_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

int bench_render_timed(const scene *s, const render_options *ro, float *rgb, double *seconds,
                       char *err, size_t err_size)
{
    render_scene rs;
    if (render_prepare(s, ro, &rs, err, err_size)) return -1;
    double t0 = bench_wall_seconds();
    int rc = render_image(&rs, ro, rgb, NULL);
    if (seconds) *seconds = bench_wall_seconds() - t0;
    render_release(&rs);
    if (rc) snprintf(err, err_size, "cannot start render threads");
    return rc;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int bench_render_medians(const scene *sv, int count, const render_options *ro, int reps,
                         float *const *img, double *sec, char *err, size_t err_size)
{
    double *t = malloc(sizeof(double) * (size_t)(reps * count));
    if (!t) {
        snprintf(err, err_size, "out of memory");
        return -1;
    }
    for (int r = -1; r < reps; ++r) /* r = -1: untimed warm-up */
        for (int v = 0; v < count; ++v) {
            double s;
            if (bench_render_timed(&sv[v], ro, img[v], &s, err, err_size)) {
                free(t);
                return -1;
            }
            if (r >= 0) t[v * reps + r] = s;
        }
    for (int v = 0; v < count; ++v) {
        qsort(t + v * reps, (size_t)reps, sizeof(double), cmp_double);
        sec[v] = t[v * reps + reps / 2];
    }
    free(t);
    return 0;
}

void bench_masked_sums(const float *img, const float *ref, const float *mask, size_t pixels,
                       double *num, double *den)
{
    double n = 0, d = 0;
    for (size_t p = 0; p < pixels; ++p) {
        if (mask && !(mask[3 * p] > 0.5f)) continue;
        for (int c = 0; c < 3; ++c) {
            double e = (double)img[3 * p + c] - ref[3 * p + c];
            n += e * e;
            d += (double)ref[3 * p + c] * ref[3 * p + c];
        }
    }
    *num = n;
    *den = d;
}

void bench_material_json(FILE *out, int i, const char *name, const char *models, double nmse)
{
    fprintf(out, "%s{\"material\": ", i ? ", " : "");
    cli_json_string(out, name);
    fprintf(out, ", \"models\": ");
    cli_json_string(out, models);
    fprintf(out, ", \"nmse\": %.6g}", isfinite(nmse) ? nmse : -1.0);
}
