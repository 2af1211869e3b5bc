/* cmd_sample.c - `abrdf sample MODEL --wo X,Y,Z [-n N] [...]`: directions drawn by the
 * model's importance sampler (abrdf_sample), with their pdf and weight. */
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "cli.h"

#define SAMPLE_MAX 10000000L

static int usage(void)
{
    printf("usage: abrdf sample MODEL --wo X,Y,Z [-n N] [--normal X,Y,Z] [--tangent X,Y,Z]\n"
           "                    [--set NAME=VALUE ...] [--seed S] [--json]\n\n"
           "Draws N (default 1, at most %ld) light directions wi for the view direction wo with\n"
           "the model's importance sampler (abrdf models --json names it; see docs/RENDERER.md,\n"
           "\"Importance sampling\") and prints each with its pdf (per steradian) and its weight\n"
           "f_r * max(0, N.wi) / pdf (RGB). A sample below the surface has weight 0 and is\n"
           "printed like the others. wo must point above the surface; vectors need not be\n"
           "unit length. The normal defaults to 0,0,1, the tangent to an axis orthogonal to\n"
           "it. The uniform numbers come from a generator seeded with S (default 1): the same\n"
           "seed prints the same samples. --json prints one JSON object per line:\n"
           "{\"wi\": [x, y, z], \"pdf\": p, \"weight\": [r, g, b]}.\n",
           SAMPLE_MAX);
    return 0;
}

/* SplitMix64 (G. Steele, D. Lea, C. Flood, "Fast splittable pseudorandom number
 * generators", OOPSLA 2014): a double in [0, 1) from the top 53 bits. */
static double next_uniform(uint64_t *s)
{
    uint64_t z = (*s += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    return (double)(z >> 11) * (1.0 / 9007199254740992.0);
}

int cmd_sample(int argc, char **argv)
{
    const char *cmd = "sample";
    const char *name = NULL;
    double wo[3], n[3] = {0, 0, 1}, t[3];
    int have_wo = 0, have_t = 0, json = 0;
    long count = 1, seed = 1;
    const char *sets[64];
    int nsets = 0;
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        if (cli_is_help(a)) return usage();
        int has_val = i + 1 < argc;
        if (!strcmp(a, "--json")) {
            json = 1;
        } else if (!strcmp(a, "--wo") || !strcmp(a, "--normal") || !strcmp(a, "--tangent")) {
            if (!has_val) return cli_fail(cmd, "%s needs a vector X,Y,Z", a);
            double *dst = a[2] == 'w' ? wo : (a[2] == 'n' ? n : t);
            if (!cli_parse_dir3(argv[++i], dst))
                return cli_fail(cmd, "%s: '%s' is not a vector X,Y,Z of finite numbers", a,
                                argv[i]);
            have_wo |= dst == wo;
            have_t |= dst == t;
        } else if (!strcmp(a, "-n")) {
            if (!has_val || !cli_parse_int(argv[++i], 1, SAMPLE_MAX, &count))
                return cli_fail(cmd, "-n needs a whole number of samples in [1, %ld]%s%s%s",
                                SAMPLE_MAX, has_val ? ", not '" : "", has_val ? argv[i] : "",
                                has_val ? "'" : "");
        } else if (!strcmp(a, "--seed")) {
            if (!has_val || !cli_parse_int(argv[++i], 0, LONG_MAX, &seed))
                return cli_fail(cmd, "--seed needs a whole number >= 0%s%s%s",
                                has_val ? ", not '" : "", has_val ? argv[i] : "",
                                has_val ? "'" : "");
        } else if (!strcmp(a, "--set")) {
            if (!has_val) return cli_fail(cmd, "--set needs NAME=VALUE");
            if (nsets == 64) return cli_fail(cmd, "too many --set options (64 at most)");
            sets[nsets++] = argv[++i];
        } else if (a[0] == '-' && a[1]) {
            return cli_fail(cmd,
                            "unknown option '%s'; options: --wo -n --normal --tangent --set "
                            "--seed --json",
                            a);
        } else if (!name) {
            name = a;
        } else {
            return cli_fail(cmd, "unexpected argument '%s' (one model only)", a);
        }
    }
    abrdf_model model;
    if (cli_model(cmd, name, &model)) return CLI_EXIT_USAGE;
    if (!have_wo) return cli_fail(cmd, "missing --wo X,Y,Z (the direction toward the viewer)");
    double wl = sqrt(wo[0] * wo[0] + wo[1] * wo[1] + wo[2] * wo[2]);
    if (!(wl > 0.0) || !isfinite(wl))
        return cli_fail(cmd, "--wo %g,%g,%g has no direction; give one toward the viewer", wo[0],
                        wo[1], wo[2]);
    abrdf_params p;
    abrdf_params_init(model, &p);
    for (int i = 0; i < nsets; ++i)
        if (cli_set_param(cmd, model, &p, sets[i])) return CLI_EXIT_USAGE;
    abrdf_frame frame;
    if (abrdf_frame_make(n, have_t ? t : NULL, &frame) != ABRDF_OK)
        return cli_fail(cmd, "--normal %g,%g,%g is degenerate (zero length)", n[0], n[1], n[2]);
    double cos_o = (wo[0] * frame.n[0] + wo[1] * frame.n[1] + wo[2] * frame.n[2]) / wl;
    if (!(cos_o > 0.0))
        return cli_fail(cmd,
                        "--wo %g,%g,%g points below the surface (N.wo = %.3g): a view direction "
                        "above it is needed to sample",
                        wo[0], wo[1], wo[2], cos_o);
    abrdf_sample_result r;
    abrdf_sample_result_init(&r);
    uint64_t state = (uint64_t)seed;
    const char *mname = abrdf_model_get(model)->name;
    if (!json) printf("# abrdf sample %s: wi_x wi_y wi_z pdf weight_r weight_g weight_b\n", mname);
    for (long i = 0; i < count; ++i) {
        double u1 = next_uniform(&state), u2 = next_uniform(&state);
        int st = abrdf_sample(model, &p, &frame, wo, u1, u2, &r);
        if (st != ABRDF_OK) return cli_fail(cmd, "%s", abrdf_strerror(st));
        if (json)
            printf("{\"wi\": [%.17g, %.17g, %.17g], \"pdf\": %.17g, \"weight\": [%.17g, %.17g, "
                   "%.17g]}\n",
                   r.wi[0], r.wi[1], r.wi[2], r.pdf, r.weight[0], r.weight[1], r.weight[2]);
        else
            printf("%.10g %.10g %.10g %.10g %.10g %.10g %.10g\n", r.wi[0], r.wi[1], r.wi[2], r.pdf,
                   r.weight[0], r.weight[1], r.weight[2]);
    }
    return 0;
}
