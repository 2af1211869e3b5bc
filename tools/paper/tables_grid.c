/* tables_grid.c - the small grid printer shared by the table generators (tables.h):
 * Markdown for reading, CSV for scripts. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "tables.h"

void tab_init(tab_grid *g, const char *title, const char *corner, int cols, const char *fmt)
{
    memset(g, 0, sizeof *g);
    g->title = title;
    g->corner = corner;
    g->cols = cols;
    for (int c = 0; c < TAB_MAX_COLS; ++c) g->fmt[c] = fmt;
    for (int r = 0; r < TAB_MAX_ROWS; ++r)
        for (int c = 0; c < TAB_MAX_COLS; ++c) g->v[r][c] = NAN;
}

int tab_row(tab_grid *g, const char *label)
{
    if (g->rows == TAB_MAX_ROWS) return TAB_MAX_ROWS - 1; /* generators stay far below */
    snprintf(g->row[g->rows], sizeof g->row[0], "%s", label);
    return g->rows++;
}

/* A cell for printing: round-off residue of a difference shows as 0, not -0.0000. */
/* A fixed-point column shows a difference below 1e-9 as 0 (not "-0.00"); a column in
 * exponent notation (Tables 6-7's NMSE) shows every value as it is. */
static double cell(const tab_grid *g, int r, int c)
{
    double v = g->v[r][c];
    int fixed = strchr(g->fmt[c], 'f') != NULL;
    return fixed && fabs(v) < 1e-9 ? 0.0 : v;
}

static int column_used(const tab_grid *g, int c)
{
    for (int r = 0; r < g->rows; ++r)
        if (!isnan(g->v[r][c])) return 1;
    return 0;
}

void tab_markdown(const tab_grid *g)
{
    if (g->title) printf("### %s\n\n", g->title);
    printf("| %s |", g->corner);
    for (int c = 0; c < g->cols; ++c)
        if (column_used(g, c)) printf(" %s |", g->col[c]);
    printf("\n|---|");
    for (int c = 0; c < g->cols; ++c)
        if (column_used(g, c)) printf("---:|");
    printf("\n");
    for (int r = 0; r < g->rows; ++r) {
        printf("| %s |", g->row[r]);
        for (int c = 0; c < g->cols; ++c) {
            if (!column_used(g, c)) continue;
            if (isnan(g->v[r][c]))
                printf(" — |");
            else {
                printf(" ");
                printf(g->fmt[c], cell(g, r, c));
                printf(" |");
            }
        }
        printf("\n");
    }
    printf("\n");
}

void tab_csv(const tab_grid *g, const char *tag_name, const char *tag, int header)
{
    if (header) {
        printf("%s", g->corner);
        if (tag_name) printf(",%s", tag_name);
        for (int c = 0; c < g->cols; ++c) printf(",%s", g->col[c]);
        printf("\n");
    }
    for (int r = 0; r < g->rows; ++r) {
        printf("%s", g->row[r]);
        if (tag) printf(",%s", tag);
        for (int c = 0; c < g->cols; ++c) {
            printf(",");
            if (!isnan(g->v[r][c])) printf(g->fmt[c], cell(g, r, c));
        }
        printf("\n");
    }
}
