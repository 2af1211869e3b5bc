/* plot_grid.c - the decade grid of the log-log SVG plots (plot_grid.h). */
#include "plot_grid.h"

#include <math.h>

void plot_grid_write(FILE *f, const plot_grid *g)
{
    const double W = g->W, H = g->H, L = g->L, Rm = g->Rm, T = g->T, B = g->B;
    const double lx0 = g->lx0, lx1 = g->lx1, ly0 = g->ly0, ly1 = g->ly1;
    for (double e = lx0; e <= lx1; ++e) {
        double x = L + (log10(pow(10, e)) - lx0) / (lx1 - lx0) * (W - L - Rm);
        fprintf(f,
                "<line x1=\"%.1f\" y1=\"%g\" x2=\"%.1f\" y2=\"%g\" stroke=\"#ddd\"/><text "
                "x=\"%.1f\" y=\"%g\" text-anchor=\"middle\">1e%g</text>\n",
                x, T, x, H - B, x, H - B + 15, e);
    }
    for (double e = ly0; e <= ly1; ++e) {
        double v = fmin(fmax(pow(10, e), g->y_min), g->y_max);
        double y = H - B - (log10(v) - ly0) / (ly1 - ly0) * (H - T - B);
        fprintf(f,
                "<line x1=\"%g\" y1=\"%.1f\" x2=\"%g\" y2=\"%.1f\" stroke=\"#ddd\"/><text x=\"%g\" "
                "y=\"%.1f\" text-anchor=\"end\">1e%g</text>\n",
                L, y, W - Rm, y, L - 5, y + 4, e);
    }
}
