/* special.c - dispatch of the models evaluated in double only (hair and layered models). */
#include "special.h"

/* ---- hair (hair.h) ------------------------------------------------------------------ */
#include "hair.h"

static int is_hair(abrdf_model model)
{
    return model == ABRDF_MARSCHNER || model == ABRDF_HUANG;
}

static void eval_hair(abrdf_model model, const abrdf_params *p, const double wi[3],
                      const double wo[3], double f[3])
{
    if (model == ABRDF_MARSCHNER) abrdf__marschner_eval(p, wi, wo, f);
    else if (model == ABRDF_HUANG) abrdf__huang_eval(p, wi, wo, f);
}
/* ---- end hair ----------------------------------------------------------------------- */

int abrdf__is_double_only(abrdf_model model)
{
    return is_hair(model);
}

void abrdf__eval_special(abrdf_model model, const abrdf_params *p, const double wi[3],
                         const double wo[3], double f[3])
{
    f[0] = f[1] = f[2] = 0.0;
    if (is_hair(model)) eval_hair(model, p, wi, wo, f);
    /* The abrdf.h promise: never NaN, Inf or negative, whatever a model computed. */
    for (int c = 0; c < 3; ++c)
        if (!(f[c] >= 0.0 && f[c] <= 1.7976931348623157e308)) f[c] = 0.0;
}
