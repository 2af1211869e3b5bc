/* tables_images.c - `abrdf tables 6|7`: the image experiment (paper_images.c) printed beside
 * the published values, with the Table-8 class of each cell. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "metrics.h"
#include "tables.h"

/* Index of the largest alpha_g from which on (it and every smaller alpha_g; rows sorted by
 * decreasing alpha_g) v < limit; -1 if even the smallest fails. */
static int reach_row(const double *v, double limit)
{
    int best = -1;
    for (int r = PAPER_IMAGES_ROWS - 1; r >= 0 && v[r] < limit; --r) best = r;
    return best;
}

static const char *short_class(double v)
{
    const char *c = abrdf_nmse_class(v);
    return !strcmp(c, "significant") ? "sig" : !strcmp(c, "noticeable") ? "noti" : c;
}

/* The published NMSE per cell (NaN where the paper gives none). */
typedef struct published_nmse {
    double v[PAPER_IMAGES_ROWS][PAPER_IMAGES_MODELS];
} published_nmse;

/* The computed and the published grids (alpha, then per model its NMSE and argmin n), and
 * the published NMSE per cell. */
static void grids_fill(int table, const paper_images_result *res, const paper_data *paper,
                       tab_grid *comp, tab_grid *pub, published_nmse *published)
{
    tab_init(comp, "computed: minimum NMSE over n, and the argmin n", "alpha_g",
             1 + 2 * PAPER_IMAGES_MODELS, "%.2e");
    tab_init(pub, "published (Zavalniuk & Romanyuk 2024)", "alpha_g", 1 + 2 * PAPER_IMAGES_MODELS,
             "%g");
    strcpy(comp->col[0], "alpha");
    strcpy(pub->col[0], "alpha");
    comp->fmt[0] = "%.4f";
    for (int m = 0; m < PAPER_IMAGES_MODELS; ++m) {
        snprintf(comp->col[1 + 2 * m], sizeof comp->col[0], "%s", res->model[m]);
        snprintf(comp->col[2 + 2 * m], sizeof comp->col[0], "%s_n", res->model[m]);
        strcpy(pub->col[1 + 2 * m], comp->col[1 + 2 * m]);
        strcpy(pub->col[2 + 2 * m], comp->col[2 + 2 * m]);
        comp->fmt[2 + 2 * m] = "%g";
    }
    for (int r = 0; r < PAPER_IMAGES_ROWS; ++r) {
        tab_row(comp, res->label[r]);
        tab_row(pub, res->label[r]);
        comp->v[r][0] = sqrt(res->alpha_g[r]);
        double a;
        if (paper_data_number(paper, table, res->label[r], "alpha", &a) == 0) pub->v[r][0] = a;
        for (int m = 0; m < PAPER_IMAGES_MODELS; ++m) {
            comp->v[r][1 + 2 * m] = res->nmse[r][m];
            comp->v[r][2 + 2 * m] = res->n[r][m];
            published->v[r][m] = NAN;
            if (paper_data_number(paper, table, res->label[r], res->model[m], &a) == 0)
                pub->v[r][1 + 2 * m] = published->v[r][m] = a;
        }
    }
}

/* The table's heading and how it was measured. */
static void print_intro(int table, const paper_images_options *io, const paper_images_result *res)
{
    printf("## Table %d: minimum NMSE over n, %s vs the Disney GGX specular\n\n", table,
           table == 6 ? "simple empirical lobes" : "lobes with a Fresnel factor");
    printf("Robot %dx%d, %d spp%s, one directional light, no ambient; ", io->width, io->height,
           io->spp, io->spp == 1 ? " (pixel centres)" : "");
    if (io->kd > 0)
        printf("Lambert kd = %g + specular", io->kd);
    else
        printf("specular only");
    printf("; F0 = %g%s; n over the paper's %d values %g..%g; %d renders (docs/TABLES.md, "
           "\"Tables 6 and 7\").\n\n",
           io->f0, table == 6 ? " (these lobes have no Fresnel factor: ks = F0)" : "",
           PAPER_IMAGES_EXPONENTS, paper_images_exponents[0],
           paper_images_exponents[PAPER_IMAGES_EXPONENTS - 1], res->renders);
}

