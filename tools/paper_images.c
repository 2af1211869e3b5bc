/* paper_images.c - Tables 6 and 7 of Zavalniuk & Romanyuk 2024 (Sec. 4, "the image
 * experiment"): the robot rendered with the Disney GGX specular (the reference) at each
 * alpha_g, each candidate lobe rendered at each exponent n; per alpha_g the minimum over n of
 * NMSE(candidate vs reference) (tools/metrics.h), with its argmin n, beside the published
 * values (data/paper_tables_6_7.csv, compiled in). Set-up and discussion: docs/TABLES_6_7.md. */
#define _POSIX_C_SOURCE 200809L
#include "paper_images.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"
#include "metrics.h"
#include "render.h"

/* Generated from scenes/robot.scene and data/paper_tables_6_7.csv (tools/CMakeLists.txt). */
extern const char abrdf_embedded_robot_scene[];
extern const char abrdf_embedded_paper_tables[];

/* The exponents searched, as listed in the paper (Sec. 4). */
static const double paper_n[] = {1, 5, 10, 20, 40, 60, 80, 100, 200, 300, 400, 500, 600, 700,
                                 800, 900, 950, 1000};
#define N_COUNT (int)(sizeof paper_n / sizeof paper_n[0])
#define ROWS_MAX 32
#define CANDIDATES 4

static const char *const table_models[2][CANDIDATES] = {
    {"f_phe", "f_be", "f_2e", "f_16e"},     /* Table 6: no Fresnel factor */
    {"f_ge", "f_ctphe", "f_ct2e", "f_ct16e"} /* Table 7: with a Fresnel factor */
};

/* The published table: one row per alpha_g, the printed text of each model's value. */
typedef struct published {
    int rows;
    double alpha_g[ROWS_MAX], alpha[ROWS_MAX];
    char text[ROWS_MAX][8][16];
    double value[ROWS_MAX][8];
} published;

void paper_images_defaults(paper_images_options *o)
{
    long cpus = sysconf(_SC_NPROCESSORS_ONLN);
    *o = (paper_images_options){6, 128, 128, 1, cpus > 0 ? (int)(cpus < 64 ? cpus : 64) : 1,
                                0.04, 0.5, NULL, 0, 0};
}

/* Parse the CSV (comment lines start with '#'; a header row; then alpha_g, alpha and the
 * eight models in the order of table_models). */
static int parse_published(const char *text, published *pub, char *err, size_t err_size)
{
    memset(pub, 0, sizeof *pub);
    const char *line = text;
    int header = 0, lineno = 0;
    while (*line) {
        const char *end = strchr(line, '\n');
        size_t len = end ? (size_t)(end - line) : strlen(line);
        char buf[512];
        ++lineno;
        if (len >= sizeof buf) len = sizeof buf - 1;
        memcpy(buf, line, len);
        buf[len] = '\0';
        line = end ? end + 1 : line + len;
        if (!buf[0] || buf[0] == '#') continue;
        if (!header) {
            header = 1;
            continue;
        }
        if (pub->rows == ROWS_MAX) break;
        int r = pub->rows, field = 0;
        for (char *tok = strtok(buf, ","); tok; tok = strtok(NULL, ","), ++field) {
            double v;
            if (field >= 10 || !cli_parse_double(tok, &v)) {
                snprintf(err, err_size, "paper_tables_6_7.csv:%d: bad field '%s'", lineno, tok);
                return -1;
            }
            if (field == 0) pub->alpha_g[r] = v;
            else if (field == 1) pub->alpha[r] = v;
            else {
                snprintf(pub->text[r][field - 2], sizeof pub->text[r][field - 2], "%s", tok);
                pub->value[r][field - 2] = v;
            }
        }
        if (field != 10) {
            snprintf(err, err_size, "paper_tables_6_7.csv:%d: %d fields, want 10", lineno, field);
            return -1;
        }
        ++pub->rows;
    }
    if (pub->rows == 0) {
        snprintf(err, err_size, "paper_tables_6_7.csv: no rows");
        return -1;
    }
    return 0;
}

/* Every material of s becomes: Lambert(kd) (if kd > 0) + `model` with parameters p. The
 * ambient term is removed: one light only, as in the lit-object view. */
