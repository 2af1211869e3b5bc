/* hair_marschner.c - Marschner et al. hair scattering: R, TT and TRT lobes.
 *
 * S. R. Marschner, H. W. Jensen, M. Cammarano, S. Worley, P. Hanrahan, "Light scattering
 * from human hair fibers", ACM TOG 22(3) (SIGGRAPH 2003), 780-791. The paper's practical
 * model (its Sec. 4), in the angles of hair.h (theta from the normal plane of the fibre,
 * phi around it), theta_h = (theta_i + theta_o)/2, theta_d = (theta_o - theta_i)/2,
 * phi = phi_o - phi_i:
 *   S_M = sum_p M_p(theta_h) N_p(phi) / cos^2(theta_d),  p = R, TT, TRT
 *   M_p  = Gaussian of width beta_p about alpha_p        (alpha_TT = -alpha_R/2,
 *          alpha_TRT = -3 alpha_R/2, beta_TT = beta_R/2, beta_TRT = 2 beta_R)
 *   N_p(phi) = sum over roots h of Phi(p, h) = phi of A_p(h) / |2 dPhi/dh|
 *   Phi(p, h) = 2 p gamma_t - 2 gamma_i + p pi,  gamma_i = asin h, gamma_t = asin(h / eta')
 *   A_0 = F(eta', eta'', gamma_i)
 *   A_p = (1 - F(eta', eta'', gamma_i)) (1 - F(1/eta', 1/eta'', gamma_t))
 *         F(1/eta', 1/eta'', gamma_t)^(p-1) T^p
 * with the Bravais indices eta' = sqrt(eta^2 - sin^2 theta_d)/cos theta_d and
 * eta'' = eta^2 cos theta_d / sqrt(eta^2 - sin^2 theta_d) (the paper's Appendix B), F the
 * Fresnel reflectance with eta' for the perpendicular and eta'' for the parallel
 * polarisation, averaged.
 *
 * Choices (MODELS.md B7.1; each is stated in docs/MODELS.md, "Hair models"):
 *  - Phi is the EXACT map above, not the paper's cubic approximation; its roots are found by
 *    safeguarded Newton in gamma_i on the intervals where Phi is monotone (split at the TRT
 *    caustic h_c); R's is exact, gamma_i = -phi/2.
 *  - Absorption T = exp(-2 sigma_a cos(gamma_t) / cos(theta_t)), sin(theta_t) =
 *    sin(theta_d)/eta: the chord 2 cos(gamma_t) of the unit circle (pbrt-v4; the paper's
 *    printed form is not used). theta_d makes T symmetric in wi and wo.
 *  - M_p is normalised over theta_r: the paper's smooth cylinder scatters into
 *    delta(theta_r + theta_i) = delta(theta_h)/2, so the practical Gaussian in theta_h has to
 *    carry the same 1/2; with a unit-area Gaussian in theta_h a lossless fibre would reflect
 *    twice the light it receives.
 *  - The paper's rendering equation L = D * integral S_M L cos(theta_i) dw_i gives the fibre
 *    function of hair.h: S = S_M cos(theta_i).
 *  - TRT caustics use the paper's glint smoothing (Sec. 4.4, "caustic" terms h_c, w_c, k_G,
 *    Delta eta', Delta h_M) with fixed constants below, and its eccentricity trick: TRT is
 *    evaluated with eta* = ((eta*_1 + eta*_2) + cos(2 phi_h)(eta*_1 - eta*_2))/2,
 *    eta*_1 = 2(eta - 1)a^2 - eta + 2, eta*_2 = 2(eta - 1)/a^2 - eta + 2, a the axis ratio and
 *    phi_h measured from the major axis (local +y).
 *  - Parameters: r is beta_R in radians, cuticle_tilt alpha (deg) gives alpha_R = -2 alpha
 *    (the paper's Fig. 1: R is shifted by twice the scale tilt). */
#include <math.h>

#include "hair.h"

/* Glint smoothing constants; the paper gives ranges (Table 1: k_G 0.5-5, w_c 10-25 deg,
 * Delta eta' 0.2-0.4, Delta h_M 0.2-0.4). We take the lower intensity and mid widths. */
