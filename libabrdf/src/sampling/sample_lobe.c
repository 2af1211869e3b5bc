/* sample_lobe.c - the components a model's sampler mixes (sample.h): each draws a local
 * direction wi for a local wo above the surface and gives its solid-angle density; every
 * one is a density over the whole sphere that integrates to 1.
 *
 * COSINE: cos(theta)/pi, by Malley's method (a uniform disk point lifted to the hemisphere;
 *   Pharr, Jakob, Humphreys, "Physically Based Rendering", 4th ed., App. A.5).
 * UNIFORM: 1/(2 pi) on the hemisphere, cos(theta) = u1 (the same book and appendix).
 * MIRROR: a 1-D density of c = wi.R about R, the mirror of wo, azimuth uniform (Lafortune,
 *   Willems 1994 for Phong; the other lobes on R.V the same way).
 * HALF: a 1-D density of c = N.h for the half vector, azimuth uniform, wi = 2 (wo.h) h - wo;
 *   the change of variables h -> wi has the Jacobian 1/(4 |wo.h|) (K. E. Torrance,
 *   E. M. Sparrow 1967; Walter et al. 2007, Eq. 14).
 * GGX_VNDF: the GGX distribution of normals visible from wo, D_wo(h) = G1(wo) max(0, wo.h)
 *   D(h) / wo.z (E. Heitz, "Sampling the GGX distribution of visible normals", JCGT 7(4),
 *   2018), drawn by the spherical-cap construction of J. Dupuy, A. Benyoub, "Sound and
 *   robust sampling of the GGX distribution of visible normals" (HPG 2023): in the
 *   configuration stretched by (alpha_x, alpha_y) the visible normals of wo are a uniform
 *   point of the cap z > -wo_h.z plus wo_h. After reflection pdf(wi) = D(h) G1(wo) /
 *   (4 wo.z) = D(h) V1(wo) / 2 with V1 = G1 / (2 wo.z), so the weight of disney_specular
 *   is F G1(wi).
 * FIBRE_SIN: Kajiya-Kay's diffuse term kd sin(T, wi) times N.wi, exactly: in fibre angles
 *   (theta from T, phi about T from B toward N), wi = (cos theta, sin theta cos phi,
 *   sin theta sin phi), the density is (3/8) sin^2(theta) sin(phi) per solid angle:
 *   x = cos(theta) has density (3/4)(1 - x^2), inverted by the trigonometric root of the
 *   cubic x^3 - 3x + 4u - 2 = 0, and cos(phi) = 1 - 2 u2.
 * FIBRE_CONE: Kajiya-Kay's specular term [cos(theta - theta*)]^n, theta* = pi - theta(T, wo)
 *   (the mirror cone of wo about the fibre): theta - theta* from a logistic of the
 *   variance of cos^n's Gaussian limit (1/n), trimmed to where the lobe is not 0, phi as in
 *   FIBRE_SIN. The ratio to the lobe is bounded (the logistic's tails are heavier). */
#include <math.h>

#include "sample.h"
#include "k_terms.h"

#define TWO_PI (2.0 * ABRDF__PI)

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* |a x b|^2, the sin^2 of the angle between unit vectors without the cancellation of
 * 1 - (a.b)^2. */
static double cross2(const double a[3], const double b[3])
{
    double x = a[1] * b[2] - a[2] * b[1], y = a[2] * b[0] - a[0] * b[2],
           z = a[0] * b[1] - a[1] * b[0];
    return x * x + y * y + z * z;
}

static int normalise(double v[3])
{
    double l = sqrt(dot3(v, v));
    if (!(l > 0.0) || !isfinite(l)) return 0;
    for (int c = 0; c < 3; ++c) v[c] /= l;
    return 1;
}

/* Orthonormal e1, e2 completing the unit axis r: T. Duff et al., "Building an orthonormal
 * basis, revisited", JCGT 6(1), 2017 (continuous except where r.z changes sign). */
static void basis(const double r[3], double e1[3], double e2[3])
{
    double sg = r[2] >= 0.0 ? 1.0 : -1.0;
    double a = -1.0 / (sg + r[2]), b = r[0] * r[1] * a;
    e1[0] = 1.0 + sg * r[0] * r[0] * a;
    e1[1] = sg * b;
    e1[2] = -sg * r[0];
    e2[0] = b;
    e2[1] = sg + r[1] * r[1] * a;
    e2[2] = -r[1];
}

