/* sample_dist.c - the 1-D densities of a cosine to an axis that the direction samplers draw
 * from (sample.h), each sampled by inverting its CDF in closed form, and the trimmed
 * logistic.
 *
 * POW, (n + 1) c^n: the cosine-power lobe of Phong, sampled about its axis as in
 *   E. Lafortune, Y. Willems, "Using the modified Phong reflectance model for physically
 *   based rendering", TR CW197, KU Leuven 1994: c = (1 - u)^(1/(n + 1)).
 * FM, ((n/m)(c - 1) + 1)^m (the paper's Table-1 power form): with b = (n/m)(c - 1) + 1 the
 *   CDF from c = 1 is (m/n)(1 - b^(m+1))/(m + 1), inverted in closed form.
 * SCHLICK, 1/(1 + n t), t = 1 - c: the tail of Schlick's c/(n - n c + c) (Graphics Gems IV,
 *   1994), whose ratio to this density is (1 - t)(1 + n t)/(1 + (n - 1) t) <= 1; CDF
 *   log(1 + n t)/log(1 + n).
 * LINEAR, 1 - a t: fkv's a c^2 + (1 - a) c = c (1 - a t) without its factor c <= 1.
 * BECKMANN, D cos: B. Walter, S. Marschner, H. Li, K. Torrance, "Microfacet models for
 *   refraction through rough surfaces", EGSR 2007, Eqs. 28-29: tan^2 = -alpha^2 log(1 - u).
 * GTR1, D cos: B. Burley, "Physically-Based Shading at Disney", SIGGRAPH 2012 course notes,
 *   App. B, Eq. 2: cos^2 = (1 - alpha^(2(1 - u)))/(1 - alpha^2).
 * Trimmed logistic: the density pbrt-v4 draws hair azimuths from (M. Pharr, W. Jakob,
 *   G. Humphreys, "Physically Based Rendering", 4th ed., Sec. 9.9), any interval. */
#include <math.h>

#include "sample.h"

/* t from sin^2 and cos without the cancellation of 1 - c near the axis. */
static double t_of(double c, double s2) { return c > 0.0 ? s2 / (1.0 + c) : 1.0 - c; }

static void make_uniform(abrdf__dist *d, double t_max)
{
    d->kind = ABRDF__DIST_UNIFORM;
    d->t_max = t_max;
    d->norm = 1.0 / t_max;
}

void abrdf__dist_setup(abrdf__dist *d, double lo)
{
    double t_dom = 1.0 - lo;
    d->t_max = 1.0;
    d->norm = 1.0;
    d->q = 0.0;
    switch (d->kind) {
    case ABRDF__DIST_UNIFORM: make_uniform(d, t_dom); break;
    case ABRDF__DIST_POW:
        if (!(d->n > 0.0)) make_uniform(d, t_dom); /* pow_pos(x, 0) = 1 on the whole domain */
        break;
    case ABRDF__DIST_FM: {
        double k = d->n / d->m; /* b = 1 - k t */
        if (!(k * t_dom >= ABRDF__SAMPLE_FLAT)) {
            make_uniform(d, t_dom);
            break;
        }
        d->t_max = fmin(t_dom, 1.0 / k);
        double b_end = 1.0 - k * d->t_max;
        d->q = b_end > 0.0 ? -expm1((d->m + 1) * log(b_end)) : 1.0;
        d->norm = d->q / (k * (d->m + 1)); /* integral of b^m dt over the support */
        break;
    }
    case ABRDF__DIST_SCHLICK:
        if (!(d->n >= ABRDF__SAMPLE_FLAT)) {
            make_uniform(d, 1.0);
            break;
        }
        d->norm = log1p(d->n) / d->n; /* integral of 1/(1 + n t) over [0, 1] */
        break;
    case ABRDF__DIST_LINEAR:
        d->t_max = d->a > 1.0 ? 1.0 / d->a : 1.0;
        if (!(d->a * d->t_max >= ABRDF__SAMPLE_FLAT)) {
            make_uniform(d, d->t_max);
            break;
        }
        d->norm = d->t_max - 0.5 * d->a * d->t_max * d->t_max;
        break;
    case ABRDF__DIST_GTR1:
        /* D_GTR1 = 1/pi at alpha = 1 (k_terms.h): D cos is then POW with n = 1 */
        if (1.0 - d->a * d->a < ABRDF__GTR1_ALPHA_ONE) {
            d->kind = ABRDF__DIST_POW;
            d->n = 1.0;
        }
        break;
    case ABRDF__DIST_BECKMANN: break;
    }
}

/* t = 1 - c of POW with exponent n for u in [0, 1). */
static double pow_sample(double n, double u) { return -expm1(log1p(-u) / (n + 1.0)); }

static double pow_pdf(double n, double c, double s2)
{
    if (!(c > 0.0)) return 0.0;
    double lc = c > 0.5 ? 0.5 * log1p(-s2) : log(c); /* log c, accurate near the axis */
    return (n + 1.0) * exp(n * lc);
}

