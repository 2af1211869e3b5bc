/* sample.c - the public entry points of importance sampling (abrdf.h, "sampling"):
 * validation, world <-> local frame, the weight f_r cos / pdf. The samplers are in
 * sample_mix.c (which model mixes what), sample_lobe.c, sample_dist.c and sample_hair.c. */
#include <math.h>
#include <string.h>

#include "prepared.h"
#include "sample.h"
#include "vec.h"

int abrdf_sample_result_init_sized(abrdf_sample_result *r, size_t struct_size)
{
    if (!r) return ABRDF_E_NULL;
    if (struct_size < sizeof *r) return ABRDF_E_SIZE; /* this is the first layout */
    memset(r, 0, struct_size);
    r->struct_size = struct_size;
    return ABRDF_OK;
}

/* The frame's axes are finite (abrdf_frame_make makes them orthonormal). */
static int frame_ok(const abrdf_frame *fr)
{
    return abrdf__finite3(fr->n) && abrdf__finite3(fr->t) && abrdf__finite3(fr->b);
}

/* World (or local, frame NULL) direction -> unit local direction; 0 if degenerate. */
static int to_local(const abrdf_frame *fr, const double v[3], double out[3])
{
    double u[3];
    if (!abrdf__normalise3(v, u)) return 0;
    if (!fr) {
        memcpy(out, u, sizeof u);
        return 1;
    }
    double l[3] = {abrdf__dot3(u, fr->t), abrdf__dot3(u, fr->b), abrdf__dot3(u, fr->n)};
    return abrdf__normalise3(l, out);
}

static void to_world(const abrdf_frame *fr, const double l[3], double out[3])
{
    if (!fr) {
        memcpy(out, l, 3 * sizeof *l);
        return;
    }
    for (int c = 0; c < 3; ++c) out[c] = l[0] * fr->t[c] + l[1] * fr->b[c] + l[2] * fr->n[c];
}

/* No sample: wi = N, pdf 0, weight 0. */
static void no_sample(const abrdf_frame *fr, abrdf_sample_result *r)
{
    static const double up[3] = {0.0, 0.0, 1.0};
    if (fr && abrdf__finite3(fr->n))
        memcpy(r->wi, fr->n, sizeof r->wi);
    else
        memcpy(r->wi, up, sizeof r->wi);
    r->pdf = 0.0;
    r->weight[0] = r->weight[1] = r->weight[2] = 0.0;
}

/* The sampler of a prepared model for local wo: from its parameters, or from its table. */
static void mixture_of(const abrdf__prep *pr, const double wo[3], abrdf__mixture *mx)
{
    if (pr->model == ABRDF_MEASURED)
        abrdf__mixture_setup_measured(&pr->special.measured, wo, mx);
    else
        abrdf__mixture_setup(pr->model, &pr->params, wo, mx);
}

/* abrdf_sample's body on a prepared model (pr holds validated parameters in this library's
 * layout); result checked, u1 and u2 not yet. */
static int sample_prep(const abrdf__prep *pr, const abrdf_frame *frame, const double wo[3],
                       double u1, double u2, abrdf_sample_result *result)
{
    if (!(u1 >= 0.0 && u1 <= 1.0 && u2 >= 0.0 && u2 <= 1.0)) return ABRDF_E_RANGE;
    double lo[3], li[3];
    if ((frame && !frame_ok(frame)) || !to_local(frame, wo, lo) || !(lo[2] > 0.0))
        return ABRDF_OK; /* degenerate or below the surface: no sample */
    abrdf__mixture mx;
    mixture_of(pr, lo, &mx);
    if (!abrdf__mixture_sample(&mx, u1, u2, li)) return ABRDF_OK;
    double pdf = abrdf__mixture_pdf(&mx, li);
    if (!(pdf > 0.0) || !isfinite(pdf)) return ABRDF_OK; /* a set of measure zero */
    double f[3] = {0.0, 0.0, 0.0};
    if (li[2] > 0.0) abrdf__eval_prepared_d(pr, li, lo, f);
    for (int c = 0; c < 3; ++c) {
        double w = f[c] * fmax(li[2], 0.0) / pdf;
        result->weight[c] = (w >= 0.0 && isfinite(w)) ? w : 0.0;
    }
    result->pdf = pdf;
    to_world(frame, li, result->wi);
    return ABRDF_OK;
}

/* abrdf_pdf's body on a prepared model. */
static double pdf_prep(const abrdf__prep *pr, const abrdf_frame *frame, const double wi[3],
                       const double wo[3])
{
    double li[3], lo[3];
    if ((frame && !frame_ok(frame)) || !to_local(frame, wi, li) || !to_local(frame, wo, lo) ||
        !(lo[2] > 0.0))
        return 0.0;
    abrdf__mixture mx;
    mixture_of(pr, lo, &mx);
    double p = abrdf__mixture_pdf(&mx, li);
    return (p >= 0.0 && isfinite(p)) ? p : 0.0;
}

int abrdf_sample(abrdf_model model, const abrdf_params *params, const abrdf_frame *frame,
                 const double wo[3], double u1, double u2, abrdf_sample_result *result)
{
    if (!result) return ABRDF_E_NULL;
    if (result->struct_size < sizeof *result) return ABRDF_E_SIZE;
    no_sample(frame, result);
    if (!params || !wo) return ABRDF_E_NULL;
    abrdf__prep pr; /* the double path's part of abrdf_prepare: the same bits */
    int st = abrdf__prep_checked(model, params, &pr, ABRDF__PREP_DOUBLE | ABRDF__PREP_ONCE);
    if (st != ABRDF_OK) return st;
    return sample_prep(&pr, frame, wo, u1, u2, result);
}

int abrdf_sample_prepared(const abrdf_prepared *prepared, const abrdf_frame *frame,
                          const double wo[3], double u1, double u2, abrdf_sample_result *result)
{
    if (!result) return ABRDF_E_NULL;
    if (result->struct_size < sizeof *result) return ABRDF_E_SIZE;
    no_sample(frame, result);
    if (!prepared || !wo) return ABRDF_E_NULL;
    const abrdf__prep *pr = abrdf__prep_of(prepared);
    if (!pr) return ABRDF_E_MODEL;
    return sample_prep(pr, frame, wo, u1, u2, result);
}

int abrdf_pdf(abrdf_model model, const abrdf_params *params, const abrdf_frame *frame,
              const double wi[3], const double wo[3], double *pdf)
{
    if (!pdf) return ABRDF_E_NULL;
    *pdf = 0.0;
    if (!params || !wi || !wo) return ABRDF_E_NULL;
    int st = abrdf_params_check(model, params, NULL, 0);
    if (st != ABRDF_OK) return st;
    abrdf_params full;
    abrdf__prep pr; /* only model and params: the mixture reads nothing else */
    pr.model = model;
    pr.params = *abrdf__params_view(model, params, &full);
    *pdf = pdf_prep(&pr, frame, wi, wo);
    return ABRDF_OK;
}

int abrdf_pdf_prepared(const abrdf_prepared *prepared, const abrdf_frame *frame, const double wi[3],
                       const double wo[3], double *pdf)
{
    if (!pdf) return ABRDF_E_NULL;
    *pdf = 0.0;
    if (!prepared || !wi || !wo) return ABRDF_E_NULL;
    const abrdf__prep *pr = abrdf__prep_of(prepared);
    if (!pr) return ABRDF_E_MODEL;
    *pdf = pdf_prep(pr, frame, wi, wo);
    return ABRDF_OK;
}
