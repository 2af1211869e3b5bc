/* sample_stats.h - what the sampling suites share: a (theta, phi) grid of the sphere about a
 * chosen pole, adaptive integration of a function of direction over its cells, and
 * Pearson's chi-square goodness-of-fit test of sampled directions against a density
 * (as pbrt-v4's and Mitsuba 3's sampling tests do: expected counts from the density
 * integrated over each cell, cells with small expected counts pooled). */
#ifndef ABRDF_SAMPLE_STATS_H
#define ABRDF_SAMPLE_STATS_H

/* A function of a unit direction (local frame): a density or an integrand. */
typedef double (*ss_fn)(void *ctx, const double w[3]);

/* The grid: theta measured from `pole` in [0, pi], phi about it from e1 toward e2.
 * Rings are uniform in x = (theta/pi)^(1/warp) (warp 2 crowds them toward the pole, where a
 * peaked lobe centred there has its mass). */
typedef struct ss_grid {
    double pole[3], e1[3], e2[3];
    int ntheta, nphi;
    double warp;
} ss_grid;

/* A grid about the unit pole (any e1, e2). */
void ss_grid_make(ss_grid *g, const double pole[3], int ntheta, int nphi, double warp);
/* Cell index of direction w, in [0, ntheta * nphi). */
int ss_cell(const ss_grid *g, const double w[3]);
/* Integral of fn over every cell (out has ntheta * nphi entries), adaptive: a cell's 4 x 4
 * Gauss-Legendre value is accepted when its four quarters agree with it to within
 * abs_tol + rel_tol |value|, else each quarter is refined, to at most max_depth levels.
 * Returns the total; *evals (if not NULL) counts the calls of fn. */
double ss_integrate(const ss_grid *g, ss_fn fn, void *ctx, double abs_tol, double rel_tol,
                    int max_depth, double *out, long *evals);

/* Regularised upper incomplete gamma Q(a, x) (series below a + 1, continued fraction above). */
double ss_gamma_q(double a, double x);

/* Pearson's chi-square of observed counts against expected counts (n cells): cells with
 * expected < min_expected are pooled into one. *p_value: probability of a statistic at
 * least this large if the counts follow the expectation (dof = bins - 1). Returns the
 * statistic; *dof receives the degrees of freedom. A pooled bin with expectation 0 but
 * observations gives p = 0. */
double ss_chi2(const double *observed, const double *expected, int n, double min_expected,
               double *p_value, int *dof);

#endif
