/* measured_cases.h - what the measured suites share (test_measured.c, test_fit_measured.c): a
 * table in memory with its descriptor, the directions of a cell of abrdf.h's grid, and tables
 * written from analytic models as `abrdf tabulate` writes them. */
#ifndef ABRDF_MEASURED_CASES_H
#define ABRDF_MEASURED_CASES_H

#include <stddef.h>

#include "abrdf.h"

typedef struct mc_table {
    abrdf_measured desc;
    float *data; /* owned: free() it */
} mc_table;

/* The offset of cell (ih, id, ip)'s red value in the table's data. */
size_t mc_cell(const abrdf_measured *t, int ih, int id, int ip);
/* The directions of cell (ih, id, ip) (abrdf.h's grid, phi_h = 0): d rotated by theta_h about
 * y is wi; wo is wi mirrored about h. */
void mc_cell_dirs(const abrdf_measured *t, int ih, int id, int ip, double wi[3], double wo[3]);
/* A table of the grid nh x nd x np filled with diffuse + specular (either may be
 * ABRDF_MODEL_NONE) at parameters p: cells with a direction below the horizon not measured
 * (-1), as no instrument measures there and `abrdf tabulate` writes them. */
void mc_table_of(mc_table *t, int nh, int nd, int np, abrdf_model diffuse, abrdf_model specular,
                 const abrdf_params *p);

#endif