static int set_material(scene *s, abrdf_model model, const abrdf_params *p, double kd, char *err,
                        size_t err_size)
{
    char msg[256];
    if (abrdf_params_check(model, p, msg, sizeof msg) != ABRDF_OK) {
        snprintf(err, err_size, "%s: %s", abrdf_model_get(model)->name, msg);
        return -1;
    }
    for (int c = 0; c < 3; ++c) s->ambient[c] = 0;
    for (int i = 0; i < s->material_count; ++i) {
        scene_material *m = &s->materials[i];
        m->kind = SCENE_MAT_MODELS;
        m->params = *p;
        for (int c = 0; c < 3; ++c) m->params.kd[c] = kd, m->ka[c] = 0;
        m->lobe_count = 0;
        if (kd > 0) m->lobes[m->lobe_count++] = ABRDF_LAMBERT;
        m->lobes[m->lobe_count++] = model;
    }
    return 0;
}

static int render_with(scene *s, const paper_images_options *o, abrdf_model model,
                       const abrdf_params *p, float *rgb, char *err, size_t err_size)
{
    if (set_material(s, model, p, o->kd, err, err_size)) return -1;
    render_options ro = {o->width, o->height, o->spp, 0, o->threads, 0};
    render_scene rs;
    if (render_prepare(s, &ro, &rs, err, err_size)) return -1;
    int rc = render_image(&rs, &ro, rgb, NULL);
    render_release(&rs);
    if (rc) snprintf(err, err_size, "cannot start render threads");
    return rc;
}

/* Largest alpha_g from which on (it and every smaller alpha_g of the list, rows sorted by
 * decreasing alpha_g) value < limit; -1 if even the smallest fails. */
static int reach_row(int rows, const double *value, const int *defined, double limit)
{
    int best = -1;
    for (int r = rows - 1; r >= 0; --r) {
        if (!defined[r] || !(value[r] < limit)) break;
        best = r;
    }
    return best;
}

static void print_reach(FILE *out, const char *model, const published *pub, const double *ours,
                        const int *defined, const double *paper)
{
    static const struct { const char *name; double limit; } cls[] = {
        {"noticeable or better (NMSE < 1e-3)", ABRDF_NMSE_SIGNIFICANT},
        {"slight or better (NMSE < 2.5e-4)", ABRDF_NMSE_NOTICEABLE},
        {"no visible difference (NMSE < 1e-4)", ABRDF_NMSE_SLIGHT},
    };
    int all[ROWS_MAX];
    for (int r = 0; r < pub->rows; ++r) all[r] = 1;
    fprintf(out, "\n%s reaches each Table-8 class at alpha_g <= (alpha <=), for that and every smaller alpha_g:\n", model);
    fprintf(out, "  %-38s %-22s %s\n", "class", "computed", "paper");
    for (int k = 0; k < 3; ++k) {
        int a = reach_row(pub->rows, ours, defined, cls[k].limit);
        int b = reach_row(pub->rows, paper, all, cls[k].limit);
        char sa[40] = "never", sb[40] = "never";
        if (a >= 0) snprintf(sa, sizeof sa, "%g (%.4f)", pub->alpha_g[a], pub->alpha[a]);
        if (b >= 0) snprintf(sb, sizeof sb, "%g (%.4f)", pub->alpha_g[b], pub->alpha[b]);
        fprintf(out, "  %-38s %-22s %s\n", cls[k].name, sa, sb);
    }
}

