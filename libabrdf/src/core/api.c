/* api.c - the public entry points: validation, world <-> local frame, shading, converters. */
#include <float.h>
#include <stddef.h>
#include <math.h>
#include <string.h>

#include "abrdf_inline.h"
#include "abrdf_internal.h"
#include "prepared.h"
#include "vec.h"

int abrdf_frame_make(const double n[3], const double t[3], abrdf_frame *frame)
{
    static const abrdf_frame identity = {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}};
    if (!frame) return ABRDF_E_NULL;
    *frame = identity;
    double nn[3];
    if (!n || !abrdf__normalise3(n, nn)) return ABRDF_E_GEOMETRY;
    /* Tangent: Gram-Schmidt of t against n; if t is missing or (nearly) parallel to n, the
     * axis least aligned with n, which is deterministic and never parallel. The 1e-6
     * threshold on |t_perp| keeps the normalisation well conditioned. */
    double tt[3] = {0, 0, 0};
    int have_t = 0;
    if (t && abrdf__finite3(t)) {
        double tn[3];
        if (abrdf__normalise3(t, tn)) {
            double d = abrdf__dot3(tn, nn);
            for (int c = 0; c < 3; ++c) tt[c] = tn[c] - d * nn[c];
            have_t = sqrt(abrdf__dot3(tt, tt)) > 1e-6;
        }
    }
    if (!have_t) {
        double ax[3] = {0, 0, 0};
        int k = fabs(nn[0]) <= fabs(nn[1]) ? (fabs(nn[0]) <= fabs(nn[2]) ? 0 : 2)
                                           : (fabs(nn[1]) <= fabs(nn[2]) ? 1 : 2);
        ax[k] = 1.0;
        double d = abrdf__dot3(ax, nn);
        for (int c = 0; c < 3; ++c) tt[c] = ax[c] - d * nn[c];
    }
    abrdf__normalise3(tt, frame->t);
    memcpy(frame->n, nn, sizeof nn);
    abrdf__cross3(frame->n, frame->t, frame->b);
    return ABRDF_OK;
}

static void to_local(const abrdf_frame *fr, const double v[3], double out[3])
{
    out[0] = abrdf__dot3(v, fr->t);
    out[1] = abrdf__dot3(v, fr->b);
    out[2] = abrdf__dot3(v, fr->n);
}

/* ---- prepared evaluation ------------------------------------------------------------ */

/* The prepared state must fit abrdf_prepared, whose size is frozen (abrdf.h), and the
 * public struct's alignment (double, pointer) must suit it: a C99 compile-time check. */
typedef char abrdf__prep_fits[sizeof(abrdf__prep) <= ABRDF_PREPARED_SIZE ? 1 : -1];
struct abrdf__prep_align {
    char c;
    abrdf__prep p;
};
struct abrdf__prepared_align {
    char c;
    abrdf_prepared p;
};
typedef char abrdf__prep_aligned
    [offsetof(struct abrdf__prep_align, p) <= offsetof(struct abrdf__prepared_align, p) ? 1 : -1];

void abrdf__prep_make(abrdf__prep *pr, abrdf_model model, const abrdf_params *p, unsigned what)
{
    pr->magic = ABRDF__PREP_MAGIC;
    pr->model = model;
    pr->params = *p;
    pr->params.struct_size = sizeof(abrdf_params);
    if (abrdf__is_double_only(model)) {
        abrdf__prep_setup_special(pr, what);
        return;
    }
    if (what & ABRDF__PREP_DOUBLE) abrdf__prep_setup_d(pr);
    if (what & ABRDF__PREP_FLOAT) abrdf__prep_setup_f(pr);
}

int abrdf__prep_checked(abrdf_model model, const abrdf_params *params, abrdf__prep *pr,
                        unsigned what)
{
    int st = abrdf_params_check(model, params, NULL, 0);
    if (st != ABRDF_OK) return st;
    abrdf_params full;
    abrdf__prep_make(pr, model, abrdf__params_view(model, params, &full), what);
    return ABRDF_OK;
}

const abrdf__prep *abrdf__prep_of(const abrdf_prepared *prepared)
{
    const abrdf__prep *pr = (const abrdf__prep *)(const void *)prepared;
    return prepared && pr->magic == ABRDF__PREP_MAGIC && pr->model >= 0 &&
                   pr->model < ABRDF_MODEL_COUNT
               ? pr
               : NULL;
}

