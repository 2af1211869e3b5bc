/* measured_table.h - a measured BRDF as the tools hold it: an isotropic table on the
 * half/difference grid of Rusinkiewicz (1998) that the MERL database uses (Matusik et al.,
 * "A Data-Driven Reflectance Model", SIGGRAPH 2003), read from a file (MERL binary, RGL
 * .bsdf) or written from an analytic model. The table is the memory libabrdf's `measured`
 * model evaluates (abrdf_measured in abrdf.h): this file owns it, the library only points
 * at it.
 *
 * THE GRID (the same in the library, the readers and the writers). Cell (ih, id, ip) holds
 * f_r (1/sr, linear RGB, without the cosine) at
 *   theta_h = (ih / n_theta_h)^2 * pi/2     (MERL's square-root index: dense at the highlight)
 *   theta_d = id / n_theta_d * pi/2
 *   phi_d   = ip / n_phi_d * pi             (phi_d and phi_d + pi are the same cell:
 *                                            reciprocity of an isotropic BRDF)
 * with phi_h = 0, at data[((ih * n_theta_d + id) * n_phi_d + ip) * 3 + c]. A negative value
 * means "not measured".
 *
 *   measured_table_alloc       a table of the given grid, every cell "not measured"
 *   measured_table_free        release it
 *   measured_table_cell        the offset of cell (ih, id, ip)'s red value in data
 *   measured_table_directions  the light and view directions of a cell (local frame, N = +z)
 */
#ifndef ABRDF_MEASURED_TABLE_H
#define ABRDF_MEASURED_TABLE_H

#include <stddef.h>

#define MEASURED_DIM_MIN 2                   /* cells per axis */
#define MEASURED_DIM_MAX 1024                /* cells per axis */
#define MEASURED_MAX_CELLS ((size_t)1 << 24) /* 16.8 M cells (MERL: 1.46 M), 192 MiB of floats */

typedef struct measured_table {
    int n_theta_h, n_theta_d, n_phi_d; /* the grid, each [MEASURED_DIM_MIN, MEASURED_DIM_MAX];
                                          MERL: 90, 90, 180 */
    float *data;       /* 3 floats per cell (above); f_r in 1/sr, < 0 = not measured */
    size_t unmeasured; /* cells with at least one channel not measured */
} measured_table;

/* 0 and a table of that grid with every value -1, or -1 with a one-line reason in err
 * (a dimension out of range, more than MEASURED_MAX_CELLS cells, out of memory). */
int measured_table_alloc(measured_table *t, int n_theta_h, int n_theta_d, int n_phi_d, char *err,
                         size_t err_size);
void measured_table_free(measured_table *t);
size_t measured_table_cell(const measured_table *t, int ih, int id, int ip);
/* Unit wi (toward the light) and wo (toward the viewer) of cell (ih, id, ip), phi_h = 0. */
void measured_table_directions(const measured_table *t, int ih, int id, int ip, double wi[3],
                               double wo[3]);

#endif