#define ABRDF__MARSCHNER_GLINT_KG 0.5
#define ABRDF__MARSCHNER_GLINT_WC (15.0 * ABRDF__HAIR_DEG)
#define ABRDF__MARSCHNER_GLINT_DETA 0.3
#define ABRDF__MARSCHNER_GLINT_DHM 0.3

/* Steps of the root search for Phi: each is a Newton step in gamma_i = asin h kept inside
 * the bracket, or a bisection where Newton would leave it, so 60 still halve a [-pi/2, pi/2]
 * interval to below 1e-17 in the worst case. Phi is close to a cubic in gamma_i (the paper's
 * approximation), so Newton from the secant of the bracket ends it in ~3 steps (each costs
 * one sine, cosine and asin). */
#define ABRDF__MARSCHNER_BISECT_STEPS 60
/* The search stops after a Newton step of at most this (gamma_i in [-pi/2, pi/2]): Newton
 * converges quadratically, so the step after one this small would be below double precision;
 * the root is then as accurate as Phi can be evaluated (~1e-16). */
#define ABRDF__MARSCHNER_ROOT_TOL 1e-10
/* ... or earlier, once two Newton steps s' then s show the quadratic convergence: the next
 * step would be about s (s / s')^2, and when that is below this the root is as exact. */
#define ABRDF__MARSCHNER_ROOT_NEXT 1e-17

void abrdf__marschner_setup(const abrdf_params *p, abrdf__marschner *m)
{
    m->eta = p->eta;
    m->aspect = p->aspect_ratio;
    abrdf__hair_sigma_a(p->melanin, p->redness, m->sigma_a);
    double a_r = -2.0 * p->cuticle_tilt * ABRDF__HAIR_DEG;
    double b_r = p->r;
    m->alpha[0] = a_r;
    m->alpha[1] = -a_r / 2.0;
    m->alpha[2] = -3.0 * a_r / 2.0;
    m->beta[0] = b_r;
    m->beta[1] = b_r / 2.0;
    m->beta[2] = 2.0 * b_r;
}

double abrdf__marschner_mp(const abrdf__marschner *m, int p, double theta_h)
{
    return 0.5 * abrdf__gauss(theta_h - m->alpha[p], m->beta[p]);
}

/* max(x, lo) for a finite lo: lo when x is NaN, as fmax, but inline (fmax is a libm call). */
static double at_least(double x, double lo) { return x > lo ? x : lo; }

/* abrdf__clamp(x, -1, 1), inline. */
static double clamp_unit(double x) { return x > -1.0 ? (x < 1.0 ? x : 1.0) : -1.0; }

/* abrdf__wrap_pi for an angle within 3 pi of 0 (every one wrapped here: differences and sums
 * of two wrapped angles), without its fmod. */
static double wrap_pi_near(double a)
{
    if (a > ABRDF__PI) return a - 2.0 * ABRDF__PI;
    if (a <= -ABRDF__PI) return a + 2.0 * ABRDF__PI;
    return a;
}

/* Phi(p, h) from gamma_t = asin(h / eta') and gamma_i = asin h. */
static double phi_of_gammas(int p, double gamma_t, double gamma_i)
{
    return 2.0 * p * gamma_t - 2.0 * gamma_i + p * ABRDF__PI;
}

/* Phi(p, h) and its first two derivatives in h, for |h| < 1 <= eta1. */
static double phi_of(int p, double h, double eta1)
{
    return phi_of_gammas(p, asin(h / eta1), asin(h));
}

/* x^1.5 for x >= 0. */
static double pow_1_5(double x) { return x * sqrt(x); }

static double d2phi_dh2(int p, double h, double eta1)
{
    return 2.0 * p * h / pow_1_5(eta1 * eta1 - h * h) - 2.0 * h / pow_1_5(1.0 - h * h);
}

/* Fresnel amplitude (c - n ct) / (c + n ct) squared, for incidence cosine c and refracted
 * cosine ct (abrdf__fresnel_s's; abrdf__fresnel_p's with c and ct swapped): 1 where the
 * denominator vanishes (grazing). */
static double fresnel_r2(double c, double n, double ct)
{
    double den = c + n * ct;
    if (!(den > 0.0)) return 1.0;
    double r = (c - n * ct) / den;
    return r * r;
}

/* The refracted cosine sqrt(1 - s2) for the squared refracted sine s2, or -1 for total
 * internal reflection. */
