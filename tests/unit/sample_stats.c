/* sample_stats.c - grids, adaptive cell integration and the chi-square test of the sampling
 * suites (sample_stats.h). */
#include <math.h>
#include <stdlib.h>

#include "sample_stats.h"

#define PI 3.14159265358979323846

static double dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

void ss_grid_make(ss_grid *g, const double pole[3], int ntheta, int nphi, double warp)
{
    for (int c = 0; c < 3; ++c) g->pole[c] = pole[c];
    /* e1: the axis least aligned with the pole, made orthogonal; e2 = pole x e1 */
    double ax[3] = {0, 0, 0};
    int k = fabs(pole[0]) <= fabs(pole[1]) ? (fabs(pole[0]) <= fabs(pole[2]) ? 0 : 2)
                                           : (fabs(pole[1]) <= fabs(pole[2]) ? 1 : 2);
    ax[k] = 1.0;
    double d = dot(ax, pole), l = 0.0;
    for (int c = 0; c < 3; ++c) {
        g->e1[c] = ax[c] - d * pole[c];
        l += g->e1[c] * g->e1[c];
    }
    for (int c = 0; c < 3; ++c) g->e1[c] /= sqrt(l);
    g->e2[0] = pole[1] * g->e1[2] - pole[2] * g->e1[1];
    g->e2[1] = pole[2] * g->e1[0] - pole[0] * g->e1[2];
    g->e2[2] = pole[0] * g->e1[1] - pole[1] * g->e1[0];
    g->ntheta = ntheta;
    g->nphi = nphi;
    g->warp = warp;
}

static double ring_theta(const ss_grid *g, double x) { return PI * pow(x, g->warp); }

int ss_cell(const ss_grid *g, const double w[3])
{
    double z = dot(w, g->pole), x = dot(w, g->e1), y = dot(w, g->e2);
    double theta = atan2(sqrt(x * x + y * y), z), phi = atan2(y, x);
    if (phi < 0.0) phi += 2.0 * PI;
    int i = (int)(pow(theta / PI, 1.0 / g->warp) * g->ntheta);
    int j = (int)(phi / (2.0 * PI) * g->nphi);
    i = i < 0 ? 0 : (i >= g->ntheta ? g->ntheta - 1 : i);
    j = j < 0 ? 0 : (j >= g->nphi ? g->nphi - 1 : j);
    return i * g->nphi + j;
}

static const double gl4_x[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                                0.8611363115940526};
static const double gl4_w[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
                                0.3478548451374538};

/* 4 x 4 Gauss-Legendre of fn sin(theta) over [t0, t1] x [p0, p1]. */
static double cell_gl(const ss_grid *g, ss_fn fn, void *ctx, double t0, double t1, double p0,
                      double p1, long *evals)
{
    double sum = 0.0;
    for (int a = 0; a < 4; ++a) {
        double t = 0.5 * (t0 + t1) + 0.5 * (t1 - t0) * gl4_x[a], st = sin(t), ct = cos(t);
        for (int b = 0; b < 4; ++b) {
            double p = 0.5 * (p0 + p1) + 0.5 * (p1 - p0) * gl4_x[b];
            double cp = cos(p), sp = sin(p), w[3];
            for (int c = 0; c < 3; ++c)
                w[c] = st * (cp * g->e1[c] + sp * g->e2[c]) + ct * g->pole[c];
            sum += gl4_w[a] * gl4_w[b] * fn(ctx, w) * st;
        }
    }
    if (evals) *evals += 16;
    return sum * 0.25 * (t1 - t0) * (p1 - p0);
}

