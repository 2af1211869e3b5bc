/* cmd_tabulate.c - `abrdf tabulate MODEL -o FILE [...]`: a model's f_r on the measured grid
 * (measured_table.h), with optional noise and holes, written as a measured-BRDF file
 * (measured_file.h; docs/MEASURED.md, "Files"). */
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>

#include "cli.h"
#include "measured_file.h"
#include "out_file.h"
#include "rgl_bsdf.h"

#define CMD "tabulate"
#define TABULATE_NOISE_MAX 2.0 /* sigma: exp(2 z) already spans 50x at 2 standard deviations */

static int usage(void)
{
    printf("usage: abrdf tabulate MODEL -o FILE [--set NAME=VALUE ...] [--grid NH,ND,NP]\n"
           "                      [--noise SIGMA] [--holes FRACTION] [--seed N]\n\n"
           "Writes MODEL's f_r (double reference, local frame N = +z, phi_h = 0) at every cell of\n"
           "the half/difference grid as a measured-BRDF file, its format by FILE's extension:\n"
           ".binary = MERL BRDF database; .bsdf = RGL BSDF (Dupuy-Jakob), sampled on its own\n"
           "adaptive grid (no --grid, --noise, --holes). Cells with the light or the view at or "
           "below the\n"
           "horizon are not measured (-1), as in a measurement.\n"
           "  --grid NH,ND,NP   cells over theta_h, theta_d, phi_d, each %d to %d (default\n"
           "                    90,90,180, MERL's grid); %zu cells at most\n"
           "  --noise SIGMA     f_r * exp(SIGMA z - SIGMA^2/2), z standard normal per cell and\n"
           "                    channel (the mean is kept); SIGMA in [0, %g], default 0\n"
           "  --holes FRACTION  that fraction of cells, drawn at random, marked not measured;\n"
           "                    [0, 1], default 0\n"
           "  --seed N          the noise and the holes, deterministic per N in [0, 2147483647],\n"
           "                    default 1\n"
           "--set changes a parameter (R,G,B or one value for colours); see abrdf models.\n",
           MEASURED_DIM_MIN, MEASURED_DIM_MAX, (size_t)MEASURED_MAX_CELLS, TABULATE_NOISE_MAX);
    return 0;
}

/* A uniform number in (0, 1) for (seed, cell, stream): SplitMix64's finaliser of a counter,
 * so that a cell's draw does not depend on the order the cells are visited in. Streams 0-5:
 * the noise's two uniforms per channel; stream 6: the hole. */
static double cell_uniform(uint64_t seed, uint64_t cell, unsigned stream)
{
    uint64_t z = seed * 0x9e3779b97f4a7c15ull + cell * 8 + stream + 1;
    for (int k = 0; k < 2; ++k) {
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        z ^= z >> 31;
    }
    return ((double)(z >> 11) + 0.5) * (1.0 / 9007199254740992.0); /* 2^-53 */
}

/* A standard normal number by Box-Muller from two of the cell's uniforms. */
static double cell_normal(uint64_t seed, uint64_t cell, unsigned stream)
{
    double u1 = cell_uniform(seed, cell, stream), u2 = cell_uniform(seed, cell, stream + 1);
    return sqrt(-2.0 * log(u1)) * cos(6.283185307179586 * u2);
}

static int parse_grid(const char *s, int grid[3])
{
    char buf[64];
    const char *parts[3] = {buf, NULL, NULL};
    int n = 1;
    if (strlen(s) < sizeof buf) {
        strcpy(buf, s);
        for (char *p = buf; *p; ++p)
            if (*p == ',') {
                *p = '\0';
                if (n < 3) parts[n] = p + 1;
                ++n;
            }
    }
    long v[3];
    for (int k = 0; k < 3 && n == 3; ++k)
        if (!cli_parse_int(parts[k], LONG_MIN, LONG_MAX, &v[k])) n = 0;
    if (n != 3) return cli_fail(CMD, "--grid: '%s' is not three whole numbers NH,ND,NP", s);
    for (int k = 0; k < 3; ++k)
        if (v[k] < MEASURED_DIM_MIN || v[k] > MEASURED_DIM_MAX)
            return cli_fail(CMD, "--grid %s: each of NH,ND,NP must be in [%d, %d]", s,
                            MEASURED_DIM_MIN, MEASURED_DIM_MAX);
    size_t cells = (size_t)v[0] * (size_t)v[1] * (size_t)v[2];
    if (cells > MEASURED_MAX_CELLS)
        return cli_fail(CMD, "--grid %s: %zu cells, more than the %zu a table may hold", s, cells,
                        (size_t)MEASURED_MAX_CELLS);
    for (int k = 0; k < 3; ++k) grid[k] = (int)v[k];
    return 0;
}