static double cos_of_sin2(double s2) { return s2 >= 1.0 ? -1.0 : sqrt(1.0 - s2); }

/* A_p from h^2 <= 1 and the cosines of gamma_i and gamma_t (sin gamma_t = h / eta').
 * Snell's law in the normal plane makes the four Fresnel terms share their cosines: entry
 * and exit for eta' (perpendicular) are the same reflectance, F_s(eta', cos gamma_i) =
 * F_s(1/eta', cos gamma_t), and the parallel ones refract at sin = h / eta'' and
 * h eta'' / eta'. */
static void ap_of(const abrdf__marschner *m, int p, double h2, double cos_gi, double cos_gt,
                  double eta1, double eta2, double cos_theta_t, double a[3])
{
    double fs = fresnel_r2(cos_gi, eta1, cos_gt); /* eta1 >= 1: no total reflection */
    double cpi = cos_of_sin2(h2 / (eta2 * eta2));
    double fi = 0.5 * (fs + (cpi < 0.0 ? 1.0 : fresnel_r2(eta2 * cos_gi, 1.0, cpi)));
    if (p == 0) {
        a[0] = a[1] = a[2] = fi; /* A_0 */
        return;
    }
    double cpo = cos_of_sin2(h2 * (eta2 * eta2) / (eta1 * eta1));
    double fo = 0.5 * (fs + (cpo < 0.0 ? 1.0 : fresnel_r2(cos_gt, eta2, cpo)));
    double ct = at_least(cos_theta_t, ABRDF__HAIR_COS_MIN);
    double tr = (1.0 - fi) * (1.0 - fo);
    for (int q = 1; q < p; ++q) tr *= fo; /* F^(p-1) */
    for (int c = 0; c < 3; ++c) {
        /* sigma_a = 0 must give T = 1 even where cos_theta_t -> 0 (no 0/0). */
        double tau = m->sigma_a[c] > 0.0 ? 2.0 * m->sigma_a[c] * cos_gt / ct : 0.0;
        a[c] = tr * exp(-tau * p); /* T^p */
    }
}

void abrdf__marschner_ap(const abrdf__marschner *m, int p, double h, double eta1, double eta2,
                         double cos_theta_t, double a[3])
{
    double h2 = h * h < 1.0 ? h * h : 1.0;
    ap_of(m, p, h2, sqrt(1.0 - h2), sqrt(1.0 - h2 / (eta1 * eta1)), eta1, eta2, cos_theta_t, a);
}

/* Bravais indices for index eta at theta_d, and the refracted longitudinal cosine. */
static void bravais(double eta, double sin_d, double cos_d, double *eta1, double *eta2,
                    double *cos_t)
{
    double q = sqrt(at_least(eta * eta - sin_d * sin_d, 0.0));
    *eta1 = at_least(q / cos_d, 1.0);
    *eta2 = eta * eta * cos_d / at_least(q, ABRDF__HAIR_COS_MIN);
    double st = sin_d / eta;
    *cos_t = sqrt(at_least(1.0 - st * st, 0.0));
}

/* Marschner's eccentricity trick for TRT: the effective index for an elliptical section. */
static double eta_star(double eta, double a, double cos_phi_sum)
{
    double e1 = 2.0 * (eta - 1.0) * a * a - eta + 2.0;
    double e2 = 2.0 * (eta - 1.0) / (a * a) - eta + 2.0;
    return at_least(0.5 * ((e1 + e2) + cos_phi_sum * (e1 - e2)), 1.0);
}

/* One end of a piece of [-1, 1] on which Phi is monotone: h, gamma_i = asin h, Phi(p, h). */
typedef struct phi_end {
    double h, gamma, phi;
} phi_end;

/* The ends of the monotone pieces of Phi(p, .) on [-1, 1], in increasing h; returns their
 * count (2, or 4 with the caustics +-h_c). Phi'(h) = 0 where p^2 (1 - h^2) = eta'^2 - h^2:
 * the caustic, inside (-1, 1) only for p >= 2 and eta' < p. Phi(p, -h) = 2 p pi - Phi(p, h)
 * up to rounding, but each end is evaluated as phi_of does, for the same bits. */
