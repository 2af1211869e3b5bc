/* sample_hair.c - the far-field R/TT/TRT proposal of the hair models (marschner, huang).
 *
 * The structure is that of hair sampling in the literature: E. d'Eon, G. Francois,
 * M. Hill, J. Letteri, J.-M. Aubry, "An energy-conserving hair reflectance model", EGSR 2011
 * (lobe p chosen by its attenuation A_p, theta_i from the longitudinal lobe M_p, phi from
 * the azimuthal lobe about Phi(p, h)), as pbrt-v4 implements it (Pharr, Jakob, Humphreys,
 * "Physically Based Rendering", 4th ed., Sec. 9.9.6: h given by the hit point, A_p by the
 * smooth-fibre attenuation at theta_o, a trimmed logistic about Phi). abrdf's hair models
 * are FAR-FIELD, averaged over the offset h in [-1, 1], so the proposal averages h too:
 *   node      k uniform of K, h_k = -1 + (2k + 1)/K (the midpoints)
 *   lobe      p with probability A_p(h_k) / sum_q A_q(h_k) (mean over RGB): Marschner et
 *             al.'s smooth-fibre attenuation (hair_marschner.c) at the Bravais indices of
 *             theta_d ~ theta_o (theta_i lies near -theta_o for every lobe)
 *   theta_i   trimmed logistic on [-pi/2, pi/2] about 2 alpha_p - theta_o, the peak of
 *             M_p(theta_h) with theta_h = (theta_i + theta_o)/2, of the variance of M_p's
 *             Gaussian (std 2 beta_p in theta_i)
 *   phi       phi_o - phi_i = Phi(p, h_k) + xi (hair.h's phi = phi_o - phi_i), xi a
 *             trimmed logistic on [-pi, pi]; Phi the exact map of hair_marschner.c with the
 *             index eta' of theta_d = (theta_o - theta_i)/2
 * and the density over directions is
 *   pdf(wi) = sum_p TL(theta_i) [sum_k P(p|k) TL(phi_o - phi_i - Phi(p, h_k)) / K] / cos(theta_i)
 * (dw = cos(theta) dtheta dphi), exact for this procedure however well it matches S.
 * Widths: marschner uses its own alpha_p, beta_p (r = beta_R); huang, a GGX fibre of
 * roughness alpha = r, has no M_p to copy: its lobes get Marschner's shifts for the same
 * cuticle tilt and width beta_p = alpha (R, TT) and 2 alpha (TRT), its azimuths the scale of
 * a GGX reflection, alpha/2. Huang's elliptical section, TRRT+ and the TRT glints of
 * Marschner are not in the proposal; the cosine component that abrdf__mixture_setup adds
 * to every hair sampler (ABRDF__HAIR_SAMPLE_COSINE) keeps the weights bounded there. */
#include <math.h>

#include "hair.h"
#include "sample.h"

#define SQRT3_OVER_PI 0.55132889542179204 /* logistic scale per unit standard deviation */

/* Smallest azimuthal logistic scale: below it the K = 32 offsets would show as separate
 * peaks (their Phi are up to ~0.35 rad apart near |h| = 1). */
#define HAIR_PHI_SCALE_MIN 0.12

static double phi_map(int p, double h, double eta1, double asin_h)
{
    return 2.0 * p * asin(h / eta1) - 2.0 * asin_h + p * ABRDF__PI; /* hair_marschner.c */
}

/* Bravais index eta' for the longitudinal half-difference theta_d (hair_marschner.c). */
static double eta_prime(double eta, double theta_d)
{
    double sd = sin(theta_d), cd = fmax(cos(theta_d), ABRDF__HAIR_COS_MIN);
    return fmax(abrdf__safe_sqrt(eta * eta - sd * sd) / cd, 1.0);
}

