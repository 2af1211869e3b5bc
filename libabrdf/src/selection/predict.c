/* predict.c - the image error a BRDF would show against a reference, predicted without ray
 * tracing: both render a small image - an analytic sphere under directional lights, or the
 * caller's shading terms - and the prediction is the image NMSE of the paper's Table 8
 * (MODELS.md B9). Following Bieron & Peers ("An adaptive BRDF fitting metric", EGSR 2020),
 * the error that decides is the rendered one, not a BRDF-space distance; Lavoue et al.
 * (Eurographics 2021) found BRDF-space metrics weak predictors of what is seen.
 *
 * THE SPHERE. A unit sphere seen by an orthographic camera along view_dir, sampled like a
 * renderer samples it: resolution x resolution point samples at the pixel centres of the
 * square image of its disk, each seeing the normal N at its disk position with
 *     I = sum_lights E_l max(0, N.L_l) f(L_l, V) in the frame (N, T(N)),
 * the tangent T running around the sphere's axis `up` (the scene format's `u` rule). A
 * highlight narrower than the sample spacing is missed as a renderer with that sampling rate
 * usually misses it, so the prediction is for images sampled at that rate: the tools pass the
 * rate of the scene they render (docs/SELECTION.md, "2. The prediction"). Whether one sample
 * of a grid happens to fall on such a highlight is luck, and a hit changes the NMSE (the
 * highlight's energy joins the reference's): the sphere is therefore rendered on
 * ABRDF__PRED_SHIFTS grids, shifted by half a spacing, and the prediction is the largest of
 * their NMSEs - the one a render that misses (or hits) the highlight would show, whichever is
 * worse.
 *
 * The ambient term a renderer adds (ka Ia) is the same for both BRDFs and is left out: it
 * would only add to the reference's energy, so leaving it out errs on the high side. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "fit_internal.h"
#include "vec.h"

#define PRED_LIGHTS_MAX 64
#define PRED_RES_MAX 1024
/* Default samples across the sphere: 128 x 128 (12.9 k on the disk) is the sampling of a
 * sphere 64 pixels across at 4 samples per pixel. */
#define PRED_RES_DEFAULT 128
/* The most when a lobe integrates numerically in every evaluation (hair, ~1 ms each): 24 x 24
 * on each of the grids keeps the reference's images to about a second per light. Hair's
 * lobes are broad (r >= 0.05), so the coarser sampling still resolves them. */
#define PRED_RES_INTEGRATING 24

/* ---- the default view --------------------------------------------------------------- */

/* The key light of scenes/sphere.scene and a weaker fill from the other side, low, so the
 * sphere shows two highlights and the grazing angles between them. Irradiances in the scene
 * format's units. */
static const abrdf_light_dir default_lights[] = {
    {{-1.0, 1.0, 1.0}, {3.0, 3.0, 3.0}},
    {{1.0, 0.3, 0.5}, {1.0, 1.0, 1.0}},
};
#define DEFAULT_LIGHTS ((int)(sizeof default_lights / sizeof default_lights[0]))

#define END_OF(type, field) (offsetof(type, field) + sizeof(((type *)0)->field))
#define VIEW_SIZE_0_3 END_OF(abrdf_view, terms)

static void view_defaults(abrdf_view *v)
{
    memset(v, 0, sizeof *v);
    v->struct_size = sizeof *v;
    v->view_dir[2] = 1.0;
    v->up[1] = 1.0;
}

int abrdf_view_init_sized(abrdf_view *v, size_t struct_size)
{
    if (!v) return ABRDF_E_NULL;
    if (struct_size < VIEW_SIZE_0_3) return ABRDF_E_SIZE;
    abrdf_view d;
    view_defaults(&d);
    memset(v, 0, struct_size);
    memcpy(v, &d, struct_size < sizeof d ? struct_size : sizeof d);
    v->struct_size = struct_size;
    return ABRDF_OK;
}