int abrdf_prepare(abrdf_model model, const abrdf_params *params, abrdf_prepared *prepared)
{
    if (!prepared) return ABRDF_E_NULL;
    memset(prepared, 0, sizeof *prepared); /* not prepared, and no stale bytes in a copy */
    if (!params) return ABRDF_E_NULL;
    abrdf__prep *pr = (abrdf__prep *)(void *)prepared;
    int st = abrdf__prep_checked(model, params, pr, ABRDF__PREP_DOUBLE | ABRDF__PREP_FLOAT);
    if (st != ABRDF_OK) pr->magic = 0;
    return st;
}

int abrdf_measured_init_sized(abrdf_measured *table, size_t struct_size)
{
    if (!table) return ABRDF_E_NULL;
    if (struct_size < sizeof *table) return ABRDF_E_SIZE; /* this is the first layout */
    memset(table, 0, struct_size);
    table->struct_size = struct_size;
    return ABRDF_OK;
}

int abrdf_prepare_measured(const abrdf_measured *table, abrdf_prepared *prepared)
{
    if (!prepared) return ABRDF_E_NULL;
    memset(prepared, 0, sizeof *prepared); /* not prepared, and no stale bytes in a copy */
    if (!table) return ABRDF_E_NULL;
    if (table->struct_size < sizeof *table) return ABRDF_E_SIZE;
    if (!table->data) return ABRDF_E_NULL;
    const int dims[3] = {table->n_theta_h, table->n_theta_d, table->n_phi_d};
    for (int k = 0; k < 3; ++k)
        if (dims[k] < ABRDF__MEASURED_DIM_MIN || dims[k] > ABRDF__MEASURED_DIM_MAX)
            return ABRDF_E_TABLE;
    if ((size_t)dims[0] * (size_t)dims[1] * (size_t)dims[2] > ABRDF__MEASURED_CELLS_MAX)
        return ABRDF_E_TABLE;
    abrdf__prep *pr = (abrdf__prep *)(void *)prepared;
    pr->model = ABRDF_MEASURED;
    abrdf_params_init(ABRDF_MEASURED, &pr->params);
    abrdf__measured_setup(table, &pr->special.measured);
    pr->magic = ABRDF__PREP_MAGIC;
    return ABRDF_OK;
}

/* ---- huang tabulated (hair_huang_table.c) ---------------------------------------------- */

/* The model's setup at params into pr, and the table's sizes (t->v NULL). */
static int huang_table_args(const abrdf_params *params, const int sizes[4], abrdf__prep *pr,
                            abrdf__huang_table *t)
{
    if (!params || !sizes) return ABRDF_E_NULL;
    int st = abrdf__prep_checked(ABRDF_HUANG, params, pr, ABRDF__PREP_DOUBLE | ABRDF__PREP_FLOAT);
    if (st != ABRDF_OK) return st;
    if (!abrdf__huang_table_check(&pr->special.huang, sizes[0], sizes[1], sizes[2], sizes[3]))
        return ABRDF_E_TABLE;
    *t = (abrdf__huang_table){sizes[0], sizes[1], sizes[2], sizes[3], NULL};
    return ABRDF_OK;
}

int abrdf_huang_table_size(const abrdf_params *params, const int sizes[4], long *values, int *rows)
{
    if (!values || !rows) return ABRDF_E_NULL;
    abrdf__prep pr;
    abrdf__huang_table t;
    int st = huang_table_args(params, sizes, &pr, &t);
    if (st != ABRDF_OK) return st;
    *values = ABRDF__HUANG_TABLE_HEADER + abrdf__huang_table_count(t.nt, t.nv, t.np);
    *rows = t.nt * t.nv;
    return ABRDF_OK;
}

int abrdf_huang_table_build(const abrdf_params *params, const int sizes[4], int row0, int row1,
                            double *values)
{
    if (!values) return ABRDF_E_NULL;
    abrdf__prep pr;
    abrdf__huang_table t;
    int st = huang_table_args(params, sizes, &pr, &t);
    if (st != ABRDF_OK) return st;
    if (row0 < 0 || row1 < row0 || row1 > t.nt * t.nv) return ABRDF_E_RANGE;
    if (row0 == 0) abrdf__huang_table_header(&pr.special.huang, &t, values);
    abrdf__huang_table_rows(&pr.special.huang, &t, row0, row1, values + ABRDF__HUANG_TABLE_HEADER);
    return ABRDF_OK;
}

