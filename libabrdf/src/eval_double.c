/* eval_double.c - the double-precision scalar reference path. */
#define ABRDF_REAL double
#define ABRDF_SFX d
#include "k_all.h"
#include "special.h"

#define ABRDF__CASE(ID, KERNEL) case ID: FN(KERNEL)(&k, &g, v); break;

void abrdf__eval_local_d(abrdf_model model, const abrdf_params *p, const double wi[3],
                         const double wo[3], double f[3])
{
    f[0] = f[1] = f[2] = 0.0;
    if (abrdf__is_double_only(model)) {
        abrdf__eval_special(model, p, wi, wo, f);
        return;
    }
    kp k;
    geo g;
    FN(kp_make)(&k, model, p);
    FN(geo_make)(&g, wi[0], wi[1], wi[2], wo[0], wo[1], wo[2]);
    if (!FN(geo_front)(&g)) return;
    double v[3] = {0.0, 0.0, 0.0};
    switch (model) {
    ABRDF__KERNEL_MODELS(ABRDF__CASE)
    default: return;
    }
    /* Last line of defence: a kernel result that is not a finite non-negative number is a
     * bug, but it must never reach the caller (abrdf.h promise). */
    for (int c = 0; c < 3; ++c) f[c] = (v[c] >= 0.0 && v[c] <= 1.7976931348623157e308) ? v[c] : 0.0;
}
