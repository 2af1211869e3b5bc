/* simd_bound.c - how fast can a Table-1 approximation be on this machine at all?
 * Times, in one run, the powf Blinn-Phong unit of `abrdf bench` and the least work any
 * f_m lobe on the same structure-of-arrays data must do (load wi and wo, H = wi + wo,
 * c = H.z / |H|, ((n/m)(c - 1) + 1)^2 clamped at 0, three stores), with no guards and no
 * library call. The ratio is the ceiling of the "Table-1 approximations >= 20x faster"
 * target for the given compiler flags (docs/BENCHMARKS.md).
 *
 *   cc -std=c99 -O3 -fno-math-errno -fno-trapping-math tools/bench/simd_bound.c -lm && ./a.out
 *   cc -std=c99 -O3 -fno-math-errno -fno-trapping-math -march=native tools/bench/simd_bound.c -lm && ./a.out
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#define PAIRS 4096 /* as abrdf bench: warm in L2 */
#define CALLS 200
#define REPS 50

static double cpu_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

__attribute__((noinline)) static void bound(size_t n, const float *restrict ix,
                                            const float *restrict iy, const float *restrict iz,
                                            const float *restrict ox, const float *restrict oy,
                                            const float *restrict oz, float *restrict fr,
                                            float *restrict fg, float *restrict fb)
{
    for (size_t i = 0; i < n; ++i) {
        float hx = ix[i] + ox[i], hy = iy[i] + oy[i], hz = iz[i] + oz[i];
        float c = hz / sqrtf(hx * hx + hy * hy + hz * hz);
        float t = 50.0f * (c - 1.0f) + 1.0f;
        t = t > 0.0f ? t : 0.0f;
        t *= t;
        fr[i] = 0.5f * t;
        fg[i] = 0.5f * t;
        fb[i] = 0.5f * t;
    }
}

__attribute__((noinline)) static void unit(size_t n, const float *restrict ix,
                                           const float *restrict iy, const float *restrict iz,
                                           const float *restrict ox, const float *restrict oy,
                                           const float *restrict oz, float *restrict fr)
{
    for (size_t i = 0; i < n; ++i) {
        float hx = ix[i] + ox[i], hy = iy[i] + oy[i], hz = iz[i] + oz[i];
        float c = hz / sqrtf(hx * hx + hy * hy + hz * hz);
        fr[i] = c > 0.0f ? powf(c, 100.0f) : 0.0f;
    }
}

int main(void)
{
    float *b = malloc(9 * PAIRS * sizeof *b);
    if (!b) return 1;
    unsigned s = 12345;
    for (int i = 0; i < 6 * PAIRS; ++i) {
        s = s * 1103515245u + 12345u;
        b[i] = 0.3f + 0.4f * (float)(s >> 8) / 16777216.0f;
    }
    float *p[9];
    for (int k = 0; k < 9; ++k) p[k] = b + k * PAIRS;
    double tb = 1e30, tu = 1e30;
    for (int r = 0; r < REPS; ++r) { /* best of REPS: interference only adds time */
        double t = cpu_seconds();
        for (int k = 0; k < CALLS; ++k)
            bound(PAIRS, p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7], p[8]);
        t = cpu_seconds() - t;
        tb = t < tb ? t : tb;
        t = cpu_seconds();
        for (int k = 0; k < CALLS; ++k) unit(PAIRS, p[0], p[1], p[2], p[3], p[4], p[5], p[6]);
        t = cpu_seconds() - t;
        tu = t < tu ? t : tu;
    }
    printf("least f_m work: %.3f ns/eval, powf unit: %.3f ns/eval, ceiling of the speedup: %.1fx\n",
           1e9 * tb / CALLS / PAIRS, 1e9 * tu / CALLS / PAIRS, tu / tb);
    free(b);
    return 0;
}