static int phi_ends(int p, double eta1, phi_end e[4])
{
    double gt = p > 0 ? asin(1.0 / eta1) : 0.0, gi = asin(1.0); /* R: Phi has no gamma_t */
    e[0].h = -1.0;
    e[0].gamma = -gi;
    e[0].phi = phi_of_gammas(p, -gt, -gi);
    int n = 1;
    if (p >= 2 && eta1 < p) {
        double hc = sqrt((p * p - eta1 * eta1) / (p * p - 1.0));
        double ct = asin(hc / eta1), ci = asin(hc);
        e[1].h = -hc;
        e[1].gamma = -ci;
        e[1].phi = phi_of_gammas(p, -ct, -ci);
        e[2].h = hc;
        e[2].gamma = ci;
        e[2].phi = phi_of_gammas(p, ct, ci);
        n = 3;
    }
    e[n].h = 1.0;
    e[n].gamma = gi;
    e[n].phi = phi_of_gammas(p, gt, gi);
    return n + 1;
}

/* Below this step d (the last Newton steps of a root search are), sin and cos of x + d come
 * from those of x by the angle-sum formulas with Taylor's series for sin d and cos d to d^5
 * and d^4: the terms left out are below d^6 / 720 < 1e-20, and each such update adds an ulp
 * or so of rounding. */
#define ABRDF__MARSCHNER_STEP_TAYLOR 1e-3

/* sin and cos of x + d from *s = sin x and *c = cos x, in place (|d| small, as above). */
static void rotate_small(double d, double *s, double *c)
{
    double d2 = d * d;
    double cd = 1.0 - d2 * (0.5 - d2 * (1.0 / 24.0));
    double sd = d * (1.0 - d2 * (1.0 / 6.0 - d2 * (1.0 / 120.0)));
    double sx = *s, cx = *c;
    *s = sx * cd + cx * sd;
    *c = cx * cd - sx * sd;
}

/* The root h = sin gamma_i of Phi(p, h) = target between the ends lo and hi, where Phi is
 * monotone and target lies between their values. R (p = 0) is exact: Phi = -2 gamma_i. */
static double root_h(int p, double target, double eta1, const phi_end *lo, const phi_end *hi)
{
    if (p == 0) return sin(-0.5 * target);
    /* Safeguarded Newton in gamma_i: Phi is monotone on the piece, so the root stays
     * bracketed; dPhi/dgamma_i is 0 at a caustic, where the Newton step leaves the bracket
     * and a bisection is taken instead. */
    int inc = hi->phi > lo->phi;
    double x0 = lo->gamma, x1 = hi->gamma;
    double x = x0 + (target - lo->phi) * (x1 - x0) / (hi->phi - lo->phi); /* the secant */
    if (!(x > x0 && x < x1)) x = 0.5 * (x0 + x1);
    double last = 0.0;                 /* the previous Newton step, 0 after a bisection */
    double xs = x, sx = 0.0, cx = 1.0; /* sin and cos at xs */
    for (int it = 0; it < ABRDF__MARSCHNER_BISECT_STEPS; ++it) {
        if (it > 0 && fabs(x - xs) < ABRDF__MARSCHNER_STEP_TAYLOR) {
            rotate_small(x - xs, &sx, &cx);
        } else {
            sx = sin(x);
            cx = cos(x);
        }
        xs = x;
        double g = phi_of_gammas(p, asin(sx / eta1), x) - target;
        if (g == 0.0) break; /* on the root (its Newton step would not move) */
        if ((g < 0.0) == inc)
            x0 = x;
        else
            x1 = x;
        /* dPhi/dgamma_i = 2 p cos(gamma_i) / (eta' cos(gamma_t)) - 2 */
        double dg = 2.0 * p * cx / sqrt(eta1 * eta1 - sx * sx) - 2.0;
        double xn = x - g / dg;
        int newton = xn > x0 && xn < x1;
        if (!newton) xn = 0.5 * (x0 + x1);
        double step = fabs(xn - x);
        x = xn;
        if (step <= ABRDF__MARSCHNER_ROOT_TOL) break;
        if (newton && last > 0.0 && step < last &&
            step * step * step <= ABRDF__MARSCHNER_ROOT_NEXT * last * last)
            break;
        last = newton ? step : 0.0;
    }
    if (x == xs) return sx;
    if (!(fabs(x - xs) < ABRDF__MARSCHNER_STEP_TAYLOR)) return sin(x);
    rotate_small(x - xs, &sx, &cx);
    return sx;
}

