/* eval_double.c - the double-precision scalar reference path: the closed-form models' setups
 * in double and their kernels, one direction pair per call. */
#include "k_dispatch.h"
#include "prepared.h"

#define ABRDF__SETUP_CASE(ID, SETUP, KERNEL, FORM)                                                 \
    case ID: SETUP(&pr->kd, &pr->params); break;

void abrdf__prep_setup_d(abrdf__prep *pr)
{
    switch (pr->model) {
        ABRDF__KERNEL_MODELS(ABRDF__SETUP_CASE)
    default: break;
    }
}

/* One case per model, each making the geometry itself: with geo_make inlined into the case,
 * the compiler drops what that model's kernel does not read (a Lambert term needs only the
 * two cosines, not the half vector's square root and division), so a per-sample call costs
 * what its model reads. */
#define ABRDF__EVAL_CASE(ID, SETUP, KERNEL, FORM)                                                  \
    case ID:                                                                                       \
        geo_make(&g, wi[0], wi[1], wi[2], wo[0], wo[1], wo[2]);                                    \
        if (geo_front(&g)) KERNEL(&pr->kd, &g, v);                                                 \
        break;

void abrdf__eval_prepared_d(const abrdf__prep *pr, const double wi[3], const double wo[3],
                            double f[3])
{
    double v[3] = {0.0, 0.0, 0.0};
    abrdf__geo g;
    switch (pr->model) {
        ABRDF__KERNEL_MODELS(ABRDF__EVAL_CASE)
    case ABRDF_WEIDLICH_WILKIE: /* a closed form too: no second dispatch (setup: special.c) */
        abrdf__eval_weidlich_wilkie(&pr->special.ww, wi, wo, v);
        break;
    default: /* the other double-only models (hair, layered): special.c */
        abrdf__eval_special_prepared(pr, wi, wo, v);
        break;
    }
    /* A result that is not a finite non-negative number is a bug, but it must never reach
     * the caller (abrdf.h promise). */
    for (int c = 0; c < 3; ++c) f[c] = finite_or_zero(v[c]);
}
