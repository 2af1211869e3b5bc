/* eval_float.c - the float structure-of-arrays batch path. One loop per model, with the
 * model's kernel inlined, so the compiler can vectorise it; the front-facing test and the
 * finiteness guard are selects, not branches. */
#define ABRDF_REAL float
#define ABRDF_SFX f
#include "k_all.h"
#include "special.h"

#define ABRDF__FLT_MAX 3.402823466e38f

#define ABRDF__BATCH_CASE(ID, KERNEL)                                                      \
    case ID:                                                                               \
        for (size_t i = 0; i < n; ++i) {                                                   \
            geo g;                                                                         \
            float v[3];                                                                    \
            FN(geo_make)(&g, b->wi_x[i], b->wi_y[i], b->wi_z[i], b->wo_x[i], b->wo_y[i],   \
                         b->wo_z[i]);                                                      \
            FN(KERNEL)(&k, &g, v);                                                         \
            int ok = FN(geo_front)(&g);                                                    \
            b->f_r[i] = (ok && v[0] >= 0.0f && v[0] <= ABRDF__FLT_MAX) ? v[0] : 0.0f;      \
            b->f_g[i] = (ok && v[1] >= 0.0f && v[1] <= ABRDF__FLT_MAX) ? v[1] : 0.0f;      \
            b->f_b[i] = (ok && v[2] >= 0.0f && v[2] <= ABRDF__FLT_MAX) ? v[2] : 0.0f;      \
        }                                                                                  \
        break;

static void abrdf__batch_special(abrdf_model model, const abrdf_params *p, const abrdf_batch *b)
{
    for (size_t i = 0; i < b->count; ++i) {
        double wi[3] = {b->wi_x[i], b->wi_y[i], b->wi_z[i]};
        double wo[3] = {b->wo_x[i], b->wo_y[i], b->wo_z[i]};
        double f[3];
        abrdf__eval_special(model, p, wi, wo, f);
        b->f_r[i] = (float)f[0];
        b->f_g[i] = (float)f[1];
        b->f_b[i] = (float)f[2];
    }
}

void abrdf__eval_batch_f(abrdf_model model, const abrdf_params *p, const abrdf_batch *b)
{
    if (abrdf__is_double_only(model)) {
        abrdf__batch_special(model, p, b);
        return;
    }
    const size_t n = b->count;
    kp k;
    FN(kp_make)(&k, model, p);
    switch (model) {
    ABRDF__KERNEL_MODELS(ABRDF__BATCH_CASE)
    default:
        for (size_t i = 0; i < n; ++i) b->f_r[i] = b->f_g[i] = b->f_b[i] = 0.0f;
        break;
    }
}