int abrdf_prepare_huang_table(const abrdf_params *params, const int sizes[4], const double *values,
                              abrdf_prepared *prepared)
{
    if (!prepared) return ABRDF_E_NULL;
    memset(prepared, 0, sizeof *prepared); /* not prepared, and no stale bytes in a copy */
    abrdf__prep *pr = (abrdf__prep *)(void *)prepared;
    abrdf__huang_table t = {0, 0, 0, 0, NULL};
    int st = huang_table_args(params, sizes, pr, &t);
    if (st == ABRDF_OK && !values) st = ABRDF_E_NULL;
    if (st == ABRDF_OK && !abrdf__huang_table_header_ok(&pr->special.huang, &t, values))
        st = ABRDF_E_TABLE;
    /* a value no build gives (NaN, infinite, negative): memory that is not the table's */
    long n = st == ABRDF_OK ? abrdf__huang_table_count(t.nt, t.nv, t.np) : 0;
    for (long i = 0; st == ABRDF_OK && i < n; ++i) {
        double x = values[ABRDF__HUANG_TABLE_HEADER + i];
        if (!(x >= 0.0 && x <= DBL_MAX)) st = ABRDF_E_TABLE;
    }
    if (st != ABRDF_OK) {
        memset(prepared, 0, sizeof *prepared);
        return st;
    }
    t.v = values + ABRDF__HUANG_TABLE_HEADER;
    pr->special.huang.table = t;
    return ABRDF_OK;
}

abrdf_model abrdf_prepared_model(const abrdf_prepared *prepared)
{
    const abrdf__prep *pr = abrdf__prep_of(prepared);
    return pr ? pr->model : ABRDF_MODEL_NONE;
}

const abrdf_params *abrdf_prepared_params(const abrdf_prepared *prepared)
{
    const abrdf__prep *pr = abrdf__prep_of(prepared);
    return pr ? &pr->params : NULL;
}

/* Squared lengths abrdf_eval_prepared_unit takes as unit (abrdf.h): a vector normalised in
 * double is within a few 1e-16; one normalised in float (1e-7 off) is normalised here. */
#define UNIT_LEN2_TOL 1e-14

/* A direction for marschner, weidlich_wilkie and belcour (test_prepared holds their values to
 * 1e-10): within UNIT_LEN2_TOL of unit length it is used as given (its components are then
 * within 5e-15 of the normalised ones), else normalised. Every entry point goes through here,
 * so abrdf_eval, abrdf_eval_prepared and abrdf_eval_prepared_unit agree bit for bit. */
static int direction_special(const double v[3], double out[3])
{
    if (fabs(abrdf__dot3(v, v) - 1.0) <= UNIT_LEN2_TOL) {
        memcpy(out, v, 3 * sizeof *v);
        return 1;
    }
    return abrdf__normalise3_unit(v, out);
}

/* abrdf_eval_prepared's body, for the public prepared object and abrdf_eval's own. */
static int eval_prep(const abrdf__prep *pr, const abrdf_frame *frame, const double wi[3],
                     const double wo[3], double f[3])
{
    double i[3], o[3], li[3], lo[3];
    /* huang's quadrature keeps the slower normalisation (vec.h says why) */
    int ok = pr->model == ABRDF_HUANG ? abrdf__normalise3(wi, i) && abrdf__normalise3(wo, o)
             : abrdf__is_double_only(pr->model)
                 ? direction_special(wi, i) && direction_special(wo, o)
                 : abrdf__normalise3_unit(wi, i) && abrdf__normalise3_unit(wo, o);
    if (!ok) return ABRDF_OK; /* degenerate: f = 0 */
    if (frame) {
        if (!abrdf__finite3(frame->n) || !abrdf__finite3(frame->t) || !abrdf__finite3(frame->b))
            return ABRDF_OK;
        to_local(frame, i, li);
        to_local(frame, o, lo);
    } else {
        memcpy(li, i, sizeof li);
        memcpy(lo, o, sizeof lo);
    }
    abrdf__eval_prepared_d(pr, li, lo, f);
    return ABRDF_OK;
}

int abrdf_eval_prepared(const abrdf_prepared *prepared, const abrdf_frame *frame,
                        const double wi[3], const double wo[3], double f[3])
{
    if (!f) return ABRDF_E_NULL;
    f[0] = f[1] = f[2] = 0.0;
    if (!prepared || !wi || !wo) return ABRDF_E_NULL;
    const abrdf__prep *pr = abrdf__prep_of(prepared);
    if (!pr) return ABRDF_E_MODEL;
    return eval_prep(pr, frame, wi, wo, f);
}

