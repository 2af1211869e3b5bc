/* plot_grid.h - the decade grid of the log-log SVG plots of `abrdf advise --plot` and
 * `abrdf bench --plot` (plot_grid.c). */
#ifndef ABRDF_PLOT_GRID_H
#define ABRDF_PLOT_GRID_H

#include <stdio.h>

/* A log-log plot: the picture's width W and height H, its left, right, top and bottom margins
 * L, Rm, T, B; the axes' decades lx0..lx1 and ly0..ly1 (log10); y values are clamped to
 * [y_min, y_max] before they are placed (-INFINITY, INFINITY: not clamped). */
typedef struct {
    double W, H, L, Rm, T, B;
    double lx0, lx1, ly0, ly1;
    double y_min, y_max;
} plot_grid;

/* One grey line and its 1eN label per decade of each axis. */
void plot_grid_write(FILE *f, const plot_grid *g);

#endif
