/* sample_hair.c - the far-field R/TT/TRT proposal of the hair models (marschner, huang).
 *
 * The structure is that of hair sampling in the literature: E. d'Eon, G. Francois,
 * M. Hill, J. Letteri, J.-M. Aubry, "An energy-conserving hair reflectance model", EGSR 2011
 * (lobe p chosen by its attenuation A_p, theta_i from the longitudinal lobe M_p, phi from
 * the azimuthal lobe about Phi(p, h)), as pbrt-v4 implements it (Pharr, Jakob, Humphreys,
 * "Physically Based Rendering", 4th ed., Sec. 9.9: h given by the hit point, A_p by the
 * smooth-fibre attenuation at theta_o, a trimmed logistic about Phi). abrdf's hair models
 * are FAR-FIELD, averaged over the offset h in [-1, 1], and defined ABOVE THE RIBBON only
 * (hair.h: f_r = 0 for wi below it), so the proposal averages h and keeps wi above:
 *   pair      (h_k, p): h_k = -1 + (2k + 1)/K the K midpoints, with probability
 *             proportional to A_p(h_k) (mean over RGB; Marschner et al.'s smooth-fibre
 *             attenuation, hair_marschner.c, at the Bravais indices of theta_d ~ theta_o:
 *             theta_i lies near -theta_o for every lobe) times the share of the pair's
 *             azimuthal lobe above the ribbon at theta_i = its centre
 *   theta_i   trimmed logistic on [-pi/2, pi/2] about 2 alpha_p - theta_o, the peak of
 *             M_p(theta_h) with theta_h = (theta_i + theta_o)/2, with the variance of M_p's
 *             Gaussian (std 2 beta_p in theta_i)
 *   phi_i     phi_o - phi_i = Phi(p, h_k) + xi (hair.h: phi = phi_o - phi_i), xi a logistic
 *             restricted to the arc of [-pi, pi] that puts phi_i in [0, pi] (wi above the
 *             ribbon); Phi the exact map of hair_marschner.c at the index eta' of
 *             theta_d = (theta_o - theta_i)/2
 * so that, with dw = cos(theta) dtheta dphi,
 *   pdf(wi) = sum_kp P_kp TL_p(theta_i) L(xi_kp) / M_kp(theta_i) / cos(theta_i),
 * M_kp the logistic's mass on the arc: exact for this procedure however well it matches S.
 * Widths: marschner uses its own alpha_p, beta_p (r = beta_R); huang, a GGX fibre of
 * roughness alpha = r, has no M_p to copy: its lobes get Marschner's shifts for the same
 * cuticle tilt, longitudinal widths beta_p = alpha (R, TT) and 2 alpha (TRT) and azimuthal
 * scale alpha/2. Huang's elliptical section, TRRT+ and Marschner's TRT glints are not in
 * the proposal; the cosine component abrdf__mixture_setup adds to every hair sampler
 * (ABRDF__HAIR_SAMPLE_COSINE) keeps the weights bounded there. */
#include <math.h>

#include "hair.h"
#include "sample.h"

#define SQRT3_OVER_PI 0.55132889542179204 /* logistic scale per unit standard deviation */

/* Smallest azimuthal logistic scale: below it the K = 32 offsets would show as separate
 * peaks (their Phi are up to ~0.35 rad apart near |h| = 1). */
#define HAIR_PHI_SCALE_MIN 0.12

#define PI ABRDF__PI

static double phi_map(int p, double h, double eta1, double asin_h)
{
    return 2.0 * p * asin(h / eta1) - 2.0 * asin_h + p * PI; /* hair_marschner.c */
}

/* Bravais index eta' for the longitudinal half-difference theta_d (hair_marschner.c). */
static double eta_prime(double eta, double theta_d)
{
    double sd = sin(theta_d), cd = fmax(cos(theta_d), ABRDF__HAIR_COS_MIN);
    return fmax(abrdf__safe_sqrt(eta * eta - sd * sd) / cd, 1.0);
}

static double node_h(int k) { return -1.0 + (2.0 * k + 1.0) / ABRDF__HAIR_NODES; }

static double wrap(double x) /* into [-pi, pi]; |x| < 7 pi here: a few steps, no fmod */
{
    while (x > PI) x -= 2.0 * PI;
    while (x < -PI) x += 2.0 * PI;
    return x;
}

/* The arc of xi keeping wi above the ribbon, for c = wrap(phi_o - Phi): xi in [c - pi, c]
 * (phi_i = c - xi in [0, pi]), within [-pi, pi] one interval for c >= 0, two for c < 0.
 * Returns the logistic mass of the arc; *m1 the mass of its first interval [a1, b1]. */
static double arc(double c, double s, double *a1, double *b1, double *m1)
{
    if (c >= 0.0) {
        *a1 = c - PI;
        *b1 = c;
        *m1 = abrdf__tlogistic_mass(s, *a1, *b1);
        return *m1;
    }
    *a1 = -PI;
    *b1 = c;
    *m1 = abrdf__tlogistic_mass(s, -PI, c);
    return *m1 + abrdf__tlogistic_mass(s, c + PI, PI);
}