static int parse_fraction(const char *opt, const char *s, double hi, double *out)
{
    if (!cli_parse_double(s, out) || *out < 0 || *out > hi)
        return cli_fail(CMD, "%s: '%s' is not a number in [0, %g]", opt, s, hi);
    return 0;
}

/* The table of model's f_r, noise and holes applied. */
static int tabulate(abrdf_model model, const abrdf_params *p, double sigma, double holes,
                    uint64_t seed, measured_table *t)
{
    size_t cell = 0;
    for (int ih = 0; ih < t->n_theta_h; ++ih)
        for (int id = 0; id < t->n_theta_d; ++id)
            for (int ip = 0; ip < t->n_phi_d; ++ip, ++cell) {
                double wi[3], wo[3], f[3] = {0, 0, 0};
                measured_table_directions(t, ih, id, ip, wi, wo);
                float *dst = t->data + measured_table_cell(t, ih, id, ip);
                /* no instrument measures with a direction below the surface: such a cell is
                 * "not measured", so the lookup near the horizon interpolates the cells
                 * above it instead of pulling toward 0 (docs/MEASURED.md) */
                if (!(wi[2] > 0 && wo[2] > 0)) {
                    dst[0] = dst[1] = dst[2] = -1.0f;
                    continue;
                }
                int st = abrdf_eval(model, p, NULL, wi, wo, f);
                if (st != ABRDF_OK) return cli_fail(CMD, "%s", abrdf_strerror(st));
                if (holes > 0 && cell_uniform(seed, cell, 6) < holes) {
                    dst[0] = dst[1] = dst[2] = -1.0f;
                    continue;
                }
                for (int c = 0; c < 3; ++c) {
                    double v = f[c];
                    if (sigma > 0 && v > 0)
                        v *= exp(sigma * cell_normal(seed, cell, 2 * c) - 0.5 * sigma * sigma);
                    dst[c] = (float)v;
                }
            }
    t->unmeasured = 0;
    for (size_t i = 0; i < cell; ++i) t->unmeasured += t->data[3 * i] < 0;
    return 0;
}

/* ---- RGL .bsdf: the model itself sampled by rgl_write ---- */

typedef struct model_fn {
    abrdf_model model;
    const abrdf_params *p;
} model_fn;

static void eval_model(void *user, const double wi[3], const double wo[3], double rgb[3])
{
    const model_fn *m = user;
    if (abrdf_eval(m->model, m->p, NULL, wi, wo, rgb) != ABRDF_OK) rgb[0] = rgb[1] = rgb[2] = 0;
}

static int is_bsdf(const char *path)
{
    size_t n = strlen(path);
    return n > 5 && strcasecmp(path + n - 5, ".bsdf") == 0;
}

static int tabulate_bsdf(abrdf_model model, const abrdf_params *p, const char *path, double sigma,
                         double holes, int grid_given)
{
    if (sigma > 0 || holes > 0 || grid_given)
        return cli_fail(CMD, "--noise, --holes and --grid apply to .binary files; a .bsdf file "
                             "has its own adaptive grid (docs/MEASURED.md, \"RGL .bsdf files\")");
    model_fn m = {model, p};
    rgl_write_grid g = RGL_WRITE_GRID_DEFAULT;
    char desc[128], err[1024];
    snprintf(desc, sizeof desc, "abrdf tabulate %s", abrdf_model_get(model)->name);
    if (rgl_write(path, eval_model, &m, &g, desc, err, sizeof err)) {
        fprintf(stderr, "abrdf %s: %s\n", CMD, err);
        return 1;
    }
    fprintf(stderr, "abrdf %s: wrote %s (RGL BSDF, %d elevations, %d x %d warp)\n", CMD, path,
            g.n_theta_i, g.n_warp, g.n_warp);
    return 0;
}

