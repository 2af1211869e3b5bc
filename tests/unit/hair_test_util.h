/* hair_test_util.h - helpers shared by the hair suites (Marschner, Huang). */
#ifndef ABRDF_HAIR_TEST_UTIL_H
#define ABRDF_HAIR_TEST_UTIL_H

/* Fibre direction from longitudinal angle theta and azimuth phi (radians), hair.h frame. */
void htu_fdir(double theta, double phi, double w[3]);

/* The direction (theta, phi) in the frame of huang's table (hair_huang_table.c: phi about
 * the fibre, 0 along local z). */
void htu_table_dir(double theta, double phi, double w[3]);

/* Four numbers in [0, 1) from a linear congruential sequence (the tests' own, repeatable). */
void htu_uniforms(unsigned *seed, double a[4]);

/* A fibre scattering function S (hair.h convention) of model state m. */
typedef void (*htu_fibre_fn)(const void *m, const double wi[3], const double wo[3], unsigned lobes,
                             double s[3]);

/* Fibre albedo: integral of S (channel 0) over the sphere of wi, view at theta_o (azimuth
 * 0.3), by the midpoint rule on nt x np cells. */
double htu_fibre_albedo(htu_fibre_fn S, const void *m, double theta_o, unsigned lobes, int nt,
                        int np);

/* The convergence cylinder of docs/MODELS.md, "Convergence on an image": a fibre cylinder,
 * axis (and fibres) along world y, seen orthographically along -z, lit by the two directional
 * lights of scenes/mixed.scene; along the axis nothing changes, so the image is one row of
 * HTU_CYL_SAMPLES pixel centres across it, each
 *     L = sum_l E_l max(0, N.L_l) f_r(L_l, V),   local frame (T = y, B = N x T, N),
 * f_r from eval (the model's f_r in the local frame, wi the light). */
#define HTU_CYL_SAMPLES 64
typedef void (*htu_eval_fn)(const void *m, const double wi[3], const double wo[3], double f[3]);
void htu_cylinder_image(htu_eval_fn eval, const void *m, double img[HTU_CYL_SAMPLES][3]);
/* The same, backlit if backlit is not 0: the second light behind the cylinder (its z negated,
 * (0.7, 0.25, -0.45)), so that the fibres near the silhouette it lights let it through to the
 * view (TT, which the front lights never give). */
void htu_cylinder_image_lit(htu_eval_fn eval, const void *m, int backlit,
                            double img[HTU_CYL_SAMPLES][3]);

/* Table 8's image NMSE of img against ref. */
double htu_image_nmse(const double ref[HTU_CYL_SAMPLES][3], const double img[HTU_CYL_SAMPLES][3]);
#endif