int paper_images_run(const paper_images_options *o, FILE *out, char *err, size_t err_size)
{
    if (o->table != 6 && o->table != 7) {
        snprintf(err, err_size, "table %d: only Tables 6 and 7 are image experiments", o->table);
        return -1;
    }
    const int t = o->table - 6;
    published pub;
    if (parse_published(abrdf_embedded_paper_tables, &pub, err, err_size)) return -1;
    abrdf_model models[CANDIDATES];
    for (int k = 0; k < CANDIDATES; ++k)
        if (abrdf_model_find(table_models[t][k], &models[k]) != ABRDF_OK) {
            snprintf(err, err_size, "model %s is not in the library", table_models[t][k]);
            return -1;
        }
    scene s;
    int parsed = o->scene_path ? scene_parse_file(o->scene_path, &s, err, err_size)
                               : scene_parse_text("robot.scene", abrdf_embedded_robot_scene,
                                                  strlen(abrdf_embedded_robot_scene), &s, err, err_size);
    if (parsed) return -1;

    const int rows = pub.rows;
    size_t px = (size_t)o->width * (size_t)o->height * 3;
    float *ref = malloc((size_t)rows * px * sizeof *ref), *img = malloc(px * sizeof *img);
    double best[ROWS_MAX][CANDIDATES];
    int arg[ROWS_MAX][CANDIDATES], defined[ROWS_MAX];
    int rc = -1, total = rows + CANDIDATES * N_COUNT, done = 0;
    if (!ref || !img) {
        snprintf(err, err_size, "out of memory for %d images of %dx%d", rows + 1, o->width, o->height);
        goto out;
    }
    /* Reference: Disney specular, ks = 1, F0 = f0, r = sqrt(alpha_g) (alpha_g = r^2). */
    for (int r = 0; r < rows; ++r) {
        abrdf_params p;
        abrdf_params_init(ABRDF_DISNEY_SPECULAR, &p);
        for (int c = 0; c < 3; ++c) p.ks[c] = 1, p.f0[c] = o->f0;
        p.r = sqrt(pub.alpha_g[r]);
        if (render_with(&s, o, ABRDF_DISNEY_SPECULAR, &p, ref + (size_t)r * px, err, err_size)) goto out;
        for (int k = 0; k < CANDIDATES; ++k) best[r][k] = INFINITY, arg[r][k] = 0;
        defined[r] = 0;
        if (o->progress) fprintf(stderr, "\rTable %d: %d/%d renders", o->table, ++done, total);
    }
    /* Candidates: lobes without a Fresnel factor get ks = f0 (the reference's reflectance at
     * normal incidence); lobes with one get ks = 1 and F0 = f0, like the reference. */
    for (int k = 0; k < CANDIDATES; ++k) {
        int fresnel = (abrdf_model_get(models[k])->needs & ABRDF_NEEDS_FRESNEL) != 0;
        for (int j = 0; j < N_COUNT; ++j) {
            abrdf_params p;
            abrdf_params_init(models[k], &p);
            for (int c = 0; c < 3; ++c) p.ks[c] = fresnel ? 1 : o->f0, p.f0[c] = o->f0;
            p.n = paper_n[j];
            if (render_with(&s, o, models[k], &p, img, err, err_size)) goto out;
            for (int r = 0; r < rows; ++r) {
                abrdf_metrics m;
                if (abrdf_metrics_compute(img, ref + (size_t)r * px, o->width, o->height, 3, &m) !=
                    ABRDF_METRICS_OK) {
                    snprintf(err, err_size, "non-finite pixel in a render of %s", table_models[t][k]);
                    goto out;
                }
                defined[r] = m.nmse_defined;
                if (m.nmse_defined && m.nmse < best[r][k]) best[r][k] = m.nmse, arg[r][k] = j;
            }
            if (o->progress) fprintf(stderr, "\rTable %d: %d/%d renders", o->table, ++done, total);
        }
    }
    if (o->progress) fputc('\n', stderr);

    if (o->csv) {
        fprintf(out, "table,alpha_g,alpha,model,nmse,n,paper_nmse\n");
        for (int r = 0; r < rows; ++r)
            for (int k = 0; k < CANDIDATES; ++k) {
                fprintf(out, "%d,%g,%.4f,%s,", o->table, pub.alpha_g[r], pub.alpha[r], table_models[t][k]);
                if (defined[r]) fprintf(out, "%.6e,%g,", best[r][k], paper_n[arg[r][k]]);
                else fprintf(out, ",,");
                fprintf(out, "%s\n", pub.text[r][4 * t + k]);
            }
        rc = 0;
        goto out;
    }
    fprintf(out, "Table %d - minimum NMSE over n, %s vs the Disney GGX specular (Zavalniuk & Romanyuk 2024)\n",
            o->table, t ? "models with a Fresnel factor" : "simple empirical models");
    fprintf(out, "robot %dx%d, %d spp, one directional light, no ambient; ", o->width, o->height, o->spp);
    if (o->kd > 0) fprintf(out, "Lambert kd = %g + specular", o->kd);
    else fprintf(out, "specular only");
    fprintf(out, "; F0 = %g%s\n", o->f0, t ? "" : " (lobes without Fresnel: ks = F0)");
    fprintf(out, "n searched over the paper's 18 values 1..1000; columns: computed NMSE [argmin n] | paper\n\n");
    fprintf(out, "%-8s %-6s", "alpha_g", "alpha");
    for (int k = 0; k < CANDIDATES; ++k) fprintf(out, "  %-27s", table_models[t][k]);
    fputc('\n', out);
    for (int r = 0; r < rows; ++r) {
        fprintf(out, "%-8g %-6.4f", pub.alpha_g[r], pub.alpha[r]);
        for (int k = 0; k < CANDIDATES; ++k) {
            char cell[40];
            if (defined[r]) snprintf(cell, sizeof cell, "%.2e [%g]", best[r][k], paper_n[arg[r][k]]);
            else snprintf(cell, sizeof cell, "undefined");
            fprintf(out, "  %-17s| %-8s", cell, pub.text[r][4 * t + k]);
        }
        fputc('\n', out);
    }
    /* The "2e" lobe of the table: f_2e (Table 6) or f_ct2e (Table 7). */
    double ours[ROWS_MAX], paper[ROWS_MAX];
    for (int r = 0; r < rows; ++r) ours[r] = best[r][2], paper[r] = pub.value[r][4 * t + 2];
    print_reach(out, table_models[t][2], &pub, ours, defined, paper);
    rc = 0;
out:
    free(ref);
    free(img);
    scene_free(&s);
    return rc;
}