static int finite3(const double v[3]) { return abrdf__finite3(v); }

int abrdf__view_check(const abrdf_view *view, abrdf_view *full, char *msg, size_t msg_size)
{
    view_defaults(full);
    if (!view) return ABRDF_OK;
    if (view->struct_size < VIEW_SIZE_0_3) {
        snprintf(msg, msg_size,
                 "abrdf_view: struct_size %zu is below its first layout: "
                 "initialise it with abrdf_view_init",
                 view->struct_size);
        return ABRDF_E_SIZE;
    }
    memcpy(full, view, view->struct_size < sizeof *full ? view->struct_size : sizeof *full);
    full->struct_size = sizeof *full;
    if (full->term_count < 0) {
        snprintf(msg, msg_size, "abrdf_view: term_count %d is negative", full->term_count);
        return ABRDF_E_RANGE;
    }
    if (full->term_count > 0) {
        if (!full->terms) {
            snprintf(msg, msg_size, "abrdf_view: term_count %d but no terms", full->term_count);
            return ABRDF_E_NULL;
        }
        for (int i = 0; i < full->term_count; ++i) {
            const abrdf_view_term *t = &full->terms[i];
            int ok = t->sample >= 0 && t->sample < full->term_count && finite3(t->n) &&
                     finite3(t->t) && finite3(t->wi) && finite3(t->wo) && finite3(t->e);
            for (int c = 0; c < 3 && ok; ++c) ok = t->e[c] >= 0.0;
            if (!ok) {
                snprintf(msg, msg_size,
                         "abrdf_view: term %d has a sample index outside [0, %d), a non-finite "
                         "vector or a negative irradiance",
                         i, full->term_count);
                return ABRDF_E_RANGE;
            }
        }
        return ABRDF_OK;
    }
    double vd[3], up[3], x[3];
    if (!abrdf__normalise3(full->view_dir, vd) || !abrdf__normalise3(full->up, up)) {
        snprintf(msg, msg_size, "abrdf_view: view_dir or up is zero or not finite");
        return ABRDF_E_GEOMETRY;
    }
    abrdf__cross3(up, vd, x);
    if (!(abrdf__dot3(x, x) > 1e-12)) {
        snprintf(msg, msg_size, "abrdf_view: up is parallel to view_dir");
        return ABRDF_E_GEOMETRY;
    }
    if (full->light_count < 0 || full->light_count > PRED_LIGHTS_MAX ||
        (full->light_count > 0 && !full->lights)) {
        snprintf(msg, msg_size, "abrdf_view: light_count %d is outside [0, %d] (or no lights)",
                 full->light_count, PRED_LIGHTS_MAX);
        return ABRDF_E_RANGE;
    }
    for (int l = 0; l < full->light_count; ++l) {
        const abrdf_light_dir *L = &full->lights[l];
        double d[3];
        int ok = abrdf__normalise3(L->dir, d) && finite3(L->e);
        for (int c = 0; c < 3 && ok; ++c) ok = L->e[c] >= 0.0;
        if (!ok) {
            snprintf(msg, msg_size,
                     "abrdf_view: light %d has a zero or non-finite direction or a negative "
                     "irradiance",
                     l);
            return ABRDF_E_RANGE;
        }
    }
    if (full->resolution < 0 || full->resolution > PRED_RES_MAX) {
        snprintf(msg, msg_size, "abrdf_view: resolution %d is outside [0, %d]", full->resolution,
                 PRED_RES_MAX);
        return ABRDF_E_RANGE;
    }
    return ABRDF_OK;
}

static int sphere_res(const abrdf_view *v, int integrating)
{
    int r = v->resolution > 0 ? v->resolution : PRED_RES_DEFAULT;
    return integrating && r > PRED_RES_INTEGRATING ? PRED_RES_INTEGRATING : r;
}

static int light_count(const abrdf_view *v)
{
    return v->light_count ? v->light_count : DEFAULT_LIGHTS;
}

