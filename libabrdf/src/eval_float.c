/* eval_float.c - the float structure-of-arrays batch path. One loop per model, with the
 * model's kernel inlined, so the compiler can vectorise it. */
#define ABRDF__KERNEL_FLOAT 1 /* kernel.h: the kernels in float */
#include "k_dispatch.h"
#include "vec.h"

/* One loop per model with the kernel inlined. The front-facing test and the finiteness
 * guard are combined with & (not &&) so the body has no control flow, and the arrays are
 * restrict parameters (abrdf.h: outputs may not alias inputs), so the compiler needs no
 * run-time alias checks: both are required for the loop to vectorise. */
#if defined(__GNUC__)
#define ABRDF__NOINLINE __attribute__((noinline)) /* inlining would drop the restrict facts */
#else
#define ABRDF__NOINLINE
#endif
/* The front-facing test as float arithmetic on single float compares: an int flag combined
 * with float compares is a mixed mask GCC's vectoriser rejects, and a select whose other arm
 * is 0 is one compare and one AND. 1 for front-facing pairs, else 0; finite_or_zero's
 * result is finite and >= 0, so the product is exact. */
static inline float abrdf__front(float ci, float co)
{
    float w = ci > 0.0f ? 1.0f : 0.0f;
    return co > 0.0f ? w : 0.0f;
}
static inline float abrdf__keep(float front, float x)
{
    return ABRDF__FN(finite_or_zero)(x) * front;
}

/* ABRDF__BATCH_LOOP(id, setup, k_f8) defines batch_k_f8_f, the loop of kernel k_f8_f. */
#define ABRDF__BATCH_LOOP(ID, SETUP, KERNEL)                                                       \
    ABRDF__NOINLINE static void ABRDF__FN(batch_##KERNEL)(                                         \
        const ABRDF__KP *restrict k, size_t n, const float *restrict ix, const float *restrict iy, \
        const float *restrict iz, const float *restrict ox, const float *restrict oy,              \
        const float *restrict oz, float *restrict fr, float *restrict fg, float *restrict fb)      \
    {                                                                                              \
        for (size_t i = 0; i < n; ++i) {                                                           \
            ABRDF__GEO g;                                                                          \
            float v[3];                                                                            \
            ABRDF__FN(geo_make)(&g, ix[i], iy[i], iz[i], ox[i], oy[i], oz[i]);                     \
            ABRDF__FN(KERNEL)(k, &g, v);                                                           \
            float front = abrdf__front(g.ci, g.co);                                                \
            fr[i] = abrdf__keep(front, v[0]);                                                      \
            fg[i] = abrdf__keep(front, v[1]);                                                      \
            fb[i] = abrdf__keep(front, v[2]);                                                      \
        }                                                                                          \
    }
ABRDF__KERNEL_MODELS(ABRDF__BATCH_LOOP)

#define ABRDF__BATCH_CASE(ID, SETUP, KERNEL)                                                       \
    case ID:                                                                                       \
        ABRDF__FN(SETUP)(&k, p);                                                                   \
        ABRDF__FN(batch_##KERNEL)                                                                  \
        (&k, n, b->wi_x, b->wi_y, b->wi_z, b->wo_x, b->wo_y, b->wo_z, b->f_r, b->f_g, b->f_b);     \
        break;

/* Double-only models per element, through the scalar path itself: the float inputs are
 * renormalised in double first (they are unit only to 2^-24, and an integrating model need
 * not tolerate that), degenerate vectors give 0, and a value beyond float's range gives 0
 * like the closed-form loops, never Inf (abrdf__eval_local_d's result is finite, >= 0). */
static float abrdf__to_float(double v) { return v <= FLT_MAX ? (float)v : 0.0f; }

static void abrdf__batch_special(abrdf_model model, const abrdf_params *p, const abrdf_batch *b)
{
    for (size_t i = 0; i < b->count; ++i) {
        double wi[3] = {b->wi_x[i], b->wi_y[i], b->wi_z[i]};
        double wo[3] = {b->wo_x[i], b->wo_y[i], b->wo_z[i]};
        double ui[3], uo[3], f[3] = {0.0, 0.0, 0.0};
        if (abrdf__normalise3(wi, ui) && abrdf__normalise3(wo, uo))
            abrdf__eval_local_d(model, p, ui, uo, f);
        b->f_r[i] = abrdf__to_float(f[0]);
        b->f_g[i] = abrdf__to_float(f[1]);
        b->f_b[i] = abrdf__to_float(f[2]);
    }
}

void abrdf__eval_batch_f(abrdf_model model, const abrdf_params *p, const abrdf_batch *b)
{
    if (abrdf__is_double_only(model)) {
        abrdf__batch_special(model, p, b);
        return;
    }
    const size_t n = b->count;
    ABRDF__KP k;
    switch (model) {
        ABRDF__KERNEL_MODELS(ABRDF__BATCH_CASE)
    default:
        for (size_t i = 0; i < n; ++i) b->f_r[i] = b->f_g[i] = b->f_b[i] = 0.0f;
        break;
    }
}
