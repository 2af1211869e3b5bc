/* eval_float.c - the float structure-of-arrays batch path. One loop per model, with the
 * model's kernel inlined, so the compiler can vectorise it. */
#define ABRDF__KERNEL_FLOAT 1 /* kernel.h: the kernels in float */
#include "isa.h"
#include "k_dispatch.h"
#include "prepared.h"
#include "vec.h"

#include <float.h>
#include <math.h>
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
 * rows_<KERNEL>_<L> below (ABRDF__ROWS_LOOP_ISA), one_<KERNEL>_<L> (ABRDF__ONE_FN_ISA: the
 * kernel on one pair) and scalar_<KERNEL> of eval_double.c they are the only generated
 * function names of the library; ABRDF__BATCH_CASE_ISA, ABRDF__ROWS_CASE_ISA and the table
 * one_of call them. */
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

/* ROWS OF ANY LENGTH (abrdf_eval_prepared_rows). A direction whose squared length, in double,
 * is within ROWS_UNIT_TOL of 1 is used as given; any other is scaled by 1 / sqrt(len2) in
 * double and rounded to float, and a zero or non-finite one gives f = 0. The tolerance
 * keeps rows normalised in float (a few roundings off) as they are. The rule is decided in
 * double, where the products of floats are exact, so a fused sum rounds as the plain one and
 * the rule makes the same directions at every instruction-set level. The vector loops' test
 * (rows_test) is in float: its squared length is within 3 roundings (1.8e-7) of the exact
 * one, so rows it passes (within 8e-7) are unit by the rule. A loop stops before the
 * first ROWS_CHECK pairs with a row it does not pass, and the general path (rows_general)
 * takes them: there rows_normalise applies the rule to every row (rows the float test could
 * not decide included). Nothing but the test is added to the loops: a call, or the rule's
 * code, in a loop made GCC keep the kernels' values on the stack (1.2-1.6x the time), and a
 * reduction per block cost twice what the test does now (docs/BENCHMARKS.md, section 4). */
#define ABRDF__ROWS_UNIT_TOL 1e-6
#define ABRDF__ROWS_UNIT_TOL_F 8e-7f
/* The test's flag is a float select kept as its bits: an int flag from float compares is a
 * mixed mask GCC's vectoriser rejects (abrdf__front). rows_test ORs a block's flags into
 * off, lane by lane (no reduction in the block); rows_passed reduces off once per
 * ROWS_CHECK pairs, and a loop stops before the first ROWS_CHECK pairs it does not pass. */
static inline ABRDF__ALWAYS_INLINE float rows_off(float x, float y, float z)
{
    return fabsf(x * x + y * y + z * z - 1.0f) <= ABRDF__ROWS_UNIT_TOL_F ? 0.0f : 1.0f;
}
/* The pair's flag as its bits: 0 when both directions pass the test. */
static inline ABRDF__ALWAYS_INLINE uint32_t rows_off_bits(float ix, float iy, float iz, float ox,
                                                          float oy, float oz)
{
    float t = rows_off(ix, iy, iz) + rows_off(ox, oy, oz);
    uint32_t u;
    memcpy(&u, &t, sizeof u);
    return u;
}
static inline ABRDF__ALWAYS_INLINE void
rows_test(const float *restrict ix, const float *restrict iy, const float *restrict iz,
          const float *restrict ox, const float *restrict oy, const float *restrict oz,
          uint32_t *restrict off)
{
    for (int j = 0; j < ABRDF__ROWS_VEC; ++j)
        off[j] |= rows_off_bits(ix[j], iy[j], iz[j], ox[j], oy[j], oz[j]);
}
static inline ABRDF__ALWAYS_INLINE int rows_passed(const uint32_t *off)
{
    uint32_t any = 0;
    for (int j = 0; j < ABRDF__ROWS_VEC; ++j) any |= off[j];
    return any == 0;
}
#define ABRDF__ROWS_CHECK 256 /* = ROWS_BLOCK: what the general path takes at once */

#define ABRDF__ROWS_ARGS                                                                           \
    const abrdf__kp *restrict k, size_t n, const float *restrict wi, const float *restrict wo,     \
        float *restrict f