static const abrdf_light_dir *lights_of(const abrdf_view *v)
{
    return v->light_count ? v->lights : default_lights;
}

size_t abrdf__pred_bytes(const abrdf_view *view, int integrating)
{
    abrdf_view v;
    char msg[8];
    if (abrdf__view_check(view, &v, msg, sizeof msg) != ABRDF_OK) return 0;
    size_t samples, terms;
    if (v.term_count > 0) {
        samples = terms = (size_t)v.term_count;
    } else {
        int r = sphere_res(&v, integrating);
        samples = (size_t)ABRDF__PRED_SHIFTS * (size_t)r * (size_t)r;
        terms = samples * (size_t)light_count(&v);
    }
    /* li, lo, ec and the sample index per term; weight, ref, img per sample; rounding slack */
    size_t doubles = terms * 10 + samples * 7 + 64;
    return doubles * sizeof(double);
}

/* ---- resolving the view into terms ---------------------------------------------------- */

static void to_local(const abrdf_frame *fr, const double v[3], double out[3])
{
    out[0] = abrdf__dot3(v, fr->t);
    out[1] = abrdf__dot3(v, fr->b);
    out[2] = abrdf__dot3(v, fr->n);
}

/* Add one term (world vectors) to pr; ec = e * max(0, n.wi). */
static void add_term(abrdf__pred *pr, int sample, const abrdf_frame *fr, const double wi[3],
                     const double wo[3], const double e[3])
{
    double ci = abrdf__dot3(fr->n, wi);
    if (!(ci > 0.0) || !(abrdf__dot3(fr->n, wo) > 0.0)) return;
    int k = pr->terms++;
    to_local(fr, wi, pr->li + 3 * k);
    to_local(fr, wo, pr->lo + 3 * k);
    for (int c = 0; c < 3; ++c) pr->ec[3 * k + c] = e[c] * ci;
    pr->sample_of[k] = sample;
}

/* The sphere: res x res samples at the pixel centres of an orthographic image of the unit
 * disk; the sample at disk point (x, y) sees the normal x X + y Y + sqrt(1 - x^2 - y^2) V. */
static int make_sphere(abrdf__pred *pr, const abrdf_view *v, int integrating, abrdf__arena *a)
{
    int res = sphere_res(v, integrating);
    double V[3], up[3], Xu[3], X[3], Y[3];
    abrdf__normalise3(v->view_dir, V);
    abrdf__normalise3(v->up, up);
    abrdf__cross3(up, V, Xu); /* screen right (abrdf__normalise3 must not alias) */
    abrdf__normalise3(Xu, X);
    abrdf__cross3(V, X, Y); /* screen up */
    int nl = light_count(v);
    const abrdf_light_dir *L = lights_of(v);
    double Ld[PRED_LIGHTS_MAX][3];
    for (int l = 0; l < nl; ++l) abrdf__normalise3(L[l].dir, Ld[l]);
    size_t cap = (size_t)ABRDF__PRED_SHIFTS * (size_t)res * (size_t)res;
    size_t nterms = cap * (size_t)nl;
    pr->li = abrdf__arena_doubles(a, 3 * nterms);
    pr->lo = abrdf__arena_doubles(a, 3 * nterms);
    pr->ec = abrdf__arena_doubles(a, 3 * nterms);
    pr->sample_of = (int *)(void *)abrdf__arena_doubles(a, nterms);
    pr->weight = abrdf__arena_doubles(a, cap);
    if (a->failed) return ABRDF_E_SIZE;
    pr->samples = pr->terms = 0;
    pr->images = ABRDF__PRED_SHIFTS;
    static const double shift[ABRDF__PRED_SHIFTS][2] = {{0, 0}, {0.5, 0}, {0, 0.5}, {0.5, 0.5}};
    for (int g = 0; g < ABRDF__PRED_SHIFTS; ++g) {
        for (int j = 0; j < res; ++j)
            for (int i = 0; i < res; ++i) {
                double x = (2.0 * (i + shift[g][0]) + 1.0) / res - 1.0;
                double y = 1.0 - (2.0 * (j + shift[g][1]) + 1.0) / res;
                double z2 = 1.0 - x * x - y * y;
                if (!(z2 > 0.0)) continue; /* off the disk: black in both images */
                double z = sqrt(z2), N[3], T[3];
                for (int c = 0; c < 3; ++c) N[c] = x * X[c] + y * Y[c] + z * V[c];
                abrdf__cross3(N, up, T); /* around the axis: the scene format's `u` rule */
                abrdf_frame fr;
                abrdf_frame_make(N, T, &fr);
                int s = pr->samples++;
                pr->weight[s] = 1.0;
                for (int l = 0; l < nl; ++l) add_term(pr, s, &fr, Ld[l], V, L[l].e);
            }
        pr->image_end[g] = pr->samples;
    }
    return ABRDF_OK;
}

