/* cmd_slice.c - `abrdf slice MODEL`: f_r over the outgoing angle in the plane of incidence. */
#include <math.h>
#include <string.h>

#include "cli.h"

static int usage(void)
{
    printf(
        "usage: abrdf slice MODEL [--theta-i DEG] [--steps N] [--csv] [--set NAME=VALUE ...]\n\n"
        "Evaluates f_r and f_r*cos(theta_o) for theta_o from -90 to 90 degrees in the plane\n"
        "of incidence (normal +z, tangent +x). The light is at theta_i (default 45) on the\n"
        "negative-x side, so the mirror direction is theta_o = +theta_i. --steps is the number\n"
        "of intervals (default 180). --csv writes CSV with '#' header lines describing the run.\n");
    return 0;
}

int cmd_slice(int argc, char **argv)
{
    const char *cmd = "slice";
    const char *name = NULL;
    double theta_i = 45.0;
    long steps = 180;
    int csv = 0;
    const char *sets[64];
    int nsets = 0;
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        if (cli_is_help(a)) return usage();
        if (!strcmp(a, "--csv"))
            csv = 1;
        else if (!strcmp(a, "--theta-i")) {
            if (i + 1 >= argc || !cli_parse_double(argv[++i], &theta_i) || theta_i < 0 ||
                theta_i > 90)
                return cli_fail(cmd, "--theta-i needs degrees in [0, 90]");
        } else if (!strcmp(a, "--steps")) {
            if (i + 1 >= argc || !cli_parse_int(argv[++i], 1, 1000000, &steps))
                return cli_fail(cmd, "--steps needs a whole number in [1, 1000000]");
        } else if (!strcmp(a, "--set")) {
            if (i + 1 >= argc) return cli_fail(cmd, "--set needs NAME=VALUE");
            if (nsets == 64) return cli_fail(cmd, "too many --set options (64 at most)");
            sets[nsets++] = argv[++i];
        } else if (a[0] == '-' && a[1]) {
            return cli_fail(cmd, "unknown option '%s'; options: --theta-i --steps --csv --set", a);
        } else if (!name) {
            name = a;
        } else {
            return cli_fail(cmd, "unexpected argument '%s' (one model only)", a);
        }
    }
    abrdf_model model;
    if (cli_model(cmd, name, &model)) return CLI_EXIT_USAGE;
    abrdf_params p;
    abrdf_params_init(model, &p);
    for (int i = 0; i < nsets; ++i)
        if (cli_set_param(cmd, model, &p, sets[i])) return CLI_EXIT_USAGE;
    const abrdf_model_info *m = abrdf_model_get(model);
    const double deg = 3.14159265358979323846 / 180.0;
    double wi[3] = {-sin(theta_i * deg), 0.0, cos(theta_i * deg)};
    if (csv) {
        /* '#' lines describe the run completely: model, geometry, every parameter, columns. */
        printf("# abrdf %s slice\n# model: %s (%s, %s)\n", abrdf_version(), m->name, m->title,
               m->equation);
        printf(
            "# geometry: plane of incidence x-z, normal +z; wi = (-sin theta_i, 0, cos theta_i), "
            "theta_i = %.17g deg; wo = (sin theta_o, 0, cos theta_o)\n",
            theta_i);
        printf(
            "# rows: %ld, theta_o from -90 to 90 deg in %ld equal steps; theta_o = +theta_i is the "
            "mirror direction\n",
            steps + 1, steps);
        printf("# params:");
        for (int k = 0; k < m->param_count; ++k) {
            double v[3];
            int c = abrdf_param_read(&p, m->params[k].id, v);
            printf(" %s=%.17g", abrdf_param_get(m->params[k].id)->name, v[0]);
            for (int j = 1; j < c; ++j) printf(",%.17g", v[j]);
        }
        printf(
            "\n# columns: theta_o_deg; f_r,f_g,f_b = BRDF f_r per RGB channel in 1/sr (no cosine); "
            "fcos_r,fcos_g,fcos_b = f * max(0, cos theta_o)\n");
        printf("theta_o_deg,f_r,f_g,f_b,fcos_r,fcos_g,fcos_b\n");
    } else {
        printf("%s, theta_i = %g deg\n%10s %14s %14s %14s %14s\n", m->name, theta_i, "theta_o",
               "f_r", "f_g", "f_b", "f_r*cos");
    }
    for (long s = 0; s <= steps; ++s) {
        double th = -90.0 + 180.0 * (double)s / (double)steps;
        double wo[3] = {sin(th * deg), 0.0, cos(th * deg)};
        double f[3];
        abrdf_eval(model, &p, NULL, wi, wo, f);
        double c = fmax(0.0, wo[2]);
        if (csv)
            printf("%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", th, f[0], f[1], f[2], f[0] * c,
                   f[1] * c, f[2] * c);
        else
            printf("%10.3f %14.6g %14.6g %14.6g %14.6g\n", th, f[0], f[1], f[2], f[0] * c);
    }
    return 0;
}
