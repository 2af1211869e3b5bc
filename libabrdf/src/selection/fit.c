/* fit.c - one reflectance model fitted to another (abrdf_fit.h).
 *
 * OBJECTIVE. Over a deterministic set of direction pairs (wi_j, wo_j) with solid-angle
 * weights q_j covering the hemisphere, minimise
 *     E = sum_j q_j cos^2(theta_i,j) sum_c w_jc (f_cand,c(wi_j, wo_j) - f_ref,c(wi_j, wo_j))^2,
 * the squared error of f cos(theta_i), the radiance a surface reflects per unit irradiance:
 * the cosine-weighted L2 of Lafortune et al. (SIGGRAPH 1997) and Ngan, Durand, Matusik
 * (EGSR 2005), who fitted analytic models to the MERL measurements with it. w_jc = 1 is that
 * metric (ABRDF_FIT_L2). Low et al. (ACM TOG 2012) fit log(1 + f cos) instead, which
 * compresses the highlight; Fores, Ferwerda, Gu (CIC 2012) found the cube root (f cos)^(1/3)
 * closer to perceived differences. Both are used here linearised about the reference,
 * g(a) - g(b) ~ g'(b) (a - b): w_jc = 1/(1 + y)^2 (ABRDF_FIT_LOG) and
 * w_jc = 1/(9 (y + y0)^(4/3)) (ABRDF_FIT_CBRT), y = f_ref,c cos(theta_i), y0 a floor of 1e-3
 * of the largest y, so that every metric stays a weighted least-squares problem.
 *
 * DIRECTION SET. Incidence: Gauss-Legendre nodes in cos(theta_i) (and midpoint nodes in the
 * tangent azimuth when a lobe reads the tangent frame). Outgoing: for lobes about the
 * mirror direction, the half vector h in (theta_h, phi_h) with wo = 2 (wi.h) h - wi and
 * dw_o = 4 (wi.h) dw_h, theta_h placed by a density with half its mass in a Cauchy bump
 * as wide as the reference's highlight (abrdf__brdf_highlight_width) and weighted by the
 * density's inverse, so a sharp lobe gets as many nodes as a broad one; for fibre models
 * (Kajiya-Kay, hair), whose highlight is a cone about the fibre, the longitudinal angle to
 * the fibre with the bump on the specular cone, and the azimuth about the fibre.
 *
 * OPTIMISER: variable projection (Golub & Pereyra 1973). A BRDF is linear in its weights: f
 * = fixed + kd D + ks S per channel, and a lobe with Schlick's Fresnel (Eq. 8) is linear in
 * (ks, ks f0): ks F(f0) S' = ks S'(f0=0) + ks f0 (S'(f0=1) - S'(f0=0)). For every trial of
 * the other ("searched") parameters the columns D, S, ... are evaluated and the weights of
 * each channel solved in closed form: the bounded least-squares problem (kd, ks in their
 * ranges, ks f0 in [f0_min ks, f0_max ks]) has at most three unknowns, so every active set
 * is tried and the best feasible point kept. E of a trial is then a function of the
 * searched parameters only (at most three, each in [0, 1] after a linear or log map of its
 * registry range): one is explored by a scan and golden-section search, several by a grid
 * and bounded Nelder-Mead (Nelder & Mead 1965) from the best grid points and the starting
 * points the paper's converters give (n <-> alpha_g, abrdf.h). Every step is deterministic
 * and its count bounded.
 *
 * ERRORS REPORTED (abrdf_fit_result): the relative L2 of f cos; the largest relative error
 * over the reference's highlight zone, the pairs where f_ref cos is at least half its largest
 * value for the same incidence (Table 2's zone for cos^n is the concave part of its half-
 * maximum cone, approx_error.c); and the largest absolute error of f cos relative to the
 * largest f_ref cos (Table 3's measure for a lobe of peak 1). */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "fit_internal.h"
#include "vec.h"

/* ---- what is fitted, per model (docs/SELECTION.md, "1. The fit") --------------------- */

typedef struct fit_param {
    const char *name; /* registry name of a searched parameter */
    int log;          /* searched in log space */
    double lo, hi;    /* search interval (intersected with the model's range) */
} fit_param;

typedef struct model_fit {
    int schlick;        /* linear in f0 through Schlick's F (Eq. 8), with ks */
    int affine;         /* has a part no weight (kd, ks) scales */
    int count;          /* searched parameters */
    fit_param param[3]; /* the searched parameters */
} model_fit;

#define N_LOG                                                                                      \
    {                                                                                              \
        "n", 1, 1.0, 1e6                                                                           \
    }
/* r of a microfacet lobe in log space: alpha_g = r^2 from 1e-6 (the floor) to 1. */
#define R_LOG                                                                                      \
    {                                                                                              \
        "r", 1, 1e-3, 1.0                                                                          \
    }

static const model_fit fit_table[ABRDF_MODEL_COUNT] = {
    [ABRDF_LAMBERT] = {0, 0, 0, {{0}}},
    [ABRDF_LAMBERT_FRESNEL] = {0, 0, 0, {{0}}}, /* f0 kept: kd (1 - F(f0)) is bilinear */
    [ABRDF_DISNEY_DIFFUSE] = {0, 0, 1, {{"r", 0, 0.0, 1.0}}},
    [ABRDF_OREN_NAYAR] = {0, 0, 1, {{"sigma", 0, 0.0, 1.5707963267948966}}},
    [ABRDF_PHONG] = {0, 0, 1, {N_LOG}},
    [ABRDF_BLINN_PHONG] = {0, 0, 1, {N_LOG}},
    [ABRDF_F2] = {0, 0, 1, {N_LOG}},
    [ABRDF_F4] = {0, 0, 1, {N_LOG}},
    [ABRDF_F8] = {0, 0, 1, {N_LOG}},
    [ABRDF_F16] = {0, 0, 1, {N_LOG}},
    [ABRDF_FS] = {0, 0, 1, {N_LOG}},
    [ABRDF_FKV] = {0, 0, 1, {N_LOG}},
    [ABRDF_FKUB] = {0, 0, 1, {N_LOG}},
    [ABRDF_F_PHE] = {0, 0, 1, {N_LOG}},
    [ABRDF_F_BE] = {0, 0, 1, {N_LOG}},
    [ABRDF_F_2E] = {0, 0, 1, {N_LOG}},
    [ABRDF_F_16E] = {0, 0, 1, {N_LOG}},
    [ABRDF_F_GE] = {1, 0, 1, {N_LOG}},
    [ABRDF_F_CTPHE] = {1, 0, 1, {N_LOG}},
    [ABRDF_F_CT2E] = {1, 0, 1, {N_LOG}},
    [ABRDF_F_CT16E] = {1, 0, 1, {N_LOG}},
    [ABRDF_COOK_TORRANCE] = {1, 0, 1, {R_LOG}},
    [ABRDF_DISNEY_SPECULAR] = {1, 0, 1, {R_LOG}},
    [ABRDF_DISNEY_SPECULAR_ANISO] = {1, 0, 2, {R_LOG, {"anisotropic", 0, 0.0, 1.0}}},
    [ABRDF_DISNEY_CLEARCOAT] = {0, 0, 1, {{"clearcoat_gloss", 0, 0.0, 1.0}}},
    /* f0 kept: it enters both the diffuse (1 - F) and the sheen F terms */
    [ABRDF_NEUBELT_PETTINEO] = {0, 0, 2, {{"r", 0, 0.0, 1.0}, {"k_amp", 1, 0.1, 100.0}}},
    [ABRDF_KAJIYA_KAY] = {0, 0, 1, {{"n", 1, 1.0, 1e4}}},
    /* no weight: longitudinal width, cuticle tilt and pigment are searched */
    [ABRDF_MARSCHNER] = {0,
                         1,
                         3,
                         {{"r", 1, 0.02, 1.0},
                          {"cuticle_tilt", 0, -10.0, 10.0},
                          {"melanin", 0, 0.0, 1.0}}},
    /* ~1 ms per evaluation: nothing is searched, it is the reference's stand-in for itself */
    [ABRDF_HUANG] = {0, 1, 0, {{0}}},
    [ABRDF_WEIDLICH_WILKIE] = {0, 1, 1, {{"layer0_r", 1, 1e-3, 1.0}}},
    [ABRDF_BELCOUR] = {0, 1, 0, {{0}}},
};

/* ---- the reference's highlight ------------------------------------------------------------ */

static double mean3(const double f[3]) { return (f[0] + f[1] + f[2]) / 3.0; }