#define ABRDF__ROWS_LOOP_ISA(KERNEL, FORM, L)                                                      \
    ABRDF__NOINLINE ABRDF__ISA_ATTR_##L static size_t rows_##KERNEL##_##L(ABRDF__ROWS_ARGS)        \
    {                                                                                              \
        for (size_t c = 0; c < n; c += ABRDF__ROWS_CHECK) {                                        \
            uint32_t off[ABRDF__ROWS_VEC] = {0};                                                   \
            size_t c_end = n - c < ABRDF__ROWS_CHECK ? n : c + ABRDF__ROWS_CHECK;                  \
            for (size_t s = c; s < c_end; s += ABRDF__ROWS_VEC) {                                  \
                const float *pi = wi + 3 * s, *po = wo + 3 * s;                                    \
                float *pf = f + 3 * s;                                                             \
                float d[9][ABRDF__ROWS_VEC]; /* wi x y z, wo x y z, f r g b */                     \
                for (int j = 0; j < ABRDF__ROWS_VEC; ++j) {                                        \
                    d[0][j] = pi[3 * j], d[1][j] = pi[3 * j + 1], d[2][j] = pi[3 * j + 2];         \
                    d[3][j] = po[3 * j], d[4][j] = po[3 * j + 1], d[5][j] = po[3 * j + 2];         \
                }                                                                                  \
                rows_test(d[0], d[1], d[2], d[3], d[4], d[5], off);                                \
                for (int j = 0; j < ABRDF__ROWS_VEC; ++j) {                                        \
                    abrdf__geo g;                                                                  \
                    geo_make(&g, d[0][j], d[1][j], d[2][j], d[3][j], d[4][j], d[5][j]);            \
                    ABRDF__STORE_##FORM(KERNEL, j, d[6], d[7], d[8]);                              \
                }                                                                                  \
                for (int j = 0; j < ABRDF__ROWS_VEC; ++j)                                          \
                    pf[3 * j] = d[6][j], pf[3 * j + 1] = d[7][j], pf[3 * j + 2] = d[8][j];         \
            }                                                                                      \
            if (!rows_passed(off)) return c;                                                       \
        }                                                                                          \
        return n;                                                                                  \
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
        if (ok) abrdf__huang_prepared_run(&pr->special.huang, n, (const double(*)[3])ui, uo, f);
        for (int l = 0; l < n; ++l) {
            int good = ok && live[l];
            b->f_r[i + l] = good ? abrdf__to_float(abrdf__nonneg(f[l][0])) : 0.0f;
            b->f_g[i + l] = good ? abrdf__to_float(abrdf__nonneg(f[l][1])) : 0.0f;
            b->f_b[i + l] = good ? abrdf__to_float(abrdf__nonneg(f[l][2])) : 0.0f;
        }
        i = end;
    }
}

/* The double-only models' float batch (marschner, belcour) in blocks: one loop normalises a
 * block's directions in double, as abrdf__normalise3_unit does for a squared length in
 * [0.25, 4] (the same arithmetic, so the same bits), with the square roots and divisions of
 * many pairs in flight; a pair at a time waited for their latency before its model began
 * (belcour: 124 -> 111 ns a pair). Other pairs, and blocks of fewer than SPECIAL_MIN pairs,
 * take abrdf__normalise3_unit one by one. */