/* wi = reflect wo about h; 0 if wo is orthogonal to h. */
static int reflect(const double wo[3], const double h[3], double wi[3])
{
    double d = dot3(wo, h);
    if (!(d != 0.0)) return 0;
    for (int c = 0; c < 3; ++c) wi[c] = 2.0 * d * h[c] - wo[c];
    return normalise(wi);
}

/* Half vector of (wi, wo) turned into the upper hemisphere, and |wi + wo| / 2 = |wo.h|;
 * 0 if wi ~ -wo. */
static int half_up(const double wi[3], const double wo[3], double h[3], double *d)
{
    double v[3] = {wi[0] + wo[0], wi[1] + wo[1], wi[2] + wo[2]};
    double l2 = dot3(v, v);
    if (!(l2 > ABRDF__HALF_LEN2_MIN)) return 0;
    double l = sqrt(l2), sg = v[2] < 0.0 ? -1.0 : 1.0;
    for (int c = 0; c < 3; ++c) h[c] = sg * v[c] / l;
    *d = 0.5 * l;
    return 1;
}

/* ---- GGX visible normals ----------------------------------------------------------- */

static int vndf_sample(double ax, double ay, const double wo[3], double u1, double u2, double wi[3])
{
    double wh[3] = {ax * wo[0], ay * wo[1], wo[2]}; /* the hemisphere configuration */
    if (!normalise(wh)) return 0;
    double phi = TWO_PI * u1;
    double z = (1.0 - u2) * (1.0 + wh[2]) - wh[2]; /* uniform on the cap z in (-wh.z, 1] */
    double st = sqrt(fmax(0.0, 1.0 - z * z));
    double h[3] = {st * cos(phi) + wh[0], st * sin(phi) + wh[1], z + wh[2]};
    h[0] *= ax;
    h[1] *= ay;
    h[2] = fmax(h[2], 0.0);
    return normalise(h) && reflect(wo, h, wi);
}

static double vndf_pdf(double ax, double ay, const double wo[3], const double wi[3])
{
    double v[3] = {wi[0] + wo[0], wi[1] + wo[1], wi[2] + wo[2]};
    if (!(dot3(v, v) > ABRDF__HALF_LEN2_MIN) || !normalise(v) || !(v[2] > 0.0)) return 0.0;
    double d = d_ggx_aniso(v[0], v[1], v[2], ax, ay);
    return 0.5 * d * v1_smith_ggx_aniso(wo[0], wo[1], wo[2], ax, ay);
}

/* ---- fibre lobes (Kajiya-Kay), angles about T = +x ------------------------------------ */

/* phi in [0, pi] with density sin(phi)/2, i.e. N.wi >= 0; wi from theta and phi. */
static void fibre_dir(double cos_t, double sin_t, double u2, double wi[3])
{
    double cp = 1.0 - 2.0 * u2, sp = sqrt(fmax(0.0, 1.0 - cp * cp));
    wi[0] = cos_t;
    wi[1] = sin_t * cp;
    wi[2] = sin_t * sp;
}

/* The cone lobe's centre theta*, its support and the logistic scale. */
static void cone_setup(double n, const double wo[3], double *centre, double *lo, double *hi,
                       double *s)
{
    double t_o = atan2(sqrt(wo[1] * wo[1] + wo[2] * wo[2]), wo[0]);
    *centre = ABRDF__PI - t_o;
    /* cos^n(d) ~ exp(-n d^2 / 2): the logistic of the same variance 1/n has scale
     * sqrt(3/n)/pi; no wider than 2 (n -> 0: almost uniform on the support). */
    *s = n > 0.0 ? fmin(sqrt(3.0 / n) / ABRDF__PI, 2.0) : 2.0;
    double a = n > 0.0 ? fmax(0.0, *centre - 0.5 * ABRDF__PI) : 0.0;
    double b = n > 0.0 ? fmin(ABRDF__PI, *centre + 0.5 * ABRDF__PI) : ABRDF__PI;
    *lo = a - *centre;
    *hi = b - *centre;
}

/* ---- the components ---------------------------------------------------------------- */

