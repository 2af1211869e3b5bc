/* test_grid.c - parameter sets from registry metadata, field access, random directions and
 * the albedo quadrature shared by the property suites (see test_grid.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test_grid.h"

#define PI 3.14159265358979323846

/* ---- parameter values per kind, by parameter name (names are part of the ABI) ------- */

typedef struct tg_vals {
    const char *name;
    int count;
    double v[6][3]; /* one RGB triple per value; scalars use v[k][0] */
} tg_vals;

#define S(x)                                                                                       \
    {                                                                                              \
        x, x, x                                                                                    \
    }
static const tg_vals typical[] = {
    {"kd", 2, {S(1.0), {0.25, 0.5, 1.0}}},
    {"ks", 2, {S(1.0), {0.25, 0.5, 1.0}}},
    {"f0", 3, {S(0.0), S(0.04), S(1.0)}},
    {"n", 5, {S(0.5), S(2.0), S(10.0), S(100.0), S(1000.0)}},
    {"r", 4, {S(0.1), S(0.3), S(0.7), S(1.0)}},
    {"anisotropic", 3, {S(0.0), S(0.5), S(1.0)}},
    {"sigma", 3, {S(0.0), S(0.3), S(1.0)}},
    {"clearcoat_gloss", 3, {S(0.0), S(0.5), S(1.0)}},
};
/* Unit weights; lobes no sharper than Phong n = 100 or alpha_g = 0.09, which the adaptive
 * quadrature resolves (tg_albedo_converged proves it per case). f0 is not listed: Schlick's
 * F grows with F0 at every angle, so the worst case is F0 = 1 for a specular lobe and
 * F0 = 0 for a diffuse lobe scaled by (1 - F); param_values picks it from the model's
 * ABRDF_PROP_DIFFUSE / ABRDF_PROP_SPECULAR flags. */
static const tg_vals furnace[] = {
    {"kd", 1, {S(1.0)}},
    {"ks", 1, {S(1.0)}},
    {"n", 5, {S(0.0), S(1.0), S(4.0), S(20.0), S(100.0)}},
    {"r", 3, {S(0.3), S(0.6), S(1.0)}},
    {"anisotropic", 2, {S(0.5), S(1.0)}}, /* 0 is the isotropic model (test_closed_form) */
    {"sigma", 4, {S(0.1), S(0.3), S(0.8), S(1.5707963267948966)}},
    {"clearcoat_gloss", 2, {S(0.0), S(0.5)}},
};
/* The hard cases; every parameter also gets its model's min and max. */
static const tg_vals hard[] = {
    {"kd", 2, {S(0.0), S(1.0)}},
    {"ks", 2, {S(0.0), S(1.0)}},
    {"f0", 3, {S(0.0), S(0.04), S(1.0)}},
    {"n", 5, {S(0.0), S(1.0), S(100.0), S(1e4), S(1e6)}},
    {"r", 5, {S(0.0), S(1e-8), S(1e-4), S(0.5), S(1.0)}},
    {"anisotropic", 3, {S(0.0), S(0.5), S(1.0)}},
    {"sigma", 2, {S(0.0), S(1.5707963267948966)}},
    {"clearcoat_gloss", 2, {S(0.0), S(1.0)}},
};
#undef S

static const tg_vals *find_vals(const tg_vals *t, int n, const char *name)
{
    for (int i = 0; i < n; ++i)
        if (!strcmp(t[i].name, name)) return &t[i];
    return NULL;
}

/* The values of one model parameter for `kind`, inside the model's range, deduplicated. */
static int param_values(tg_kind kind, unsigned props, const abrdf_model_param *mp, double out[8][3])
{
    const abrdf_param_info *pi = abrdf_param_get(mp->id);
    const tg_vals *v = NULL;
    if (kind == TG_TYPICAL)
        v = find_vals(typical, (int)(sizeof typical / sizeof *typical), pi->name);
    if (kind == TG_FURNACE)
        v = find_vals(furnace, (int)(sizeof furnace / sizeof *furnace), pi->name);
    if (kind == TG_HARD) v = find_vals(hard, (int)(sizeof hard / sizeof *hard), pi->name);
    double cand[8][3];
    int nc = 0;
    if (v)
        for (int k = 0; k < v->count; ++k) memcpy(cand[nc++], v->v[k], sizeof cand[0]);
    if (kind == TG_FURNACE && !strcmp(pi->name, "f0")) {
        double w = (props & ABRDF_PROP_SPECULAR) ? 1.0 : 0.0;
        cand[nc][0] = cand[nc][1] = cand[nc][2] = w;
        ++nc;
    } else if (!v) { /* a parameter these lists do not know: the model's default */
        cand[nc][0] = cand[nc][1] = cand[nc][2] = mp->def;
        ++nc;
    }
    if (kind == TG_HARD) {
        /* A quadrature grid's maximum only multiplies the work (huang at 32 x 32 nodes takes
         * seconds per value); its minimum, one node, is the hard case. */
        int work_only = !strcmp(pi->name, "entry_grid") || !strcmp(pi->name, "internal_grid");
        cand[nc][0] = cand[nc][1] = cand[nc][2] = mp->min;
        ++nc;
        if (!work_only) {
            cand[nc][0] = cand[nc][1] = cand[nc][2] = mp->max;
            ++nc;
        }
    }
    int n = 0;
    for (int k = 0; k < nc; ++k) {
        int ok = 1;
        for (int c = 0; c < 3; ++c) ok &= cand[k][c] >= mp->min && cand[k][c] <= mp->max;
        for (int j = 0; j < n && ok; ++j) ok = memcmp(out[j], cand[k], sizeof cand[k]) != 0;
        if (ok) memcpy(out[n++], cand[k], sizeof cand[k]);
    }
    if (n == 0) { /* none in range: the default keeps the set usable */
        out[0][0] = out[0][1] = out[0][2] = mp->def;
        n = 1;
    }
    return n;
}

