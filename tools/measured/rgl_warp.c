/* rgl_warp.c - grids and the continuous marginal/conditional warp (rgl_warp.h).
 *
 * Source: J. Dupuy, W. Jakob, "An Adaptive Parameterization for Efficient Material
 * Acquisition and Rendering", ACM TOG 37(6), 2018. The tables are stored in float,
 * their sums accumulated in double, as the files' reader in Mitsuba 3 builds them, so that the
 * two evaluate a file alike to float precision.
 */
#include "rgl_warp.h"

#include <math.h>
#include <stdlib.h>

static double lerp(double a, double b, double t) { return a + (b - a) * t; }

static double clamp01(double x) { return x > 0 ? (x < 1 ? x : 1) : 0; }

/* Value i of a table of per-slice size n, mixed over the slices. */
static double mixed(const float *tab, long n, long i, const rgl_mix *mix)
{
    double v = 0;
    for (int k = 0; k < mix->n; ++k) v += mix->w[k] * tab[mix->slice[k] * n + i];
    return v;
}

/* The patch holding pos (scaled to patches) and the position inside it. */
static void patch(double x, int nodes, int *i, double *f)
{
    x = clamp01(x) * (nodes - 1);
    int k = (int)x;
    if (k > nodes - 2) k = nodes - 2;
    *i = k;
    *f = x - k;
}

double rgl_grid_eval(const rgl_grid *g, const rgl_mix *mix, const double pos[2])
{
    int ix, iy;
    double fx, fy;
    patch(pos[0], g->w, &ix, &fx);
    patch(pos[1], g->h, &iy, &fy);
    long n = (long)g->w * g->h, i = (long)iy * g->w + ix;
    double v00 = mixed(g->v, n, i, mix), v10 = mixed(g->v, n, i + 1, mix);
    double v01 = mixed(g->v, n, i + g->w, mix), v11 = mixed(g->v, n, i + g->w + 1, mix);
    return lerp(lerp(v00, v10, fx), lerp(v01, v11, fx), fy);
}

void rgl_warp_free(rgl_warp *t)
{
    free(t->data);
    free(t->cond);
    free(t->marg);
    t->data = t->cond = t->marg = NULL;
}

int rgl_warp_init(rgl_warp *t, const float *v, int n_slices, int h, int w)
{
    size_t nd = (size_t)w * h, nc = (size_t)(w - 1) * h, nm = (size_t)(h - 1);
    t->w = w, t->h = h, t->n_slices = n_slices;
    t->data = malloc(nd * n_slices * sizeof *t->data);
    t->cond = malloc(nc * n_slices * sizeof *t->cond);
    t->marg = malloc(nm * n_slices * sizeof *t->marg);
    double *rows = malloc((size_t)h * sizeof *rows);
    if (!t->data || !t->cond || !t->marg || !rows) {
        free(rows);
        rgl_warp_free(t);
        return -1;
    }
    double hx = 0.5 / (w - 1), hy = 0.5 / (h - 1); /* trapezoids of the bilinear interpolant */
    for (int s = 0; s < n_slices; ++s) {
        const float *d = v + nd * s;
        float *cond = t->cond + nc * s, *marg = t->marg + nm * s, *out = t->data + nd * s;
        for (int y = 0; y < h; ++y) {
            double acc = 0;
            for (int x = 0; x < w - 1; ++x) {
                acc += hx * ((double)d[y * w + x] + d[y * w + x + 1]);
                cond[y * (w - 1) + x] = (float)acc;
            }
            rows[y] = acc;
        }
        double acc = 0;
        for (int y = 0; y < h - 1; ++y) {
            acc += hy * (rows[y] + rows[y + 1]);
            marg[y] = (float)acc;
        }
        if (!(acc > 0) || !isfinite(acc)) {
            free(rows);
            rgl_warp_free(t);
            return s + 1;
        }
        float norm = (float)(1.0 / acc);
        for (size_t k = 0; k < nc; ++k) cond[k] *= norm;
        for (size_t k = 0; k < nm; ++k) marg[k] *= norm;
        for (size_t k = 0; k < nd; ++k) out[k] = d[k] * norm;
    }
    free(rows);
    return 0;
}