static double node_h(int k) { return -1.0 + (2.0 * k + 1.0) / ABRDF__HAIR_NODES; }

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
    double alpha = abrdf__clamp(p->r, ABRDF__HUANG_ALPHA_MIN, 1.0);
    for (int l = 0; l < 3; ++l) {
        double beta = model == ABRDF_HUANG ? (l == 2 ? 2.0 : 1.0) * alpha : m.beta[l];
        h->mu[l] = 2.0 * m.alpha[l] - h->theta_o;
        h->s_theta[l] = 2.0 * beta * SQRT3_OVER_PI;
        h->s_phi[l] = fmax(HAIR_PHI_SCALE_MIN, model == ABRDF_HUANG ? 0.5 * alpha : 0.0);
        h->phi_mass[l] = abrdf__tlogistic_mass(h->s_phi[l], -ABRDF__PI, ABRDF__PI);
    }
    /* Bravais indices and the refracted longitudinal cosine at theta_d = theta_o */
    double q = abrdf__safe_sqrt(m.eta * m.eta - so * so), cd = fmax(co, ABRDF__HAIR_COS_MIN);
    double eta1 = fmax(q / cd, 1.0), eta2 = m.eta * m.eta * cd / fmax(q, ABRDF__HAIR_COS_MIN);
    double st = so / m.eta, cos_t = abrdf__safe_sqrt(1.0 - st * st);
    for (int k = 0; k < ABRDF__HAIR_NODES; ++k) {
        double hk = node_h(k), a[3], sum = 0.0;
        h->asin_h[k] = asin(hk);
        for (int l = 0; l < 3; ++l) {
            double ap[3];
            abrdf__marschner_ap(&m, l, hk, eta1, eta2, cos_t, ap);
            a[l] = (ap[0] + ap[1] + ap[2]) / 3.0;
            sum += a[l];
        }
        for (int l = 0; l < 3; ++l) h->prob[k][l] = sum > 0.0 ? a[l] / sum : 1.0 / 3.0;
    }
}

void abrdf__hair_sampler_sample(const abrdf__hair_sampler *h, double u1, double u2, double wi[3])
{
    const double pi = ABRDF__PI;
    int k = (int)(u2 * ABRDF__HAIR_NODES);
    k = k < ABRDF__HAIR_NODES ? k : ABRDF__HAIR_NODES - 1;
    double v = fmin(u2 * ABRDF__HAIR_NODES - k, ABRDF__SAMPLE_U_MAX);
    int l = 0;
    double c = 0.0;
    while (l < 2 && u1 >= c + h->prob[k][l]) c += h->prob[k][l++];
    while (l > 0 && !(h->prob[k][l] > 0.0)) c -= h->prob[k][--l]; /* rounding past the end */
    double u = fmin(fmax((u1 - c) / h->prob[k][l], 0.0), ABRDF__SAMPLE_U_MAX);
    double mu = h->mu[l];
    double ti = mu + abrdf__tlogistic_sample(h->s_theta[l], -0.5 * pi - mu, 0.5 * pi - mu, u);
    double eta1 = eta_prime(h->eta, 0.5 * (h->theta_o - ti));
    double xi = abrdf__tlogistic_sample(h->s_phi[l], -pi, pi, v);
    double phi_i = h->phi_o - phi_map(l, node_h(k), eta1, h->asin_h[k]) - xi;
    double ct = cos(ti);
    wi[0] = sin(ti);
    wi[1] = ct * cos(phi_i);
    wi[2] = ct * sin(phi_i);
}

double abrdf__hair_sampler_pdf(const abrdf__hair_sampler *h, const double wi[3])
{
    const double pi = ABRDF__PI;
    double si, ci, phi_i;
    abrdf__fibre_angles(wi, &si, &ci, &phi_i);
    if (!(ci > 0.0)) return 0.0; /* along the fibre: a set of measure zero */
    double ti = atan2(si, ci);
    double eta1 = eta_prime(h->eta, 0.5 * (h->theta_o - ti));
    double sum = 0.0;
    for (int l = 0; l < 3; ++l) {
        double mu = h->mu[l];
        double pt = abrdf__tlogistic_pdf(ti - mu, h->s_theta[l], -0.5 * pi - mu, 0.5 * pi - mu);
        if (!(pt > 0.0)) continue;
        double pp = 0.0;
        for (int k = 0; k < ABRDF__HAIR_NODES; ++k) {
            if (!(h->prob[k][l] > 0.0)) continue;
            double xi = h->phi_o - phi_i - phi_map(l, node_h(k), eta1, h->asin_h[k]);
            while (xi > pi) xi -= 2.0 * pi; /* |xi| < 7 pi: a few steps, no fmod */
            while (xi < -pi) xi += 2.0 * pi;
            pp += h->prob[k][l] * abrdf__logistic_pdf(xi, h->s_phi[l]);
        }
        sum += pt * pp / (h->phi_mass[l] * ABRDF__HAIR_NODES);
    }
    return sum / ci;
}