double abrdf__dist_sample(const abrdf__dist *d, double u, double *s)
{
    double t = 0.0;
    switch (d->kind) {
    case ABRDF__DIST_UNIFORM: t = u * d->t_max; break;
    case ABRDF__DIST_POW: t = pow_sample(d->n, u); break;
    case ABRDF__DIST_FM: {
        /* b^(m+1) = 1 - u q, t = (m/n)(1 - b) */
        double one_minus_b = -expm1(log1p(-u * d->q) / (d->m + 1));
        t = fmin(d->t_max, one_minus_b * d->m / d->n);
        break;
    }
    case ABRDF__DIST_SCHLICK: t = fmin(1.0, expm1(u * log1p(d->n)) / d->n); break;
    case ABRDF__DIST_LINEAR: {
        double z = u * d->norm; /* a t^2/2 - t + z = 0, the root in [0, t_max] */
        t = fmin(d->t_max, 2.0 * z / (1.0 + sqrt(fmax(0.0, 1.0 - 2.0 * d->a * z))));
        break;
    }
    case ABRDF__DIST_BECKMANN: {
        double tan2 = -d->a * d->a * log1p(-u); /* Walter et al. 2007, Eq. 28 */
        double r = sqrt(1.0 + tan2);
        t = isinf(tan2) ? 1.0 : tan2 / ((1.0 + r) * r);
        *s = isinf(tan2) ? 1.0 : sqrt(tan2) / r;
        return t;
    }
    case ABRDF__DIST_GTR1: {
        double a2 = d->a * d->a, e = exp((1.0 - u) * log(a2));          /* alpha^(2(1 - u)) */
        double c2 = (1.0 - e) / (1.0 - a2), s2 = (e - a2) / (1.0 - a2); /* Burley, App. B */
        double c = sqrt(fmax(0.0, c2));
        *s = sqrt(fmax(0.0, s2));
        return fmax(0.0, s2) / (1.0 + c);
    }
    }
    t = fmin(fmax(t, 0.0), 2.0);
    *s = sqrt(fmax(0.0, t * (2.0 - t)));
    return t;
}

double abrdf__dist_pdf(const abrdf__dist *d, double c, double s2)
{
    double t = t_of(c, s2);
    switch (d->kind) {
    case ABRDF__DIST_UNIFORM: return t <= d->t_max ? d->norm : 0.0;
    case ABRDF__DIST_POW: return pow_pdf(d->n, c, s2);
    case ABRDF__DIST_FM: {
        if (!(t <= d->t_max)) return 0.0;
        double b = fmax(0.0, 1.0 - t * d->n / d->m);
        return pow(b, d->m) / d->norm;
    }
    case ABRDF__DIST_SCHLICK: return t <= 1.0 ? 1.0 / ((1.0 + d->n * t) * d->norm) : 0.0;
    case ABRDF__DIST_LINEAR: return t <= d->t_max ? fmax(0.0, 1.0 - d->a * t) / d->norm : 0.0;
    case ABRDF__DIST_BECKMANN: {
        if (!(c > 0.0)) return 0.0;
        double a2 = d->a * d->a;
        /* 2 pi D c = 2 exp(-tan^2/alpha^2) / (alpha^2 c^3), in log form (no Inf * 0) */
        return 2.0 / a2 * exp(-(s2 / (c * c)) / a2 - 3.0 * log(c));
    }
    case ABRDF__DIST_GTR1: {
        if (!(c > 0.0)) return 0.0;
        double a2 = d->a * d->a;
        return 2.0 * c * (a2 - 1.0) / (log(a2) * (s2 + a2 * c * c)); /* 2 pi D_GTR1 c */
    }
    }
    return 0.0;
}

/* ---- trimmed logistic ---------------------------------------------------------------- */

static double logistic_cdf(double x, double s) { return 1.0 / (1.0 + exp(-x / s)); }

/* Intervals are mirrored so that their midpoint is <= 0: the CDF values then lie in the
 * lower tail, where they keep their relative precision. */
double abrdf__tlogistic_sample(double s, double a, double b, double u)
{
    if (a + b > 0.0) return -abrdf__tlogistic_sample(s, -b, -a, ABRDF__SAMPLE_U_MAX - u);
    double fa = logistic_cdf(a, s), fb = logistic_cdf(b, s);
    double y = fa + u * (fb - fa);
    double x = -s * log((1.0 - y) / y);
    return fmin(fmax(x, a), b);
}

double abrdf__logistic_pdf(double x, double s)
{
    double e = exp(-fabs(x) / s);
    return e / (s * (1.0 + e) * (1.0 + e));
}

double abrdf__tlogistic_mass(double s, double a, double b)
{
    if (a + b > 0.0) return abrdf__tlogistic_mass(s, -b, -a);
    return logistic_cdf(b, s) - logistic_cdf(a, s);
}

double abrdf__tlogistic_pdf(double x, double s, double a, double b)
{
    if (!(x >= a && x <= b)) return 0.0;
    return abrdf__logistic_pdf(x, s) / abrdf__tlogistic_mass(s, a, b);
}