int cmd_tabulate(int argc, char **argv)
{
    const char *name = NULL, *out_path = NULL;
    const char *sets[64];
    int nsets = 0, grid[3] = {90, 90, 180}, grid_given = 0;
    double sigma = 0, holes = 0;
    long seed = 1;
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        if (cli_is_help(a)) return usage();
        int has_val = i + 1 < argc;
        if (!strcmp(a, "-o")) {
            if (!has_val) return cli_fail(CMD, "-o needs a file name");
            out_path = argv[++i];
        } else if (!strcmp(a, "--set")) {
            if (!has_val) return cli_fail(CMD, "--set needs NAME=VALUE");
            if (nsets == 64) return cli_fail(CMD, "too many --set options (64 at most)");
            sets[nsets++] = argv[++i];
        } else if (!strcmp(a, "--grid")) {
            if (!has_val) return cli_fail(CMD, "--grid needs NH,ND,NP");
            if (parse_grid(argv[++i], grid)) return CLI_EXIT_USAGE;
            grid_given = 1;
        } else if (!strcmp(a, "--noise")) {
            if (!has_val)
                return cli_fail(CMD, "--noise needs SIGMA in [0, %g]", TABULATE_NOISE_MAX);
            if (parse_fraction(a, argv[++i], TABULATE_NOISE_MAX, &sigma)) return CLI_EXIT_USAGE;
        } else if (!strcmp(a, "--holes")) {
            if (!has_val) return cli_fail(CMD, "--holes needs FRACTION in [0, 1]");
            if (parse_fraction(a, argv[++i], 1.0, &holes)) return CLI_EXIT_USAGE;
        } else if (!strcmp(a, "--seed")) {
            if (!has_val || !cli_parse_int(argv[i + 1], 0, 2147483647L, &seed))
                return cli_fail(CMD, "--seed needs a whole number in [0, 2147483647]");
            ++i;
        } else if (a[0] == '-' && a[1]) {
            return cli_fail(CMD,
                            "unknown option '%s'; options: -o --set --grid --noise --holes "
                            "--seed",
                            a);
        } else if (!name) {
            name = a;
        } else {
            return cli_fail(CMD, "unexpected argument '%s' (one model only; parameters by --set)",
                            a);
        }
    }
    abrdf_model model;
    if (cli_model(CMD, name, &model)) return CLI_EXIT_USAGE;
    abrdf_params p;
    abrdf_params_init(model, &p);
    for (int i = 0; i < nsets; ++i)
        if (cli_set_param(CMD, model, &p, sets[i])) return CLI_EXIT_USAGE;
    char err[1024];
    if (abrdf_params_check(model, &p, err, sizeof err) != ABRDF_OK) return cli_fail(CMD, "%s", err);
    if (!out_path)
        return cli_fail(CMD, "missing -o FILE (FILE.binary: a MERL BRDF file; FILE.bsdf: RGL)");
    if (is_bsdf(out_path)) return tabulate_bsdf(model, &p, out_path, sigma, holes, grid_given);
    const measured_format *format = measured_file_format(out_path, 1, err, sizeof err);
    if (!format) return cli_fail(CMD, "%s", err);

    out_file o = OUT_FILE_INIT;
    if (out_file_open(&o, out_path, err, sizeof err)) {
        fprintf(stderr, "abrdf %s: %s\n", CMD, err);
        return 1;
    }
    measured_table t;
    if (measured_table_alloc(&t, grid[0], grid[1], grid[2], err, sizeof err)) {
        fprintf(stderr, "abrdf %s: %s\n", CMD, err);
        out_file_discard(&o);
        return 1;
    }
    int rc = tabulate(model, &p, sigma, holes, (uint64_t)seed, &t);
    if (rc == 0) {
        out_file *const files[1] = {&o};
        if (format->write_to(&o, &t, err, sizeof err) ||
            out_file_commit(files, 1, err, sizeof err)) {
            fprintf(stderr, "abrdf %s: %s\n", CMD, err);
            rc = 1;
        } else {
            fprintf(stderr, "abrdf %s: wrote %s (%s, %d x %d x %d cells, %zu not measured)\n", CMD,
                    out_path, format->name, grid[0], grid[1], grid[2], t.unmeasured);
        }
    }
    out_file_discard(&o);
    measured_table_free(&t);
    return rc;
}
