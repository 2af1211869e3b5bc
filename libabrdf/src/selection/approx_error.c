/* approx_error.c - error of the Table-1 approximations of Blinn-Phong, computed from first
 * principles: the paper's Table 2 (maximum relative error in the highlight zone) and
 * Table 3 (maximum absolute error) for any exponent n.
 *
 * Zavalniuk & Romanyuk 2024, Tables 1-3. Both the approximation and cos^n are evaluated by
 * the library itself (abrdf_eval, double path, local frame) at mirror geometry wi = wo, where
 * N.H = c exactly, so the numbers describe what the library computes.
 *
 * HIGHLIGHT ZONE (the paper only says "the zone of the highlight's epicentre"; the choice
 * below reproduces its Table 2 to 0.16 percentage points on average, docs/TABLES.md):
 *   the directions where the lobe cos^n(theta_h) is both concave in theta_h (from the peak
 *   to its inflection point, sin^2 theta_h = 1/n) and at least half its peak, i.e.
 *       c >= zone_cos = max(sqrt(1 - 1/n), 0.5^(1/n)).
 *   For n >= 2 the inflection point lies inside the half-maximum cone, so the zone ends at
 *   the inflection point; for n < 2 (no inflection below 90 deg for n <= 1) it is the
 *   half-maximum cone, which keeps the relative error finite (every approximation but fs
 *   is > 0 at c = 0 when n < m, where cos^n is 0).
 *
 * MAXIMUM SEARCH: dense uniform sampling, then golden-section refinement of the largest
 * sampled local maxima inside their neighbouring samples. The absolute error is sampled
 * twice, uniformly in c over [0, 1] and uniformly over c in [1 - 64/n, 1], where every
 * feature of cos^n and of the approximations lives for large n (their width scales as 1/n;
 * the zero crossings of f16 and fkub lie at 16/n and about 4.6/n). */
#include <math.h>
#include <string.h>

#include "abrdf_internal.h"
#include "abrdf_select.h"

/* Samples per dense pass: at n = 1e6 the near-peak window [1 - 64/n, 1] is then resolved
 * to 0.03/n, far finer than any feature, and refinement does the rest. */
#define SAMPLES 2048
/* Sampled local maxima refined per pass (the error curves have at most three humps). */
#define REFINE_TOP 4
/* Width of the near-peak window in units of 1/n (covers the features named above). */
#define PEAK_WINDOW 64.0
/* Golden-section steps: 0.618^80 shrinks a bracket of one sample spacing below 1e-19. */
#define GOLDEN_STEPS 80

typedef struct err_ctx {
    abrdf_prepared pa, pb; /* the approximation and Blinn-Phong, ks = 1, same n: prepared once
                              (abrdf_eval is exactly abrdf_prepare then the prepared call) */
    int relative;          /* 1: |f - g| / g, 0: |f - g| */
} err_ctx;

static int is_table1(abrdf_model m)
{
    return m == ABRDF_F2 || m == ABRDF_F4 || m == ABRDF_F8 || m == ABRDF_F16 || m == ABRDF_FS ||
           m == ABRDF_FKV || m == ABRDF_FKUB;
}

/* Error at N.H = c (mirror geometry: wi = wo, so H = wi). */
static double err_at(const err_ctx *e, double c)
{
    if (c < 0.0) c = 0.0;
    if (c > 1.0) c = 1.0;
    double w[3] = {sqrt((1.0 - c) * (1.0 + c)), 0.0, c}; /* no cancellation near c = 1 */
    double f[3], g[3];
    abrdf_eval_prepared(&e->pa, NULL, w, w, f);
    abrdf_eval_prepared(&e->pb, NULL, w, w, g);
    double d = fabs(f[0] - g[0]);
    if (!e->relative) return d;
    return g[0] > 0.0 ? d / g[0] : 0.0;
}

