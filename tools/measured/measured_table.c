/* measured_table.c - the tools' measured table (measured_table.h). */
#include "measured_table.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#define PI 3.14159265358979323846

int measured_table_alloc(measured_table *t, int n_theta_h, int n_theta_d, int n_phi_d, char *err,
                         size_t err_size)
{
    t->n_theta_h = t->n_theta_d = t->n_phi_d = 0;
    t->data = NULL;
    t->unmeasured = 0;
    const int dims[3] = {n_theta_h, n_theta_d, n_phi_d};
    static const char *const names[3] = {"theta_h", "theta_d", "phi_d"};
    for (int k = 0; k < 3; ++k)
        if (dims[k] < MEASURED_DIM_MIN || dims[k] > MEASURED_DIM_MAX) {
            snprintf(err, err_size, "%s: %d cells, expected %d to %d", names[k], dims[k],
                     MEASURED_DIM_MIN, MEASURED_DIM_MAX);
            return -1;
        }
    size_t cells = (size_t)n_theta_h * (size_t)n_theta_d * (size_t)n_phi_d;
    if (cells > MEASURED_MAX_CELLS) {
        snprintf(err, err_size, "%d x %d x %d = %zu cells, more than the %zu a table may hold",
                 n_theta_h, n_theta_d, n_phi_d, cells, MEASURED_MAX_CELLS);
        return -1;
    }
    t->data = malloc(cells * 3 * sizeof *t->data);
    if (!t->data) {
        snprintf(err, err_size, "out of memory for %zu cells", cells);
        return -1;
    }
    for (size_t i = 0; i < cells * 3; ++i) t->data[i] = -1.0f;
    t->n_theta_h = n_theta_h;
    t->n_theta_d = n_theta_d;
    t->n_phi_d = n_phi_d;
    t->unmeasured = cells;
    return 0;
}

void measured_table_free(measured_table *t)
{
    free(t->data);
    t->data = NULL;
    t->n_theta_h = t->n_theta_d = t->n_phi_d = 0;
    t->unmeasured = 0;
}

size_t measured_table_cell(const measured_table *t, int ih, int id, int ip)
{
    return (((size_t)ih * (size_t)t->n_theta_d + (size_t)id) * (size_t)t->n_phi_d + (size_t)ip) * 3;
}

/* Rusinkiewicz's change of variables inverted with phi_h = 0: the difference vector d (the
 * light seen from the half vector's frame) rotated by theta_h about the y axis gives wi, and
 * wo is wi mirrored about the half vector. */
void measured_table_directions(const measured_table *t, int ih, int id, int ip, double wi[3],
                               double wo[3])
{
    double u = (double)ih / t->n_theta_h;
    double th = u * u * (PI / 2), td = (double)id / t->n_theta_d * (PI / 2);
    double pd = (double)ip / t->n_phi_d * PI;
    double d[3] = {sin(td) * cos(pd), sin(td) * sin(pd), cos(td)};
    double h[3] = {sin(th), 0.0, cos(th)};
    wi[0] = d[0] * cos(th) + d[2] * sin(th);
    wi[1] = d[1];
    wi[2] = -d[0] * sin(th) + d[2] * cos(th);
    double hi = wi[0] * h[0] + wi[2] * h[2];
    for (int c = 0; c < 3; ++c) wo[c] = 2.0 * hi * h[c] - wi[c];
}