static double adapt(const ss_grid *g, ss_fn fn, void *ctx, double t0, double t1, double p0,
                    double p1, double whole, double abs_tol, double rel_tol, int depth, long *evals)
{
    double tm = 0.5 * (t0 + t1), pm = 0.5 * (p0 + p1);
    double q[4] = {
        cell_gl(g, fn, ctx, t0, tm, p0, pm, evals), cell_gl(g, fn, ctx, tm, t1, p0, pm, evals),
        cell_gl(g, fn, ctx, t0, tm, pm, p1, evals), cell_gl(g, fn, ctx, tm, t1, pm, p1, evals)};
    double sum = q[0] + q[1] + q[2] + q[3];
    if (depth <= 0 || fabs(sum - whole) <= abs_tol + rel_tol * fabs(sum)) return sum;
    return adapt(g, fn, ctx, t0, tm, p0, pm, q[0], 0.25 * abs_tol, rel_tol, depth - 1, evals) +
           adapt(g, fn, ctx, tm, t1, p0, pm, q[1], 0.25 * abs_tol, rel_tol, depth - 1, evals) +
           adapt(g, fn, ctx, t0, tm, pm, p1, q[2], 0.25 * abs_tol, rel_tol, depth - 1, evals) +
           adapt(g, fn, ctx, tm, t1, pm, p1, q[3], 0.25 * abs_tol, rel_tol, depth - 1, evals);
}

double ss_integrate(const ss_grid *g, ss_fn fn, void *ctx, double abs_tol, double rel_tol,
                    int max_depth, double *out, long *evals)
{
    double total = 0.0;
    for (int i = 0; i < g->ntheta; ++i) {
        double t0 = ring_theta(g, (double)i / g->ntheta);
        double t1 = ring_theta(g, (double)(i + 1) / g->ntheta);
        for (int j = 0; j < g->nphi; ++j) {
            double p0 = 2.0 * PI * j / g->nphi, p1 = 2.0 * PI * (j + 1) / g->nphi;
            double whole = cell_gl(g, fn, ctx, t0, t1, p0, p1, evals);
            double v = adapt(g, fn, ctx, t0, t1, p0, p1, whole, abs_tol, rel_tol, max_depth, evals);
            if (out) out[i * g->nphi + j] = v;
            total += v;
        }
    }
    return total;
}

/* ---- chi-square ------------------------------------------------------------------------ */

double ss_gamma_q(double a, double x)
{
    if (!(x > 0.0)) return 1.0;
    double lg = lgamma(a);
    if (x < a + 1.0) { /* P by its series, Q = 1 - P */
        double term = 1.0 / a, sum = term;
        for (int n = 1; n < 10000 && fabs(term) > 1e-17 * fabs(sum); ++n) {
            term *= x / (a + n);
            sum += term;
        }
        return 1.0 - sum * exp(-x + a * log(x) - lg);
    }
    /* Q by its continued fraction (modified Lentz) */
    const double tiny = 1e-300;
    double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
    for (int i = 1; i < 10000; ++i) {
        double an = -i * (i - a);
        b += 2.0;
        d = an * d + b;
        if (fabs(d) < tiny) d = tiny;
        c = b + an / c;
        if (fabs(c) < tiny) c = tiny;
        d = 1.0 / d;
        double del = d * c;
        h *= del;
        if (fabs(del - 1.0) < 1e-16) break;
    }
    return exp(-x + a * log(x) - lg) * h;
}

double ss_chi2(const double *observed, const double *expected, int n, double min_expected,
               double *p_value, int *dof)
{
    double chi2 = 0.0, pool_o = 0.0, pool_e = 0.0;
    int bins = 0;
    for (int i = 0; i < n; ++i) {
        if (expected[i] < min_expected) {
            pool_o += observed[i];
            pool_e += expected[i];
            continue;
        }
        double d = observed[i] - expected[i];
        chi2 += d * d / expected[i];
        ++bins;
    }
    if (pool_e > 0.0) {
        double d = pool_o - pool_e;
        chi2 += d * d / pool_e;
        ++bins;
    } else if (pool_o > 0.0) {
        *p_value = 0.0;
        *dof = bins;
        return INFINITY;
    }
    *dof = bins - 1;
    *p_value = *dof > 0 ? ss_gamma_q(0.5 * *dof, 0.5 * chi2) : 1.0;
    return chi2;
}
