/* param_effect.c - does a parameter change the reflectance (param_effect.h)? */
#include <math.h>
#include <string.h>

#include "param_effect.h"

int param_nudge(const abrdf_params *p, int id, int dir, abrdf_params *q)
{
    *q = *p;
    const abrdf_param_info *pi = abrdf_param_get(id);
    double v[3];
    int n = abrdf_param_read(p, id, v);
    if (!pi || n < 1) return -1;
    double step =
        (dir > 0 ? 1.0 : -1.0) * (pi->kind == ABRDF_PARAM_INT ? 1.0 : 0.1 * (pi->max - pi->min));
    for (int c = 0; c < n; ++c) {
        v[c] += step;
        if (!(v[c] >= pi->min && v[c] <= pi->max)) return -1;
    }
    return abrdf_param_set(q, id, v, n) == ABRDF_OK ? 0 : -1;
}

int param_matters(const abrdf_model *lobes, int count, const abrdf_params *p, int id)
{
    for (int dir = 1; dir >= -1; dir -= 2) {
        abrdf_params q;
        if (!param_nudge(p, id, dir, &q) && lobes_differ(lobes, count, p, lobes, count, &q))
            return 1;
    }
    return 0;
}

/* f_r summed over the lobes at pair k, or -1 if a lobe cannot be evaluated. */
static int eval_sum(const abrdf_model *lobes, int n, const abrdf_params *p, int k, double f[3])
{
    static const double PI = 3.14159265358979323846;
    /* incidence from 8 to 80 degrees, azimuths around the circle, outgoing directions near
     * the mirror direction, across it and to the side */
    double ti = (8.0 + 72.0 * (k % 6) / 5.0) * PI / 180.0, pi_ = 2.39996 * k;
    double to = (5.0 + 80.0 * ((k * 7) % 24) / 23.0) * PI / 180.0;
    double po = pi_ + PI + (k % 4) * 0.9;
    if (k % 3 == 0) to = ti, po = pi_ + PI; /* the mirror direction */
    double wi[3] = {sin(ti) * cos(pi_), sin(ti) * sin(pi_), cos(ti)};
    double wo[3] = {sin(to) * cos(po), sin(to) * sin(po), cos(to)};
    static const double nz[3] = {0, 0, 1}, tx[3] = {1, 0, 0};
    abrdf_frame fr;
    abrdf_frame_make(nz, tx, &fr);
    f[0] = f[1] = f[2] = 0.0;
    for (int l = 0; l < n; ++l) {
        double g[3];
        /* a table lobe reads no parameter: the same in both evaluations compared */
        if (abrdf_model_get(lobes[l])->needs & ABRDF_NEEDS_TABLE) continue;
        if (abrdf_eval(lobes[l], p, &fr, wi, wo, g) != ABRDF_OK) return -1;
        for (int c = 0; c < 3; ++c) f[c] += g[c];
    }
    return 0;
}

int lobes_differ(const abrdf_model *a, int na, const abrdf_params *pa, const abrdf_model *b, int nb,
                 const abrdf_params *pb)
{
    for (int k = 0; k < 24; ++k) {
        double fa[3], fb[3];
        if (eval_sum(a, na, pa, k, fa) || eval_sum(b, nb, pb, k, fb)) return 1;
        if (memcmp(fa, fb, sizeof fa)) return 1;
    }
    return 0;
}
