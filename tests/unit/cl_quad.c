/* cl_quad.c - the batch check of the cloth and layered suites. */
#include "cl_quad.h"
#include "test_util.h"

void clq_batch_matches_scalar(const abrdf_model *ms, int nm, int n, unsigned seed, double rel,
                              double abs_tol)
{
    static float ix[CLQ_BATCH_MAX], iy[CLQ_BATCH_MAX], iz[CLQ_BATCH_MAX];
    static float ox[CLQ_BATCH_MAX], oy[CLQ_BATCH_MAX], oz[CLQ_BATCH_MAX];
    static float fr[CLQ_BATCH_MAX], fg[CLQ_BATCH_MAX], fb[CLQ_BATCH_MAX];
    ck_assert(n > 0 && n <= CLQ_BATCH_MAX);
    unsigned s = seed;
    for (int i = 0; i < n; ++i) {
        double a[3], b[3];
        quad_rand_dir(&s, 0.05, a);
        quad_rand_dir(&s, 0.05, b);
        ix[i] = (float)a[0];
        iy[i] = (float)a[1];
        iz[i] = (float)a[2];
        ox[i] = (float)b[0];
        oy[i] = (float)b[1];
        oz[i] = (float)b[2];
    }
    abrdf_batch bt = {(size_t)n, ix, iy, iz, ox, oy, oz, fr, fg, fb};
    for (int k = 0; k < nm; ++k) {
        abrdf_params p;
        abrdf_params_init(ms[k], &p);
        ck_assert_int_eq(abrdf_eval_batch(ms[k], &p, &bt), ABRDF_OK);
        for (int i = 0; i < n; ++i) {
            double a[3] = {ix[i], iy[i], iz[i]}, b[3] = {ox[i], oy[i], oz[i]}, f[3];
            abrdf_eval(ms[k], &p, NULL, a, b, f);
            ck_assert_msg(tu_close(fr[i], f[0], rel, abs_tol), "%s: %.9g vs %.9g",
                          abrdf_model_get(ms[k])->name, fr[i], f[0]);
        }
    }
}
