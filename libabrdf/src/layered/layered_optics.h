/* layered_optics.h - the optics of one rough interface shared by the layered models
 * (Weidlich-Wilkie, Belcour) and by the generator of Belcour's tables: exact Fresnel for a
 * complex relative index, GGX D, separable Smith visibility, Snell refraction. Double only.
 *
 * Exact Fresnel (unpolarised) for a relative index eta + i kappa, as in M. Born, E. Wolf,
 * "Principles of Optics", Sec. 14.2 (the form of pbrt's FrComplex written with real
 * arithmetic). kappa = 0 gives the dielectric formula, including total internal reflection
 * (F = 1) when eta < 1 and sin(theta) > eta. */
#ifndef ABRDF_LAYERED_OPTICS_H
#define ABRDF_LAYERED_OPTICS_H
#include <math.h>

#include "guards.h"

#define ABRDF__LO_PI 3.14159265358979323846

/* Reflectance of an interface of relative index eta + i kappa at incidence cosine c. Selects,
 * no branch, so that a loop over lanes calling it vectorises (Weidlich-Wilkie's conductor
 * interface); every value is that of the guarded form: index-matched (eta 1, kappa 0) 0,
 * grazing incidence (or a NaN) 1, a vanishing p denominator rs. */
static inline double abrdf__fresnel_exact(double c, double eta, double kappa)
{
    c = c < 0.0 ? 0.0 : (c > 1.0 ? 1.0 : c);
    double c2 = c * c, s2 = 1.0 - c2;
    double t0 = eta * eta - kappa * kappa - s2;
    double a2pb2 = sqrt(t0 * t0 + 4.0 * eta * eta * kappa * kappa);
    double a = abrdf__safe_sqrt(0.5 * (a2pb2 + t0));
    double t1 = a2pb2 + c2, t2 = 2.0 * c * a, ds = t1 + t2;
    double rs = (t1 - t2) / (ds > 0.0 ? ds : 1.0);
    double t3 = c2 * a2pb2 + s2 * s2, t4 = t2 * s2, dp = t3 + t4;
    double rp = dp > 0.0 ? rs * (t3 - t4) / (dp > 0.0 ? dp : 1.0) : rs;
    double f = 0.5 * (rs + rp);
    f = f < 0.0 ? 0.0 : (f > 1.0 ? 1.0 : f);
    f = ds > 0.0 ? f : 1.0; /* grazing incidence: finite from here on */
    /* index-matched: no interface at all; a factor, not a select on a condition that a loop
     * over lanes holds constant, which GCC's vectoriser does not take */
    return f * (eta == 1.0 && kappa == 0.0 ? 0.0 : 1.0);
}

/* GGX D (Eq. 6) with ch = N.H and sh2 = |N x H|^2; ag the microfacet roughness. */
static inline double abrdf__lo_d_ggx(double ch, double sh2, double ag)
{
    if (!(ch > 0.0)) return 0.0;
    double a2 = ag * ag, t = sh2 + a2 * ch * ch;
    return t > 0.0 ? a2 / (ABRDF__LO_PI * t * t) : 0.0;
}

/* Separable Smith for GGX (Eq. 9) as visibility: G1(c) / (2c). */
static inline double abrdf__lo_v1(double c, double ag)
{
    double a2 = ag * ag;
    return 1.0 / (c + sqrt(a2 + (1.0 - a2) * c * c));
}

/* Smith G1 for GGX (Eq. 9). */
static inline double abrdf__lo_g1(double c, double ag)
{
    return c > 0.0 ? 2.0 * c * abrdf__lo_v1(c, ag) : 0.0;
}

/* Refract the upward unit direction w through the upward unit normal m into the medium
 * below (relative index eta = n_below / n_above) and return the refracted ray reversed,
 * i.e. pointing upward from below, in out. Returns 0 on total internal reflection or if w
 * is behind m. */
static inline int abrdf__lo_refract(const double w[3], const double m[3], double eta, double out[3])
{
    double ci = w[0] * m[0] + w[1] * m[1] + w[2] * m[2];
    if (!(ci > 0.0)) return 0;
    double s2t = (1.0 - ci * ci) / (eta * eta);
    if (!(s2t < 1.0)) return 0;
    double ct = sqrt(1.0 - s2t);
    double k = ci / eta - ct;
    for (int c = 0; c < 3; ++c) out[c] = w[c] / eta - k * m[c];
    return 1;
}

#endif
