/* eval_float.c - the float structure-of-arrays batch path. One loop per model, with the
 * model's kernel inlined, so the compiler can vectorise it. */
#define ABRDF__KERNEL_FLOAT 1 /* kernel.h: the kernels in float */
#include "isa.h"
#include "k_dispatch.h"
#include "prepared.h"
#include "vec.h"

#include <stdint.h>
#include <string.h>

/* One loop per model with the kernel inlined. The front-facing test and the finiteness
 * guard are combined with & (not &&) so the body has no control flow, and the arrays are
 * restrict parameters (abrdf.h: outputs may not alias inputs), so the compiler needs no
 * run-time alias checks: both are required for the loop to vectorise. */
/* The front-facing test as float arithmetic on single float compares: an int flag combined
 * with float compares is a mixed mask GCC's vectoriser rejects, and a select whose other arm
 * is 0 is one compare and one AND. 1 for front-facing pairs, else 0; finite_or_zero's
 * result is finite and >= 0, so the product is exact. */
static inline float abrdf__front(float ci, float co)
{
    float w = ci > 0.0f ? 1.0f : 0.0f;
    return co > 0.0f ? w : 0.0f;
}
/* finite_or_zero (kernel.h) in one compare: a binary32 is a finite number >= +0 exactly when
 * its bits, read as an unsigned integer, are at most those of FLT_MAX (negative numbers and
 * -0 have the sign bit set, Inf and NaN the largest exponent). -0 gives +0. */
static inline float abrdf__keep(float front, float x)
{
    uint32_t u;
    memcpy(&u, &x, sizeof u);
    return (u <= 0x7F7FFFFFu ? x : 0.0f) * front;
}

/* RUN-TIME INSTRUCTION SETS (isa.h). The float tolerance of the batch path holds at every
 * level (FMA contraction changes the last bits); tests run every level the machine has
 * (abrdf__eval_prepared_f_isa). */
const char *abrdf__isa_name(int level)
{
    static const char *const names[] = {"baseline", "avx2+fma", "avx512"};
    return level >= 0 && level < ABRDF__ISA_COUNT ? names[level] : "none";
}

/* The store of pair J after the geometry g is made, per form (k_dispatch.h). RGB: the
 * kernel's three channels, each guarded. LOBE: the lobe guarded once, then times ks in
 * [0, 1], which keeps it finite and >= 0 (the same values as guarding each channel).
 * SCHLICK: the lobe guarded once, then times ks F = ks_f0 + ks_f1 (1 - cos_d)^5, both
 * products of the setup (kp_base) and >= 0, so ks F is in [0, ks]: one guard and two
 * operations a channel where RGB's ks F lobe took three and a guard. */
#define ABRDF__STORE_RGB(KERNEL, J, FR, FG, FB)                                                    \
    do {                                                                                           \
        float v[3];                                                                                \
        KERNEL(k, &g, v);                                                                          \
        float front = abrdf__front(g.ci, g.co);                                                    \
        (FR)[J] = abrdf__keep(front, v[0]);                                                        \
        (FG)[J] = abrdf__keep(front, v[1]);                                                        \
        (FB)[J] = abrdf__keep(front, v[2]);                                                        \
    } while (0)
