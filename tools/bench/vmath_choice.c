/* vmath_choice.c - which vector math should the float batch path use? Times, in one run and
 * on the same data, x^n and e^y over 4096 floats (the batch size of abrdf bench, warm in
 * cache) done four ways, and measures each one's error against double:
 *
 *   libm     C's powf/expf, one call per element (what the batch loops did): the reference
 *   fmath    libabrdf's own polynomials (libabrdf/src/base/fmath.h), inlined in the loop
 *   libmvec  glibc's vector math (_ZGV*_powf/_expf, what `#pragma omp declare simd` reaches)
 *   sleef    SLEEF's 1.0-ulp functions (Sleef_powf8_u10avx2, ...)
 *
 * at the two vector widths the dispatcher compiles for (AVX2 + FMA: 8 lanes; AVX-512: 16
 * lanes), where the CPU has them. Bases x in (0, 1] and n = 100 (a Blinn-Phong lobe),
 * arguments y in [-20, 0] (a Beckmann or velvet exponent). Cost is CPU ns per element, the
 * best of REPS runs; error is the largest over the data, in ulp of the float result.
 *
 *   build/bin/vmath_choice            (docs/BENCHMARKS.md quotes its output)
 */
#define _POSIX_C_SOURCE 200809L
#include <immintrin.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "fmath.h"

#define COUNT 4096
#define CALLS 200
#define REPS 7
#define EXPONENT 100.0f

/* SLEEF 3's functions (libsleef): declared here, as sleef.h declares each ISA's functions
 * only when the translation unit is compiled for that ISA (these are compiled per function). */
__m256 Sleef_powf8_u10avx2(__m256, __m256);
__m256 Sleef_expf8_u10avx2(__m256);
__m512 Sleef_powf16_u10avx512f(__m512, __m512);
__m512 Sleef_expf16_u10avx512f(__m512);
/* glibc's vector math (libmvec), by its vector-ABI names: AVX2 ('d') and AVX-512 ('e'). */
__m256 _ZGVdN8vv_powf(__m256, __m256);
__m256 _ZGVdN8v_expf(__m256);
__m512 _ZGVeN16vv_powf(__m512, __m512);
__m512 _ZGVeN16v_expf(__m512);

static float xs[COUNT], ys[COUNT], out[COUNT];

#define AVX2 __attribute__((noinline, target("avx2,fma")))
#define AVX512 __attribute__((noinline, target("avx512f,avx512vl,avx512dq,avx512bw,avx2,fma")))

__attribute__((noinline)) static void pow_libm(void)
{
    for (int i = 0; i < COUNT; ++i) out[i] = powf(xs[i], EXPONENT);
}
__attribute__((noinline)) static void exp_libm(void)
{
    for (int i = 0; i < COUNT; ++i) out[i] = expf(ys[i]);
}
AVX2 static void pow_fmath_avx2(void)
{
    for (int i = 0; i < COUNT; ++i) out[i] = abrdf__powf_pos(xs[i], EXPONENT);
}
AVX2 static void exp_fmath_avx2(void)
{
    for (int i = 0; i < COUNT; ++i) out[i] = abrdf__expf(ys[i]);
}
AVX512 static void pow_fmath_avx512(void)
{
    for (int i = 0; i < COUNT; ++i) out[i] = abrdf__powf_pos(xs[i], EXPONENT);
}
AVX512 static void exp_fmath_avx512(void)
{
    for (int i = 0; i < COUNT; ++i) out[i] = abrdf__expf(ys[i]);
}
AVX2 static void pow_mvec_avx2(void)
{
    __m256 e = _mm256_set1_ps(EXPONENT);
    for (int i = 0; i < COUNT; i += 8)
        _mm256_storeu_ps(out + i, _ZGVdN8vv_powf(_mm256_loadu_ps(xs + i), e));
}
AVX2 static void exp_mvec_avx2(void)
{
    for (int i = 0; i < COUNT; i += 8)
        _mm256_storeu_ps(out + i, _ZGVdN8v_expf(_mm256_loadu_ps(ys + i)));
}
AVX512 static void pow_mvec_avx512(void)
{
    __m512 e = _mm512_set1_ps(EXPONENT);
    for (int i = 0; i < COUNT; i += 16)
        _mm512_storeu_ps(out + i, _ZGVeN16vv_powf(_mm512_loadu_ps(xs + i), e));
}
AVX512 static void exp_mvec_avx512(void)
{
    for (int i = 0; i < COUNT; i += 16)
        _mm512_storeu_ps(out + i, _ZGVeN16v_expf(_mm512_loadu_ps(ys + i)));
}
AVX2 static void pow_sleef_avx2(void)
{
    __m256 e = _mm256_set1_ps(EXPONENT);
    for (int i = 0; i < COUNT; i += 8)
        _mm256_storeu_ps(out + i, Sleef_powf8_u10avx2(_mm256_loadu_ps(xs + i), e));
}
AVX2 static void exp_sleef_avx2(void)
{
    for (int i = 0; i < COUNT; i += 8)
        _mm256_storeu_ps(out + i, Sleef_expf8_u10avx2(_mm256_loadu_ps(ys + i)));
}
AVX512 static void pow_sleef_avx512(void)
{
    __m512 e = _mm512_set1_ps(EXPONENT);
    for (int i = 0; i < COUNT; i += 16)
        _mm512_storeu_ps(out + i, Sleef_powf16_u10avx512f(_mm512_loadu_ps(xs + i), e));
}
AVX512 static void exp_sleef_avx512(void)
{
    for (int i = 0; i < COUNT; i += 16)
        _mm512_storeu_ps(out + i, Sleef_expf16_u10avx512f(_mm512_loadu_ps(ys + i)));
}

