/* lobes.c - a BRDF of one or two lobes over one parameter block, as the fit and the
 * prediction use it (fit_internal.h): validated once, prepared once (abrdf__prep_make, the
 * library's prepared evaluation, prepared.h) and evaluated at many direction pairs on the
 * double path: the values equal abrdf_eval's. Also the caller's workspace, carved into
 * arrays. */
#include <stdio.h>
#include <string.h>

#include "fit_internal.h"

void abrdf__lobe_prepare(abrdf__lobe_prep *lp, abrdf_model m, const abrdf_params *p)
{
    lp->model = m;
    if (m != ABRDF_MODEL_NONE) abrdf__prep_make(&lp->pr, m, p, ABRDF__PREP_DOUBLE);
}

void abrdf__lobe_eval(const abrdf__lobe_prep *lp, const double wi[3], const double wo[3],
                      double f[3])
{
    if (lp->model == ABRDF_MODEL_NONE) {
        f[0] = f[1] = f[2] = 0.0;
        return;
    }
    abrdf__eval_prepared_d(&lp->pr, wi, wo, f);
}

/* ---- a BRDF of one or two lobes --------------------------------------------------------- */

int abrdf__brdf_make(abrdf__brdf *b, abrdf_model diffuse, abrdf_model specular,
                     const abrdf_params *p, char *msg, size_t msg_size)
{
    b->lobe[0] = diffuse;
    b->lobe[1] = specular;
    b->prepared = NULL;
    if (diffuse == ABRDF_MODEL_NONE && specular == ABRDF_MODEL_NONE) {
        snprintf(msg, msg_size, "a BRDF needs a diffuse or a specular model (both are none)");
        return ABRDF_E_MODEL;
    }
    abrdf_params scratch;
    const abrdf_params *v =
        abrdf__params_view(diffuse != ABRDF_MODEL_NONE ? diffuse : specular, p, &scratch);
    if (!v) {
        snprintf(msg, msg_size,
                 "abrdf_params: struct_size %zu is below its 0.2.0 layout: initialise it "
                 "with abrdf_params_init",
                 p->struct_size);
        return ABRDF_E_SIZE;
    }
    b->p = *v;
    for (int l = 0; l < 2; ++l) {
        if (b->lobe[l] == ABRDF_MODEL_NONE) continue;
        if (!abrdf_model_get(b->lobe[l])) {
            snprintf(msg, msg_size, "unknown model id %d", (int)b->lobe[l]);
            return ABRDF_E_MODEL;
        }
        if (abrdf_model_get(b->lobe[l])->needs & ABRDF_NEEDS_TABLE) {
            snprintf(msg, msg_size,
                     "%s evaluates a caller's table, which a model and a parameter block do "
                     "not give: prepare it (abrdf_prepare_measured) and use abrdf_fit_to / "
                     "abrdf_predict_nmse_to",
                     abrdf_model_get(b->lobe[l])->name);
            return ABRDF_E_TABLE;
        }
        int st = abrdf_params_check(b->lobe[l], &b->p, msg, msg_size);
        if (st != ABRDF_OK) return st;
    }
    return ABRDF_OK;
}

int abrdf__brdf_from_prepared(abrdf__brdf *b, const abrdf_prepared *prepared, char *msg,
                              size_t msg_size)
{
    const abrdf__prep *pr = abrdf__prep_of(prepared);
    if (!pr) {
        snprintf(msg, msg_size, "the reference is %s",
                 prepared ? "not prepared (abrdf_prepare, abrdf_prepare_measured)" : "NULL");
        return prepared ? ABRDF_E_MODEL : ABRDF_E_NULL;
    }
    b->lobe[0] = ABRDF_MODEL_NONE;
    b->lobe[1] = pr->model;
    b->p = pr->params;
    b->prepared = pr;
    return ABRDF_OK;
}

void abrdf__brdf_prepare(const abrdf__brdf *b, abrdf__brdf_prep *bp)
{
    bp->prepared = b->prepared;
    if (b->prepared) return;
    for (int l = 0; l < 2; ++l) abrdf__lobe_prepare(&bp->lobe[l], b->lobe[l], &b->p);
}

void abrdf__brdf_prep_eval(const abrdf__brdf_prep *bp, const double wi[3], const double wo[3],
                           double f[3])
{
    double g[3];
    if (bp->prepared) {
        abrdf__eval_prepared_d(bp->prepared, wi, wo, f);
        return;
    }
    abrdf__lobe_eval(&bp->lobe[0], wi, wo, f);
    if (bp->lobe[1].model == ABRDF_MODEL_NONE) return;
    abrdf__lobe_eval(&bp->lobe[1], wi, wo, g);
    for (int c = 0; c < 3; ++c) f[c] += g[c];
}

unsigned abrdf__brdf_needs(const abrdf__brdf *b)
{
    unsigned n = 0;
    for (int l = 0; l < 2; ++l)
        if (b->lobe[l] != ABRDF_MODEL_NONE) n |= abrdf_model_get(b->lobe[l])->needs;
    return n;
}

static int is_fibre_model(abrdf_model m)
{
    return m == ABRDF_KAJIYA_KAY || m == ABRDF_MARSCHNER || m == ABRDF_HUANG;
}

int abrdf__brdf_is_fibre(const abrdf__brdf *b)
{
    return is_fibre_model(b->lobe[0]) || is_fibre_model(b->lobe[1]);
}

int abrdf__brdf_uses_tangent(const abrdf__brdf *b)
{
    for (int l = 0; l < 2; ++l) {
        abrdf_model m = b->lobe[l];
        if (m == ABRDF_MODEL_NONE || !(abrdf_model_get(m)->needs & ABRDF_NEEDS_TANGENT)) continue;
        if (m == ABRDF_DISNEY_SPECULAR_ANISO && !(b->p.anisotropic > 0.0)) continue;
        return 1;
    }
    return 0;
}

/* ---- the workspace ----------------------------------------------------------------------- */

void abrdf__arena_init(abrdf__arena *a, void *base, size_t size)
{
    a->base = base;
    a->size = base ? size : 0;
    a->used = 0;
    a->failed = 0;
}

double *abrdf__arena_doubles(abrdf__arena *a, size_t n)
{
    size_t align = sizeof(double), start = (a->used + align - 1) / align * align;
    size_t bytes = (n ? n : 1) * sizeof(double);
    if (a->failed || start > a->size || bytes > a->size - start) {
        a->failed = 1;
        return NULL;
    }
    a->used = start + bytes;
    return (double *)(void *)(a->base + start);
}
