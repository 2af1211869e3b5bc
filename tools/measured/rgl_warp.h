/* rgl_warp.h - the tables of an RGL .bsdf file as functions on the unit square (rgl_bsdf.h):
 * piecewise-bilinear grids, and the warp of Dupuy & Jakob 2018: a grid taken as a
 * density on the square, mapped to the square by its continuous marginal (over rows) and
 * conditional (along a row) CDFs, both of the bilinear interpolant. A table holds several
 * slices (one per incident direction); a lookup mixes up to 4 of them linearly, value by value,
 * before any other arithmetic, so that a warp between slices is the warp of the mixed table.
 *
 *   rgl_grid_eval    the bilinear interpolant at a point of the square
 *   rgl_warp_init    normalise each slice to integrate to 1 and build its CDFs
 *   rgl_warp_invert  a point of the square -> its warped position (the CDFs' values)
 *   rgl_warp_sample  the inverse, for one slice: a warped position -> the point
 *   rgl_warp_free    release the tables
 */
#ifndef ABRDF_RGL_WARP_H
#define ABRDF_RGL_WARP_H

typedef struct rgl_mix {
    int slice[4];
    double w[4]; /* weights, summing to 1 */
    int n;       /* slices mixed, [1, 4] */
} rgl_mix;

typedef struct rgl_grid {
    int w, h;     /* nodes along x (the first coordinate) and y, each >= 2 */
    int n_slices; /* slices of h x w floats, one after the other */
    float *v;
} rgl_grid;

typedef struct rgl_warp {
    int w, h, n_slices;
    float *data; /* each slice scaled to integrate to 1 over the square */
    float *cond; /* per slice h rows of w - 1: the integral of row y from 0 to node x + 1 */
    float *marg; /* per slice h - 1: the integral over rows 0 to y + 1 (the last is 1) */
} rgl_warp;

/* pos is clamped to the square. */
double rgl_grid_eval(const rgl_grid *g, const rgl_mix *mix, const double pos[2]);
/* 0; k + 1 if slice k integrates to 0 (it cannot be normalised); -1 out of memory.
 * On failure nothing stays allocated. v holds n_slices * h * w non-negative floats. */
int rgl_warp_init(rgl_warp *t, const float *v, int n_slices, int h, int w);
void rgl_warp_invert(const rgl_warp *t, const rgl_mix *mix, const double u[2], double s[2]);
void rgl_warp_sample(const rgl_warp *t, int slice, const double s[2], double u[2]);
void rgl_warp_free(rgl_warp *t);

#endif
