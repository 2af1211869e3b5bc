/* abrdf_web.h - the functions the browser explorer's JavaScript calls (abrdf_web.c; the page
 * reaches them through static/abrdf_api.js, docs/EXPLORER.md). Directions are in the local
 * frame (normal +z, tangent +x); f_r is RGB, 1/sr, without the cosine. Functions returning int
 * give 0 or -1; texts stay valid until the next call returning a text; after a failure
 * aw_error() holds one line saying why and aw_error_param() the parameter it names (or ""). */
#ifndef ABRDF_WEB_H
#define ABRDF_WEB_H

#define AW_SLOTS 4 /* model slots: 0 and 1 are the page's A and B */
/* The largest arguments taken (larger ones are refused with a message): */
#define AW_MAX_PAIRS (1 << 24)      /* direction pairs of one aw_eval */
#define AW_MAX_SIZE 4096            /* sphere and mask images, pixels per side */
#define AW_MAX_GRID 1024            /* hemisphere grid, views per side */
#define AW_MAX_GRID_CELLS (1 << 20) /* ... and in all */

const char *aw_error(void);
const char *aw_error_param(void);
const char *aw_version(void);
/* Every model with its parameters (JSON array); the material table's rows (JSON array). */
const char *aw_models(void);
const char *aw_materials(void);
/* Put `model` with its defaults and spec's values ("r=0.3;kd=0.5,0.4,0.3") into `slot`,
 * prepared; on any error the slot keeps its model. */
int aw_set_model(int slot, const char *model, const char *spec);
/* The same with a diffuse lobe (name, or "" for none) reading the same block: the slot's f_r
 * is the sum, as abrdf_shade evaluates a material's choice. */
int aw_set_pair(int slot, const char *diffuse, const char *model, const char *spec);
/* f_r of count pairs, wi and wo interleaved xyz (any length), into out (3 count floats). */
int aw_eval(int slot, const float *wi, const float *wo, int count, float *out);
/* The plane of incidence: light at theta_i degrees (azimuth 0), views from -90 to +90
 * degrees, count in [2, 1024] (theta_o receives the angles). */
int aw_plane(int slot, double theta_i, int count, double *theta_o, float *out);
/* f_r at views theta_j = (j + 0.5)/nt 90 degrees, phi_k = k/np 360, entry (j np + k) 3. */
int aw_hemisphere(int slot, double theta_i, double phi_i, int nt, int np, float *out);
/* Rows [y0, y1) of a size x size unit sphere seen from +z under a directional light toward
 * (lx, ly, lz) of irradiance pi: L = f_r max(0, n.l) pi, 0 outside the disk; step > 1
 * evaluates one pixel per step x step block. out: 3 size (y1 - y0) floats. */
int aw_sphere_rows(int slot, int size, double lx, double ly, double lz, int y0, int y1, int step,
                   float *out);
/* 1 inside the sphere's disk (size x size bytes). */
int aw_mask(int size, unsigned char *out);
/* NMSE of img against ref (n floats; NaN for n < 0) and the paper's Table-8 class of a
 * value. */
double aw_nmse(const float *img, const float *ref, int n);
const char *aw_nmse_class(double nmse);
/* The flowchart's choice as `abrdf advise --json` prints it; the budget mode (pareto 0) or
 * the front (pareto 1) as `abrdf advise --budget|--pareto --json` do. spec: "name=gold",
 * values over it ("name=gold;r=0.1") or explicit ones ("type=general;n=300;kd=0.5"). NULL on
 * error. */
const char *aw_select(const char *spec, const char *goal);
const char *aw_budget(const char *spec, double max_nmse, int pareto);

#endif
