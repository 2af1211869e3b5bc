/* hair_huang_surface.c - huang's f_r on the ribbon, from its fibre function S: integrated
 * per call (hair_huang.c) or read from a table (hair_huang_table.c). f_r = S / |N.wi| for
 * the lights above the ribbon seen from a view above it, 0 otherwise (abrdf.h, "hair
 * models"). */
#include "hair.h"

/* f_r of count lights of one view: S from the table t, or integrated when t is NULL. */
static void surface_run(const abrdf__huang *m, const abrdf__huang_table *t, int count,
                        const double (*wi)[3], const double wo[3], double (*f)[3])
{
    double s[ABRDF__HUANG_RUN_MAX][3], lit[ABRDF__HUANG_RUN_MAX][3];
    int slot[ABRDF__HUANG_RUN_MAX], n = 0;
    for (int l = 0; l < count; ++l) f[l][0] = f[l][1] = f[l][2] = 0.0;
    if (count < 1 || count > ABRDF__HUANG_RUN_MAX || !(wo[2] > 0.0)) return;
    for (int l = 0; l < count; ++l) /* lights above the ribbon; the others keep f_r = 0 */
        if (wi[l][2] > 0.0) {
            for (int c = 0; c < 3; ++c) lit[n][c] = wi[l][c];
            slot[n++] = l;
        }
    if (n == 0) return;
    if (t)
        abrdf__huang_table_fibre_run(m, t, n, (const double(*)[3])lit, wo, 15u, s);
    else
        abrdf__huang_fibre_run(m, n, (const double(*)[3])lit, wo, 15u, s);
    for (int l = 0; l < n; ++l)
        for (int c = 0; c < 3; ++c) f[slot[l]][c] = s[l][c] / lit[l][2]; /* f_r = S / |N.wi| */
}

void abrdf__huang_eval_run(const abrdf__huang *m, int count, const double (*wi)[3],
                           const double wo[3], double (*f)[3])
{
    surface_run(m, NULL, count, wi, wo, f);
}

void abrdf__huang_eval(const abrdf__huang *m, const double wi[3], const double wo[3], double f[3])
{
    double fl[1][3];
    surface_run(m, NULL, 1, (const double(*)[3])wi, wo, fl);
    for (int c = 0; c < 3; ++c) f[c] = fl[0][c];
}

void abrdf__huang_table_eval_run(const abrdf__huang *m, const abrdf__huang_table *t, int count,
                                 const double (*wi)[3], const double wo[3], double (*f)[3])
{
    surface_run(m, t, count, wi, wo, f);
}

void abrdf__huang_prepared_run(const abrdf__huang *m, int count, const double (*wi)[3],
                               const double wo[3], double (*f)[3])
{
    surface_run(m, m->table.v ? &m->table : NULL, count, wi, wo, f);
}
