/* quad.h - hemisphere quadrature and random directions shared by the table generator, the
 * measurement tool and the cloth and layered suites. */
#ifndef ABRDF_TOOLS_QUAD_H
#define ABRDF_TOOLS_QUAD_H
#include "abrdf.h"

/* Largest order quad_albedo integrates with (larger orders are clamped). */
#define QUAD_ORDER_MAX 1024

/* Gauss-Legendre nodes x[0..n-1] and weights w[0..n-1] on [0, 1], by Newton's iteration on
 * P_n (deterministic: the generated tables depend on the exact values). */
void quad_gauss_legendre01(int n, double *x, double *w);

/* Directional albedo rho(wi) = int f_r(wi, wo) cos_o dwo (channel c) for wi at theta_deg
 * (azimuth 0), integrated over the half vector h of the pair, wo = 2 (wi.h) h - wi
 * (dwo = 4 (wi.h) dwh), with nodes concentrated at GGX width a: Gauss-Legendre of order n
 * in v (u = 1 - (1 - v)^2, tan^2 theta_h = a^2 u / (1 - u)), 2n uniform azimuths. Local
 * frame. */
double quad_albedo(abrdf_model m, const abrdf_params *p, double theta_deg, double a, int n, int c);
/* Deterministic pseudo-random numbers in [0, 1) (a 32-bit LCG, top 24 bits) and unit
 * directions with z uniform in [zmin, 1) and a uniform azimuth. */
double quad_rand(unsigned *state);
void quad_rand_dir(unsigned *state, double zmin, double out[3]);
#endif