#define SPECIAL_BLOCK 64
#define SPECIAL_MIN 8
static void abrdf__batch_special(const abrdf__prep *pr, const abrdf_batch *b)
{
    if (pr->model == ABRDF_HUANG) {
        abrdf__batch_huang(pr, b);
        return;
    }
    double u[6][SPECIAL_BLOCK], near[SPECIAL_BLOCK];
    for (size_t i0 = 0; i0 < b->count; i0 += SPECIAL_BLOCK) {
        const int n = b->count - i0 < SPECIAL_BLOCK ? (int)(b->count - i0) : SPECIAL_BLOCK;
        /* a few pairs (the per-sample float call's one) go one by one: near = 0 */
        const int m = n >= SPECIAL_MIN ? n : 0;
        for (int j = m; j < n; ++j) near[j] = 0.0;
        for (int j = 0; j < m; ++j) { /* abrdf__normalise3_unit's arithmetic, so its bits */
            const size_t i = i0 + (size_t)j;
            double ax = b->wi_x[i], ay = b->wi_y[i], az = b->wi_z[i];
            double bx = b->wo_x[i], by = b->wo_y[i], bz = b->wo_z[i];
            double di = ax * ax + ay * ay + az * az, dn = bx * bx + by * by + bz * bz;
            double ni = di >= 0.25 ? (di <= 4.0 ? 1.0 : 0.0) : 0.0; /* NaN: 0 */
            double no = dn >= 0.25 ? (dn <= 4.0 ? 1.0 : 0.0) : 0.0;
            double ia = 1.0 / sqrt(ni > 0.0 ? di : 1.0), ib = 1.0 / sqrt(no > 0.0 ? dn : 1.0);
            u[0][j] = ax * ia, u[1][j] = ay * ia, u[2][j] = az * ia;
            u[3][j] = bx * ib, u[4][j] = by * ib, u[5][j] = bz * ib;
            near[j] = ni * no;
        }
        for (int j = 0; j < n; ++j) {
            const size_t i = i0 + (size_t)j;
            double ui[3], uo[3], f[3] = {0.0, 0.0, 0.0};
            if (near[j] > 0.0) {
                for (int c = 0; c < 3; ++c) ui[c] = u[c][j], uo[c] = u[3 + c][j];
                abrdf__eval_prepared_d(pr, ui, uo, f);
            } else {
                double wi[3] = {b->wi_x[i], b->wi_y[i], b->wi_z[i]};
                double wo[3] = {b->wo_x[i], b->wo_y[i], b->wo_z[i]};
                if (abrdf__normalise3_unit(wi, ui) && abrdf__normalise3_unit(wo, uo))
                    abrdf__eval_prepared_d(pr, ui, uo, f);
            }
            b->f_r[i] = abrdf__to_float(f[0]);
            b->f_g[i] = abrdf__to_float(f[1]);
            b->f_b[i] = abrdf__to_float(f[2]);
        }
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

/* The rule on the m directions x, y, z, with no branch, so that it vectorises: one function
 * per level, whose results are the same at every level (the products of floats are exact in
 * double, so a fused sum rounds as the plain one; the square root and the division are
 * correctly rounded). A row within the tolerance is kept as it is (times 1.0), a zero or
 * non-finite one becomes (0, 0, 0). */
#define ABRDF__NORMALISE_ISA(L)                                                                    \
    ABRDF__ISA_ATTR_##L static void rows_normalise_##L(float *restrict x, float *restrict y,       \
                                                       float *restrict z, size_t m)                \
    {                                                                                              \
        for (size_t j = 0; j < m; ++j) {                                                           \
            double a = x[j], b = y[j], c = z[j];                                                   \
            double len2 = a * a + b * b + c * c; /* floats: no overflow, no underflow to 0 */      \
            double ok = len2 > 0.0 ? 1.0 : 0.0;                                                    \
            ok = len2 <= DBL_MAX ? ok : 0.0; /* NaN fails both compares */                         \
            double s = fabs(len2 - 1.0) <= ABRDF__ROWS_UNIT_TOL                                    \
                           ? 1.0                                                                   \
                           : 1.0 / sqrt(ok > 0.0 ? len2 : 1.0);                                    \
            x[j] = ok > 0.0 ? (float)(a * s) : 0.0f;                                               \
            y[j] = ok > 0.0 ? (float)(b * s) : 0.0f;                                               \
            z[j] = ok > 0.0 ? (float)(c * s) : 0.0f;                                               \
        }                                                                                          \
    }
#if ABRDF__ISA_X86
#define ABRDF__NORMALISE_LEVELS                                                                    \
    ABRDF__NORMALISE_ISA(0) ABRDF__NORMALISE_ISA(1) ABRDF__NORMALISE_ISA(2)
#else
#define ABRDF__NORMALISE_LEVELS ABRDF__NORMALISE_ISA(0)
#endif
ABRDF__NORMALISE_LEVELS

/* 1 for a direction that is not (0, 0, 0), else 0: a float select (abrdf__front). */
static inline ABRDF__ALWAYS_INLINE float rows_nonzero(float x, float y, float z)
{
    float k = z != 0.0f ? 1.0f : 0.0f;
    k = y != 0.0f ? 1.0f : k;
    return x != 0.0f ? 1.0f : k;
}

/* The general path: m <= ROWS_BLOCK pairs laid out on the stack (9 KiB), made unit by the
 * rule, evaluated by the batch path at the level, f = 0 where a direction was zero or not
 * finite (made (0, 0, 0) by the rule: a scaled row keeps a component of at least 1/sqrt(3)),
 * and written back as rows. */
#define ABRDF__ROWS_BLOCK 256
typedef char abrdf__rows_check_fits
    [ABRDF__ROWS_CHECK <= ABRDF__ROWS_BLOCK && ABRDF__ROWS_CHECK % ABRDF__ROWS_VEC == 0 ? 1 : -1];
#define ABRDF__GENERAL_ISA(L)                                                                      \
    ABRDF__ISA_ATTR_##L static void rows_general_##L(const abrdf__prep *pr, size_t m,              \
                                                     const float *pi, const float *po, float *pf)  \
    {                                                                                              \
        float d[9][ABRDF__ROWS_BLOCK];                                                             \
        for (size_t j = 0; j < m; ++j) {                                                           \
            d[0][j] = pi[3 * j], d[1][j] = pi[3 * j + 1], d[2][j] = pi[3 * j + 2];                 \
            d[3][j] = po[3 * j], d[4][j] = po[3 * j + 1], d[5][j] = po[3 * j + 2];                 \
        }                                                                                          \
        uint32_t off = 0;                                                                          \
        for (size_t j = 0; j < m; ++j)                                                             \
            off |= rows_off_bits(d[0][j], d[1][j], d[2][j], d[3][j], d[4][j], d[5][j]);            \
        if (off) {                                                                                 \
            rows_normalise_##L(d[0], d[1], d[2], m);                                               \
            rows_normalise_##L(d[3], d[4], d[5], m);                                               \
        }                                                                                          \
        abrdf_batch b = {m, d[0], d[1], d[2], d[3], d[4], d[5], d[6], d[7], d[8]};                 \
        abrdf__eval_prepared_f_isa(pr, &b, L);                                                     \
        if (off)                                                                                   \
            for (size_t j = 0; j < m; ++j) {                                                       \
                float k = rows_nonzero(d[0][j], d[1][j], d[2][j]) *                                \
                          rows_nonzero(d[3][j], d[4][j], d[5][j]);                                 \
                d[6][j] *= k, d[7][j] *= k, d[8][j] *= k;                                          \
            }                                                                                      \
        for (size_t j = 0; j < m; ++j)                                                             \
            pf[3 * j] = d[6][j], pf[3 * j + 1] = d[7][j], pf[3 * j + 2] = d[8][j];                 \
    }