/* Bare root sum: sum over roots h of Phi(p, h) = phi (mod 2 pi) of A_p(h) / |2 Phi'(h)|,
 * with the ends of the monotone pieces of Phi from phi_ends. */
static void root_sum(const abrdf__marschner *m, int p, double phi, double eta1, double eta2,
                     double cos_t, const phi_end *ends, int nend, double n[3])
{
    n[0] = n[1] = n[2] = 0.0;
    for (int k = 0; k + 1 < nend; ++k) {
        const phi_end *a = &ends[k], *b = &ends[k + 1];
        if (fabs(b->phi - a->phi) < ABRDF__HAIR_FLAT_PHI) continue;
        double lo = a->phi < b->phi ? a->phi : b->phi, hi = a->phi < b->phi ? b->phi : a->phi;
        /* Every branch phi + 2 pi j inside [lo, hi] has exactly one root here. */
        double j0 = ceil((lo - phi) / (2.0 * ABRDF__PI)),
               j1 = floor((hi - phi) / (2.0 * ABRDF__PI));
        for (double j = j0; j <= j1; j += 1.0) {
            double h = root_h(p, phi + 2.0 * ABRDF__PI * j, eta1, a, b);
            if (!(fabs(h) < 1.0)) continue; /* |dPhi/dh| is infinite at |h| = 1: N = 0 */
            double h2 = h * h, cos_gi = sqrt(1.0 - h2), cos_gt = sqrt(1.0 - h2 / (eta1 * eta1));
            /* dPhi/dh = 2 p / sqrt(eta'^2 - h^2) - 2 / sqrt(1 - h^2) */
            double d =
                at_least(fabs(2.0 * p / (eta1 * cos_gt) - 2.0 / cos_gi), ABRDF__HAIR_DPHI_MIN);
            double ap[3];
            ap_of(m, p, h2, cos_gi, cos_gt, eta1, eta2, cos_t, ap);
            for (int c = 0; c < 3; ++c) n[c] += ap[c] / (2.0 * d);
        }
    }
}

/* N_p with phi already wrapped into (-pi, pi] and the sine and the (floored) cosine of
 * theta_d given. */
static void np_sc(const abrdf__marschner *m, int p, double phi, double sin_d, double cos_d,
                  double cos_phi_sum, int glint, double n[3])
{
    double eta = p == 2 ? eta_star(m->eta, m->aspect, cos_phi_sum) : m->eta;
    double eta1, eta2, cos_t;
    bravais(eta, sin_d, cos_d, &eta1, &eta2, &cos_t);
    phi_end ends[4];
    int nend = phi_ends(p, eta1, ends);
    root_sum(m, p, phi, eta1, eta2, cos_t, ends, nend, n);
    if (p != 2 || !glint) return;

    /* TRT glint smoothing (paper Sec. 4.4): the caustic at +-phi_c is cut out of the root sum
     * with a Gaussian notch of width w_c and replaced by a Gaussian glint of energy
     * k_G A(h_c) Delta h. Past eta' = 2 the caustics merge at phi = 0 and fade out over
     * Delta eta' (t = 1 - smoothstep). */
    double hc, dh, t, phic;
    if (nend == 4) { /* eta' < 2: the caustic is the end h_c of phi_ends */
        hc = ends[2].h;
        phic = ends[2].phi;
        double d2 = fabs(d2phi_dh2(2, hc, eta1));
        dh = d2 > 0.0 ? fmin(ABRDF__MARSCHNER_GLINT_DHM,
                             2.0 * sqrt(2.0 * ABRDF__MARSCHNER_GLINT_WC / d2))
                      : ABRDF__MARSCHNER_GLINT_DHM;
        t = 1.0;
    } else {
        hc = 0.0;
        phic = phi_of(2, hc, eta1);
        dh = ABRDF__MARSCHNER_GLINT_DHM;
        double x = fmin(1.0, (eta1 - 2.0) / ABRDF__MARSCHNER_GLINT_DETA);
        t = 1.0 - x * x * (3.0 - 2.0 * x);
    }
    if (!(t > 0.0)) return;
    phic = abrdf__wrap_pi(phic);
    /* the Gaussians of width w_c at phi -+ phi_c, relative to their peak g0 */
    double xm = wrap_pi_near(phi - phic), xp = wrap_pi_near(phi + phic);
    double k = -0.5 / (ABRDF__MARSCHNER_GLINT_WC * ABRDF__MARSCHNER_GLINT_WC);
    double em = exp(k * (xm * xm)), ep = exp(k * (xp * xp));
    double g0 = 1.0 / (ABRDF__MARSCHNER_GLINT_WC * 2.5066282746310002); /* sqrt(2 pi) */
    double notch = (1.0 - t * em) * (1.0 - t * ep);
    double ac[3];
    abrdf__marschner_ap(m, 2, hc, eta1, eta2, cos_t, ac);
    for (int c = 0; c < 3; ++c)
        n[c] = n[c] * notch + t * ABRDF__MARSCHNER_GLINT_KG * ac[c] * dh * (g0 * (em + ep));
}

