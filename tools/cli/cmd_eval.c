/* cmd_eval.c - `abrdf eval MODEL --wi X,Y,Z --wo X,Y,Z [...]`: one f_r evaluation. */
#include <math.h>
#include <string.h>

#include "cli.h"

static int usage(void)
{
    printf("usage: abrdf eval MODEL --wi X,Y,Z --wo X,Y,Z [--normal X,Y,Z] [--tangent X,Y,Z]\n"
           "                  [--set NAME=VALUE ...] [--json]\n\n"
           "Prints f_r (RGB, 1/sr, without the cosine) for light direction wi and view\n"
           "direction wo, both pointing away from the surface. Vectors need not be unit\n"
           "length, but not zero. The normal defaults to 0,0,1; the tangent to an axis\n"
           "orthogonal to it.\n"
           "--set changes a parameter (R,G,B or one value for colours); see abrdf models.\n");
    return 0;
}

int cmd_eval(int argc, char **argv)
{
    const char *cmd = "eval";
    const char *name = NULL;
    double wi[3], wo[3], n[3] = {0, 0, 1}, t[3];
    int have_wi = 0, have_wo = 0, have_t = 0, json = 0;
    const char *sets[64];
    int nsets = 0;
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        if (cli_is_help(a)) return usage();
        int has_val = i + 1 < argc;
        if (!strcmp(a, "--json"))
            json = 1;
        else if (!strcmp(a, "--wi") || !strcmp(a, "--wo") || !strcmp(a, "--normal") ||
                 !strcmp(a, "--tangent")) {
            if (!has_val) return cli_fail(cmd, "%s needs a vector X,Y,Z", a);
            double *dst = a[2] == 'w' ? (a[3] == 'i' ? wi : wo) : (a[2] == 'n' ? n : t);
            if (!cli_parse_dir3(argv[++i], dst))
                return cli_fail(cmd, "%s: '%s' is not a vector X,Y,Z of finite numbers", a,
                                argv[i]);
            if (dst == wi) have_wi = 1;
            if (dst == wo) have_wo = 1;
            if (dst == t) have_t = 1;
        } else if (!strcmp(a, "--set")) {
            if (!has_val) return cli_fail(cmd, "--set needs NAME=VALUE");
            if (nsets == 64) return cli_fail(cmd, "too many --set options (64 at most)");
            sets[nsets++] = argv[++i];
        } else if (a[0] == '-' && a[1]) {
            return cli_fail(
                cmd, "unknown option '%s'; options: --wi --wo --normal --tangent --set --json", a);
        } else if (!name) {
            name = a;
        } else {
            return cli_fail(cmd, "unexpected argument '%s' (one model only)", a);
        }
    }
    abrdf_model model;
    if (cli_model(cmd, name, &model)) return CLI_EXIT_USAGE;
    if (!have_wi || !have_wo)
        return cli_fail(cmd, "missing %s X,Y,Z (direction toward the %s); required: --wi and --wo",
                        have_wi ? "--wo" : "--wi", have_wi ? "viewer" : "light");
    if (!(fabs(wi[0]) + fabs(wi[1]) + fabs(wi[2]) > 0.0))
        return cli_fail(cmd, "--wi 0,0,0 has zero length; give a direction toward the light");
    if (!(fabs(wo[0]) + fabs(wo[1]) + fabs(wo[2]) > 0.0))
        return cli_fail(cmd, "--wo 0,0,0 has zero length; give a direction toward the viewer");
    if (have_t && !(fabs(t[0]) + fabs(t[1]) + fabs(t[2]) > 0.0))
        return cli_fail(cmd, "--tangent 0,0,0 has zero length; give a direction in the surface "
                             "(or leave --tangent out)");
    abrdf_params p;
    abrdf_params_init(model, &p);
    for (int i = 0; i < nsets; ++i)
        if (cli_set_param(cmd, model, &p, sets[i])) return CLI_EXIT_USAGE;
    abrdf_frame frame;
    if (abrdf_frame_make(n, have_t ? t : NULL, &frame) != ABRDF_OK)
        return cli_fail(cmd, "--normal %g,%g,%g is degenerate (zero length)", n[0], n[1], n[2]);
    double f[3];
    int st = abrdf_eval(model, &p, &frame, wi, wo, f);
    if (st != ABRDF_OK) return cli_fail(cmd, "%s", abrdf_strerror(st));
    if (json) {
        printf("{\"model\": ");
        cli_json_string(stdout, abrdf_model_get(model)->name);
        printf(", \"f_r\": [%.17g, %.17g, %.17g]}\n", f[0], f[1], f[2]);
    } else {
        printf("%s f_r = %.10g %.10g %.10g\n", abrdf_model_get(model)->name, f[0], f[1], f[2]);
    }
    return 0;
}
