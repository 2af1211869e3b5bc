/* cmd_inspect.c - `abrdf inspect FILE [--json]`: what a measured-BRDF file holds (its grid, the
 * cells not measured, the largest f_r, the albedo at normal incidence). */
#include <math.h>
#include <string.h>

#include "cli.h"
#include "measured_file.h"

#define CMD "inspect"
#define INSPECT_ALBEDO_STEPS 360 /* midpoint rule over the light's polar angle */

static int usage(void)
{
    printf(
        "usage: abrdf inspect FILE [--json]\n\n"
        "Prints what a measured-BRDF file holds (FILE.binary: MERL BRDF database): its grid,\n"
        "how many cells are not measured, the largest f_r per channel (1/sr), and the albedo\n"
        "at normal incidence, 2 pi * integral of f_r(wi, +z) cos sin over the light's polar\n"
        "angle, each value the cell a MERL lookup returns (unknown when one is not measured).\n");
    return 0;
}

/* The cell holding (theta_h, theta_d, phi_d), as MERL's reference lookup finds it: the grid
 * node at or below each angle (theta_h by its square-root index). */
static size_t lookup(const measured_table *t, double th, double td, double pd)
{
    const double half_pi = 1.5707963267948966;
    int ih = th > 0 ? (int)(sqrt(th / half_pi) * t->n_theta_h) : 0;
    int id = td > 0 ? (int)(td / half_pi * t->n_theta_d) : 0;
    int ip = pd > 0 ? (int)(pd / (2 * half_pi) * t->n_phi_d) : 0;
    ih = ih < t->n_theta_h ? ih : t->n_theta_h - 1;
    id = id < t->n_theta_d ? id : t->n_theta_d - 1;
    ip = ip < t->n_phi_d ? ip : t->n_phi_d - 1;
    return measured_table_cell(t, ih, id, ip);
}

/* The albedo for light from the normal, by reciprocity that of the view along the normal:
 * with wo = +z and wi at polar angle theta, the half vector is at theta/2, the difference
 * angle theta_d = theta/2 and phi_d = 0 (measured_table_directions with ip = 0). 0, or -1
 * when a cell on the way is not measured. */
static int albedo_normal(const measured_table *t, double rho[3])
{
    const double half_pi = 1.5707963267948966, step = half_pi / INSPECT_ALBEDO_STEPS;
    rho[0] = rho[1] = rho[2] = 0;
    for (int k = 0; k < INSPECT_ALBEDO_STEPS; ++k) {
        double theta = (k + 0.5) * step;
        const float *f = t->data + lookup(t, theta / 2, theta / 2, 0);
        for (int c = 0; c < 3; ++c) {
            if (f[c] < 0) return -1;
            rho[c] += 4 * half_pi * f[c] * cos(theta) * sin(theta) * step;
        }
    }
    return 0;
}

int cmd_inspect(int argc, char **argv)
{
    const char *path = NULL;
    int json = 0;
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        if (cli_is_help(a)) return usage();
        if (!strcmp(a, "--json"))
            json = 1;
        else if (a[0] == '-' && a[1])
            return cli_fail(CMD, "unknown option '%s'; options: --json", a);
        else if (!path)
            path = a;
        else
            return cli_fail(CMD, "unexpected argument '%s' (one file only)", a);
    }
    if (!path) return cli_fail(CMD, "missing FILE (a measured BRDF: FILE.binary)");
    char err[1024];
    const measured_format *format = measured_file_format(path, 0, err, sizeof err);
    if (!format) return cli_fail(CMD, "%s", err);
    measured_table t;
    if (format->read(path, &t, err, sizeof err)) {
        fprintf(stderr, "abrdf %s: %s\n", CMD, err);
        return 1;
    }
    size_t cells = (size_t)t.n_theta_h * (size_t)t.n_theta_d * (size_t)t.n_phi_d;
    double max[3] = {-1, -1, -1}, rho[3];
    for (size_t i = 0; i < 3 * cells; ++i) max[i % 3] = fmax(max[i % 3], t.data[i]);
    int have_rho = albedo_normal(&t, rho) == 0;
    if (json) {
        printf("{\"file\": ");
        cli_json_string(stdout, path);
        printf(", \"format\": ");
        cli_json_string(stdout, format->name);
        printf(", \"grid\": [%d, %d, %d], \"cells\": %zu, \"unmeasured\": %zu, \"max_f_r\": ",
               t.n_theta_h, t.n_theta_d, t.n_phi_d, cells, t.unmeasured);
        for (int c = 0; c < 3; ++c) {
            printf(c ? ", " : "[");
            cli_json_number(stdout, max[c] >= 0 ? max[c] : NAN);
        }
        printf("], \"albedo_normal\": ");
        for (int c = 0; have_rho && c < 3; ++c) {
            printf(c ? ", " : "[");
            cli_json_number(stdout, rho[c]);
        }
        printf(have_rho ? "]}\n" : "null}\n");
    } else {
        printf("format: %s\n", format->name);
        printf("grid: %d x %d x %d (theta_h x theta_d x phi_d), %zu cells\n", t.n_theta_h,
               t.n_theta_d, t.n_phi_d, cells);
        printf("not measured: %zu cells (%.3g%%)\n", t.unmeasured, 100.0 * t.unmeasured / cells);
        printf("max f_r (1/sr):");
        for (int c = 0; c < 3; ++c)
            if (max[c] >= 0)
                printf(" %.6g", max[c]);
            else
                printf(" none");
        if (have_rho)
            printf("\nalbedo at normal incidence: %.6g %.6g %.6g\n", rho[0], rho[1], rho[2]);
        else
            printf("\nalbedo at normal incidence: unknown (a cell on the way is not measured)\n");
    }
    measured_table_free(&t);
    return 0;
}