#if ABRDF__ISA_X86
#define ABRDF__GENERAL_LEVELS ABRDF__GENERAL_ISA(0) ABRDF__GENERAL_ISA(1) ABRDF__GENERAL_ISA(2)
#else
#define ABRDF__GENERAL_LEVELS ABRDF__GENERAL_ISA(0)
#endif
ABRDF__GENERAL_LEVELS

static void rows_general(const abrdf__prep *pr, size_t m, const float *pi, const float *po,
                         float *pf, int level)
{
    switch (level) {
#if ABRDF__ISA_X86
    case 2: rows_general_2(pr, m, pi, po, pf); break;
    case 1: rows_general_1(pr, m, pi, po, pf); break;
#endif
    default: rows_general_0(pr, m, pi, po, pf); break;
    }
}

/* abrdf_eval_prepared_rows at a given level: the closed-form models' rows loops on the
 * multiple of ROWS_VEC pairs, a block they stop at (one not unit) and the rest (the last
 * pairs; every pair of a measured table or a double-only model) through the general path,
 * ROWS_BLOCK pairs at a time. Every pair's value is the batch path's on the directions made
 * unit by the rule (f = 0 where one is zero or not finite), bit for bit
 * (tests/unit/test_rows.c). */
#define ABRDF__ROWS_CASE_ISA(ID, KERNEL, L)                                                        \
    case ID:                                                                                       \
        while (done < vec) {                                                                       \
            done += rows_##KERNEL##_##L(&pr->kf, vec - done, wi + 3 * done, wo + 3 * done,         \
                                        f + 3 * done);                                             \
            if (done == vec) break;                                                                \
            size_t m = vec - done < ABRDF__ROWS_CHECK ? vec - done : ABRDF__ROWS_CHECK;            \
            rows_general(pr, m, wi + 3 * done, wo + 3 * done, f + 3 * done, level);                \
            done += m;                                                                             \
        }                                                                                          \
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
    size_t done = 0, vec = n - n % ABRDF__ROWS_VEC;
    if (pr->model != ABRDF_MEASURED && !abrdf__is_double_only(pr->model)) {
        switch (level) {
            ABRDF__ISA_LEVELS(ABRDF__ROWS_SWITCH)
        default: break;
        }
    }
    for (size_t start = done; start < n; start += ABRDF__ROWS_BLOCK) {
        size_t m = n - start < ABRDF__ROWS_BLOCK ? n - start : ABRDF__ROWS_BLOCK;
        rows_general(pr, m, wi + 3 * start, wo + 3 * start, f + 3 * start, level);
    }
    return 0;
}