static int make_terms(abrdf__pred *pr, const abrdf_view *v, abrdf__arena *a)
{
    size_t n = (size_t)v->term_count;
    pr->li = abrdf__arena_doubles(a, 3 * n);
    pr->lo = abrdf__arena_doubles(a, 3 * n);
    pr->ec = abrdf__arena_doubles(a, 3 * n);
    pr->sample_of = (int *)(void *)abrdf__arena_doubles(a, n);
    pr->samples = 0;
    for (int i = 0; i < v->term_count; ++i)
        if (v->terms[i].sample + 1 > pr->samples) pr->samples = v->terms[i].sample + 1;
    pr->weight = abrdf__arena_doubles(a, (size_t)pr->samples);
    if (a->failed) return ABRDF_E_SIZE;
    for (int s = 0; s < pr->samples; ++s) pr->weight[s] = 1.0;
    pr->images = 1;
    pr->image_end[0] = pr->samples;
    pr->terms = 0;
    for (int i = 0; i < v->term_count; ++i) {
        const abrdf_view_term *t = &v->terms[i];
        abrdf_frame fr;
        double wi[3], wo[3];
        if (abrdf_frame_make(t->n, t->t, &fr) != ABRDF_OK || !abrdf__normalise3(t->wi, wi) ||
            !abrdf__normalise3(t->wo, wo))
            continue; /* degenerate geometry adds nothing, as in abrdf_eval */
        add_term(pr, t->sample, &fr, wi, wo, t->e);
    }
    return ABRDF_OK;
}

/* The image of b over pr's terms into img (3 per sample). */
static void render(const abrdf__pred *pr, const abrdf__brdf *b, double *img)
{
    memset(img, 0, sizeof *img * 3 * (size_t)pr->samples);
    abrdf__brdf_prep bp;
    abrdf__brdf_prepare(b, &bp);
    for (int k = 0; k < pr->terms; ++k) {
        double f[3];
        abrdf__brdf_prep_eval(&bp, pr->li + 3 * k, pr->lo + 3 * k, f);
        double *o = img + 3 * pr->sample_of[k];
        for (int c = 0; c < 3; ++c) o[c] += pr->ec[3 * k + c] * f[c];
    }
}

int abrdf__pred_prepare(abrdf__pred *pr, const abrdf_view *view, const abrdf__brdf *ref,
                        int integrating, abrdf__arena *a, char *msg, size_t msg_size)
{
    abrdf_view v;
    int st = abrdf__view_check(view, &v, msg, msg_size);
    if (st != ABRDF_OK) return st;
    memset(pr, 0, sizeof *pr);
    if (v.term_count > 0)
        st = make_terms(pr, &v, a);
    else
        st = make_sphere(pr, &v, integrating, a);
    if (st == ABRDF_OK) {
        pr->ref = abrdf__arena_doubles(a, 3 * (size_t)pr->samples);
        pr->img = abrdf__arena_doubles(a, 3 * (size_t)pr->samples);
        if (a->failed) st = ABRDF_E_SIZE;
    }
    if (st != ABRDF_OK) {
        snprintf(msg, msg_size, "the workspace is too small for the prediction's image");
        return st;
    }
    render(pr, ref, pr->ref);
    for (int g = 0, s = 0; g < pr->images; ++g) {
        pr->ref_energy[g] = 0.0;
        for (; s < pr->image_end[g]; ++s)
            for (int c = 0; c < 3; ++c)
                pr->ref_energy[g] += pr->weight[s] * pr->ref[3 * s + c] * pr->ref[3 * s + c];
    }
    return ABRDF_OK;
}

