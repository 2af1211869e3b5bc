/* envmap.h - the environment light's image: a latitude-longitude (equirectangular) map of
 * radiance, read with OpenImageIO, and the 2-D piecewise-constant distribution that
 * importance-samples it by luminance (docs/RENDERER.md, "Area and environment lights").
 *
 * Mapping (world y up, docs/RENDERER.md, "World, camera, lights"): a unit direction d has
 * polar angle theta = acos(d.y) from +y and azimuth phi = atan2(d.x, -d.z) in (-pi, pi]; it
 * looks up the image at u = 0.5 + phi / (2 pi) (column, left to right), v = theta / pi (row,
 * top to bottom). So the top row is the zenith, the centre column looks along -z, and the
 * map's pixels are constant over their (u, v) cells (nearest lookup).
 *
 * Sampling: cell (i, j) is chosen with probability proportional to its luminance times
 * sin(theta_j) at the row's centre (the solid angle a cell covers), a point uniform in the
 * cell gives the direction, and the density per unit solid angle is
 *   p(d) = p_uv(i, j) / (2 pi^2 sin(theta)),  p_uv = W H w_ij / sum w,
 * (M. Pharr, W. Jakob, G. Humphreys, "Physically Based Rendering", 3rd ed., Sec. 13.6.7 and
 * 14.2.4: 2-D sampling from a marginal and conditional piecewise-constant distribution).
 *
 * PUBLIC FUNCTIONS
 *   envmap_load      read the image and build the distribution
 *   envmap_from_pixels  the same from pixels in memory (a map made by a program)
 *   envmap_free      release it
 *   envmap_lookup    radiance (the image's RGB) in a direction
 *   envmap_sample    a direction from two uniform numbers, with its density
 *   envmap_pdf       the density envmap_sample has at a direction
 */
#ifndef ABRDF_ENVMAP_H
#define ABRDF_ENVMAP_H

#define ENVMAP_MAX_SIDE 16384 /* pixels along either side */

typedef struct envmap {
    char *path;        /* the file as read (the scene directory joined to file=) */
    int width, height; /* pixels */
    float *rgb;        /* width * height * 3, linear, top row first */
    double *row_cdf;   /* height + 1: marginal CDF over rows, row_cdf[height] = 1 */
    double *col_cdf;   /* height * (width + 1): each row's conditional CDF */
    double *cell_pdf;  /* width * height: p_uv of each cell (0 where the map is black) */
    double total;      /* sum of luminance * sin(theta) over the cells (0: a black map) */
} envmap;

/* Read `path` (any format OpenImageIO reads; EXR or HDR for radiance) and build the
 * distribution. 0, or -1 with a one-line message naming the file in err. */
int envmap_load(const char *path, envmap *env, char *err, int err_size);
/* The same for W x H linear RGB pixels (top row first) that the map takes over (malloc'd;
 * freed here on failure); `path` names the map in messages. */
int envmap_from_pixels(const char *path, int W, int H, float *rgb, envmap *env, char *err,
                       int err_size);
void envmap_free(envmap *env);
/* Radiance of the map toward direction d (unit). */
void envmap_lookup(const envmap *env, const double d[3], double rgb[3]);
/* Direction d from u1, u2 in [0, 1); returns its solid-angle density (0: no sample, for a
 * black map or a sample on the poles). */
double envmap_sample(const envmap *env, double u1, double u2, double d[3]);
/* Density of envmap_sample at the unit direction d (1/sr). */
double envmap_pdf(const envmap *env, const double d[3]);

#endif