/* Golden-section maximisation of err on [a, b], starting value known at the midpoint. */
static double refine(const err_ctx *e, double a, double b)
{
    const double r = 0.6180339887498949;
    double x1 = b - r * (b - a), x2 = a + r * (b - a);
    double f1 = err_at(e, x1), f2 = err_at(e, x2);
    double best = fmax(f1, f2);
    for (int i = 0; i < GOLDEN_STEPS && b - a > 0.0; ++i) {
        if (f1 >= f2) {
            b = x2;
            x2 = x1;
            f2 = f1;
            x1 = b - r * (b - a);
            f1 = err_at(e, x1);
        } else {
            a = x1;
            x1 = x2;
            f1 = f2;
            x2 = a + r * (b - a);
            f2 = err_at(e, x2);
        }
        best = fmax(best, fmax(f1, f2));
    }
    return best;
}

/* Maximum of err over [lo, hi]: SAMPLES + 1 uniform samples, then the REFINE_TOP largest
 * sampled local maxima refined between their neighbours. */
static double maximise(const err_ctx *e, double lo, double hi)
{
    double v[SAMPLES + 1];
    double h = (hi - lo) / SAMPLES;
    for (int i = 0; i <= SAMPLES; ++i) v[i] = err_at(e, i == SAMPLES ? hi : lo + h * i);
    int top[REFINE_TOP]; /* indices of the largest sampled local maxima, largest first */
    int ntop = 0;
    for (int i = 0; i <= SAMPLES; ++i) {
        int peak = (i == 0 || v[i] >= v[i - 1]) && (i == SAMPLES || v[i] >= v[i + 1]);
        if (!peak) continue;
        if (ntop == REFINE_TOP && v[i] <= v[top[ntop - 1]]) continue;
        int k = ntop < REFINE_TOP ? ntop++ : ntop - 1;
        while (k > 0 && v[top[k - 1]] < v[i]) {
            top[k] = top[k - 1];
            --k;
        }
        top[k] = i;
    }
    double best = 0.0;
    for (int i = 0; i <= SAMPLES; ++i) best = fmax(best, v[i]);
    for (int k = 0; k < ntop; ++k) {
        int i = top[k];
        double a = i > 0 ? lo + h * (i - 1) : lo;
        double b = i < SAMPLES ? lo + h * (i + 1) : hi;
        best = fmax(best, refine(e, a, b));
    }
    return best;
}

double abrdf__highlight_zone_cos(double n)
{
    double half = n > 0.0 ? pow(0.5, 1.0 / n) : 0.0;         /* cos^n = 1/2 */
    double inflection = n > 1.0 ? sqrt(1.0 - 1.0 / n) : 0.0; /* sin^2 theta_h = 1/n */
    return fmax(half, inflection);
}

int abrdf_approx_error_eval(abrdf_model approx, double n, abrdf_approx_error *out)
{
    if (!out) return ABRDF_E_NULL;
    memset(out, 0, sizeof *out);
    if (!is_table1(approx)) return ABRDF_E_MODEL;
    err_ctx e;
    abrdf_params pa, pb;
    abrdf_params_init(approx, &pa);
    abrdf_params_init(ABRDF_BLINN_PHONG, &pb);
    pa.n = pb.n = n;
    for (int c = 0; c < 3; ++c) pa.ks[c] = pb.ks[c] = 1.0;
    int st = abrdf_params_check(approx, &pa, NULL, 0);
    if (st != ABRDF_OK) return st;
    if ((st = abrdf_prepare(approx, &pa, &e.pa)) != ABRDF_OK) return st;
    if ((st = abrdf_prepare(ABRDF_BLINN_PHONG, &pb, &e.pb)) != ABRDF_OK) return st;

    double zone = abrdf__highlight_zone_cos(n);
    e.relative = 1;
    double rel = maximise(&e, zone, 1.0);
    e.relative = 0;
    double abs_err = maximise(&e, 0.0, 1.0);
    if (n > PEAK_WINDOW) abs_err = fmax(abs_err, maximise(&e, 1.0 - PEAK_WINDOW / n, 1.0));

    out->max_rel_pct = 100.0 * rel;
    out->max_abs = abs_err;
    out->zone_cos = zone;
    return ABRDF_OK;
}