/* The integral of the linear density lerp(v0, v1, .) over [0, t] of a patch of this width. */
static double segment_integral(double t, double width, double v0, double v1)
{
    return t * lerp(v0, v1, 0.5 * t) * width;
}

/* Its inverse: the t in [0, 1] whose integral is a. */
static double segment_solve(double a, double width, double v0, double v1)
{
    double q = a / width; /* v0 t + (v1 - v0) t^2 / 2 = q */
    double t;
    if (fabs(v0 - v1) > 1e-4 * (v0 + v1))
        t = (v0 - sqrt(fmax(v0 * v0 + 2 * q * (v1 - v0), 0))) / (v0 - v1);
    else
        t = v0 + v1 > 0 ? 2 * q / (v0 + v1) : 0;
    return clamp01(t);
}

void rgl_warp_invert(const rgl_warp *t, const rgl_mix *mix, const double u[2], double s[2])
{
    int w = t->w, h = t->h, ix, iy;
    double fx, fy;
    patch(u[0], w, &ix, &fx);
    patch(u[1], h, &iy, &fy);
    long nd = (long)w * h, nc = (long)(w - 1) * h, nm = h - 1;
    long i = (long)iy * w + ix, row = (long)iy * (w - 1);
    double v00 = mixed(t->data, nd, i, mix), v10 = mixed(t->data, nd, i + 1, mix);
    double v01 = mixed(t->data, nd, i + w, mix), v11 = mixed(t->data, nd, i + w + 1, mix);
    double c0 = lerp(v00, v01, fy), c1 = lerp(v10, v11, fy);
    double x = segment_integral(fx, 1.0 / (w - 1), c0, c1);
    if (ix > 0)
        x += lerp(mixed(t->cond, nc, row + ix - 1, mix),
                  mixed(t->cond, nc, row + w - 1 + ix - 1, mix), fy);
    double r0 = mixed(t->cond, nc, row + w - 2, mix),
           r1 = mixed(t->cond, nc, row + 2 * (w - 1) - 1, mix);
    double r = lerp(r0, r1, fy);
    s[0] = r > 0 ? x / r : 0;
    double y = segment_integral(fy, 1.0 / (h - 1), r0, r1);
    if (iy > 0) y += mixed(t->marg, nm, iy - 1, mix);
    s[1] = y;
}

void rgl_warp_sample(const rgl_warp *t, int slice, const double s[2], double u[2])
{
    int w = t->w, h = t->h;
    const float *data = t->data + (long)w * h * slice, *cond = t->cond + (long)(w - 1) * h * slice;
    const float *marg = t->marg + (long)(h - 1) * slice;
    /* The row: the first whose marginal CDF reaches s[1]. */
    double y = clamp01(s[1]);
    int iy = 0;
    while (iy < h - 2 && marg[iy] < y) ++iy;
    if (iy > 0) y -= marg[iy - 1];
    double r0 = cond[iy * (w - 1) + w - 2], r1 = cond[(iy + 1) * (w - 1) + w - 2];
    double fy = segment_solve(y, 1.0 / (h - 1), r0, r1);
    /* The column, along the row interpolated at fy. */
    double x = clamp01(s[0]) * lerp(r0, r1, fy);
    int ix = 0;
    double before = 0;
    for (; ix < w - 2; ++ix) {
        double c = lerp(cond[iy * (w - 1) + ix], cond[(iy + 1) * (w - 1) + ix], fy);
        if (c >= x) break;
        before = c;
    }
    x -= before;
    long i = (long)iy * w + ix;
    double c0 = lerp(data[i], data[i + w], fy), c1 = lerp(data[i + 1], data[i + w + 1], fy);
    double fx = segment_solve(x, 1.0 / (w - 1), c0, c1);
    u[0] = (ix + fx) / (w - 1);
    u[1] = (iy + fy) / (h - 1);
}