int abrdf_eval_prepared_unit(const abrdf_prepared *prepared, const double wi[3], const double wo[3],
                             double f[3])
{
    if (!f) return ABRDF_E_NULL;
    if (!prepared || !wi || !wo) {
        f[0] = f[1] = f[2] = 0.0;
        return ABRDF_E_NULL;
    }
    const abrdf__prep *pr = abrdf__prep_of(prepared);
    if (!pr) {
        f[0] = f[1] = f[2] = 0.0;
        return ABRDF_E_MODEL;
    }
    /* NaN and infinities fail the comparisons and take the checked path; huang normalises
     * every direction, the other models take unit ones as given (direction_special) */
    if (fabs(abrdf__dot3(wi, wi) - 1.0) <= UNIT_LEN2_TOL &&
        fabs(abrdf__dot3(wo, wo) - 1.0) <= UNIT_LEN2_TOL && pr->model != ABRDF_HUANG)
        return abrdf__eval_prepared_d(pr, wi, wo, f); /* ABRDF_OK, and a tail call */
    f[0] = f[1] = f[2] = 0.0;
    return eval_prep(pr, NULL, wi, wo, f);
}

int abrdf_eval(abrdf_model model, const abrdf_params *params, const abrdf_frame *frame,
               const double wi[3], const double wo[3], double f[3])
{
    if (!f) return ABRDF_E_NULL;
    f[0] = f[1] = f[2] = 0.0;
    if (!params || !wi || !wo) return ABRDF_E_NULL;
    abrdf__prep pr; /* only the double path's part: abrdf_prepare's, bit for bit */
    int st = abrdf__prep_checked(model, params, &pr, ABRDF__PREP_DOUBLE | ABRDF__PREP_ONCE);
    if (st != ABRDF_OK) return st;
    return eval_prep(&pr, frame, wi, wo, f);
}

static int batch_ok(const abrdf_batch *b)
{
    return !b->count || (b->wi_x && b->wi_y && b->wi_z && b->wo_x && b->wo_y && b->wo_z && b->f_r &&
                         b->f_g && b->f_b);
}

static void batch_zero(const abrdf_batch *b)
{
    for (size_t i = 0; i < b->count; ++i) b->f_r[i] = b->f_g[i] = b->f_b[i] = 0.0f;
}

int abrdf_eval_prepared_batch(const abrdf_prepared *prepared, const abrdf_batch *b)
{
    if (!prepared || !b) return ABRDF_E_NULL;
    if (!batch_ok(b)) return ABRDF_E_NULL;
    const abrdf__prep *pr = abrdf__prep_of(prepared);
    if (!pr) {
        batch_zero(b);
        return ABRDF_E_MODEL;
    }
    abrdf__eval_prepared_f(pr, b);
    return ABRDF_OK;
}

int abrdf_eval_prepared_rows(const abrdf_prepared *prepared, size_t count, const float *wi,
                             const float *wo, float *f)
{
    if (!prepared || (count && (!wi || !wo || !f))) return ABRDF_E_NULL;
    const abrdf__prep *pr = abrdf__prep_of(prepared);
    if (!pr) {
        for (size_t i = 0; i < 3 * count; ++i) f[i] = 0.0f;
        return ABRDF_E_MODEL;
    }
    abrdf__eval_prepared_rows(pr, count, wi, wo, f);
    return ABRDF_OK;
}

int abrdf_eval_prepared_float(const abrdf_prepared *prepared, const float wi[3], const float wo[3],
                              float f[3])
{
    if (!prepared || !wi || !wo || !f) return ABRDF_E_NULL;
    const abrdf__prep *pr = abrdf__prep_of(prepared);
    if (!pr) {
        f[0] = f[1] = f[2] = 0.0f;
        return ABRDF_E_MODEL;
    }
    abrdf__eval_prepared_one(pr, wi, wo, f);
    return ABRDF_OK;
}

int abrdf_prepared_ggx_float(const abrdf_prepared *prepared, abrdf_ggx_float *lobe)
{
    if (lobe) memset(lobe, 0, sizeof *lobe); /* every failure leaves a lobe giving 0 */
    if (!prepared || !lobe) return ABRDF_E_NULL;
    const abrdf__prep *pr = abrdf__prep_of(prepared);
    if (!pr || pr->model != ABRDF_DISNEY_SPECULAR) return ABRDF_E_MODEL;
    lobe->alpha_g = pr->kf.ag; /* the float kernel's parameters (k_microfacet_setup, kp_base) */
    for (int c = 0; c < 3; ++c) {
        lobe->ks_f0[c] = pr->kf.ks_f0[c];
        lobe->ks_f1[c] = pr->kf.ks_f1[c];
    }
    return ABRDF_OK;
}