/* f cos(theta_i) along a one-parameter family of outgoing directions dir(x) about x = 0;
 * returns the half-width above the family's floor around the largest value within
 * [-span, span] (and that value's x in *centre), or 1 if nothing stands out. */
typedef void (*dir_fn)(const double wi[3], double x, double wo[3]);

static double half_width(const abrdf__brdf *b, const double wi[3], dir_fn dir, double span,
                         double *centre)
{
    enum { STEPS = 48 };
    /* x = 0 and +-1e-4 * (span / 1e-4)^(k / STEPS): log spacing resolves widths from 1e-4 to
     * span with 20 % steps. */
    double xs[2 * STEPS + 1], vs[2 * STEPS + 1];
    int n = 0;
    for (int k = STEPS; k >= 1; --k)
        xs[n++] = -1e-4 * pow(span / 1e-4, (double)(k - 1) / (STEPS - 1));
    xs[n++] = 0.0;
    for (int k = 1; k <= STEPS; ++k)
        xs[n++] = 1e-4 * pow(span / 1e-4, (double)(k - 1) / (STEPS - 1));
    int best = STEPS;
    double floor_v = INFINITY;
    abrdf__brdf_prep bp;
    abrdf__brdf_prepare(b, &bp);
    for (int i = 0; i < n; ++i) {
        double wo[3], f[3];
        dir(wi, xs[i], wo);
        vs[i] = 0.0;
        if (wo[2] > 0.0) {
            abrdf__brdf_prep_eval(&bp, wi, wo, f);
            vs[i] = mean3(f) * wi[2];
        }
        floor_v = fmin(floor_v, vs[i]);
    }
    for (int i = 0; i < n; ++i)
        if (vs[i] > vs[best]) best = i;
    *centre = xs[best];
    double peak = vs[best], half = floor_v + 0.5 * (peak - floor_v);
    if (!(peak > 0.0) || !(peak > 1.5 * floor_v)) return 1.0;
    double w = span;
    for (int i = best + 1; i < n; ++i)
        if (vs[i] < half) {
            w = fmin(w, xs[i] - xs[best]);
            break;
        }
    for (int i = best - 1; i >= 0; --i)
        if (vs[i] < half) {
            w = fmin(w, xs[best] - xs[i]);
            break;
        }
    return w;
}

/* Half vector tilted by x radians toward the incidence azimuth; wo its mirror of wi. */
static void mirror_dir(const double wi[3], double x, double wo[3])
{
    double r = sqrt(wi[0] * wi[0] + wi[1] * wi[1]);
    double ux = r > 0.0 ? wi[0] / r : 1.0, uy = r > 0.0 ? wi[1] / r : 0.0;
    double h[3] = {sin(x) * ux, sin(x) * uy, cos(x)};
    double d = 2.0 * abrdf__dot3(wi, h);
    for (int c = 0; c < 3; ++c) wo[c] = d * h[c] - wi[c];
}

/* Outgoing direction in the fibre plane (T, N) at longitudinal angle -theta_i + x. */
static void fibre_dir(const double wi[3], double x, double wo[3])
{
    double t = -asin(fmax(-1.0, fmin(1.0, wi[0]))) + x;
    wo[0] = sin(t);
    wo[1] = 0.0;
    wo[2] = cos(t);
}

static double clamp_width(double w) { return fmax(ABRDF__FIT_WIDTH_MIN, fmin(1.0, w)); }

double abrdf__brdf_highlight_width(const abrdf__brdf *b)
{
    double c, ti = 30.0 * ABRDF__PI / 180.0;
    if (abrdf__brdf_is_fibre(b)) return 1.0;
    double wi[3] = {sin(ti), 0.0, cos(ti)};
    double w = half_width(b, wi, mirror_dir, 1.0, &c);
    if (fabs(c) > w) return 1.0;       /* no peak at the mirror direction */
    if (abrdf__brdf_uses_tangent(b)) { /* the narrower of the two tangent directions */
        double wj[3] = {0.0, sin(ti), cos(ti)};
        w = fmin(w, half_width(b, wj, mirror_dir, 1.0, &c));
    }
    return clamp_width(w);
}

/* Width and offset of a fibre model's highlight about the specular cone. */
static double fibre_width(const abrdf__brdf *b, double *shift)
{
    double ti = 30.0 * ABRDF__PI / 180.0, wi[3] = {sin(ti), 0.0, cos(ti)};
    double w = half_width(b, wi, fibre_dir, 0.6, shift);
    if (w >= 0.6) *shift = 0.0;
    return clamp_width(w);
}

/* ---- quadrature rules --------------------------------------------------------------------- */

