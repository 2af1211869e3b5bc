/* eval_double.c - the double-precision scalar reference path: the closed-form models' setups
 * in double and their evaluations, one direction pair per call. */
#include <float.h>

#include "k_dispatch.h"
#include "layered.h"
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

/* A result that is not a finite non-negative number is a bug, but it must never reach the
 * caller (abrdf.h promise). finite_or_zero per channel, with one test for the usual case:
 * three numbers >= 0 whose sum is <= DBL_MAX are each finite (NaN fails a compare), and
 * finite_or_zero returns such a number unchanged; anything else is guarded per channel. */
static inline void guard_out(const double v[3], double f[3])
{
    if (v[0] >= 0.0 && v[1] >= 0.0 && v[2] >= 0.0 && v[0] + v[1] + v[2] <= DBL_MAX) {
        f[0] = v[0];
        f[1] = v[1];
        f[2] = v[2];
        return;
    }
    for (int c = 0; c < 3; ++c) f[c] = finite_or_zero(v[c]);
}

/* THE GENERATED NAMES. ABRDF__SCALAR_FN defines scalar_<KERNEL>, the double scalar evaluation
 * of kernel KERNEL, for every model of ABRDF__KERNEL_MODELS (scalar_k_lambert is lambert's);
 * abrdf__scalar_of holds it at the model's index. Each makes its own geometry: with
 * geo_make inlined, the compiler drops what that model's kernel does not read (a Lambert
 * term needs only the signs of the two cosines, not the half vector's square root and
 * division), so a per-sample call costs what its model reads. It returns ABRDF_OK so that a
 * public entry point can end in a tail call. */
#define ABRDF__SCALAR_FN(ID, SETUP, KERNEL, FORM)                                                  \
    static int scalar_##KERNEL(const abrdf__prep *pr, const double wi[3], const double wo[3],      \
                               double f[3])                                                        \
    {                                                                                              \
        abrdf__geo g;                                                                              \
        geo_make(&g, wi[0], wi[1], wi[2], wo[0], wo[1], wo[2]);                                    \
        if (!geo_front(&g)) {                                                                      \
            f[0] = f[1] = f[2] = 0.0;                                                              \
            return ABRDF_OK;                                                                       \
        }                                                                                          \
        double v[3];                                                                               \
        KERNEL(&pr->kd, &g, v);                                                                    \
        guard_out(v, f);                                                                           \
        return ABRDF_OK;                                                                           \
    }
ABRDF__KERNEL_MODELS(ABRDF__SCALAR_FN)

/* The double-only models (hair, layered, measured): special.c. */
static int scalar_special(const abrdf__prep *pr, const double wi[3], const double wo[3],
                          double f[3])
{
    double v[3] = {0.0, 0.0, 0.0};
    abrdf__eval_special_prepared(pr, wi, wo, v);
    guard_out(v, f);
    return ABRDF_OK;
}

/* weidlich_wilkie is a closed form too: called directly (its setup: special.c). */
static int scalar_ww(const abrdf__prep *pr, const double wi[3], const double wo[3], double f[3])
{
    double v[3] = {0.0, 0.0, 0.0};
    abrdf__eval_weidlich_wilkie(&pr->special.ww, wi, wo, v);
    guard_out(v, f);
    return ABRDF_OK;
}

#define ABRDF__SCALAR_ENTRY(ID, SETUP, KERNEL, FORM) [ID] = scalar_##KERNEL,

const abrdf__eval_d_fn abrdf__scalar_of[ABRDF_MODEL_COUNT] = {
    ABRDF__KERNEL_MODELS(ABRDF__SCALAR_ENTRY)[ABRDF_MARSCHNER] = scalar_special,
    [ABRDF_HUANG] = scalar_special, [ABRDF_WEIDLICH_WILKIE] = scalar_ww,
    [ABRDF_BELCOUR] = scalar_special, [ABRDF_MEASURED] = scalar_special};