void abrdf__hair_sampler_setup(abrdf_model model, const abrdf_params *p, const double wo[3],
                               abrdf__hair_sampler *h)
{
    abrdf__marschner m;
    abrdf__marschner_setup(p, &m); /* eta, sigma_a, alpha_p; beta_p as marschner reads r */
    double so, co, po;
    abrdf__fibre_angles(wo, &so, &co, &po);
    h->theta_o = atan2(so, co);
    h->phi_o = po;
    h->eta = m.eta;
    double alpha = abrdf__clamp(p->r, ABRDF__HUANG_ALPHA_MIN, 1.0), eta_c[3];
    for (int l = 0; l < 3; ++l) {
        double beta = model == ABRDF_HUANG ? (l == 2 ? 2.0 : 1.0) * alpha : m.beta[l];
        h->mu[l] = 2.0 * m.alpha[l] - h->theta_o;
        h->s_theta[l] = 2.0 * beta * SQRT3_OVER_PI;
        h->s_phi[l] = fmax(HAIR_PHI_SCALE_MIN, model == ABRDF_HUANG ? 0.5 * alpha : 0.0);
        double tc = abrdf__clamp(h->mu[l], -0.5 * PI, 0.5 * PI); /* the lobe's theta_i */
        eta_c[l] = eta_prime(m.eta, 0.5 * (h->theta_o - tc));
    }
    /* Bravais indices and the refracted longitudinal cosine at theta_d = theta_o */
    double q = abrdf__safe_sqrt(m.eta * m.eta - so * so), cd = fmax(co, ABRDF__HAIR_COS_MIN);
    double eta1 = fmax(q / cd, 1.0), eta2 = m.eta * m.eta * cd / fmax(q, ABRDF__HAIR_COS_MIN);
    double st = so / m.eta, cos_t = abrdf__safe_sqrt(1.0 - st * st), sum = 0.0;
    for (int k = 0; k < ABRDF__HAIR_NODES; ++k) {
        double hk = node_h(k);
        h->asin_h[k] = asin(hk);
        for (int l = 0; l < 3; ++l) {
            double ap[3], a1, b1, m1;
            abrdf__marschner_ap(&m, l, hk, eta1, eta2, cos_t, ap);
            double c = wrap(h->phi_o - phi_map(l, hk, eta_c[l], h->asin_h[k]));
            h->prob[k][l] = (ap[0] + ap[1] + ap[2]) / 3.0 * arc(c, h->s_phi[l], &a1, &b1, &m1);
            sum += h->prob[k][l];
        }
    }
    for (int k = 0; k < ABRDF__HAIR_NODES; ++k)
        for (int l = 0; l < 3; ++l)
            h->prob[k][l] = sum > 0.0 ? h->prob[k][l] / sum : 1.0 / (3 * ABRDF__HAIR_NODES);
}

void abrdf__hair_sampler_sample(const abrdf__hair_sampler *h, double u1, double u2, double wi[3])
{
    /* the pair (k, l) by u1, reused for theta_i; u2 for the azimuth */
    int sel = 0, found = 0;
    double c0 = 0.0;
    for (int i = 0; i < 3 * ABRDF__HAIR_NODES && !found; ++i) {
        double pr = h->prob[i / 3][i % 3];
        if (!(pr > 0.0)) continue;
        sel = i;
        found = u1 < c0 + pr;
        if (!found) c0 += pr;
    }
    int k = sel / 3, l = sel % 3;
    if (!found) c0 -= h->prob[k][l]; /* u1 past the sum by rounding: the last pair */
    double u = fmin(fmax((u1 - c0) / h->prob[k][l], 0.0), ABRDF__SAMPLE_U_MAX);
    double mu = h->mu[l];
    double ti = mu + abrdf__tlogistic_sample(h->s_theta[l], -0.5 * PI - mu, 0.5 * PI - mu, u);
    double eta1 = eta_prime(h->eta, 0.5 * (h->theta_o - ti));
    double c = wrap(h->phi_o - phi_map(l, node_h(k), eta1, h->asin_h[k]));
    double s = h->s_phi[l], a1, b1, m1, mass = arc(c, s, &a1, &b1, &m1), xi;
    double v = u2 * mass;
    if (c >= 0.0 || v < m1)
        xi = abrdf__tlogistic_sample(s, a1, b1, fmin(v / m1, ABRDF__SAMPLE_U_MAX));
    else
        xi = abrdf__tlogistic_sample(s, c + PI, PI,
                                     fmin((v - m1) / (mass - m1), ABRDF__SAMPLE_U_MAX));
    double phi_i = c - xi, ct = cos(ti);
    wi[0] = sin(ti);
    wi[1] = ct * cos(phi_i);
    wi[2] = ct * fmax(sin(phi_i), 0.0); /* phi_i in [0, pi] up to rounding */
}

double abrdf__hair_sampler_pdf(const abrdf__hair_sampler *h, const double wi[3])
{
    double si, ci, phi_i;
    abrdf__fibre_angles(wi, &si, &ci, &phi_i);
    if (!(ci > 0.0) || wi[2] < 0.0) return 0.0; /* along the fibre, or below the ribbon */
    double ti = atan2(si, ci);
    double eta1 = eta_prime(h->eta, 0.5 * (h->theta_o - ti));
    double sum = 0.0;
    for (int l = 0; l < 3; ++l) {
        double mu = h->mu[l], s = h->s_phi[l];
        double pt = abrdf__tlogistic_pdf(ti - mu, h->s_theta[l], -0.5 * PI - mu, 0.5 * PI - mu);
        if (!(pt > 0.0)) continue;
        double pp = 0.0;
        for (int k = 0; k < ABRDF__HAIR_NODES; ++k) {
            if (!(h->prob[k][l] > 0.0)) continue;
            double c = wrap(h->phi_o - phi_map(l, node_h(k), eta1, h->asin_h[k])), a1, b1, m1;
            double mass = arc(c, s, &a1, &b1, &m1);
            pp += h->prob[k][l] * abrdf__logistic_pdf(wrap(c - phi_i), s) / mass;
        }
        sum += pt * pp;
    }
    return sum / ci;
}
