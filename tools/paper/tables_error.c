/* tables_error.c - Tables 2 and 3 of the paper: the maximum relative error in the
 * highlight zone and the maximum absolute error of every Table-1 approximation against
 * Blinn-Phong, computed by abrdf_approx_error_eval, beside the published values. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "abrdf_select.h"
#include "tables.h"

static const double paper_n[] = {2, 5, 10, 20, 50, 100, 200, 500, 700, 1000};
#define NCOLS ((int)(sizeof paper_n / sizeof paper_n[0]))
#define MAD_COL NCOLS

static const abrdf_model rows[] = {ABRDF_F2, ABRDF_F4,  ABRDF_F8,  ABRDF_F16,
                                   ABRDF_FS, ABRDF_FKV, ABRDF_FKUB};
#define NROWS ((int)(sizeof rows / sizeof rows[0]))
/* The models of the reproduction criterion (fkv's constant is unverified and fkub's
 * coefficients are not published, so their rows are fits of unknown forms). */
#define CRITERION_ROWS 5

/* Criterion of the reproduction: mean |computed - published| over f2, f4, f8, f16, fs. */
static const double criterion[2] = {0.75, 0.01};

int tables_error(const table_gen *self, const tables_opts *o, const paper_data *paper)
{
    int t = !strcmp(self->id, "2") ? 2 : 3;
    int rel = t == 2;
    const char *what = rel ? "maximum relative error (%) in the highlight zone"
                           : "maximum absolute error over N.H in [0, 1]";
    tab_grid comp, pub, diff;
    const char *fmt = rel ? "%.2f" : "%.4f";
    tab_init(&comp, "computed (abrdf_approx_error_eval)", "model", NCOLS + 1, fmt);
    tab_init(&pub, "published (Zavalniuk & Romanyuk 2024)", "model", NCOLS + 1, "%g");
    tab_init(&diff, "difference (computed - published), MAD = mean |difference| over the row",
             "model", NCOLS + 1, rel ? "%+.2f" : "%+.4f");
    diff.fmt[MAD_COL] = rel ? "%.2f" : "%.4f";
    for (int c = 0; c < NCOLS; ++c) {
        snprintf(comp.col[c], sizeof comp.col[c], "%g", paper_n[c]);
        strcpy(pub.col[c], comp.col[c]);
        strcpy(diff.col[c], comp.col[c]);
    }
    strcpy(comp.col[MAD_COL], "mad");
    strcpy(pub.col[MAD_COL], "mad");
    strcpy(diff.col[MAD_COL], "mad");

    double zone[NCOLS];
    double crit_sum = 0.0;
    int crit_cells = 0;
    for (int r = 0; r < NROWS; ++r) {
        const char *name = abrdf_model_get(rows[r])->name;
        tab_row(&comp, name);
        tab_row(&pub, name);
        tab_row(&diff, name);
        double sum = 0.0;
        int cells = 0;
        for (int c = 0; c < NCOLS; ++c) {
            abrdf_approx_error e;
            int st = abrdf_approx_error_eval(rows[r], paper_n[c], &e);
            if (st != ABRDF_OK) {
                fprintf(stderr, "abrdf tables: %s at n = %g: %s\n", name, paper_n[c],
                        abrdf_strerror(st));
                return 1;
            }
            zone[c] = e.zone_cos;
            comp.v[r][c] = rel ? e.max_rel_pct : e.max_abs;
            double p;
            if (paper_data_number(paper, t, name, comp.col[c], &p) == 0) {
                pub.v[r][c] = p;
                diff.v[r][c] = comp.v[r][c] - p;
                sum += fabs(diff.v[r][c]);
                ++cells;
            }
        }
        if (cells) diff.v[r][MAD_COL] = sum / cells;
        if (r < CRITERION_ROWS) {
            crit_sum += sum;
            crit_cells += cells;
        }
    }
    double mad = crit_cells ? crit_sum / crit_cells : NAN;

    if (o->csv) {
        tab_csv(&comp, "kind", "computed", 1);
        tab_csv(&pub, NULL, "published", 0);
        tab_csv(&diff, NULL, "difference", 0);
        return 0;
    }
    printf("## Table %d: %s of the Table-1 approximations vs Blinn-Phong cos^n\n\n", t, what);
    if (rel) {
        printf(
            "Highlight zone: N.H >= max(sqrt(1 - 1/n), 0.5^(1/n)), the concave core of the lobe\n"
            "(peak to inflection point) within its half-maximum cone (docs/TABLES.md). Zone "
            "start:\n\n");
        tab_grid z;
        tab_init(&z, NULL, "n", NCOLS, "%.5f");
        for (int c = 0; c < NCOLS; ++c) strcpy(z.col[c], comp.col[c]);
        tab_row(&z, "N.H");
        for (int c = 0; c < NCOLS; ++c) z.v[0][c] = zone[c];
        tab_markdown(&z);
    }
    tab_markdown(&comp);
    tab_markdown(&pub);
    tab_markdown(&diff);
    printf("Mean absolute deviation over f2, f4, f8, f16, fs (%d published cells): %.4g "
           "(reproduction criterion <= %g): %s\n",
           crit_cells, mad, criterion[t - 2], mad <= criterion[t - 2] ? "met" : "NOT met");
    const char *base = strrchr(paper->path, '/');
    printf("Published values: %s\n", base ? base + 1 : paper->path);
    return 0;
}
