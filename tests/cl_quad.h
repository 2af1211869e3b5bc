/* cl_quad.h - quadrature and stress helpers of the cloth and layered suites. */
#ifndef ABRDF_CL_QUAD_H
#define ABRDF_CL_QUAD_H
#include "abrdf.h"

/* Directional albedo rho(wi) = int f_r(wi, wo) cos_o dwo (channel c) for wi at theta_deg
 * (azimuth 0), integrated over the half vector with nodes concentrated at GGX width a:
 * Gauss-Legendre of order n in v (u = 1 - (1 - v)^2, tan^2 theta_h = a^2 u / (1 - u)),
 * 2n uniform azimuths. Local frame. */
double clq_albedo(abrdf_model m, const abrdf_params *p, double theta_deg, double a, int n, int c);

/* Deterministic pseudo-random numbers in [0, 1) and unit directions. */
double clq_rand(unsigned *state);
void clq_rand_dir(unsigned *state, double zmin, double out[3]);

/* Evaluation counters of the stability grids. */
typedef struct clq_counts {
    long evals, nan, inf, neg;
} clq_counts;
/* Add f[0..2] to the counters. */
void clq_count(clq_counts *k, const double f[3]);
#endif