#define ABRDF__STORE_LOBE(KERNEL, J, FR, FG, FB)                                                   \
    do {                                                                                           \
        float w = abrdf__keep(abrdf__front(g.ci, g.co), KERNEL##_lobe(k, &g));                     \
        (FR)[J] = k->ks[0] * w;                                                                    \
        (FG)[J] = k->ks[1] * w;                                                                    \
        (FB)[J] = k->ks[2] * w;                                                                    \
    } while (0)
#define ABRDF__STORE_SCHLICK(KERNEL, J, FR, FG, FB)                                                \
    do {                                                                                           \
        float w = abrdf__keep(abrdf__front(g.ci, g.co), KERNEL##_lobe(k, &g));                     \
        float m5 = schlick_m5(g.cd);                                                               \
        (FR)[J] = (k->ks_f0[0] + k->ks_f1[0] * m5) * w;                                            \
        (FG)[J] = (k->ks_f0[1] + k->ks_f1[1] * m5) * w;                                            \
        (FB)[J] = (k->ks_f0[2] + k->ks_f1[2] * m5) * w;                                            \
    } while (0)
#define ABRDF__BATCH_ARGS                                                                          \
    const abrdf__kp *restrict k, size_t n, const float *restrict ix, const float *restrict iy,     \
        const float *restrict iz, const float *restrict ox, const float *restrict oy,              \
        const float *restrict oz, float *restrict fr, float *restrict fg, float *restrict fb

/* THE GENERATED NAMES. ABRDF__BATCH_LOOP_ISA(KERNEL, FORM, L) defines batch_<KERNEL>_<L>, the
 * batch loop of kernel KERNEL at instruction-set level L, for every model of
 * ABRDF__KERNEL_MODELS and every level of ABRDF__ISA_LEVELS: batch_k_f8_2 is k_f8's loop at
 * level 2, batch_k_lambert_0 is k_lambert's at level 0 (the only level off x86). With the
 * rows_<KERNEL>_<L> below (ABRDF__ROWS_LOOP_ISA) and scalar_<KERNEL> of eval_double.c they
 * are the only generated function names of the library; ABRDF__BATCH_CASE_ISA and
 * ABRDF__ROWS_CASE_ISA call them. */
#define ABRDF__BATCH_LOOP_ISA(KERNEL, FORM, L)                                                     \
    ABRDF__NOINLINE ABRDF__ISA_ATTR_##L static void batch_##KERNEL##_##L(ABRDF__BATCH_ARGS)        \
    {                                                                                              \
        for (size_t i = 0; i < n; ++i) {                                                           \
            abrdf__geo g;                                                                          \
            geo_make(&g, ix[i], iy[i], iz[i], ox[i], oy[i], oz[i]);                                \
            ABRDF__STORE_##FORM(KERNEL, i, fr, fg, fb);                                            \
        }                                                                                          \
    }
/* ABRDF__ROWS_LOOP_ISA(KERNEL, FORM, L) defines rows_<KERNEL>_<L>, the same kernel over
 * interleaved rows (abrdf_eval_prepared_rows: x, y, z of a pair's directions in, r, g, b out)
 * for a multiple of ROWS_VEC pairs. The rows are laid out ROWS_VEC at a time in registers'
 * worth of stack, so they are read from memory while the previous pairs are evaluated (a
 * pass of its own over arrays out of cache would stall on them). ROWS_VEC is two AVX-512
 * vectors: short enough for that overlap, long enough that GCC keeps the three inner loops
 * as vector loops (at 16 it unrolls them into scalar shuffles, 4x slower). */
#define ABRDF__ROWS_VEC 32
#define ABRDF__ROWS_ARGS                                                                           \
    const abrdf__kp *restrict k, size_t n, const float *restrict wi, const float *restrict wo,     \
        float *restrict f
#define ABRDF__ROWS_LOOP_ISA(KERNEL, FORM, L)                                                      \
    ABRDF__NOINLINE ABRDF__ISA_ATTR_##L static void rows_##KERNEL##_##L(ABRDF__ROWS_ARGS)          \
    {                                                                                              \
        for (size_t s = 0; s < n; s += ABRDF__ROWS_VEC) {                                          \
            const float *pi = wi + 3 * s, *po = wo + 3 * s;                                        \
            float *pf = f + 3 * s;                                                                 \
            float d[9][ABRDF__ROWS_VEC]; /* wi x y z, wo x y z, f r g b */                         \
            for (int j = 0; j < ABRDF__ROWS_VEC; ++j) {                                            \
                d[0][j] = pi[3 * j], d[1][j] = pi[3 * j + 1], d[2][j] = pi[3 * j + 2];             \
                d[3][j] = po[3 * j], d[4][j] = po[3 * j + 1], d[5][j] = po[3 * j + 2];             \
            }                                                                                      \
            for (int j = 0; j < ABRDF__ROWS_VEC; ++j) {                                            \
                abrdf__geo g;                                                                      \
                geo_make(&g, d[0][j], d[1][j], d[2][j], d[3][j], d[4][j], d[5][j]);                \
                ABRDF__STORE_##FORM(KERNEL, j, d[6], d[7], d[8]);                                  \
            }                                                                                      \
            for (int j = 0; j < ABRDF__ROWS_VEC; ++j)                                              \
                pf[3 * j] = d[6][j], pf[3 * j + 1] = d[7][j], pf[3 * j + 2] = d[8][j];             \
        }                                                                                          \
    }
#if ABRDF__ISA_X86
#define ABRDF__BATCH_LOOP(ID, SETUP, KERNEL, FORM)                                                 \
    ABRDF__BATCH_LOOP_ISA(KERNEL, FORM, 0)                                                         \
    ABRDF__BATCH_LOOP_ISA(KERNEL, FORM, 1) ABRDF__BATCH_LOOP_ISA(KERNEL, FORM, 2)
#define ABRDF__ROWS_LOOP(ID, SETUP, KERNEL, FORM)                                                  \
    ABRDF__ROWS_LOOP_ISA(KERNEL, FORM, 0)                                                          \
    ABRDF__ROWS_LOOP_ISA(KERNEL, FORM, 1) ABRDF__ROWS_LOOP_ISA(KERNEL, FORM, 2)
#else
#define ABRDF__BATCH_LOOP(ID, SETUP, KERNEL, FORM) ABRDF__BATCH_LOOP_ISA(KERNEL, FORM, 0)
#define ABRDF__ROWS_LOOP(ID, SETUP, KERNEL, FORM) ABRDF__ROWS_LOOP_ISA(KERNEL, FORM, 0)
#endif
ABRDF__KERNEL_MODELS(ABRDF__BATCH_LOOP)
ABRDF__KERNEL_MODELS(ABRDF__ROWS_LOOP)

#define ABRDF__SETUP_CASE(ID, SETUP, KERNEL, FORM)                                                 \
    case ID: SETUP(&pr->kf, &pr->params); break;

void abrdf__prep_setup_f(abrdf__prep *pr)
{
    switch (pr->model) {
        ABRDF__KERNEL_MODELS(ABRDF__SETUP_CASE)
    default: break;
    }
}

/* Double-only models per element, through the scalar path itself: the float inputs are
 * renormalised in double first (they are unit only to 2^-24, and an integrating model need
 * not tolerate that), degenerate vectors give 0, and a value beyond float's range gives 0
 * like the closed-form loops, never Inf (abrdf__eval_prepared_d's result is finite, >= 0). */
static float abrdf__to_float(double v) { return v <= FLT_MAX ? (float)v : 0.0f; }

/* abrdf__eval_prepared_d's last line of defence, for the values that bypass it: a finite
 * number >= 0, else 0 (NaN fails both compares). */
static double abrdf__nonneg(double v) { return v >= 0.0 && v <= DBL_MAX ? v : 0.0; }

/* huang: a run of consecutive pairs with the same wo (the lights of one shading point, as a
 * renderer hands them over) is one call, which builds the view's paths once. */
static void abrdf__batch_huang(const abrdf__prep *pr, const abrdf_batch *b)
{
    size_t i = 0;
    while (i < b->count) {
        double wo[3] = {b->wo_x[i], b->wo_y[i], b->wo_z[i]}, uo[3];
        double ui[ABRDF__HUANG_RUN_MAX][3], f[ABRDF__HUANG_RUN_MAX][3];
        size_t end = i + 1;
        while (end < b->count && end - i < ABRDF__HUANG_RUN_MAX && b->wo_x[end] == b->wo_x[i] &&
               b->wo_y[end] == b->wo_y[i] && b->wo_z[end] == b->wo_z[i])
            ++end;
        int n = (int)(end - i), ok = abrdf__normalise3(wo, uo), live[ABRDF__HUANG_RUN_MAX];
        for (int l = 0; l < n; ++l) {
            double wi[3] = {b->wi_x[i + l], b->wi_y[i + l], b->wi_z[i + l]};
            live[l] = abrdf__normalise3(wi, ui[l]);
            if (!live[l]) ui[l][0] = ui[l][1] = 0.0, ui[l][2] = -1.0; /* gives 0 */
        }
        if (ok) abrdf__huang_eval_run(&pr->special.huang, n, (const double(*)[3])ui, uo, f);
        for (int l = 0; l < n; ++l) {
            int good = ok && live[l];
            b->f_r[i + l] = good ? abrdf__to_float(abrdf__nonneg(f[l][0])) : 0.0f;
            b->f_g[i + l] = good ? abrdf__to_float(abrdf__nonneg(f[l][1])) : 0.0f;
            b->f_b[i + l] = good ? abrdf__to_float(abrdf__nonneg(f[l][2])) : 0.0f;
        }
        i = end;
    }
}

static void abrdf__batch_special(const abrdf__prep *pr, const abrdf_batch *b)
{
    if (pr->model == ABRDF_HUANG) {
        abrdf__batch_huang(pr, b);
        return;
    }
    for (size_t i = 0; i < b->count; ++i) {
        double wi[3] = {b->wi_x[i], b->wi_y[i], b->wi_z[i]};
        double wo[3] = {b->wo_x[i], b->wo_y[i], b->wo_z[i]};
        double ui[3], uo[3], f[3] = {0.0, 0.0, 0.0};
        if (abrdf__normalise3_unit(wi, ui) && abrdf__normalise3_unit(wo, uo))
            abrdf__eval_prepared_d(pr, ui, uo, f);
        b->f_r[i] = abrdf__to_float(f[0]);
        b->f_g[i] = abrdf__to_float(f[1]);
        b->f_b[i] = abrdf__to_float(f[2]);
    }
}

#define ABRDF__BATCH_CASE_ISA(ID, KERNEL, L)                                                       \
    case ID:                                                                                       \
        batch_##KERNEL##_##L(&pr->kf, n, b->wi_x, b->wi_y, b->wi_z, b->wo_x, b->wo_y, b->wo_z,     \
                             b->f_r, b->f_g, b->f_b);                                              \
        return 0;
#define ABRDF__BATCH_CASE_0(ID, SETUP, KERNEL, FORM) ABRDF__BATCH_CASE_ISA(ID, KERNEL, 0)
#define ABRDF__BATCH_CASE_1(ID, SETUP, KERNEL, FORM) ABRDF__BATCH_CASE_ISA(ID, KERNEL, 1)
#define ABRDF__BATCH_CASE_2(ID, SETUP, KERNEL, FORM) ABRDF__BATCH_CASE_ISA(ID, KERNEL, 2)
#define ABRDF__ISA_SWITCH(L)                                                                       \
    case L:                                                                                        \
        switch (pr->model) {                                                                       \
            ABRDF__KERNEL_MODELS(ABRDF__BATCH_CASE_##L)                                            \
        default: break;                                                                            \
        }                                                                                          \
        break;

int abrdf__eval_prepared_f_isa(const abrdf__prep *pr, const abrdf_batch *b, int level)
{
    if (level < 0 || level > abrdf__isa_best()) return -1;
    if (pr->model == ABRDF_MEASURED) {
        abrdf__measured_batch(&pr->special.measured, b, level);
        return 0;
    }
    if (pr->model == ABRDF_WEIDLICH_WILKIE) { /* its own vector loops (layered_ww.c) */
        abrdf__ww_batch(&pr->special.ww, b, level);
        return 0;
    }
    if (abrdf__is_double_only(pr->model)) {
        abrdf__batch_special(pr, b);
        return 0;
    }
    const size_t n = b->count;
    switch (level) {
        ABRDF__ISA_LEVELS(ABRDF__ISA_SWITCH)
    default: break;
    }
    for (size_t i = 0; i < n; ++i) b->f_r[i] = b->f_g[i] = b->f_b[i] = 0.0f;
    return 0;
}

void abrdf__eval_prepared_f(const abrdf__prep *pr, const abrdf_batch *b)
{
    abrdf__eval_prepared_f_isa(pr, b, abrdf__isa_best());
}

/* abrdf_eval_prepared_rows at a given level: the closed-form models' rows loops on the
 * multiple of ROWS_VEC pairs, and the rest (the last pairs; every pair of a measured table or
 * a double-only model) through the batch path, ROWS_BLOCK pairs at a time laid out on the
 * stack (9 KiB). Every pair's value is the batch path's, bit for bit (tests/unit/test_rows.c). */
#define ABRDF__ROWS_BLOCK 256
#define ABRDF__ROWS_CASE_ISA(ID, KERNEL, L)                                                        \
    case ID:                                                                                       \
        done = n - n % ABRDF__ROWS_VEC;                                                            \
        rows_##KERNEL##_##L(&pr->kf, done, wi, wo, f);                                             \
        break;
#define ABRDF__ROWS_CASE_0(ID, SETUP, KERNEL, FORM) ABRDF__ROWS_CASE_ISA(ID, KERNEL, 0)
#define ABRDF__ROWS_CASE_1(ID, SETUP, KERNEL, FORM) ABRDF__ROWS_CASE_ISA(ID, KERNEL, 1)
#define ABRDF__ROWS_CASE_2(ID, SETUP, KERNEL, FORM) ABRDF__ROWS_CASE_ISA(ID, KERNEL, 2)
#define ABRDF__ROWS_SWITCH(L)                                                                      \
    case L:                                                                                        \
        switch (pr->model) {                                                                       \
            ABRDF__KERNEL_MODELS(ABRDF__ROWS_CASE_##L)                                             \
        default: break;                                                                            \
        }                                                                                          \
        break;

int abrdf__eval_prepared_rows_isa(const abrdf__prep *pr, size_t n, const float *wi, const float *wo,
                                  float *f, int level)
{
    if (level < 0 || level > abrdf__isa_best()) return -1;
    size_t done = 0;
    if (pr->model != ABRDF_MEASURED && !abrdf__is_double_only(pr->model)) {
        switch (level) {
            ABRDF__ISA_LEVELS(ABRDF__ROWS_SWITCH)
        default: break;
        }
    }
    float d[9][ABRDF__ROWS_BLOCK];
    for (size_t start = done; start < n; start += ABRDF__ROWS_BLOCK) {
        size_t m = n - start < ABRDF__ROWS_BLOCK ? n - start : ABRDF__ROWS_BLOCK;
        const float *pi = wi + 3 * start, *po = wo + 3 * start;
        float *pf = f + 3 * start;
        for (size_t j = 0; j < m; ++j) {
            d[0][j] = pi[3 * j], d[1][j] = pi[3 * j + 1], d[2][j] = pi[3 * j + 2];
            d[3][j] = po[3 * j], d[4][j] = po[3 * j + 1], d[5][j] = po[3 * j + 2];
        }
        abrdf_batch b = {m, d[0], d[1], d[2], d[3], d[4], d[5], d[6], d[7], d[8]};
        abrdf__eval_prepared_f_isa(pr, &b, level);
        for (size_t j = 0; j < m; ++j)
            pf[3 * j] = d[6][j], pf[3 * j + 1] = d[7][j], pf[3 * j + 2] = d[8][j];
    }
    return 0;
}

void abrdf__eval_prepared_rows(const abrdf__prep *pr, size_t n, const float *wi, const float *wo,
                               float *f)
{
    abrdf__eval_prepared_rows_isa(pr, n, wi, wo, f, abrdf__isa_best());
}
