/* hair_test_util.h - helpers shared by the hair suites (Marschner, Huang). */
#ifndef ABRDF_HAIR_TEST_UTIL_H
#define ABRDF_HAIR_TEST_UTIL_H

/* Fibre direction from longitudinal angle theta and azimuth phi (radians), hair.h frame. */
void htu_fdir(double theta, double phi, double w[3]);

/* A fibre scattering function S (hair.h convention) of model state m. */
typedef void (*htu_fibre_fn)(const void *m, const double wi[3], const double wo[3], unsigned lobes,
                             double s[3]);

/* Fibre albedo: integral of S (channel 0) over the sphere of wi, view at theta_o (azimuth
 * 0.3), by the midpoint rule on nt x np cells. */
double htu_fibre_albedo(htu_fibre_fn S, const void *m, double theta_o, unsigned lobes, int nt,
                        int np);
#endif