void *tg_param_ptr(abrdf_params *p, int id)
{
    const abrdf_param_info *pi = abrdf_param_get(id);
    if (!pi) return NULL;
    const char *nm = pi->name;
#define F(field)                                                                                   \
    if (!strcmp(nm, #field)) return (void *)&p->field
    F(kd);
    F(ks);
    F(f0);
    F(n);
    F(r);
    F(anisotropic);
    F(sigma);
    F(clearcoat_gloss);
    F(k_amp);
    F(eta);
    F(melanin);
    F(redness);
    F(cuticle_tilt);
    F(aspect_ratio);
    F(layer_count);
    F(entry_grid);
    F(internal_grid);
#undef F
    int k;
    char rest[32];
    if (sscanf(nm, "layer%d_%31s", &k, rest) == 2 && k >= 0 && k < ABRDF_MAX_LAYERS) {
        abrdf_layer *l = &p->layers[k];
        if (!strcmp(rest, "eta")) return &l->eta;
        if (!strcmp(rest, "kappa")) return &l->kappa;
        if (!strcmp(rest, "r")) return &l->r;
        if (!strcmp(rest, "sigma_a")) return l->sigma_a;
        if (!strcmp(rest, "depth")) return &l->depth;
    }
    return NULL;
}

static void store(abrdf_params *p, int id, const double v[3])
{
    const abrdf_param_info *pi = abrdf_param_get(id);
    void *ptr = tg_param_ptr(p, id);
    if (!ptr) return;
    if (pi->kind == ABRDF_PARAM_INT)
        *(int *)ptr = (int)v[0];
    else if (pi->kind == ABRDF_PARAM_RGB)
        memcpy(ptr, v, 3 * sizeof(double));
    else
        *(double *)ptr = v[0];
}

static void label_append(char *buf, size_t size, const char *name, const double v[3], int rgb)
{
    size_t l = strlen(buf);
    if (l >= size) return;
    if (rgb && (v[0] != v[1] || v[1] != v[2]))
        snprintf(buf + l, size - l, "%s%s=%g,%g,%g", l ? " " : "", name, v[0], v[1], v[2]);
    else
        snprintf(buf + l, size - l, "%s%s=%g", l ? " " : "", name, v[0]);
}

#define TG_MAXP 32

int tg_param_sets(abrdf_model model, tg_kind kind, tg_set *out, int max)
{
    const abrdf_model_info *m = abrdf_model_get(model);
    if (!m || max < 1) return 0;
    int np = m->param_count < TG_MAXP ? m->param_count : TG_MAXP;
    double vals[TG_MAXP][8][3];
    int nv[TG_MAXP];
    double product = 1.0;
    for (int i = 0; i < np; ++i) {
        nv[i] = param_values(kind, m->props, &m->params[i], vals[i]);
        product *= nv[i];
    }
    int idx[TG_MAXP];
    int count = 0;
    tg_rng rng = {0x9e3779b97f4a7c15ull ^ (unsigned long long)model};
    long total = product <= max ? (long)product : max;
    for (long s = 0; s < total; ++s) {
        if (product <= max) { /* full product: mixed-radix digits of s */
            long q = s;
            for (int i = 0; i < np; ++i) {
                idx[i] = (int)(q % nv[i]);
                q /= nv[i];
            }
        } else { /* defaults, then one parameter at a time, then random combinations */
            long q = s;
            for (int i = 0; i < np; ++i) idx[i] = 0;
            int walked = 0;
            for (int i = 0; i < np && !walked; ++i) {
                if (q < nv[i] - 1) {
                    idx[i] = (int)q + 1;
                    walked = 1;
                } else
                    q -= nv[i] - 1;
            }
            if (!walked && s > 0)
                for (int i = 0; i < np; ++i) idx[i] = (int)(tg_uniform(&rng) * nv[i]);
        }
        tg_set *t = &out[count++];
        abrdf_params_init(model, &t->p);
        t->label[0] = '\0';
        for (int i = 0; i < np; ++i) {
            store(&t->p, m->params[i].id, vals[i][idx[i]]);
            if (nv[i] > 1)
                label_append(t->label, sizeof t->label, abrdf_param_get(m->params[i].id)->name,
                             vals[i][idx[i]],
                             abrdf_param_get(m->params[i].id)->kind == ABRDF_PARAM_RGB);
        }
        if (!t->label[0]) snprintf(t->label, sizeof t->label, "defaults");
    }
    return count;
}

/* ---- random directions ------------------------------------------------------------ */

double tg_uniform(tg_rng *r)
{
    r->s ^= r->s >> 12;
    r->s ^= r->s << 25;
    r->s ^= r->s >> 27;
    unsigned long long x = r->s * 2685821657736338717ull;
    return (double)(x >> 11) * (1.0 / 9007199254740992.0);
}

void tg_sphere(tg_rng *r, double out[3])
{
    double z = 2.0 * tg_uniform(r) - 1.0, phi = 2.0 * PI * tg_uniform(r);
    double s = sqrt(fmax(0.0, 1.0 - z * z));
    out[0] = s * cos(phi);
    out[1] = s * sin(phi);
    out[2] = z;
}

void tg_hemisphere(tg_rng *r, double out[3])
{
    tg_sphere(r, out);
    out[2] = fabs(out[2]);
}

void tg_mirror(const double w[3], double out[3])
{
    out[0] = -w[0];
    out[1] = -w[1];
    out[2] = w[2];
}

#define TG_MAXBP 1024

/* ---- albedo quadrature -------------------------------------------------------------- */

/* 8-point Gauss-Legendre on [-1, 1] (exact for polynomials of degree <= 15). */
static const double gl_x[8] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290,
                               -0.1834346424956498, 0.1834346424956498,  0.5255324099163290,
                               0.7966664774136267,  0.9602898564975363};
static const double gl_w[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
                               0.3626837833783620, 0.3626837833783620, 0.3137066458778873,
                               0.2223810344533745, 0.1012285362903763};

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double tg_albedo(abrdf_model model, const abrdf_params *p, const double wi[3], int panels, int nphi,
                 long *evals)
{
    /* Every lobe of the library peaks at (or near) the mirror direction, at mu_r = cos
     * theta_i and azimuth phi_r = phi_i + pi. Panel breakpoints are graded geometrically
     * towards mu_r (mu_r +- 2^-k) on top of the uniform ones, and the azimuth is sampled
     * through the smooth periodic map phi = phi_r + 2 atan(C tan(psi / 2)), which puts 1/C
     * times more points near phi_r; the trapezoid rule in psi stays spectrally accurate. */
    const double C = 0.25;
    double bp[TG_MAXBP];
    int nb = 0;
    double mur = fmin(1.0, fmax(0.0, wi[2]));
    for (int k = 0; k <= panels; ++k) bp[nb++] = (double)k / panels;
    for (int k = 1; k <= 10; ++k) {
        double d = ldexp(1.0, -k);
        if (mur - d > 0.0) bp[nb++] = mur - d;
        if (mur + d < 1.0) bp[nb++] = mur + d;
    }
    if (mur > 0.0 && mur < 1.0) bp[nb++] = mur;
    qsort(bp, (size_t)nb, sizeof *bp, cmp_double);
    double phir = atan2(-wi[1], -wi[0]);
    double sum[3] = {0, 0, 0};
    double dpsi = 2.0 * PI / nphi;
    long n = 0;
    for (int k = 0; k + 1 < nb; ++k) {
        double a = bp[k], h = bp[k + 1] - a;
        if (!(h > 0.0)) continue;
        for (int j = 0; j < 8; ++j) {
            double mu = a + 0.5 * h * (gl_x[j] + 1.0);
            double wmu = 0.5 * h * gl_w[j];
            double s = sqrt(fmax(0.0, 1.0 - mu * mu));
            for (int q = 0; q < nphi; ++q) {
                double psi = -PI + (q + 0.5) * dpsi, t = tan(0.5 * psi);
                double phi = phir + 2.0 * atan(C * t);
                double c2 = cos(0.5 * psi), s2 = sin(0.5 * psi);
                double jac = C / (c2 * c2 + C * C * s2 * s2); /* dphi/dpsi */
                double wo[3] = {s * cos(phi), s * sin(phi), mu}, f[3];
                if (abrdf_eval(model, p, NULL, wi, wo, f) != ABRDF_OK) return -1.0;
                for (int c = 0; c < 3; ++c) sum[c] += f[c] * mu * wmu * jac * dpsi;
                ++n;
            }
        }
    }
    if (evals) *evals += n;
    return fmax(sum[0], fmax(sum[1], sum[2]));
}

double tg_albedo_converged(abrdf_model model, const abrdf_params *p, const double wi[3], double tol,
                           int max_level, double *diff, int *level, long *evals)
{
    int panels = 4, nphi = 32;
    double prev = tg_albedo(model, p, wi, panels, nphi, evals), cur = prev, d = INFINITY;
    int l = 0;
    while (l < max_level) {
        panels *= 2;
        nphi *= 2;
        ++l;
        cur = tg_albedo(model, p, wi, panels, nphi, evals);
        d = fabs(cur - prev);
        if (cur < 0.0 || prev < 0.0) break;
        if (d <= tol) break;
        prev = cur;
    }
    if (diff) *diff = d;
    if (level) *level = l;
    return cur;
}