/* ONE PAIR IN FLOAT (abrdf_eval_prepared_float): the batch loops' kernels on one pair, at
 * the level the batch path runs, so that a renderer shading one sample at a time pays what
 * the formula costs in float. one_<KERNEL>_<L> is kernel KERNEL on one pair at level L (its
 * geometry made for what that kernel reads), held in one_of at [level][model]: a sample
 * costs one indirect call, no switch. A pair whose rows the loops' test does not pass, and a
 * model without a kernel here (a measured table, a double-only model: NULL in one_of), take
 * the general path for one pair. */
typedef void (*abrdf__one_fn)(const abrdf__kp *restrict k, const float *restrict wi,
                              const float *restrict wo, float *restrict f);
#define ABRDF__ONE_FN_ISA(KERNEL, FORM, L)                                                         \
    ABRDF__ISA_ATTR_##L static void one_##KERNEL##_##L(                                            \
        const abrdf__kp *restrict k, const float *restrict wi, const float *restrict wo,           \
        float *restrict f)                                                                         \
    {                                                                                              \
        abrdf__geo g;                                                                              \
        geo_make(&g, wi[0], wi[1], wi[2], wo[0], wo[1], wo[2]);                                    \
        ABRDF__STORE_##FORM(KERNEL, 0, f, f + 1, f + 2);                                           \
    }
#define ABRDF__ONE_ENTRY_0(ID, SETUP, KERNEL, FORM) [ID] = one_##KERNEL##_0,
#if ABRDF__ISA_X86
#define ABRDF__ONE_FN(ID, SETUP, KERNEL, FORM)                                                     \
    ABRDF__ONE_FN_ISA(KERNEL, FORM, 0)                                                             \
    ABRDF__ONE_FN_ISA(KERNEL, FORM, 1) ABRDF__ONE_FN_ISA(KERNEL, FORM, 2)
#define ABRDF__ONE_ENTRY_1(ID, SETUP, KERNEL, FORM) [ID] = one_##KERNEL##_1,
#define ABRDF__ONE_ENTRY_2(ID, SETUP, KERNEL, FORM) [ID] = one_##KERNEL##_2,
ABRDF__KERNEL_MODELS(ABRDF__ONE_FN)
static const abrdf__one_fn one_of[ABRDF__ISA_COUNT][ABRDF_MODEL_COUNT] = {
    {ABRDF__KERNEL_MODELS(ABRDF__ONE_ENTRY_0)},
    {ABRDF__KERNEL_MODELS(ABRDF__ONE_ENTRY_1)},
    {ABRDF__KERNEL_MODELS(ABRDF__ONE_ENTRY_2)}};
#else
#define ABRDF__ONE_FN(ID, SETUP, KERNEL, FORM) ABRDF__ONE_FN_ISA(KERNEL, FORM, 0)
ABRDF__KERNEL_MODELS(ABRDF__ONE_FN)
static const abrdf__one_fn one_of[ABRDF__ISA_COUNT][ABRDF_MODEL_COUNT] = {
    {ABRDF__KERNEL_MODELS(ABRDF__ONE_ENTRY_0)}};
#endif

/* One pair at `level`, which the caller has checked. */
static inline void one_at(const abrdf__prep *pr, const float wi[3], const float wo[3], float f[3],
                          int level)
{
    abrdf__one_fn fn = one_of[level][pr->model];
    if (fn && !rows_off_bits(wi[0], wi[1], wi[2], wo[0], wo[1], wo[2]))
        fn(&pr->kf, wi, wo, f);
    else
        rows_general(pr, 1, wi, wo, f, level);
}

int abrdf__eval_prepared_one_f(const abrdf__prep *pr, const float wi[3], const float wo[3],
                               float f[3], int level)
{
    if (level < 0 || level > abrdf__isa_best()) return -1;
    one_at(pr, wi, wo, f, level);
    return 0;
}

void abrdf__eval_prepared_one(const abrdf__prep *pr, const float wi[3], const float wo[3],
                              float f[3])
{
    one_at(pr, wi, wo, f, abrdf__isa_best_inline());
}

void abrdf__eval_prepared_rows(const abrdf__prep *pr, size_t n, const float *wi, const float *wo,
                               float *f)
{
    abrdf__eval_prepared_rows_isa(pr, n, wi, wo, f, abrdf__isa_best());
}