double abrdf__pred_nmse(abrdf__pred *pr, const abrdf__brdf *b)
{
    render(pr, b, pr->img);
    double worst = 0.0;
    for (int g = 0, s = 0; g < pr->images; ++g) {
        double num = 0.0;
        for (; s < pr->image_end[g]; ++s)
            for (int c = 0; c < 3; ++c) {
                double d = pr->img[3 * s + c] - pr->ref[3 * s + c];
                num += pr->weight[s] * d * d;
            }
        double e = pr->ref_energy[g] > 0.0 ? num / pr->ref_energy[g] : (num > 0.0 ? INFINITY : 0.0);
        worst = fmax(worst, e);
    }
    return worst;
}

/* The prediction of b against ref once both are made (the public forms' common part). */
static int predict_made(const abrdf__brdf *ref, const abrdf__brdf *b, const abrdf_view *view,
                        double *nmse, void *work, size_t work_size)
{
    char msg[ABRDF_FIT_MESSAGE_MAX];
    int integrating =
        ((abrdf__brdf_needs(ref) | abrdf__brdf_needs(b)) & ABRDF_NEEDS_INTEGRATION) != 0;
    abrdf__arena a;
    abrdf__arena_init(&a, work, work_size);
    abrdf__pred pr;
    int st = abrdf__pred_prepare(&pr, view, ref, integrating, &a, msg, sizeof msg);
    if (st != ABRDF_OK) return st;
    *nmse = abrdf__pred_nmse(&pr, b);
    return ABRDF_OK;
}

int abrdf_predict_nmse(abrdf_model ref_diffuse, abrdf_model ref_specular,
                       const abrdf_params *ref_params, abrdf_model diffuse, abrdf_model specular,
                       const abrdf_params *params, const abrdf_view *view, double *nmse, void *work,
                       size_t work_size)
{
    if (!nmse) return ABRDF_E_NULL;
    *nmse = -1.0;
    if (!ref_params || !params || !work) return ABRDF_E_NULL;
    char msg[ABRDF_FIT_MESSAGE_MAX];
    abrdf__brdf ref, b;
    int st = abrdf__brdf_make(&ref, ref_diffuse, ref_specular, ref_params, msg, sizeof msg);
    if (st == ABRDF_OK) st = abrdf__brdf_make(&b, diffuse, specular, params, msg, sizeof msg);
    if (st != ABRDF_OK) return st;
    return predict_made(&ref, &b, view, nmse, work, work_size);
}

int abrdf_predict_nmse_to(const abrdf_prepared *reference, abrdf_model diffuse,
                          abrdf_model specular, const abrdf_params *params, const abrdf_view *view,
                          double *nmse, void *work, size_t work_size)
{
    if (!nmse) return ABRDF_E_NULL;
    *nmse = -1.0;
    if (!reference || !params || !work) return ABRDF_E_NULL;
    char msg[ABRDF_FIT_MESSAGE_MAX];
    abrdf__brdf ref, b;
    int st = abrdf__brdf_from_prepared(&ref, reference, msg, sizeof msg);
    if (st == ABRDF_OK) st = abrdf__brdf_make(&b, diffuse, specular, params, msg, sizeof msg);
    if (st != ABRDF_OK) return st;
    return predict_made(&ref, &b, view, nmse, work, work_size);
}
