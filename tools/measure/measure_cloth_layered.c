/* measure_cloth_layered.c - the numbers of docs/MODELS.md, "Cloth and layered models", for
 * one model: directional albedo at 0, 45 and 80 degrees (quadrature orders N and 2N), the
 * largest reciprocity error over random direction pairs, and the cost of one abrdf_eval in ns.
 *
 *   measure_cloth_layered MODEL [--order N] [--evals N] [--set NAME=VALUE ...]
 *
 * Albedo rho(wi) = int f_r(wi, wo) cos_o dwo is integrated over the half vector h of the
 * pair, wo = 2 (wi.h) h - wi (dwo = 4 (wi.h) dwh): theta_h by Gauss-Legendre in v with
 * tan^2(theta_h) = a^2 u / (1 - u), u = 1 - (1 - v)^2, a = max(0.02, the narrowest
 * roughness r^2 of the model), which puts nodes where glossy lobes are; phi uniformly
 * (periodic: the trapezoid rule). Timing: wall clock over --evals evaluations of random
 * front-facing pairs, after a warm-up; a measurement, not a test. */
#define _POSIX_C_SOURCE 199309L /* clock_gettime */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "abrdf.h"
#include "cli_args.h"
#include "quad.h"

int main(int argc, char **argv)
{
    const char *cmd = "measure_cloth_layered";
    if (argc < 2)
        return cli_fail(cmd, "usage: MODEL [--order N] [--evals N] [--set NAME=VALUE ...]");
    abrdf_model m;
    if (cli_model(cmd, argv[1], &m)) return CLI_EXIT_USAGE;
    abrdf_params p;
    abrdf_params_init(m, &p);
    int order = 128;
    long evals = 200000;
    for (int i = 2; i < argc; ++i) {
        if (!strcmp(argv[i], "--order") && i + 1 < argc)
            order = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--evals") && i + 1 < argc)
            evals = atol(argv[++i]);
        else if (!strcmp(argv[i], "--set") && i + 1 < argc) {
            if (cli_set_param(cmd, m, &p, argv[++i])) return CLI_EXIT_USAGE;
        } else
            return cli_fail(cmd, "unknown argument '%s'", argv[i]);
    }
    if (order < 4 || order > 512) return cli_fail(cmd, "--order must be in [4, 512]");
    double a = 1.0;
    if (m == ABRDF_WEIDLICH_WILKIE || m == ABRDF_BELCOUR) {
        for (int k = 0; k < p.layer_count; ++k) a = fmin(a, p.layers[k].r * p.layers[k].r);
    } else if (m != ABRDF_KAJIYA_KAY) {
        a = p.r * p.r;
    } else {
        a = sqrt(2.0 / (p.n + 2.0)); /* lobe width of cos^n */
    }
    if (a < 0.02) a = 0.02;
    printf("model %s, quadrature width a = %g, order N in theta_h x 2N azimuths\n",
           abrdf_model_get(m)->name, a);
    const double th[3] = {0.0, 45.0, 80.0};
    for (int k = 0; k < 3; ++k)
        printf("albedo(%2.0f deg) = %.5f (order %d), %.5f (order %d)\n", th[k],
               quad_albedo(m, &p, th[k], a, 2 * order, 0), 2 * order,
               quad_albedo(m, &p, th[k], a, order, 0), order);
    unsigned s = 12345u;
    double worst = 0.0;
    for (int i = 0; i < 100000; ++i) {
        double wi[3], wo[3], f1[3], f2[3];
        quad_rand_dir(&s, 0.02, wi);
        quad_rand_dir(&s, 0.02, wo);
        abrdf_eval(m, &p, NULL, wi, wo, f1);
        abrdf_eval(m, &p, NULL, wo, wi, f2);
        double d = fabs(f1[0] - f2[0]) / fmax(1e-300, fmax(f1[0], f2[0]));
        if (fmax(f1[0], f2[0]) > 1e-12 && d > worst) worst = d;
    }
    printf("reciprocity: max |f(wi,wo) - f(wo,wi)| / max(f) over 1e5 random pairs = %.3g\n", worst);
    enum { NDIR = 4096 };
    static double di[NDIR][3], dout[NDIR][3];
    for (int i = 0; i < NDIR; ++i) {
        quad_rand_dir(&s, 0.02, di[i]);
        quad_rand_dir(&s, 0.02, dout[i]);
    }
    double acc = 0.0, f[3];
    for (int i = 0; i < NDIR; ++i) {
        abrdf_eval(m, &p, NULL, di[i], dout[i], f);
        acc += f[0];
    }
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    for (long i = 0; i < evals; ++i) {
        abrdf_eval(m, &p, NULL, di[i % NDIR], dout[i % NDIR], f);
        acc += f[0];
    }
    clock_gettime(CLOCK_MONOTONIC, &t1);
    double ns = ((t1.tv_sec - t0.tv_sec) * 1e9 + (t1.tv_nsec - t0.tv_nsec)) / (double)evals;
    printf("cost: %.1f ns per abrdf_eval (%ld evaluations, checksum %.6g)\n", ns, evals, acc);
    return 0;
}
