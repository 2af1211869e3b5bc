/* measured_cases.c - the measured suites' tables (measured_cases.h). */
#include "measured_cases.h"

#include <check.h>
#include <math.h>
#include <stdlib.h>

#define PI 3.14159265358979323846

size_t mc_cell(const abrdf_measured *t, int ih, int id, int ip)
{
    return (((size_t)ih * t->n_theta_d + id) * t->n_phi_d + ip) * 3;
}

void mc_cell_dirs(const abrdf_measured *t, int ih, int id, int ip, double wi[3], double wo[3])
{
    double u = (double)ih / t->n_theta_h, th = u * u * PI / 2;
    double td = (double)id / t->n_theta_d * PI / 2, pd = (double)ip / t->n_phi_d * PI;
    double d[3] = {sin(td) * cos(pd), sin(td) * sin(pd), cos(td)}, h[3] = {sin(th), 0, cos(th)};
    wi[0] = d[0] * cos(th) + d[2] * sin(th);
    wi[1] = d[1];
    wi[2] = -d[0] * sin(th) + d[2] * cos(th);
    double hi = wi[0] * h[0] + wi[2] * h[2];
    for (int c = 0; c < 3; ++c) wo[c] = 2 * hi * h[c] - wi[c];
}

void mc_table_of(mc_table *t, int nh, int nd, int np, abrdf_model diffuse, abrdf_model specular,
                 const abrdf_params *p)
{
    abrdf_measured_init(&t->desc);
    t->desc.n_theta_h = nh, t->desc.n_theta_d = nd, t->desc.n_phi_d = np;
    t->data = malloc((size_t)nh * nd * np * 3 * sizeof *t->data);
    ck_assert_ptr_nonnull(t->data);
    t->desc.data = t->data;
    for (int ih = 0; ih < nh; ++ih)
        for (int id = 0; id < nd; ++id)
            for (int ip = 0; ip < np; ++ip) {
                double wi[3], wo[3], fd[3] = {0, 0, 0}, fs[3] = {0, 0, 0};
                mc_cell_dirs(&t->desc, ih, id, ip, wi, wo);
                float *v = t->data + mc_cell(&t->desc, ih, id, ip);
                if (!(wi[2] > 0.0 && wo[2] > 0.0)) {
                    v[0] = v[1] = v[2] = -1.0f;
                    continue;
                }
                if (diffuse != ABRDF_MODEL_NONE) abrdf_eval(diffuse, p, NULL, wi, wo, fd);
                if (specular != ABRDF_MODEL_NONE) abrdf_eval(specular, p, NULL, wi, wo, fs);
                for (int c = 0; c < 3; ++c) v[c] = (float)(fd[c] + fs[c]);
            }
}