static int usage(void)
{
    printf("usage: abrdf tables 6|7 [--width W] [--height H] [--spp N] [--threads N]\n"
           "                        [--f0 V] [--kd V] [--scene FILE] [--csv]\n\n"
           "The paper's image experiment (Tables 6 and 7, docs/TABLES_6_7.md): the robot rendered\n"
           "with the Disney GGX specular at each alpha_g of the paper is the reference; each\n"
           "candidate lobe is rendered at each exponent n of the paper; per alpha_g the minimum\n"
           "NMSE over n and its argmin are printed beside the published values, then the alpha_g\n"
           "at which the cosine-quadratic lobe reaches each Table-8 class.\n"
           "  --width/--height  image size (default 128 x 128)\n"
           "  --spp N           samples per pixel, a square (default 1)\n"
           "  --threads N       render threads (default: online CPUs)\n"
           "  --f0 V            Fresnel F0 of the reference and of the Fresnel lobes (default 0.04;\n"
           "                    lobes without Fresnel get ks = F0)\n"
           "  --kd V            Lambert albedo under every specular lobe (default 0.5; 0: specular only)\n"
           "  --scene FILE      another scene (default: the built-in robot, scenes/robot.scene)\n"
           "  --csv             CSV rows: table,alpha_g,alpha,model,nmse,n,paper_nmse\n");
    return 0;
}

int paper_images_cmd(int argc, char **argv)
{
    const char *cmd = "tables";
    paper_images_options o;
    paper_images_defaults(&o);
    if (argc < 1 || cli_is_help(argv[0])) return usage();
    if (strcmp(argv[0], "6") && strcmp(argv[0], "7"))
        return cli_fail(cmd, "'%s': the image experiments are tables 6 and 7", argv[0]);
    o.table = argv[0][0] - '0';
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i], *val = i + 1 < argc ? argv[i + 1] : NULL;
        long v;
        double d;
        if (cli_is_help(a)) return usage();
        if (!strcmp(a, "--csv")) o.csv = 1;
        else if (!strcmp(a, "--scene")) {
            if (!val) return cli_fail(cmd, "--scene needs a file");
            o.scene_path = argv[++i];
        } else if (!strcmp(a, "--width") || !strcmp(a, "--height") || !strcmp(a, "--spp") ||
                   !strcmp(a, "--threads")) {
            long hi = a[2] == 's' ? 4096 : a[2] == 't' ? 64 : SCENE_MAX_RESOLUTION;
            if (!cli_parse_int(val, 1, hi, &v)) return cli_fail(cmd, "%s needs a whole number in [1, %ld]", a, hi);
            ++i;
            if (a[2] == 'w') o.width = (int)v;
            else if (a[2] == 'h') o.height = (int)v;
            else if (a[2] == 't') o.threads = (int)v;
            else o.spp = (int)v;
        } else if (!strcmp(a, "--f0") || !strcmp(a, "--kd")) {
            if (!cli_parse_double(val, &d) || d < 0 || d > 1) return cli_fail(cmd, "%s needs a value in [0, 1]", a);
            ++i;
            if (a[2] == 'f') o.f0 = d;
            else o.kd = d;
        } else {
            return cli_fail(cmd, "unknown option '%s' (abrdf tables %s --help)", a, argv[0]);
        }
    }
    long k = lround(sqrt((double)o.spp));
    if (k * k != o.spp) return cli_fail(cmd, "--spp %d is not a square (1, 4, 9, 16, ...)", o.spp);
    o.progress = isatty(2);
    char err[512];
    if (paper_images_run(&o, stdout, err, sizeof err)) {
        fprintf(stderr, "abrdf tables %d: %s\n", o.table, err);
        return 1;
    }
    return 0;
}
