/* measure_hair.c - the surface albedos and costs of docs/MODELS.md, "Hair models", for one
 * hair model:
 *
 *   measure_hair MODEL [--grid NT,NP] [--evals N] [--set NAME=VALUE ...]
 *
 * Surface albedo rho(theta_o) = int f_r(wi, wo) cos(theta_i) dwi over the upper hemisphere,
 * wo at theta_o = 0, 45, 80 degrees in the plane of N and the fibre's normal B (local y-z:
 * the fibre, local +x, is seen side-on): midpoint rule, NT nodes in theta_i by NP in phi_i.
 * Cost: CPU time per abrdf_eval at one fixed pair (wi = (0.3, 0, 1), wo = (-0.3, 0.2,
 * 1), normalised), over N evaluations; a measurement, not a test. */
#define _POSIX_C_SOURCE 199309L /* clock_gettime */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "abrdf.h"
#include "cli_args.h"

static const double PI = 3.14159265358979323846;

static double albedo(abrdf_model m, const abrdf_params *p, double theta_o_deg, int nt, int np)
{
    double to = theta_o_deg * PI / 180.0;
    double wo[3] = {0.0, sin(to), cos(to)}, sum = 0.0;
    for (int i = 0; i < nt; ++i) {
        double ti = (i + 0.5) * (0.5 * PI / nt), st = sin(ti), ct = cos(ti);
        for (int j = 0; j < np; ++j) {
            double ph = (j + 0.5) * (2.0 * PI / np);
            double wi[3] = {st * cos(ph), st * sin(ph), ct}, f[3];
            if (abrdf_eval(m, p, NULL, wi, wo, f) != ABRDF_OK) continue;
            double top = fmax(f[0], fmax(f[1], f[2])); /* the largest channel */
            sum += top * ct * st;
        }
    }
    return sum * (0.5 * PI / nt) * (2.0 * PI / np);
}

int main(int argc, char **argv)
{
    const char *cmd = "measure_hair";
    if (argc < 2)
        return cli_fail(cmd, "usage: MODEL [--grid NT,NP] [--evals N] [--set NAME=VALUE ...]");
    abrdf_model m;
    if (cli_model(cmd, argv[1], &m)) return CLI_EXIT_USAGE;
    abrdf_params p;
    abrdf_params_init(m, &p);
    int nt = 60, np = 240;
    long evals = 1000;
    for (int i = 2; i < argc; ++i) {
        if (!strcmp(argv[i], "--grid") && i + 1 < argc) {
            if (sscanf(argv[++i], "%d,%d", &nt, &np) != 2 || nt < 1 || np < 1)
                return cli_fail(cmd, "--grid takes NT,NP (positive)");
        } else if (!strcmp(argv[i], "--evals") && i + 1 < argc)
            evals = atol(argv[++i]);
        else if (!strcmp(argv[i], "--set") && i + 1 < argc) {
            if (cli_set_param(cmd, m, &p, argv[++i])) return CLI_EXIT_USAGE;
        } else
            return cli_fail(cmd, "unknown argument '%s'", argv[i]);
    }
    printf("model %s, surface albedo on a %d x %d midpoint grid, wo in the N-B plane\n",
           abrdf_model_get(m)->name, nt, np);
    const double th[3] = {0.0, 45.0, 80.0};
    for (int k = 0; k < 3; ++k)
        printf("albedo(%2.0f deg) = %.4f\n", th[k], albedo(m, &p, th[k], nt, np));
    double wi[3] = {0.3, 0.0, 1.0}, wo[3] = {-0.3, 0.2, 1.0}, f[3], check = 0.0;
    for (int k = 0; k < 3; ++k) {
        double li = sqrt(0.09 + 1.0), lo = sqrt(0.09 + 0.04 + 1.0);
        wi[k] /= li, wo[k] /= lo;
    }
    struct timespec t0, t1;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t0);
    for (long i = 0; i < evals; ++i) {
        abrdf_eval(m, &p, NULL, wi, wo, f);
        check += f[0];
    }
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t1);
    double s = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
    printf("cost: %.3g us CPU per abrdf_eval (%ld evaluations, checksum %g)\n",
           1e6 * s / (double)evals, evals, check);
    return 0;
}
