/* percall_bound.c - how cheap can a per-sample call of lambert and disney_specular be at all?
 * Times, in one run, the powf Blinn-Phong unit of `abrdf bench` and, on the same direction
 * pairs (unit vectors in double, as `abrdf bench` hands them to abrdf_eval_prepared_unit),
 * the least work of one pair in double with no library call, no check and no guard:
 *   call      a function that is not inlined, taking (object, wi, wo, f) and writing f: what
 *             any per-sample entry point pays before its model does anything;
 *   lambert   the front-facing test and kd/pi in three channels (Eq. 1);
 *   ds        disney_specular as the library's kernel writes it (k_microfacet.h): H normalised
 *             (a square root and a division), GGX D (a division), two Smith visibility terms
 *             (a square root and a division each) and Schlick F per channel;
 *   ds_1div   the same with D and the two visibility terms over one denominator.
 * Each loop is scalar, as a per-sample call is (no vectorisation), and sums f_r's first
 * channel as `abrdf bench` does. The ratios to the unit are the floors of the bench's
 * per-sample columns for the given compiler flags (docs/BENCHMARKS.md, "The per-sample
 * call").
 *
 *   cc -std=c99 -O3 -fno-math-errno -fno-trapping-math tools/bench/percall_bound.c -lm && ./a.out
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#define PAIRS 4096 /* as abrdf bench: warm in L2 */
#define CALLS 100
#define REPS 30
#define PI 3.14159265358979323846

static double cpu_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static volatile double sink;

/* disney_specular's parameters at its defaults' scale: alpha_g = 0.25, ks = 1, F0 = 0.04 */
static const double kd[3] = {0.5, 0.5, 0.5}, ks[3] = {1, 1, 1}, f0[3] = {0.04, 0.04, 0.04};
static const double alpha_g = 0.25;

__attribute__((noinline)) static void unit(size_t n, const float *restrict b, float *restrict out)
{
    for (size_t i = 0; i < n; ++i) {
        float hx = b[i] + b[3 * n + i], hy = b[n + i] + b[4 * n + i],
              hz = b[2 * n + i] + b[5 * n + i];
        float c = hz / sqrtf(hx * hx + hy * hy + hz * hz);
        out[i] = c > 0.0f ? powf(c, 100.0f) : 0.0f;
    }
}

/* The least an entry point does: it is called and writes its three results. */
__attribute__((noinline)) static int empty_eval(const double *obj, const double wi[3],
                                                const double wo[3], double f[3])
{
    f[0] = obj[0] * wi[2];
    f[1] = obj[1] * wo[2];
    f[2] = obj[2];
    return 0;
}

__attribute__((noinline, optimize("no-tree-vectorize"))) static void call(size_t n, const double *d)
{
    double f[3], acc = 0.0;
    for (size_t i = 0; i < n; ++i) {
        empty_eval(kd, d + 6 * i, d + 6 * i + 3, f);
        acc += f[0];
    }
    sink = acc;
}

__attribute__((noinline, optimize("no-tree-vectorize"))) static void lambert(size_t n,
                                                                             const double *d)
{
    double f[3], acc = 0.0;
    for (size_t i = 0; i < n; ++i) {
        const double *wi = d + 6 * i, *wo = wi + 3;
        int front = wi[2] > 0.0 && wo[2] > 0.0;
        for (int c = 0; c < 3; ++c) f[c] = front ? kd[c] * (1.0 / PI) : 0.0; /* Eq. 1 */
        acc += f[0];
    }
    sink = acc;
}

__attribute__((noinline, optimize("no-tree-vectorize"))) static void ds(size_t n, const double *d,
                                                                        int one_division)
{
    double f[3], acc = 0.0, a2 = alpha_g * alpha_g;
    for (size_t i = 0; i < n; ++i) {
        const double *wi = d + 6 * i, *wo = wi + 3;
        double hx = wi[0] + wo[0], hy = wi[1] + wo[1], hz = wi[2] + wo[2];
        double len = sqrt(hx * hx + hy * hy + hz * hz), inv = 1.0 / len;
        hx *= inv, hy *= inv, hz *= inv;
        double t = hx * hx + hy * hy + a2 * hz * hz;
        double ci = wi[2], co = wo[2];
        double vi = ci + sqrt(a2 + (1.0 - a2) * ci * ci), vo = co + sqrt(a2 + (1.0 - a2) * co * co);
        double dv = one_division ? a2 / (PI * t * t * vi * vo)
                                 : a2 / (PI * t * t) * (1.0 / vi) * (1.0 / vo);
        double m = 1.0 - 0.5 * len, m5 = m * m * m * m * m;
        for (int c = 0; c < 3; ++c) f[c] = ks[c] * (f0[c] + (1.0 - f0[c]) * m5) * dv;
        acc += f[0];
    }
    sink = acc;
}

int main(void)
{
    float *b = malloc(7 * PAIRS * sizeof *b);
    double *d = malloc(6 * PAIRS * sizeof *d);
    if (!b || !d) return 1;
    unsigned s = 12345;
    for (int i = 0; i < 2 * PAIRS; ++i) { /* upper hemisphere, off the horizon */
        s = s * 1103515245u + 12345u;
        double cz = 0.01 + 0.99 * (double)(s >> 8) / 16777216.0;
        s = s * 1103515245u + 12345u;
        double phi = 2.0 * PI * (double)(s >> 8) / 16777216.0, r = sqrt(1.0 - cz * cz);
        double v[3] = {r * cos(phi), r * sin(phi), cz};
        for (int c = 0; c < 3; ++c) { /* float for the unit's arrays, double for the pairs */
            b[(size_t)(3 * (i % 2) + c) * PAIRS + (size_t)(i / 2)] = (float)v[c];
            d[6 * (i / 2) + 3 * (i % 2) + c] = v[c];
        }
    }
    double tu = 1e30, tc = 1e30, tl = 1e30, td = 1e30, t1 = 1e30;
    for (int r = 0; r < REPS; ++r) { /* best of REPS: interference only adds time */
        double t = cpu_seconds();
        for (int k = 0; k < CALLS; ++k) unit(PAIRS, b, b + 6 * PAIRS);
        t = cpu_seconds() - t, tu = t < tu ? t : tu;
        t = cpu_seconds();
        for (int k = 0; k < CALLS; ++k) call(PAIRS, d);
        t = cpu_seconds() - t, tc = t < tc ? t : tc;
        t = cpu_seconds();
        for (int k = 0; k < CALLS; ++k) lambert(PAIRS, d);
        t = cpu_seconds() - t, tl = t < tl ? t : tl;
        t = cpu_seconds();
        for (int k = 0; k < CALLS; ++k) ds(PAIRS, d, 0);
        t = cpu_seconds() - t, td = t < td ? t : td;
        t = cpu_seconds();
        for (int k = 0; k < CALLS; ++k) ds(PAIRS, d, 1);
        t = cpu_seconds() - t, t1 = t < t1 ? t : t1;
    }
    printf("powf unit %.3f ns/eval; in units: call %.3f, lambert %.3f, ds %.3f, ds_1div %.3f\n",
           1e9 * tu / CALLS / PAIRS, tc / tu, tl / tu, td / tu, t1 / tu);
    free(b);
    free(d);
    return 0;
}
