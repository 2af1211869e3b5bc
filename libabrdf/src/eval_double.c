/* eval_double.c - the double-precision scalar reference path. */
#include "k_dispatch.h"
#include "special.h"

#define ABRDF__EVAL_CASE(ID, SETUP, KERNEL)                                                        \
    case ID:                                                                                       \
        ABRDF__FN(SETUP)(&k, p);                                                                   \
        ABRDF__FN(KERNEL)(&k, &g, v);                                                              \
        break;

void abrdf__eval_local_d(abrdf_model model, const abrdf_params *p, const double wi[3],
                         const double wo[3], double f[3])
{
    double v[3] = {0.0, 0.0, 0.0};
    if (abrdf__is_double_only(model)) {
        abrdf__eval_special(model, p, wi, wo, v);
    } else {
        ABRDF__GEO g;
        ABRDF__FN(geo_make)(&g, wi[0], wi[1], wi[2], wo[0], wo[1], wo[2]);
        if (ABRDF__FN(geo_front)(&g)) {
            ABRDF__KP k;
            switch (model) {
                ABRDF__KERNEL_MODELS(ABRDF__EVAL_CASE)
            default: break;
            }
        }
    }
    /* A result that is not a finite non-negative number is a bug, but it must never reach
     * the caller (abrdf.h promise). */
    for (int c = 0; c < 3; ++c) f[c] = ABRDF__FN(finite_or_zero)(v[c]);
}