static double cpu_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* Best of REPS runs of CALLS calls, in ns per element. */
static double ns_per_element(void (*fn)(void))
{
    double best = INFINITY;
    for (int r = 0; r < REPS; ++r) {
        double t0 = cpu_seconds();
        for (int c = 0; c < CALLS; ++c) fn();
        double t = (cpu_seconds() - t0) / ((double)CALLS * COUNT) * 1e9;
        if (t < best) best = t;
    }
    return best;
}

/* The largest error of out[] in ulp of the exact (double) result. */
static double max_ulp(int is_pow)
{
    double worst = 0.0;
    for (int i = 0; i < COUNT; ++i) {
        double want = is_pow ? pow((double)xs[i], (double)EXPONENT) : exp((double)ys[i]);
        if (!(want >= 1.17549435e-38)) continue; /* fmath gives no subnormal results */
        double e = fabs((double)out[i] - want) / ldexp(1.0, ilogb(want) - 23);
        if (e > worst) worst = e;
    }
    return worst;
}

typedef struct way {
    const char *name, *width;
    void (*pow_fn)(void), (*exp_fn)(void);
    int level; /* 0 scalar, 1 AVX2 + FMA, 2 AVX-512 */
} way;

int main(void)
{
    unsigned s = 12345u;
    for (int i = 0; i < COUNT; ++i) {
        s = s * 1664525u + 1013904223u;
        float u = (float)((s >> 8) + 1u) / 16777216.0f; /* (0, 1] */
        xs[i] = 1.0f - 0.1f * (1.0f - u);               /* near the lobe's peak: [0.9, 1] */
        ys[i] = -20.0f * u;
    }
    int avx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    int avx512 = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
                 __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512bw");
    const way ways[] = {
        {"libm", "scalar", pow_libm, exp_libm, 0},
        {"fmath", "avx2", pow_fmath_avx2, exp_fmath_avx2, 1},
        {"libmvec", "avx2", pow_mvec_avx2, exp_mvec_avx2, 1},
        {"sleef", "avx2", pow_sleef_avx2, exp_sleef_avx2, 1},
        {"fmath", "avx512", pow_fmath_avx512, exp_fmath_avx512, 2},
        {"libmvec", "avx512", pow_mvec_avx512, exp_mvec_avx512, 2},
        {"sleef", "avx512", pow_sleef_avx512, exp_sleef_avx512, 2},
    };
    double unit_pow = 0.0, unit_exp = 0.0;
    printf("vmath_choice: x^%g (x in [0.9, 1]) and e^y (y in [-20, 0]) over %d floats, CPU ns "
           "per element (best of %d), ratio to libm's scalar call, max error in ulp\n\n",
           (double)EXPONENT, COUNT, REPS);
    printf("%-8s %-7s %9s %7s %8s   %9s %7s %8s\n", "way", "width", "pow ns", "ratio", "pow ulp",
           "exp ns", "ratio", "exp ulp");
    for (size_t k = 0; k < sizeof ways / sizeof *ways; ++k) {
        const way *w = &ways[k];
        if ((w->level == 1 && !avx2) || (w->level == 2 && !avx512)) {
            printf("%-8s %-7s   (the CPU has no %s)\n", w->name, w->width, w->width);
            continue;
        }
        double tp = ns_per_element(w->pow_fn), up = max_ulp(1);
        double te = ns_per_element(w->exp_fn), ue = max_ulp(0);
        if (k == 0) unit_pow = tp, unit_exp = te;
        printf("%-8s %-7s %9.3f %7.3f %8.2f   %9.3f %7.3f %8.2f\n", w->name, w->width, tp,
               tp / unit_pow, up, te, te / unit_exp, ue);
    }
    return 0;
}