int abrdf_eval_batch(abrdf_model model, const abrdf_params *params, const abrdf_batch *b)
{
    if (!params || !b) return ABRDF_E_NULL;
    if (!batch_ok(b)) return ABRDF_E_NULL;
    abrdf__prep pr;
    int st = abrdf__prep_checked(model, params, &pr, ABRDF__PREP_FLOAT);
    if (st != ABRDF_OK) {
        batch_zero(b);
        return st;
    }
    abrdf__eval_prepared_f(&pr, b);
    return ABRDF_OK;
}

int abrdf_shade(abrdf_model diffuse, abrdf_model specular, const abrdf_params *params,
                const abrdf_frame *frame, const double wi[3], const double wo[3],
                const double light[3], const double ambient[3], double out[3])
{
    if (!out) return ABRDF_E_NULL;
    out[0] = out[1] = out[2] = 0.0;
    if (!params || !wi || !wo || !light || !ambient) return ABRDF_E_NULL;
    double fd[3] = {0, 0, 0}, fs[3] = {0, 0, 0};
    int st;
    if (diffuse != ABRDF_MODEL_NONE && (st = abrdf_eval(diffuse, params, frame, wi, wo, fd)))
        return st;
    if (specular != ABRDF_MODEL_NONE && (st = abrdf_eval(specular, params, frame, wi, wo, fs)))
        return st;
    double i[3], ni[3] = {0, 0, 1};
    double cos_i = 0.0;
    if (abrdf__normalise3(wi, i)) cos_i = fmax(0.0, abrdf__dot3(i, frame ? frame->n : ni));
    for (int c = 0; c < 3; ++c) {
        double v = ambient[c] + light[c] * cos_i * (fd[c] + fs[c]); /* Sec. 1, pixel intensity */
        out[c] = (v >= 0.0 && isfinite(v)) ? v : 0.0;
    }
    return ABRDF_OK;
}

/* ---- converters (docs/MODELS.md, "Roughness converters", gives their errors) --------- */

static double clamp01(double x) { return x > 0.0 ? (x < 1.0 ? x : 1.0) : 0.0; }

double abrdf_r_to_alpha_g(double r)
{
    r = clamp01(r);
    return r * r;
}
double abrdf_alpha_g_to_r(double alpha_g) { return sqrt(clamp01(alpha_g)); }

/* Walter et al. 2007, Sec. 5.2: Blinn-Phong with exponent n matches Beckmann of roughness
 * alpha_b when n = 2/alpha_b^2 - 2; used here for the GGX alpha_g as well. */
double abrdf_alpha_g_to_n(double alpha_g)
{
    double a = fmax(alpha_g, ABRDF__ALPHA_G_MIN);
    if (!(a < 1.0)) return 0.0;
    return 2.0 / (a * a) - 2.0;
}

double abrdf_n_to_alpha_g(double n)
{
    if (!(n >= 0.0)) n = 0.0;
    if (isinf(n)) return 0.0;
    return sqrt(2.0 / (n + 2.0));
}

/* POV-Ray 3.7 `finish { specular k roughness rough }` evaluates k (N.H)^(1/rough) (the
 * parser stores 1/rough as the exponent, source/backend/parser/parstxtr.cpp; the lobe is in
 * source/backend/render/trace.cpp, ComputeSpecularColour). Roughness 0 is read as exponent 0 ("Zero roughness used."), so
 * n = 0 maps to 0. POV-Ray keeps roughness in single precision, so the result is clamped
 * to [FLT_MIN, FLT_MAX]: a smaller value would become 0 there (exponent 0), a larger one Inf. */
double abrdf_n_to_pov_roughness(double n)
{
    if (!(n > 0.0)) return 0.0;
    double rough = 1.0 / n;
    return rough > FLT_MIN ? (rough < FLT_MAX ? rough : FLT_MAX) : FLT_MIN;
}
double abrdf_pov_roughness_to_n(double rough)
{
    if (!(rough > 0.0) || isinf(rough)) return 0.0;
    double n = 1.0 / rough; /* Inf only for subnormal rough, which POV-Ray cannot hold */
    return n < DBL_MAX ? n : DBL_MAX;
}
