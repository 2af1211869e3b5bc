/* measured.h - the `measured` model: a caller-owned table of measured f_r on the isotropic
 * half/difference grid of the MERL database (abrdf.h, "measured materials"), looked up by
 * trilinear interpolation.
 *
 * Rusinkiewicz, "A New Change of Variables for Efficient BRDF Representation", EGWR 1998
 * (the half/difference angles); Matusik, Pfister, Brand, McMillan, "A Data-Driven Reflectance
 * Model", SIGGRAPH 2003 (the grid: theta_h on a square-root index, theta_d and phi_d linear,
 * phi_d over [0, pi) by reciprocity). docs/MEASURED.md states the interpolation. */
#ifndef ABRDF_MEASURED_H
#define ABRDF_MEASURED_H

#include "abrdf.h"

/* The prepared state: the caller's table and the lobe its sampler draws from. */
typedef struct abrdf__measured {
    const float *data; /* the caller's table (abrdf_measured.data) */
    int n_h, n_d, n_p; /* cells along theta_h, theta_d, phi_d */
    double alpha;      /* GGX alpha_g of the sampling lobe, fitted at prepare */
    double p_lobe;     /* probability of drawing from the lobe (else cosine) */
} abrdf__measured;

/* The grid sizes a table may have (each axis), checked by abrdf_prepare_measured. */
#define ABRDF__MEASURED_DIM_MIN 2
#define ABRDF__MEASURED_DIM_MAX 1024
/* ... and cells in all: 3 values each stay below 2^31, the batch path's 32-bit indices (a
 * MERL table has 1 458 000). */
#define ABRDF__MEASURED_CELLS_MAX (1 << 26)

/* Fill m from a table the caller checked (non-NULL data, sizes in range) and fit the sampling
 * lobe from the data. */
void abrdf__measured_setup(const abrdf_measured *table, abrdf__measured *m);
/* f_r for unit local wi, wo (double reference); 0 below the horizon. May return a value the
 * caller guards (finite_or_zero): a NaN or Inf cell in the table. */
void abrdf__measured_eval(const abrdf__measured *m, const double wi[3], const double wo[3],
                          double f[3]);
/* The float batch over a structure-of-arrays batch at instruction-set level `level` (isa.h;
 * the caller checked the CPU runs it); every output finite and >= 0. */
void abrdf__measured_batch(const abrdf__measured *m, const abrdf_batch *b, int level);

#endif /* ABRDF_MEASURED_H */