void abrdf__marschner_np(const abrdf__marschner *m, int p, double phi, double theta_d,
                         double cos_phi_sum, int glint, double n[3])
{
    np_sc(m, p, abrdf__wrap_pi(phi), sin(theta_d), fmax(cos(theta_d), ABRDF__HAIR_COS_MIN),
          cos_phi_sum, glint, n);
}

void abrdf__marschner_fibre(const abrdf__marschner *m, const double wi[3], const double wo[3],
                            unsigned lobes, double s[3])
{
    s[0] = s[1] = s[2] = 0.0;
    double si = clamp_unit(wi[0]), so = clamp_unit(wo[0]);
    double ci = sqrt(wi[1] * wi[1] + wi[2] * wi[2]), co = sqrt(wo[1] * wo[1] + wo[2] * wo[2]);
    /* theta_h = (theta_i + theta_o) / 2 from the sum's sine and cosine (one atan2, no asin);
     * theta_d's sine and cosine from the difference's by the half-angle formulas, each taken
     * where it does not cancel (|theta_d| < pi / 2, so cos theta_d >= 0) */
    double th = 0.5 * atan2(si * co + ci * so, ci * co - si * so);
    double s2d = so * ci - co * si, c2d = co * ci + so * si, sd, cd;
    if (c2d >= 0.0) {
        cd = sqrt(0.5 * (1.0 + c2d));
        sd = 0.5 * s2d / cd;
    } else {
        sd = copysign(sqrt(0.5 * (1.0 - c2d)), s2d);
        cd = 0.5 * s2d / sd;
    }
    cd = at_least(cd, ABRDF__HAIR_COS_MIN);
    /* phi = phi_o - phi_i and cos(phi_i + phi_o) = cos(2 phi_h) from the directions' (y, z)
     * parts, of lengths ci and co */
    double phi, cps, cc = ci * co;
    if (cc > 0.0) {
        double yy = wi[1] * wo[1], zz = wi[2] * wo[2];
        phi = atan2(wi[1] * wo[2] - wi[2] * wo[1], yy + zz);
        cps = (yy - zz) / cc;
    } else { /* along the fibre: azimuth 0, atan2(0, 0)'s (abrdf__fibre_angles) */
        double pi_ = atan2(wi[2], wi[1]), po = atan2(wo[2], wo[1]);
        phi = abrdf__wrap_pi(po - pi_);
        cps = cos(pi_ + po);
    }
    for (int p = 0; p < 3; ++p) {
        if (!(lobes & (1u << p))) continue;
        double n[3];
        np_sc(m, p, phi, sd, cd, cps, 1, n);
        double w = abrdf__marschner_mp(m, p, th) / (cd * cd) * ci; /* S = S_M cos(theta_i) */
        for (int c = 0; c < 3; ++c) s[c] += w * n[c];
    }
}

void abrdf__marschner_eval(const abrdf__marschner *m, const double wi[3], const double wo[3],
                           double f[3])
{
    f[0] = f[1] = f[2] = 0.0;
    if (!(wi[2] > 0.0 && wo[2] > 0.0)) return;
    double s[3];
    abrdf__marschner_fibre(m, wi, wo, 7u, s);
    for (int c = 0; c < 3; ++c) f[c] = s[c] / wi[2]; /* f_r = S / |N.wi| */
}
