/* cl_quad.h - random directions of the cloth and layered suites;
 * the quadrature itself is tools/quad.h. */
#ifndef ABRDF_CL_QUAD_H
#define ABRDF_CL_QUAD_H
#include "abrdf.h"
#include "quad.h" /* quad_albedo, quad_gauss_legendre01 (tools/) */

/* Deterministic pseudo-random numbers in [0, 1) and unit directions. */
double clq_rand(unsigned *state);
void clq_rand_dir(unsigned *state, double zmin, double out[3]);

#endif