/* Gauss-Legendre rule of n <= 32 nodes on (0, 1) (Newton on P_n from Tricomi's guesses). */
static void gauss_legendre01(int n, double *x, double *w)
{
    for (int i = 0; i < n; ++i) {
        double z = cos(ABRDF__PI * (i + 0.75) / (n + 0.5)), dp = 1.0;
        for (int it = 0; it < 100; ++it) {
            double p0 = 1.0, p1 = z;
            for (int k = 2; k <= n; ++k) {
                double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            if (n == 1) p0 = 1.0, p1 = z;
            dp = n * (z * p1 - p0) / (z * z - 1.0);
            double dz = p1 / dp;
            z -= dz;
            if (fabs(dz) < 1e-15) break;
        }
        x[i] = 0.5 * (1.0 - z);
        w[i] = 1.0 / ((1.0 - z * z) * dp * dp);
    }
}

/* m nodes on [a, b] with half of them in a Cauchy bump of width g at mu (share 0: uniform),
 * weights = interval share / density (midpoint rule in the cumulative). */
static double cauchy_cdf(double x, double a, double b, double mu, double g, double share)
{
    return (1.0 - share) * (x - a) / (b - a) +
           share * (atan((x - mu) / g) - atan((a - mu) / g)) / ABRDF__PI;
}

static void warped_nodes(int m, double a, double b, double mu, double g, double share, double *x,
                         double *w)
{
    double total = cauchy_cdf(b, a, b, mu, g, share);
    for (int j = 0; j < m; ++j) {
        double target = total * (j + 0.5) / m, lo = a, hi = b;
        for (int it = 0; it < 64; ++it) {
            double mid = 0.5 * (lo + hi);
            if (cauchy_cdf(mid, a, b, mu, g, share) < target)
                lo = mid;
            else
                hi = mid;
        }
        x[j] = 0.5 * (lo + hi);
        double d = (x[j] - mu) / g;
        double pdf = (1.0 - share) / (b - a) + share / (ABRDF__PI * g * (1.0 + d * d));
        w[j] = total / (m * pdf);
    }
}

/* ---- the direction set ------------------------------------------------------------------- */

enum { SET_ISO, SET_TANGENT, SET_FIBRE, SET_KINDS };
#define LEVELS 5
#define DEFAULT_LEVEL 2
/* Nodes per level: incidence cos(theta_i), incidence azimuth, outgoing polar, outgoing
 * azimuth. Level 2 (the default) holds 1920 (isotropic), 4608 (tangent) and 4704 (fibre)
 * pairs; each level has 2-4 times the previous one's. */
static const int set_dims[SET_KINDS][4][LEVELS] = {
    [SET_ISO] = {{4, 6, 8, 11, 16}, {1, 1, 1, 1, 1}, {10, 14, 20, 28, 40}, {6, 9, 12, 17, 24}},
    [SET_TANGENT] = {{3, 3, 4, 6, 8}, {4, 4, 6, 8, 12}, {8, 10, 12, 16, 24}, {10, 12, 16, 24, 32}},
    [SET_FIBRE] = {{2, 3, 4, 6, 8}, {3, 4, 6, 8, 12}, {8, 10, 14, 20, 28}, {8, 10, 14, 20, 28}},
};
#define DIM_MAX 40

static int set_pairs(int kind, int level)
{
    int n = 1;
    for (int d = 0; d < 4; ++d) n *= set_dims[kind][d][level];
    return n;
}

size_t abrdf__fit_bytes(int resolution)
{
    int level = abrdf__fit_level(resolution, 0); /* the larger of the two defaults */
    int n = 0;
    for (int k = 0; k < SET_KINDS; ++k)
        if (set_pairs(k, level) > n) n = set_pairs(k, level);
    /* the set: wi, wo, q, cosi, group, yref (12 per pair); the fit: four columns of three
     * channels, the metric weights and the current candidate's values (18 per pair). */
    return ((size_t)n * 30 + 64) * sizeof(double);
}

/* The pair (wi, wo) with weight q; wo must be above the surface. */
static void set_add(abrdf__fit_set *s, int group, const double wi[3], const double wo[3], double q)
{
    if (!(wo[2] > 1e-9) || !(q > 0.0)) return;
    int j = s->n++;
    memcpy(s->wi + 3 * j, wi, 3 * sizeof *wi);
    memcpy(s->wo + 3 * j, wo, 3 * sizeof *wo);
    s->cosi[j] = wi[2];
    s->q[j] = q * wi[2] * wi[2] * wo[2]; /* (f cos_i)^2 over the projected area cos_o */
    s->group[j] = group;
}

int abrdf__fit_set_make(abrdf__fit_set *s, const abrdf__brdf *ref, int tangent, int fibre,
                        int level, abrdf__arena *a)
{
    if (level < 0) level = 0;
    if (level >= LEVELS) level = LEVELS - 1;
    int kind = fibre ? SET_FIBRE : tangent ? SET_TANGENT : SET_ISO;
    int nm = set_dims[kind][0][level], na = set_dims[kind][1][level];
    int np = set_dims[kind][2][level], nq = set_dims[kind][3][level];
    size_t cap = (size_t)set_pairs(kind, level);
    memset(s, 0, sizeof *s);
    s->wi = abrdf__arena_doubles(a, 3 * cap);
    s->wo = abrdf__arena_doubles(a, 3 * cap);
    s->q = abrdf__arena_doubles(a, cap);
    s->cosi = abrdf__arena_doubles(a, cap);
    s->group = (int *)(void *)abrdf__arena_doubles(a, cap);
    s->yref = abrdf__arena_doubles(a, 3 * cap);
    if (a->failed) return ABRDF_E_SIZE;
    s->tangent = tangent || fibre;
    s->fibre = fibre;
    double shift = 0.0;
    s->width = fibre ? fibre_width(ref, &shift) : abrdf__brdf_highlight_width(ref);
    double xm[DIM_MAX], wm[DIM_MAX], xp[DIM_MAX], wp[DIM_MAX];
    gauss_legendre01(nm, xm, wm);
    double share = s->width < 0.5 ? 0.5 : 0.0;
    for (int i = 0; i < nm; ++i)
        for (int k = 0; k < na; ++k) {
            double mu = xm[i], st = sqrt(fmax(0.0, 1.0 - mu * mu));
            /* isotropic: one azimuth stands for all (weight 2 pi); else midpoint nodes */
            double phi = kind == SET_ISO ? 0.0 : 2.0 * ABRDF__PI * (k + 0.5) / na;
            double wi[3] = {st * cos(phi), st * sin(phi), mu};
            double qi = wm[i] * 2.0 * ABRDF__PI / na;
            int group = i * na + k;
            s->groups = group + 1;
            if (kind == SET_FIBRE) {
                /* wo = (sin t, cos t sin p, cos t cos p): t longitudinal angle to the fibre
                 * (T = +x), p the azimuth about it; dw = cos t dt dp, p in (-pi/2, pi/2). */
                double tc = -asin(fmax(-1.0, fmin(1.0, wi[0]))) + shift;
                warped_nodes(np, -0.5 * ABRDF__PI, 0.5 * ABRDF__PI, tc, s->width, share, xp, wp);
                for (int u = 0; u < np; ++u)
                    for (int v = 0; v < nq; ++v) {
                        double p = -0.5 * ABRDF__PI + ABRDF__PI * (v + 0.5) / nq;
                        double ct = cos(xp[u]);
                        double wo[3] = {sin(xp[u]), ct * sin(p), ct * cos(p)};
                        set_add(s, group, wi, wo, qi * wp[u] * ct * ABRDF__PI / nq);
                    }
                continue;
            }
            /* half vectors about N; isotropic: phi_h in [0, pi] stands for both halves */
            warped_nodes(np, 0.0, 0.5 * ABRDF__PI, 0.0, s->width, share, xp, wp);
            double span = kind == SET_ISO ? ABRDF__PI : 2.0 * ABRDF__PI;
            double mult = kind == SET_ISO ? 2.0 : 1.0;
            for (int u = 0; u < np; ++u)
                for (int v = 0; v < nq; ++v) {
                    double ph = span * (v + 0.5) / nq, sh = sin(xp[u]);
                    double h[3] = {sh * cos(ph), sh * sin(ph), cos(xp[u])};
                    double d = abrdf__dot3(wi, h), wo[3];
                    if (!(d > 0.0)) continue;
                    for (int c = 0; c < 3; ++c) wo[c] = 2.0 * d * h[c] - wi[c];
                    /* dw_o = 4 (wi.h) dw_h, dw_h = sin(theta_h) dtheta_h dphi_h */
                    set_add(s, group, wi, wo, qi * wp[u] * sh * (span / nq) * mult * 4.0 * d);
                }
        }
    abrdf__brdf_prep bp;
    abrdf__brdf_prepare(ref, &bp);
    for (int j = 0; j < s->n; ++j)
        abrdf__brdf_prep_eval(&bp, s->wi + 3 * j, s->wo + 3 * j, s->yref + 3 * j);
    return ABRDF_OK;
}

/* ---- the candidate's parameters ----------------------------------------------------------- */

/* Does model m read parameter id? */
static int reads(abrdf_model m, int id)
{
    if (m == ABRDF_MODEL_NONE) return 0;
    const abrdf_model_info *mi = abrdf_model_get(m);
    for (int k = 0; k < mi->param_count; ++k)
        if (mi->params[k].id == id) return 1;
    return 0;
}

static int brdf_reads(const abrdf__brdf *b, int id)
{
    return reads(b->lobe[0], id) || reads(b->lobe[1], id);
}

/* The range the BRDF's lobes allow for parameter id (intersection). */
static void brdf_range(const abrdf__brdf *b, int id, double *lo, double *hi)
{
    const abrdf_param_info *pi = abrdf_param_get(id);
    *lo = pi->min;
    *hi = pi->max;
    for (int l = 0; l < 2; ++l) {
        if (b->lobe[l] == ABRDF_MODEL_NONE) continue;
        const abrdf_model_info *mi = abrdf_model_get(b->lobe[l]);
        for (int k = 0; k < mi->param_count; ++k)
            if (mi->params[k].id == id) {
                *lo = fmax(*lo, mi->params[k].min);
                *hi = fmin(*hi, mi->params[k].max);
            }
    }
}

static double clampd(double v, double lo, double hi) { return v < lo ? lo : (v > hi ? hi : v); }

void abrdf__fit_start(const abrdf__brdf *ref, abrdf__brdf *cand)
{
    cand->prepared = NULL;
    abrdf_params_init(cand->lobe[1] != ABRDF_MODEL_NONE ? cand->lobe[1] : cand->lobe[0], &cand->p);
    if (cand->lobe[0] != ABRDF_MODEL_NONE && cand->lobe[1] != ABRDF_MODEL_NONE) {
        /* the diffuse lobe's own parameters at its defaults too */
        abrdf_params d;
        abrdf_params_init(cand->lobe[0], &d);
        const abrdf_model_info *mi = abrdf_model_get(cand->lobe[0]);
        for (int k = 0; k < mi->param_count; ++k) {
            int id = mi->params[k].id;
            double v[3];
            if (reads(cand->lobe[1], id)) continue;
            int cnt = abrdf_param_read(&d, id, v);
            if (cnt > 0) abrdf_param_set(&cand->p, id, v, cnt);
        }
    }
    int count = abrdf_param_count();
    for (int id = 0; id < count; ++id) {
        if (!brdf_reads(cand, id) || !brdf_reads(ref, id)) continue;
        double v[3], lo, hi;
        int cnt = abrdf_param_read(&ref->p, id, v);
        brdf_range(cand, id, &lo, &hi);
        for (int c = 0; c < cnt; ++c) v[c] = clampd(v[c], lo, hi);
        if (cnt > 0) abrdf_param_set(&cand->p, id, v, cnt);
    }
}

/* ---- the fit's working state -------------------------------------------------------------- */

enum { COL_FIXED, COL_KD, COL_KS, COL_B, COLS };
#define SEARCH_MAX 3

typedef struct fit_work {
    const abrdf__fit_set *s;
    const abrdf__brdf *ref;
    abrdf__brdf *cand;
    /* searched parameters */
    int ns, sid[SEARCH_MAX], slog[SEARCH_MAX];
    double slo[SEARCH_MAX], shi[SEARCH_MAX];
    /* linear structure */
    int has[COLS];           /* column used */
    int idx[COLS];           /* its coefficient index (COL_KD..COL_B), -1 if unused */
    int m;                   /* coefficients per channel */
    int lobe_varies[2];      /* the lobe reads a searched parameter */
    int held[2];             /* the lobe is the reference's own, kept as it is */
    int lobe_schlick[2];     /* linear in f0 through ks f0 */
    int kd_id, ks_id, f0_id; /* registry ids of kd, ks, f0 */
    double kd_lo, kd_hi, ks_lo, ks_hi, f0_lo, f0_hi;
    double *cconst; /* COLS * 3n: the columns of lobes that do not vary */
    double *wmet;   /* 3n: metric weights */
    /* the best trial */
    double best_e, best_x[SEARCH_MAX], best_c[3][3];
    double cur_c[3][3];
    int evals;
} fit_work;

/* Lobe l prepared with the four unit blocks (unit_blocks): fixed, kd, ks (f0 = 0), ks (f0 = 1). */
typedef struct lobe_units {
    abrdf__lobe_prep u[4];
    int affine, kd, ks, schlick; /* what the lobe contributes */
} lobe_units;

static void lobe_units_prepare(const fit_work *w, int l, const abrdf_params blk[4], lobe_units *lu)
{
    abrdf_model m = w->cand->lobe[l];
    for (int k = 0; k < 4; ++k) abrdf__lobe_prepare(&lu->u[k], m, &blk[k]);
    lu->kd = w->has[COL_KD] && reads(m, w->kd_id) && !w->held[l];
    lu->ks = w->has[COL_KS] && reads(m, w->ks_id) && !w->held[l];
    lu->schlick = w->lobe_schlick[l];
    /* a part no solved weight scales: the model's own, or weights held at their values */
    lu->affine = fit_table[m].affine || w->held[l] || (reads(m, w->kd_id) && !lu->kd) ||
                 (reads(m, w->ks_id) && !lu->ks);
}

/* Contributions of a prepared lobe at pair j to the columns g. */
static void lobe_columns(const fit_work *w, const lobe_units *lu, int j, double g[COLS][3])
{
    const double *wi = w->s->wi + 3 * j, *wo = w->s->wo + 3 * j;
    double fx[3] = {0, 0, 0}, f[3], f1[3];
    if (lu->affine) {
        abrdf__lobe_eval(&lu->u[0], wi, wo, fx);
        for (int c = 0; c < 3; ++c) g[COL_FIXED][c] += fx[c];
    }
    if (lu->kd) {
        abrdf__lobe_eval(&lu->u[1], wi, wo, f);
        for (int c = 0; c < 3; ++c) g[COL_KD][c] += f[c] - fx[c];
    }
    if (lu->ks) {
        abrdf__lobe_eval(&lu->u[2], wi, wo, f);
        for (int c = 0; c < 3; ++c) g[COL_KS][c] += f[c] - fx[c];
        if (lu->schlick) {
            abrdf__lobe_eval(&lu->u[3], wi, wo, f1);
            for (int c = 0; c < 3; ++c) g[COL_B][c] += f1[c] - f[c];
        }
    }
}

/* The blocks for unit weights: fixed (kd = ks = 0), kd = 1, ks = 1 with f0 = 0 (or the
 * kept f0 when no lobe is linear in it), ks = 1 with f0 = 1. */
static void unit_blocks(const fit_work *w, abrdf_params *pfix, abrdf_params *pkd,
                        abrdf_params *pks0, abrdf_params *pks1)
{
    *pfix = w->cand->p; /* the solved weights at 0, held ones at their values */
    for (int c = 0; c < 3; ++c) {
        if (w->has[COL_KD]) pfix->kd[c] = 0.0;
        if (w->has[COL_KS]) pfix->ks[c] = 0.0;
    }
    *pkd = *pfix;
    *pks0 = *pfix;
    for (int c = 0; c < 3; ++c) {
        pkd->kd[c] = 1.0;
        pks0->ks[c] = 1.0;
        if (w->has[COL_B]) pks0->f0[c] = 0.0;
    }
    *pks1 = *pks0;
    for (int c = 0; c < 3; ++c) pks1->f0[c] = 1.0;
}

/* ---- bounded least squares of at most three unknowns ------------------------------------- */

/* Solve the n x n system A x = b (n <= 6) by Gaussian elimination with partial pivoting;
 * 0 if singular. */
static int solve(int n, double A[6][6], double b[6], double x[6])
{
    for (int k = 0; k < n; ++k) {
        int p = k;
        for (int i = k + 1; i < n; ++i)
            if (fabs(A[i][k]) > fabs(A[p][k])) p = i;
        if (!(fabs(A[p][k]) > 1e-300)) return 0;
        if (p != k) {
            for (int j = 0; j < n; ++j) {
                double t = A[k][j];
                A[k][j] = A[p][j];
                A[p][j] = t;
            }
            double t = b[k];
            b[k] = b[p];
            b[p] = t;
        }
        for (int i = k + 1; i < n; ++i) {
            double f = A[i][k] / A[k][k];
            for (int j = k; j < n; ++j) A[i][j] -= f * A[k][j];
            b[i] -= f * b[k];
        }
    }
    for (int i = n - 1; i >= 0; --i) {
        double s = b[i];
        for (int j = i + 1; j < n; ++j) s -= A[i][j] * x[j];
        x[i] = s / A[i][i];
        if (!isfinite(x[i])) return 0;
    }
    return 1;
}

/* Minimise c'Mc - 2 v'c subject to rows a_r c <= beta_r: every active set of at most m rows
 * is solved (KKT system) and the feasible solution of least value kept (the problem is
 * convex, so that is the minimum). Returns the value c'Mc - 2 v'c. */
static double bounded_lsq(int m, const double M[3][3], const double v[3], int rows,
                          const double a[6][3], const double beta[6], double c[3])
{
    double best = INFINITY;
    for (int k = 0; k < m; ++k) c[k] = 0.0;
    for (unsigned set = 0; set < (1u << rows); ++set) {
        int act[6], na = 0;
        for (int r = 0; r < rows; ++r)
            if (set >> r & 1u) act[na++] = r;
        if (na > m) continue;
        double A[6][6] = {{0}}, b[6] = {0}, x[6];
        int n = m + na;
        for (int i = 0; i < m; ++i) {
            for (int j = 0; j < m; ++j) A[i][j] = M[i][j];
            b[i] = v[i];
        }
        for (int r = 0; r < na; ++r) {
            for (int j = 0; j < m; ++j) A[m + r][j] = A[j][m + r] = a[act[r]][j];
            b[m + r] = beta[act[r]];
        }
        if (!solve(n, A, b, x)) continue;
        int ok = 1;
        for (int r = 0; r < rows && ok; ++r) {
            double s = 0.0;
            for (int j = 0; j < m; ++j) s += a[r][j] * x[j];
            ok = s <= beta[r] + 1e-12 * (1.0 + fabs(beta[r]));
        }
        if (!ok) continue;
        double val = 0.0;
        for (int i = 0; i < m; ++i) {
            double s = 0.0;
            for (int j = 0; j < m; ++j) s += M[i][j] * x[j];
            val += x[i] * s - 2.0 * v[i] * x[i];
        }
        if (val < best) {
            best = val;
            for (int k = 0; k < m; ++k) c[k] = x[k];
        }
        if (set == 0) break; /* the unconstrained minimum is feasible: it is the answer */
    }
    return best;
}

/* ---- the objective ------------------------------------------------------------------------ */

static double x_to_value(const fit_work *w, int k, double x)
{
    x = clampd(x, 0.0, 1.0);
    double v = w->slog[k] ? w->slo[k] * pow(w->shi[k] / w->slo[k], x)
                          : w->slo[k] + x * (w->shi[k] - w->slo[k]);
    return clampd(v, w->slo[k], w->shi[k]);
}

static double value_to_x(const fit_work *w, int k, double v)
{
    v = clampd(v, w->slo[k], w->shi[k]);
    if (w->shi[k] <= w->slo[k]) return 0.5;
    return w->slog[k] ? log(v / w->slo[k]) / log(w->shi[k] / w->slo[k])
                      : (v - w->slo[k]) / (w->shi[k] - w->slo[k]);
}

static void set_search(fit_work *w, const double *x)
{
    for (int k = 0; k < w->ns; ++k) {
        double v = x_to_value(w, k, x[k]);
        abrdf_param_set(&w->cand->p, w->sid[k], &v, 1);
    }
}

/* The columns of the varying lobes at the current searched values, plus the constant ones. */
static void columns_at(const fit_work *w, int j, double g[COLS][3], const lobe_units *lu, int nlu)
{
    const double *cc = w->cconst + (size_t)j * COLS * 3;
    memcpy(g, cc, sizeof(double) * COLS * 3);
    for (int k = 0; k < nlu; ++k) lobe_columns(w, &lu[k], j, g);
}

static void constraints(const fit_work *w, int *rows, double a[6][3], double beta[6])
{
    int r = 0;
    memset(a, 0, sizeof(double) * 18);
    if (w->idx[COL_KD] >= 0) {
        int i = w->idx[COL_KD];
        a[r][i] = -1.0, beta[r++] = -w->kd_lo;
        a[r][i] = 1.0, beta[r++] = w->kd_hi;
    }
    if (w->idx[COL_KS] >= 0) {
        int i = w->idx[COL_KS];
        a[r][i] = -1.0, beta[r++] = -w->ks_lo;
        a[r][i] = 1.0, beta[r++] = w->ks_hi;
        if (w->idx[COL_B] >= 0) { /* f0_lo ks <= b <= f0_hi ks */
            int b = w->idx[COL_B];
            a[r][i] = w->f0_lo, a[r][b] = -1.0, beta[r++] = 0.0;
            a[r][i] = -w->f0_hi, a[r][b] = 1.0, beta[r++] = 0.0;
        }
    }
    *rows = r;
}

/* E at searched point x (in [0, 1]^ns); the channels' coefficients go to w->cur_c. */
static double objective(fit_work *w, const double *x)
{
    set_search(w, x);
    abrdf_params blk[4];
    unit_blocks(w, &blk[0], &blk[1], &blk[2], &blk[3]);
    lobe_units lu[2];
    int nlu = 0;
    for (int l = 0; l < 2; ++l)
        if (w->cand->lobe[l] != ABRDF_MODEL_NONE && w->lobe_varies[l])
            lobe_units_prepare(w, l, blk, &lu[nlu++]);
    int m = w->m;
    double M[3][3][3] = {{{0}}}, v[3][3] = {{0}}, yy[3] = {0};
    const abrdf__fit_set *s = w->s;
    for (int j = 0; j < s->n; ++j) {
        double g[COLS][3];
        columns_at(w, j, g, lu, nlu);
        for (int c = 0; c < 3; ++c) {
            double q = s->q[j] * w->wmet[3 * j + c];
            double y = s->yref[3 * j + c] - g[COL_FIXED][c];
            double col[3];
            for (int k = COL_KD; k < COLS; ++k)
                if (w->idx[k] >= 0) col[w->idx[k]] = g[k][c];
            yy[c] += q * y * y;
            for (int a = 0; a < m; ++a) {
                v[c][a] += q * col[a] * y;
                for (int b = 0; b <= a; ++b) M[c][a][b] += q * col[a] * col[b];
            }
        }
    }
    double e = 0.0, a[6][3], beta[6];
    int rows;
    constraints(w, &rows, a, beta);
    for (int c = 0; c < 3; ++c) {
        for (int i = 0; i < m; ++i)
            for (int k = 0; k < i; ++k) M[c][k][i] = M[c][i][k];
        double val = m ? bounded_lsq(m, M[c], v[c], rows, a, beta, w->cur_c[c]) : 0.0;
        e += fmax(0.0, yy[c] + val);
    }
    ++w->evals;
    if (e < w->best_e) {
        w->best_e = e;
        for (int k = 0; k < w->ns; ++k) w->best_x[k] = clampd(x[k], 0.0, 1.0);
        memcpy(w->best_c, w->cur_c, sizeof w->best_c);
    }
    return e;
}

/* ---- the search over the nonlinear parameters --------------------------------------------- */

#define SCAN_1D 21   /* coarse scan of one parameter: steps of 5 % of its (log) range */
#define GOLDEN_1D 20 /* golden-section steps: the bracket (1/10 of the range) shrinks to 1e-5 */
#define GRID_2D 6    /* 36 points for two parameters */
#define GRID_3D 4    /* 64 points for three */
#define NM_ITER 60   /* Nelder-Mead iterations per parameter */
#define NM_TOL 1e-4  /* stop when the simplex spans less than this in every coordinate */

static void golden(fit_work *w, double a, double b)
{
    const double r = 0.6180339887498949;
    double x1 = b - r * (b - a), x2 = a + r * (b - a);
    double f1 = objective(w, &x1), f2 = objective(w, &x2);
    for (int i = 0; i < GOLDEN_1D; ++i) {
        if (f1 <= f2) {
            b = x2, x2 = x1, f2 = f1;
            x1 = b - r * (b - a);
            f1 = objective(w, &x1);
        } else {
            a = x1, x1 = x2, f1 = f2;
            x2 = a + r * (b - a);
            f2 = objective(w, &x2);
        }
    }
}

/* Bounded Nelder-Mead (coordinates clamped into [0, 1]) from x0 with step h. */
static void nelder_mead(fit_work *w, const double *x0, double h)
{
    int d = w->ns;
    double p[SEARCH_MAX + 1][SEARCH_MAX], f[SEARCH_MAX + 1];
    for (int i = 0; i <= d; ++i) {
        for (int k = 0; k < d; ++k) p[i][k] = x0[k];
        if (i > 0) p[i][i - 1] += p[i][i - 1] + h <= 1.0 ? h : -h;
        f[i] = objective(w, p[i]);
    }
    for (int it = 0; it < NM_ITER * d; ++it) {
        /* order: best first */
        for (int i = 1; i <= d; ++i)
            for (int j = i; j > 0 && f[j] < f[j - 1]; --j) {
                double t = f[j];
                f[j] = f[j - 1], f[j - 1] = t;
                for (int k = 0; k < d; ++k) t = p[j][k], p[j][k] = p[j - 1][k], p[j - 1][k] = t;
            }
        double span = 0.0;
        for (int i = 1; i <= d; ++i)
            for (int k = 0; k < d; ++k) span = fmax(span, fabs(p[i][k] - p[0][k]));
        if (span < NM_TOL) break;
        double cen[SEARCH_MAX] = {0}, xr[SEARCH_MAX], xe[SEARCH_MAX], xc[SEARCH_MAX];
        for (int i = 0; i < d; ++i)
            for (int k = 0; k < d; ++k) cen[k] += p[i][k] / d;
        for (int k = 0; k < d; ++k) xr[k] = clampd(2.0 * cen[k] - p[d][k], 0.0, 1.0);
        double fr = objective(w, xr);
        if (fr < f[0]) {
            for (int k = 0; k < d; ++k) xe[k] = clampd(3.0 * cen[k] - 2.0 * p[d][k], 0.0, 1.0);
            double fe = objective(w, xe);
            const double *keep = fe < fr ? xe : xr;
            for (int k = 0; k < d; ++k) p[d][k] = keep[k];
            f[d] = fmin(fe, fr);
        } else if (fr < f[d - 1]) {
            for (int k = 0; k < d; ++k) p[d][k] = xr[k];
            f[d] = fr;
        } else {
            for (int k = 0; k < d; ++k) xc[k] = 0.5 * (cen[k] + p[d][k]);
            double fc = objective(w, xc);
            if (fc < f[d]) {
                for (int k = 0; k < d; ++k) p[d][k] = xc[k];
                f[d] = fc;
            } else { /* shrink toward the best */
                for (int i = 1; i <= d; ++i) {
                    for (int k = 0; k < d; ++k) p[i][k] = 0.5 * (p[0][k] + p[i][k]);
                    f[i] = objective(w, p[i]);
                }
            }
        }
    }
}

/* Starting values of the searched parameters from the reference: its own value of the same
 * parameter, or the paper's converters between n and r (Walter et al. 2007). */
static double start_value(const fit_work *w, int k)
{
    int id = w->sid[k];
    const abrdf_param_info *pi = abrdf_param_get(id);
    double v[3], cur[3];
    abrdf_param_read(&w->cand->p, id, cur);
    int rid, nid;
    abrdf_param_find("r", &rid);
    abrdf_param_find("n", &nid);
    if (brdf_reads(w->ref, id)) {
        abrdf_param_read(&w->ref->p, id, v);
        return v[0];
    }
    if (!strcmp(pi->name, "n") && brdf_reads(w->ref, rid))
        return abrdf_alpha_g_to_n(abrdf_r_to_alpha_g(w->ref->p.r));
    if (!strcmp(pi->name, "r") && brdf_reads(w->ref, nid))
        return abrdf_alpha_g_to_r(abrdf_n_to_alpha_g(w->ref->p.n));
    /* a measured table reads no parameter: the GGX lobe its sampler fitted at prepare
     * (measured.h) gives r and, through the converters, n */
    if (w->ref->prepared && w->ref->prepared->model == ABRDF_MEASURED) {
        double ag = w->ref->prepared->special.measured.alpha;
        if (!strcmp(pi->name, "r")) return abrdf_alpha_g_to_r(ag);
        if (!strcmp(pi->name, "n")) return abrdf_alpha_g_to_n(ag);
    }
    return cur[0];
}

static void search(fit_work *w)
{
    double x[SEARCH_MAX] = {0}, start[SEARCH_MAX] = {0};
    for (int k = 0; k < w->ns; ++k) start[k] = value_to_x(w, k, start_value(w, k));
    if (w->ns == 0) {
        objective(w, x);
        return;
    }
    objective(w, start);
    if (w->ns == 1) {
        double best_f = INFINITY;
        int best = 0;
        for (int i = 0; i < SCAN_1D; ++i) {
            x[0] = (double)i / (SCAN_1D - 1);
            double f = objective(w, x);
            if (f < best_f) best_f = f, best = i;
        }
        double step = 1.0 / (SCAN_1D - 1);
        /* refine around the better of the scan's best and the converter's start */
        double c = w->best_x[0];
        (void)best;
        golden(w, fmax(0.0, c - step), fmin(1.0, c + step));
        return;
    }
    int g = w->ns == 2 ? GRID_2D : GRID_3D, total = 1;
    for (int k = 0; k < w->ns; ++k) total *= g;
    double first[SEARCH_MAX], first_f = INFINITY, second[SEARCH_MAX], second_f = INFINITY;
    for (int i = 0; i < total; ++i) {
        int r = i;
        for (int k = 0; k < w->ns; ++k) {
            x[k] = (r % g + 0.5) / g;
            r /= g;
        }
        double f = objective(w, x);
        if (f < first_f) {
            memcpy(second, first, sizeof first);
            second_f = first_f;
            memcpy(first, x, sizeof x);
            first_f = f;
        } else if (f < second_f) {
            memcpy(second, x, sizeof x);
            second_f = f;
        }
    }
    double h = 0.5 / g;
    nelder_mead(w, start, h);
    nelder_mead(w, first, h);
    if (isfinite(second_f)) nelder_mead(w, second, h);
    /* Each parameter scanned over its whole range from the best point, the others held: the
     * grid is cell-centred (no point at a range's end), and a lobe whose weight the solve
     * sets to 0 leaves its own parameters flat, where Nelder-Mead stops anywhere (r of a
     * specular lobe the fit switched off). A better point found starts a last Nelder-Mead. */
    double e0 = w->best_e;
    for (int k = 0; k < w->ns; ++k) {
        double y[SEARCH_MAX];
        memcpy(y, w->best_x, sizeof y);
        for (int i = 0; i < SCAN_1D; ++i) {
            y[k] = (double)i / (SCAN_1D - 1);
            objective(w, y);
        }
    }
    if (w->best_e < e0 * (1.0 - 1e-9)) { /* not on rounding alone (a lobe switched off) */
        double b[SEARCH_MAX];
        memcpy(b, w->best_x, sizeof b);
        nelder_mead(w, b, h);
    }
}

/* ---- running a fit ------------------------------------------------------------------------- */

static void metric_weights(const abrdf__fit_set *s, abrdf_fit_metric metric, double *wm)
{
    double ymax = 0.0;
    for (int j = 0; j < 3 * s->n; ++j) ymax = fmax(ymax, s->yref[j] * s->cosi[j / 3]);
    double y0 = 1e-3 * ymax + DBL_MIN; /* the cube root's floor: 1e-3 of the largest value */
    for (int j = 0; j < 3 * s->n; ++j) {
        double y = fmax(0.0, s->yref[j] * s->cosi[j / 3]);
        if (metric == ABRDF_FIT_LOG)
            wm[j] = 1.0 / ((1.0 + y) * (1.0 + y)); /* d log(1 + y) = dy / (1 + y) */
        else if (metric == ABRDF_FIT_CBRT)
            wm[j] = 1.0 / (9.0 * pow(y + y0, 4.0 / 3.0)); /* d y^(1/3) = dy / (3 y^(2/3)) */
        else
            wm[j] = 1.0;
    }
}

void abrdf__fit_errors(const abrdf__fit_set *s, const abrdf__brdf *cand, abrdf_fit_result *res)
{
    double num = 0.0, den = 0.0, ymax = 0.0, dmax = 0.0, rel = 0.0;
    /* the log and cube-root metrics, exact: squared differences of g(f cos) with the set's
     * solid-angle weights (q without its cos^2(theta_i), which g's argument carries) */
    double lnum = 0.0, lden = 0.0, cnum = 0.0, cden = 0.0;
    abrdf__brdf_prep bp;
    abrdf__brdf_prepare(cand, &bp);
    /* the highlight zone: per incidence group, pairs with f_ref cos >= half the group's max */
    for (int g0 = 0; g0 < s->n;) {
        int g1 = g0;
        double gmax = 0.0;
        while (g1 < s->n && s->group[g1] == s->group[g0]) {
            gmax = fmax(gmax, mean3(s->yref + 3 * g1) * s->cosi[g1]);
            ++g1;
        }
        for (int j = g0; j < g1; ++j) {
            double f[3];
            abrdf__brdf_prep_eval(&bp, s->wi + 3 * j, s->wo + 3 * j, f);
            int zone = mean3(s->yref + 3 * j) * s->cosi[j] >= 0.5 * gmax && gmax > 0.0;
            for (int c = 0; c < 3; ++c) {
                double y = s->yref[3 * j + c], d = f[c] - y;
                num += s->q[j] * d * d;
                den += s->q[j] * y * y;
                ymax = fmax(ymax, y * s->cosi[j]);
                dmax = fmax(dmax, fabs(d) * s->cosi[j]);
                if (zone && y > 0.0) rel = fmax(rel, fabs(d) / y);
                double qa = s->q[j] / (s->cosi[j] * s->cosi[j]);
                double a = fmax(0.0, f[c]) * s->cosi[j], b = fmax(0.0, y) * s->cosi[j];
                double gl = log1p(a) - log1p(b), gc = cbrt(a) - cbrt(b);
                lnum += qa * gl * gl;
                lden += qa * log1p(b) * log1p(b);
                cnum += qa * gc * gc;
                cden += qa * cbrt(b) * cbrt(b);
            }
        }
        g0 = g1;
    }
    res->rel_l2 = den > 0.0 ? sqrt(num / den) : (num > 0.0 ? INFINITY : 0.0);
    res->max_rel_pct = 100.0 * rel;
    res->max_abs = ymax > 0.0 ? dmax / ymax : (dmax > 0.0 ? INFINITY : 0.0);
    res->rel_log = lden > 0.0 ? sqrt(lnum / lden) : (lnum > 0.0 ? INFINITY : 0.0);
    res->rel_cbrt = cden > 0.0 ? sqrt(cnum / cden) : (cnum > 0.0 ? INFINITY : 0.0);
}

void abrdf__fit_run(const abrdf__fit_set *s, const abrdf__brdf *ref, abrdf__brdf *cand,
                    abrdf_fit_metric metric, int keep_shared, abrdf__pred *pr,
                    abrdf_fit_result *res, abrdf__arena *a)
{
    size_t mark = a->used;
    fit_work w;
    memset(&w, 0, sizeof w);
    w.s = s;
    w.ref = ref;
    w.cand = cand;
    w.best_e = INFINITY;
    abrdf_param_find("kd", &w.kd_id);
    abrdf_param_find("ks", &w.ks_id);
    abrdf_param_find("f0", &w.f0_id);
    int kd_id = w.kd_id, ks_id = w.ks_id, f0_id = w.f0_id;
    /* a lobe the candidate shares with the reference keeps the reference's parameters (the
     * fit changes only what it replaces); so does every parameter such a lobe reads */
    for (int l = 0; l < 2; ++l)
        w.held[l] = keep_shared && cand->lobe[l] != ABRDF_MODEL_NONE &&
                    (cand->lobe[l] == ref->lobe[0] || cand->lobe[l] == ref->lobe[1]);
    /* searched parameters: every free lobe's, each once */
    for (int l = 0; l < 2; ++l) {
        abrdf_model m = cand->lobe[l];
        if (m == ABRDF_MODEL_NONE || w.held[l]) continue;
        for (int k = 0; k < fit_table[m].count && w.ns < SEARCH_MAX; ++k) {
            int id, dup = 0;
            abrdf_param_find(fit_table[m].param[k].name, &id);
            for (int i = 0; i < w.ns; ++i) dup |= w.sid[i] == id;
            for (int h = 0; h < 2; ++h) dup |= w.held[h] && reads(cand->lobe[h], id);
            if (dup) continue;
            double lo, hi;
            brdf_range(cand, id, &lo, &hi);
            w.sid[w.ns] = id;
            w.slog[w.ns] = fit_table[m].param[k].log;
            w.slo[w.ns] = fmax(lo, fit_table[m].param[k].lo);
            w.shi[w.ns] = fmin(hi, fit_table[m].param[k].hi);
            if (!(w.shi[w.ns] > w.slo[w.ns])) continue; /* nothing to search */
            ++w.ns;
        }
    }
    /* linear structure: a weight is solved when a free lobe reads it and no held one does */
    int f0_readers = reads(cand->lobe[0], f0_id) + reads(cand->lobe[1], f0_id);
    int held_kd = 0, held_ks = 0;
    for (int l = 0; l < 2; ++l)
        if (w.held[l])
            held_kd |= reads(cand->lobe[l], kd_id), held_ks |= reads(cand->lobe[l], ks_id);
    for (int l = 0; l < 2; ++l) {
        abrdf_model m = cand->lobe[l];
        if (m == ABRDF_MODEL_NONE || w.held[l]) continue;
        w.has[COL_KD] |= reads(m, kd_id) && !held_kd;
        w.has[COL_KS] |= reads(m, ks_id) && !held_ks;
        w.lobe_schlick[l] = fit_table[m].schlick && reads(m, f0_id) && f0_readers == 1 &&
                            reads(m, ks_id) && !held_ks;
        w.has[COL_B] |= w.lobe_schlick[l];
        for (int k = 0; k < w.ns; ++k) w.lobe_varies[l] |= reads(m, w.sid[k]);
    }
    for (int l = 0; l < 2; ++l)
        if (cand->lobe[l] != ABRDF_MODEL_NONE)
            w.has[COL_FIXED] |= fit_table[cand->lobe[l]].affine || w.held[l];
    w.m = 0;
    for (int k = 0; k < COLS; ++k) w.idx[k] = -1;
    for (int k = COL_KD; k < COLS; ++k)
        if (w.has[k]) w.idx[k] = w.m++;
    brdf_range(cand, kd_id, &w.kd_lo, &w.kd_hi);
    brdf_range(cand, ks_id, &w.ks_lo, &w.ks_hi);
    brdf_range(cand, f0_id, &w.f0_lo, &w.f0_hi);
    w.cconst = abrdf__arena_doubles(a, (size_t)s->n * COLS * 3);
    w.wmet = abrdf__arena_doubles(a, 3 * (size_t)s->n);
    if (a->failed) {
        snprintf(res->message, sizeof res->message, "the workspace is too small for the fit");
        a->used = mark;
        return;
    }
    metric_weights(s, metric, w.wmet);
    /* the constant columns, with the starting block */
    abrdf_params blk[4];
    unit_blocks(&w, &blk[0], &blk[1], &blk[2], &blk[3]);
    memset(w.cconst, 0, sizeof(double) * (size_t)s->n * COLS * 3);
    for (int l = 0; l < 2; ++l) {
        if (cand->lobe[l] == ABRDF_MODEL_NONE || w.lobe_varies[l]) continue;
        lobe_units lu;
        lobe_units_prepare(&w, l, blk, &lu);
        for (int j = 0; j < s->n; ++j)
            lobe_columns(&w, &lu, j, (double(*)[3])(w.cconst + (size_t)j * COLS * 3));
    }
    search(&w);
    /* the best trial's parameters (+ 0.0: a weight the solve left at -0 is written as 0) */
    set_search(&w, w.best_x);
    for (int c = 0; c < 3; ++c) {
        if (w.idx[COL_KD] >= 0)
            cand->p.kd[c] = clampd(w.best_c[c][w.idx[COL_KD]], w.kd_lo, w.kd_hi) + 0.0;
        if (w.idx[COL_KS] >= 0) {
            double ks = clampd(w.best_c[c][w.idx[COL_KS]], w.ks_lo, w.ks_hi) + 0.0;
            cand->p.ks[c] = ks;
            if (w.idx[COL_B] >= 0 && ks > 0.0)
                cand->p.f0[c] = clampd(w.best_c[c][w.idx[COL_B]] / ks, w.f0_lo, w.f0_hi);
        }
    }
    res->objective = w.best_e;
    res->metric = metric;
    res->evals += w.evals;
    res->fitted = 3 * w.m + w.ns;
    res->directions = s->n;
    abrdf__fit_errors(s, cand, res);
    res->nmse_pred = pr ? abrdf__pred_nmse(pr, cand) : -1.0;
    a->used = mark;
}

/* ---- the public entry points ------------------------------------------------------------- */

#define END_OF(type, field) (offsetof(type, field) + sizeof(((type *)0)->field))
#define OPTIONS_SIZE_0_3 END_OF(abrdf_fit_options, keep_shared)
#define RESULT_SIZE_0_3 END_OF(abrdf_fit_result, message)

static const char *const metric_names[ABRDF_FIT_METRIC_COUNT] = {"l2", "log", "cbrt", "auto"};

const char *abrdf_fit_metric_name(abrdf_fit_metric m)
{
    return ((int)m >= 0 && m < ABRDF_FIT_METRIC_COUNT) ? metric_names[m] : NULL;
}

int abrdf_fit_metric_find(const char *name, abrdf_fit_metric *out)
{
    if (!name || !out) return ABRDF_E_NULL;
    for (int i = 0; i < ABRDF_FIT_METRIC_COUNT; ++i)
        if (!strcmp(name, metric_names[i])) {
            *out = (abrdf_fit_metric)i;
            return ABRDF_OK;
        }
    return ABRDF_E_RANGE;
}

static void options_defaults(abrdf_fit_options *o)
{
    memset(o, 0, sizeof *o);
    o->struct_size = sizeof *o;
    o->metric = ABRDF_FIT_L2;
    o->predict = 1;
    o->keep_shared = 1;
}

static void result_empty(abrdf_fit_result *r)
{
    memset(r, 0, sizeof *r);
    r->struct_size = sizeof *r;
    r->rel_l2 = r->max_rel_pct = r->max_abs = r->nmse_pred = r->objective = -1.0;
    r->rel_log = r->rel_cbrt = -1.0;
}

/* An _init: the defaults in the caller's struct_size bytes. */
static int init_sized(void *p, size_t size, size_t min, const void *d, size_t full)
{
    if (!p) return ABRDF_E_NULL;
    if (size < min) return ABRDF_E_SIZE;
    memset(p, 0, size);
    memcpy(p, d, size < full ? size : full);
    *(size_t *)p = size;
    return ABRDF_OK;
}

int abrdf_fit_options_init_sized(abrdf_fit_options *o, size_t struct_size)
{
    abrdf_fit_options d;
    options_defaults(&d);
    return init_sized(o, struct_size, OPTIONS_SIZE_0_3, &d, sizeof d);
}

int abrdf_fit_result_init_sized(abrdf_fit_result *r, size_t struct_size)
{
    abrdf_fit_result d;
    result_empty(&d);
    return init_sized(r, struct_size, RESULT_SIZE_0_3, &d, sizeof d);
}

/* The caller's options over the defaults; 0 if struct_size is too small. */
static int read_options(const abrdf_fit_options *opt, abrdf_fit_options *o)
{
    options_defaults(o);
    if (!opt) return 1;
    if (opt->struct_size < OPTIONS_SIZE_0_3) return 0;
    memcpy(o, opt, opt->struct_size < sizeof *o ? opt->struct_size : sizeof *o);
    o->struct_size = sizeof *o;
    return 1;
}

size_t abrdf_fit_workspace_size(const abrdf_fit_options *opt, const abrdf_view *view)
{
    abrdf_fit_options o;
    if (!read_options(opt, &o) || o.resolution < 0 || o.resolution > LEVELS) return 0;
    size_t p = abrdf__pred_bytes(view, 0);
    if (!p) return 0;
    return p + abrdf__fit_bytes(o.resolution) + 256;
}

int abrdf__fit_level(int resolution, int integrating)
{
    /* The default even for hair (~1 ms per evaluation, seconds per fit): the coarser sets
     * place Kajiya-Kay's cone between their nodes and fit it to a wrong width (a predicted
     * NMSE of 41 at level 1 against 0.14 at level 2, hair_brown). */
    (void)integrating;
    if (resolution > 0) return resolution < LEVELS ? resolution - 1 : LEVELS - 1;
    return DEFAULT_LEVEL;
}

/* The fit of the candidate to a reference already made (abrdf_fit, abrdf_fit_to): st is
 * ABRDF_OK so far, or the status whose message r holds. Returns the status; on success
 * cand_params receives the fitted block in the caller's layout. */
static int fit_against(int st, const abrdf__brdf *ref, abrdf_model cand_diffuse,
                       abrdf_model cand_specular, abrdf_params *cand_params,
                       const abrdf_fit_options *o, abrdf_fit_result *rr, void *work,
                       size_t work_size)
{
    abrdf_fit_result r = *rr;
    abrdf__brdf cand;
    abrdf__arena a;
    if (st != ABRDF_OK) {
        /* message set */
    } else if (cand_diffuse == ABRDF_MODEL_NONE && cand_specular == ABRDF_MODEL_NONE) {
        st = ABRDF_E_MODEL;
        snprintf(r.message, sizeof r.message, "the candidate has no model (both lobes are none)");
    } else if (!(cand_diffuse == ABRDF_MODEL_NONE || abrdf_model_get(cand_diffuse)) ||
               !(cand_specular == ABRDF_MODEL_NONE || abrdf_model_get(cand_specular))) {
        st = ABRDF_E_MODEL;
        snprintf(r.message, sizeof r.message, "the candidate names an unknown model id");
    } else if ((cand_diffuse != ABRDF_MODEL_NONE &&
                (abrdf_model_get(cand_diffuse)->needs & ABRDF_NEEDS_TABLE)) ||
               (cand_specular != ABRDF_MODEL_NONE &&
                (abrdf_model_get(cand_specular)->needs & ABRDF_NEEDS_TABLE))) {
        st = ABRDF_E_MODEL;
        snprintf(r.message, sizeof r.message,
                 "the candidate evaluates a caller's table: it has nothing to fit");
    } else if (cand_params->struct_size < END_OF(abrdf_params, layers)) {
        st = ABRDF_E_SIZE;
        snprintf(r.message, sizeof r.message,
                 "abrdf_params: struct_size %zu is below its 0.2.0 layout: initialise the "
                 "candidate's block with abrdf_params_init",
                 cand_params->struct_size);
    } else {
        cand.lobe[0] = cand_diffuse;
        cand.lobe[1] = cand_specular;
        abrdf__fit_start(ref, &cand);
        int integrating =
            ((abrdf__brdf_needs(ref) | abrdf__brdf_needs(&cand)) & ABRDF_NEEDS_INTEGRATION) != 0;
        abrdf__arena_init(&a, work, work_size);
        abrdf__pred pr, *ppr = NULL;
        abrdf__fit_set s;
        if (o->predict) {
            st = abrdf__pred_prepare(&pr, o->view, ref, integrating, &a, r.message,
                                     sizeof r.message);
            ppr = &pr;
        }
        if (st == ABRDF_OK) {
            int tangent = abrdf__brdf_uses_tangent(ref) || abrdf__brdf_uses_tangent(&cand) ||
                          (cand_specular == ABRDF_DISNEY_SPECULAR_ANISO);
            int fibre = abrdf__brdf_is_fibre(ref) || abrdf__brdf_is_fibre(&cand);
            if (abrdf__fit_set_make(&s, ref, tangent, fibre,
                                    abrdf__fit_level(o->resolution, integrating), &a) != ABRDF_OK) {
                st = ABRDF_E_SIZE;
                snprintf(r.message, sizeof r.message,
                         "the workspace (%zu bytes) is too small: abrdf_fit_workspace_size",
                         work_size);
            }
        }
        if (st == ABRDF_OK) {
            if (o->metric != ABRDF_FIT_AUTO) {
                abrdf__fit_run(&s, ref, &cand, o->metric, o->keep_shared, ppr, &r, &a);
            } else { /* Bieron & Peers 2020: each metric's fit, the best rendered one kept */
                abrdf__brdf start = cand, best = cand;
                abrdf_fit_result rb = r;
                int evals = 0, have = 0;
                for (int k = 0; k < ABRDF_FIT_AUTO; ++k) {
                    abrdf_fit_result rk;
                    result_empty(&rk);
                    cand = start;
                    abrdf__fit_run(&s, ref, &cand, (abrdf_fit_metric)k, o->keep_shared, ppr, &rk,
                                   &a);
                    evals += rk.evals;
                    if (rk.message[0]) {
                        rb = rk; /* the workspace: reported below */
                        break;
                    }
                    /* the first metric's fit, then any with a lower error (ties: the first) */
                    double err = ppr ? rk.nmse_pred : rk.rel_l2;
                    double best_err = ppr ? rb.nmse_pred : rb.rel_l2;
                    if (!have || err < best_err) {
                        best = cand;
                        rb = rk;
                        have = 1;
                    }
                }
                r = rb;
                r.evals = evals;
                cand = best;
            }
            if (r.message[0]) st = ABRDF_E_SIZE;
        }
        if (st == ABRDF_OK) {
            /* the fitted block in the caller's layout */
            size_t size = cand_params->struct_size;
            cand.p.struct_size = size;
            memcpy(cand_params, &cand.p, size < sizeof cand.p ? size : sizeof cand.p);
        }
    }
    *rr = r;
    return st;
}

/* The checks every fit makes before its reference: ABRDF_OK (o filled), or the status with
 * its message in r. */
static int fit_checks(const char *fn, int have_blocks, const abrdf_fit_options *opt,
                      abrdf_fit_options *o, abrdf_fit_result *r)
{
    if (!have_blocks) {
        snprintf(r->message, sizeof r->message, "%s: a parameter block or the workspace is NULL",
                 fn);
        return ABRDF_E_NULL;
    }
    if (!read_options(opt, o)) {
        snprintf(r->message, sizeof r->message,
                 "abrdf_fit_options: struct_size %zu is below its first layout: initialise it "
                 "with abrdf_fit_options_init",
                 opt->struct_size);
        return ABRDF_E_SIZE;
    }
    if (!((int)o->metric >= 0 && o->metric < ABRDF_FIT_METRIC_COUNT) || o->resolution < 0 ||
        o->resolution > LEVELS) {
        snprintf(r->message, sizeof r->message,
                 "abrdf_fit_options: metric %d is unknown or resolution %d is outside [0, %d]",
                 (int)o->metric, o->resolution, LEVELS);
        return ABRDF_E_RANGE;
    }
    return ABRDF_OK;
}

/* The result into the caller's struct, in its layout. */
static void result_copy(abrdf_fit_result *res, abrdf_fit_result *r)
{
    size_t size = res->struct_size;
    r->struct_size = size;
    memcpy(res, r, size < sizeof *r ? size : sizeof *r);
}

int abrdf_fit(abrdf_model ref_diffuse, abrdf_model ref_specular, const abrdf_params *ref_params,
              abrdf_model cand_diffuse, abrdf_model cand_specular, abrdf_params *cand_params,
              const abrdf_fit_options *opt, abrdf_fit_result *res, void *work, size_t work_size)
{
    if (!res) return ABRDF_E_NULL;
    if (res->struct_size < RESULT_SIZE_0_3) return ABRDF_E_SIZE; /* nowhere to say why */
    abrdf_fit_result r;
    result_empty(&r);
    abrdf_fit_options o;
    abrdf__brdf ref;
    int st = fit_checks("abrdf_fit", ref_params && cand_params && work, opt, &o, &r);
    if (st == ABRDF_OK)
        st = abrdf__brdf_make(&ref, ref_diffuse, ref_specular, ref_params, r.message,
                              sizeof r.message);
    st = fit_against(st, &ref, cand_diffuse, cand_specular, cand_params, &o, &r, work, work_size);
    result_copy(res, &r);
    return st;
}

int abrdf_fit_to(const abrdf_prepared *reference, abrdf_model cand_diffuse,
                 abrdf_model cand_specular, abrdf_params *cand_params, const abrdf_fit_options *opt,
                 abrdf_fit_result *res, void *work, size_t work_size)
{
    if (!res) return ABRDF_E_NULL;
    if (res->struct_size < RESULT_SIZE_0_3) return ABRDF_E_SIZE; /* nowhere to say why */
    abrdf_fit_result r;
    result_empty(&r);
    abrdf_fit_options o;
    abrdf__brdf ref;
    int st = fit_checks("abrdf_fit_to", cand_params && work, opt, &o, &r);
    if (st == ABRDF_OK)
        st = abrdf__brdf_from_prepared(&ref, reference, r.message, sizeof r.message);
    st = fit_against(st, &ref, cand_diffuse, cand_specular, cand_params, &o, &r, work, work_size);
    result_copy(res, &r);
    return st;
}
