/* envmap.c - the environment light's lat-long map and its luminance distribution
 * (envmap.h). */
#include "envmap.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "image_io.h"

static const double PI = 3.14159265358979323846;

void envmap_free(envmap *env)
{
    if (!env) return;
    free(env->path), free(env->rgb), free(env->row_cdf), free(env->col_cdf), free(env->cell_pdf);
    memset(env, 0, sizeof *env);
}

/* Rec. 709 luminance of linear RGB (the weights of the sampling distribution). */
static double luminance(const float *p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

int envmap_load(const char *path, envmap *env, char *err, int err_size)
{
    memset(env, 0, sizeof *env);
    abrdf_image img;
    if (abrdf_image_read(path, &img, err, err_size)) return -1;
    /* the pixels (malloc'd by abrdf_image_read) are the map's now, or freed on failure */
    return envmap_from_pixels(path, img.width, img.height, img.pixels, env, err, err_size);
}

int envmap_from_pixels(const char *path, int W, int H, float *rgb, envmap *env, char *err,
                       int err_size)
{
    memset(env, 0, sizeof *env);
    if (W < 1 || H < 1 || W > ENVMAP_MAX_SIDE || H > ENVMAP_MAX_SIDE) {
        snprintf(err, (size_t)err_size, "%s: %dx%d pixels; an environment map needs 1 to %d a side",
                 path, W, H, ENVMAP_MAX_SIDE);
        free(rgb);
        return -1;
    }
    size_t n = (size_t)W * (size_t)H;
    for (size_t k = 0; k < 3 * n; ++k)
        if (!(rgb[k] >= 0.0f) || !isfinite(rgb[k])) {
            snprintf(err, (size_t)err_size,
                     "%s: pixel (%d, %d) holds %g; radiance must be finite and >= 0", path,
                     (int)(k / 3 % (size_t)W), (int)(k / 3 / (size_t)W), (double)rgb[k]);
            free(rgb);
            return -1;
        }
    env->path = malloc(strlen(path) + 1);
    env->row_cdf = malloc(((size_t)H + 1) * sizeof *env->row_cdf);
    env->col_cdf = malloc((size_t)H * ((size_t)W + 1) * sizeof *env->col_cdf);
    env->cell_pdf = malloc(n * sizeof *env->cell_pdf);
    env->rgb = rgb;
    if (!env->path || !env->row_cdf || !env->col_cdf || !env->cell_pdf) {
        envmap_free(env);
        snprintf(err, (size_t)err_size, "%s: out of memory", path);
        return -1;
    }
    strcpy(env->path, path);
    env->width = W, env->height = H;
    /* Row sums of luminance * sin(theta at the row's centre), each row's CDF, the marginal. */
    env->row_cdf[0] = 0.0;
    for (int j = 0; j < H; ++j) {
        double s = sin(PI * (j + 0.5) / H), *cdf = env->col_cdf + (size_t)j * ((size_t)W + 1);
        cdf[0] = 0.0;
        for (int i = 0; i < W; ++i)
            cdf[i + 1] = cdf[i] + luminance(env->rgb + 3 * ((size_t)j * W + i)) * s;
        env->row_cdf[j + 1] = env->row_cdf[j] + cdf[W];
    }
    env->total = env->row_cdf[H];
    for (int j = 0; j < H; ++j) {
        double *cdf = env->col_cdf + (size_t)j * ((size_t)W + 1), row = cdf[W];
        for (int i = 0; i < W; ++i) {
            double w = cdf[i + 1] - cdf[i];
            env->cell_pdf[(size_t)j * W + i] = env->total > 0 ? w * (double)n / env->total : 0.0;
        }
        for (int i = 1; i <= W; ++i) cdf[i] = row > 0 ? cdf[i] / row : (double)i / W;
        cdf[W] = 1.0;
    }
    for (int j = 1; j <= H; ++j)
        env->row_cdf[j] = env->total > 0 ? env->row_cdf[j] / env->total : (double)j / H;
    env->row_cdf[H] = 1.0;
    return 0;
}

/* The cell of direction d, and sin(theta); 0 if d is on the poles' axis. */
static double cell_of(const envmap *env, const double d[3], int *i, int *j)
{
    double y = d[1] > 1.0 ? 1.0 : d[1] < -1.0 ? -1.0 : d[1];
    double theta = acos(y), phi = atan2(d[0], -d[2]);
    double u = 0.5 + phi / (2.0 * PI), v = theta / PI;
    int ii = (int)floor(u * env->width), jj = (int)floor(v * env->height);
    *i = ii < 0 ? 0 : ii >= env->width ? env->width - 1 : ii;
    *j = jj < 0 ? 0 : jj >= env->height ? env->height - 1 : jj;
    return sqrt(d[0] * d[0] + d[2] * d[2]);
}

void envmap_lookup(const envmap *env, const double d[3], double rgb[3])
{
    int i, j;
    cell_of(env, d, &i, &j);
    const float *p = env->rgb + 3 * ((size_t)j * env->width + i);
    rgb[0] = p[0], rgb[1] = p[1], rgb[2] = p[2];
}

/* Index k with cdf[k] <= u < cdf[k + 1] among n intervals (cdf[0] = 0, cdf[n] = 1), skipping
 * empty intervals; the offset of u inside it, in [0, 1). */
static int find_interval(const double *cdf, int n, double u, double *frac)
{
    int lo = 0, hi = n; /* cdf[lo] <= u < cdf[hi] */
    while (hi - lo > 1) {
        int mid = (lo + hi) / 2;
        if (cdf[mid] <= u)
            lo = mid;
        else
            hi = mid;
    }
    double w = cdf[lo + 1] - cdf[lo];
    double f = w > 0 ? (u - cdf[lo]) / w : 0.5;
    *frac = f < 0 ? 0 : f >= 1 ? 0x1.fffffffffffffp-1 : f;
    return lo;
}

double envmap_sample(const envmap *env, double u1, double u2, double d[3])
{
    d[0] = 0, d[1] = 1, d[2] = 0;
    if (!(env->total > 0)) return 0.0;
    int W = env->width, H = env->height;
    double fv, fu;
    int j = find_interval(env->row_cdf, H, u1, &fv);
    int i = find_interval(env->col_cdf + (size_t)j * ((size_t)W + 1), W, u2, &fu);
    double p_uv = env->cell_pdf[(size_t)j * W + i];
    if (!(p_uv > 0)) return 0.0; /* u on the boundary of an empty cell: measure zero */
    double theta = PI * (j + fv) / H, phi = 2.0 * PI * ((i + fu) / W - 0.5);
    double st = sin(theta);
    if (!(st > 0)) return 0.0;
    d[0] = st * sin(phi), d[1] = cos(theta), d[2] = -st * cos(phi);
    return p_uv / (2.0 * PI * PI * st);
}

double envmap_pdf(const envmap *env, const double d[3])
{
    if (!(env->total > 0)) return 0.0;
    int i, j;
    double st = cell_of(env, d, &i, &j);
    if (!(st > 0)) return 0.0;
    return env->cell_pdf[(size_t)j * env->width + i] / (2.0 * PI * PI * st);
}