int abrdf__lobe_sample(const abrdf__lobe *l, const abrdf__mixture *mx, double u1, double u2,
                       double wi[3])
{
    const double *wo = mx->wo;
    switch (l->kind) {
    case ABRDF__LOBE_COSINE: {
        double r = sqrt(u1), phi = TWO_PI * u2;
        wi[0] = r * cos(phi);
        wi[1] = r * sin(phi);
        wi[2] = sqrt(fmax(0.0, 1.0 - u1));
        return normalise(wi);
    }
    case ABRDF__LOBE_UNIFORM: {
        double z = u1, r = sqrt(fmax(0.0, 1.0 - z * z)), phi = TWO_PI * u2;
        wi[0] = r * cos(phi);
        wi[1] = r * sin(phi);
        wi[2] = z;
        return normalise(wi);
    }
    case ABRDF__LOBE_MIRROR: {
        double r[3] = {-wo[0], -wo[1], wo[2]}, e1[3], e2[3], s;
        double t = abrdf__dist_sample(&l->dist, u1, &s), phi = TWO_PI * u2;
        basis(r, e1, e2);
        for (int c = 0; c < 3; ++c)
            wi[c] = s * cos(phi) * e1[c] + s * sin(phi) * e2[c] + (1.0 - t) * r[c];
        return normalise(wi);
    }
    case ABRDF__LOBE_HALF: {
        double s, t = abrdf__dist_sample(&l->dist, u1, &s), phi = TWO_PI * u2;
        double h[3] = {s * cos(phi), s * sin(phi), 1.0 - t};
        return normalise(h) && reflect(wo, h, wi);
    }
    case ABRDF__LOBE_GGX_VNDF: return vndf_sample(l->ax, l->ay, wo, u1, u2, wi);
    case ABRDF__LOBE_FIBRE_SIN: {
        double x = 2.0 * cos((TWO_PI - acos(1.0 - 2.0 * u1)) / 3.0); /* (3/4)(1 - x^2) */
        x = fmin(1.0, fmax(-1.0, x));
        fibre_dir(x, sqrt(fmax(0.0, 1.0 - x * x)), u2, wi);
        return normalise(wi);
    }
    case ABRDF__LOBE_FIBRE_CONE: {
        double centre, lo, hi, s;
        cone_setup(l->n, wo, &centre, &lo, &hi, &s);
        double t = centre + abrdf__tlogistic_sample(s, lo, hi, u1);
        fibre_dir(cos(t), sin(t), u2, wi);
        return normalise(wi);
    }
    case ABRDF__LOBE_HAIR: abrdf__hair_sampler_sample(&mx->hair, u1, u2, wi); return normalise(wi);
    }
    return 0;
}

double abrdf__lobe_pdf(const abrdf__lobe *l, const abrdf__mixture *mx, const double wi[3])
{
    const double *wo = mx->wo;
    switch (l->kind) {
    case ABRDF__LOBE_COSINE: return wi[2] > 0.0 ? wi[2] * ABRDF__INV_PI : 0.0;
    case ABRDF__LOBE_UNIFORM: return wi[2] >= 0.0 ? 0.5 * ABRDF__INV_PI : 0.0;
    case ABRDF__LOBE_MIRROR: {
        double r[3] = {-wo[0], -wo[1], wo[2]};
        return abrdf__dist_pdf(&l->dist, dot3(wi, r), cross2(wi, r)) / TWO_PI;
    }
    case ABRDF__LOBE_HALF: {
        double h[3], d;
        if (!half_up(wi, wo, h, &d)) return 0.0;
        double ph = abrdf__dist_pdf(&l->dist, h[2], h[0] * h[0] + h[1] * h[1]) / TWO_PI;
        return ph / (4.0 * d);
    }
    case ABRDF__LOBE_GGX_VNDF: return vndf_pdf(l->ax, l->ay, wo, wi);
    case ABRDF__LOBE_FIBRE_SIN:
        return wi[2] > 0.0 ? 0.375 * sqrt(wi[1] * wi[1] + wi[2] * wi[2]) * wi[2] : 0.0;
    case ABRDF__LOBE_FIBRE_CONE: {
        double s2 = wi[1] * wi[1] + wi[2] * wi[2];
        if (!(wi[2] > 0.0 && s2 > 0.0)) return 0.0;
        double centre, lo, hi, s;
        cone_setup(l->n, wo, &centre, &lo, &hi, &s);
        double t = atan2(sqrt(s2), wi[0]);
        /* p(theta) p(phi) / sin(theta), p(phi) = sin(phi)/2 = wi.z / (2 sin(theta)) */
        return abrdf__tlogistic_pdf(t - centre, s, lo, hi) * wi[2] / (2.0 * s2);
    }
    case ABRDF__LOBE_HAIR: return abrdf__hair_sampler_pdf(&mx->hair, wi);
    }
    return 0.0;
}
