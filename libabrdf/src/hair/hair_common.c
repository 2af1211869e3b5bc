/* hair_common.c - pieces shared by the hair models: melanin absorption, exact dielectric
 * Fresnel, Gaussians, fibre angles.
 *
 * Melanin mapping: Blender Cycles, src/kernel/svm/closure.h (perceptual remap of the
 * concentration, Bitterli's eumelanin/pheomelanin split) and src/kernel/closure/bsdf_util.h
 * (bsdf_principled_hair_sigma_from_concentration, RGB fit of the melanin spectra of
 * d'Eon et al. 2011 / Chiang et al. 2016). MODELS.md B7.2. */
#include <math.h>

#include "hair.h"

void abrdf__hair_sigma_a(double melanin, double redness, double sigma[3])
{
    static const double eu[3] = {0.506, 0.841, 1.653};   /* eumelanin, per unit radius */
    static const double pheo[3] = {0.343, 0.733, 1.924}; /* pheomelanin */
    double m = -log(fmax(1.0 - melanin, ABRDF__HAIR_MELANIN_REST_MIN));
    double ce = m * (1.0 - redness), cp = m * redness;
    for (int c = 0; c < 3; ++c) sigma[c] = ce * eu[c] + cp * pheo[c];
}

/* c clamped to [0, 1], NaN to 0 (abrdf__clamp's result, inline: fmin and fmax are libm
 * calls, and these run several times per azimuthal root). */
static double clamp_cos(double c) { return c > 0.0 ? (c < 1.0 ? c : 1.0) : 0.0; }

/* Cosine of the refracted angle for relative index n, or -1 for total internal reflection. */
static double cos_refracted(double n, double c)
{
    double s2 = (1.0 - c * c) / (n * n); /* c in [0, 1]: 1 - c^2 >= 0 */
    return s2 >= 1.0 ? -1.0 : sqrt(1.0 - s2);
}

double abrdf__fresnel_s(double n, double c)
{
    c = clamp_cos(c);
    double ct = cos_refracted(n, c);
    if (ct < 0.0) return 1.0;
    double den = c + n * ct;
    if (!(den > 0.0)) return 1.0;
    double r = (c - n * ct) / den;
    return r * r;
}

double abrdf__fresnel_p(double n, double c)
{
    c = clamp_cos(c);
    double ct = cos_refracted(n, c);
    if (ct < 0.0) return 1.0;
    double den = n * c + ct;
    if (!(den > 0.0)) return 1.0;
    double r = (n * c - ct) / den;
    return r * r;
}

double abrdf__fresnel_dielectric(double n, double c)
{
    return 0.5 * (abrdf__fresnel_s(n, c) + abrdf__fresnel_p(n, c));
}

double abrdf__gauss(double x, double sd)
{
    return exp(-0.5 * (x * x) / (sd * sd)) / (sd * 2.5066282746310002); /* sqrt(2 pi) */
}

double abrdf__wrap_pi(double a)
{
    a = fmod(a, 2.0 * ABRDF__PI); /* (-2pi, 2pi) */
    if (a > ABRDF__PI)
        a -= 2.0 * ABRDF__PI;
    else if (a <= -ABRDF__PI)
        a += 2.0 * ABRDF__PI;
    return a;
}

void abrdf__fibre_angles(const double w[3], double *sin_t, double *cos_t, double *phi)
{
    *sin_t = abrdf__clamp(w[0], -1.0, 1.0);
    *cos_t = sqrt(w[1] * w[1] + w[2] * w[2]);
    *phi = atan2(w[2], w[1]); /* atan2(0, 0) = 0: a direction along T has any azimuth */
}