/* Every cell's Table-8 class, computed beside published, and how many agree. */
static void print_classes(const paper_images_result *res, const published_nmse *published)
{
    printf("### Table-8 class, computed / published\n\n| alpha_g |");
    for (int m = 0; m < PAPER_IMAGES_MODELS; ++m) printf(" %s |", res->model[m]);
    printf("\n|---|");
    for (int m = 0; m < PAPER_IMAGES_MODELS; ++m) printf("---|");
    printf("\n");
    int agree = 0, cells = 0;
    for (int r = 0; r < PAPER_IMAGES_ROWS; ++r) {
        printf("| %s |", res->label[r]);
        for (int m = 0; m < PAPER_IMAGES_MODELS; ++m) {
            const char *a = res->defined[r] ? short_class(res->nmse[r][m]) : "undefined";
            const char *b = isnan(published->v[r][m]) ? "—" : short_class(published->v[r][m]);
            printf(" %s / %s |", a, b);
            if (!isnan(published->v[r][m])) agree += !strcmp(a, b), ++cells;
        }
        printf("\n");
    }
    printf("\nSame class in %d of %d cells.\n\n", agree, cells);
}

/* For the quadratic lobe: the largest alpha_g from which on it stays in each class,
 * computed beside published. */
static void print_reach(const paper_images_result *res, const published_nmse *published)
{
    double ours[PAPER_IMAGES_ROWS], theirs[PAPER_IMAGES_ROWS];
    for (int r = 0; r < PAPER_IMAGES_ROWS; ++r) {
        ours[r] = res->defined[r] ? res->nmse[r][PAPER_IMAGES_QUADRATIC] : NAN;
        theirs[r] = published->v[r][PAPER_IMAGES_QUADRATIC];
    }
    static const struct {
        const char *name;
        double limit;
    } cls[] = {
        {"noticeable or better (NMSE < 1e-3)", ABRDF_NMSE_SIGNIFICANT},
        {"slight or better (NMSE < 2.5e-4)", ABRDF_NMSE_NOTICEABLE},
        {"no visible difference (NMSE < 1e-4)", ABRDF_NMSE_SLIGHT},
    };
    printf("### %s: largest alpha_g (alpha) from which on it stays in each Table-8 class\n\n",
           res->model[PAPER_IMAGES_QUADRATIC]);
    printf("| class | computed | published |\n|---|---|---|\n");
    for (int c = 0; c < 3; ++c) {
        int a = reach_row(ours, cls[c].limit), b = reach_row(theirs, cls[c].limit);
        printf("| %s |", cls[c].name);
        if (a >= 0)
            printf(" %s (%.4f) |", res->label[a], sqrt(res->alpha_g[a]));
        else
            printf(" never |");
        if (b >= 0)
            printf(" %s (%.4f) |\n", res->label[b], sqrt(res->alpha_g[b]));
        else
            printf(" never |\n");
    }
}

int tables_images(const table_gen *self, const tables_opts *o, const paper_data *paper)
{
    int table = !strcmp(self->id, "6") ? 6 : 7;
    paper_images_result res;
    char err[512];
    if (paper_images_compute(table, &o->images, &res, err, sizeof err)) {
        fprintf(stderr, "abrdf tables %d: %s\n", table, err);
        return 1;
    }
    /* NMSE is relative to the reference: with every reference black nothing was measured,
     * and an empty table must not pass for a result. */
    int defined = 0;
    for (int r = 0; r < PAPER_IMAGES_ROWS; ++r) defined += res.defined[r];
    if (!defined) {
        fprintf(stderr,
                "abrdf tables %d: every reference image is black (%s): nothing was measured; "
                "the scene needs a visible object lit by its light\n",
                table, o->images.scene_path ? o->images.scene_path : "the built-in robot");
        return 1;
    }
    tab_grid comp, pub;
    published_nmse published;
    grids_fill(table, &res, paper, &comp, &pub, &published);
    if (o->csv) {
        for (int m = 0; m < PAPER_IMAGES_MODELS; ++m)
            comp.fmt[1 + 2 * m] = "%.9e"; /* for re-checks */
        tab_csv(&comp, "kind", "computed", 1);
        tab_csv(&pub, NULL, "published", 0);
        return 0;
    }
    print_intro(table, &o->images, &res);
    tab_markdown(&comp);
    tab_markdown(&pub);
    print_classes(&res, &published);
    print_reach(&res, &published);
    const char *base = strrchr(paper->path, '/');
    printf("\nPublished values: %s\n", base ? base + 1 : paper->path);
    return 0;
}
