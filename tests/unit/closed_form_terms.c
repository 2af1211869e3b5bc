/* closed_form_terms.c - the split terms of the kernels (guards, Schlick F, D, G, the
 * Table-5 normalisations) in the double instantiation, against hand formulas and against
 * their defining property: every distribution D integrates to 1 over the projected
 * hemisphere of half vectors, int D(h) cos(theta_h) dw_h = 1 (MODELS.md B5.2). Part of the
 * test_closed_form suite. The kernel headers are included in double (ABRDF__KERNEL_FLOAT
 * not defined), so the plain names below are the double kernels (kernel.h, naming rule). */
#include "kernel.h"
#include "k_empirical.h"
#include "k_energy.h"
#include "k_microfacet.h"

#include <check.h>
#include "test_util.h"

#define PI_ 3.14159265358979323846

TCase *closed_form_terms_tcase(void);

START_TEST(guards)
{
    ck_assert(pos(-1.0) == 0.0 && pos(NAN) == 0.0 && pos(2.0) == 2.0);
    ck_assert(safe_sqrt(-1e-30) == 0.0 && safe_sqrt(4.0) == 2.0);
    ck_assert(safe_div(1.0, 0.0) == 0.0 && safe_div(1.0, 4.0) == 0.25);
    ck_assert(pow_pos(-0.5, 2.0) == 0.0 && pow_pos(-0.5, 0.5) == 0.0);
    ck_assert(pow2k(-3.0, 1) == 0.0 && pow2k(0.5, 4) == pow(0.5, 16.0));
    ck_assert(clampr(2.0, -1.0, 1.0) == 1.0 && clampr(-2.0, -1.0, 1.0) == -1.0);
    /* the Table-1 base is clamped before squaring: no spurious lobe at n = 64, c = 0.5 */
    ck_assert(lobe_fm(64.0, 0.5, 1) == 0.0);
    ck_assert(tu_close(lobe_fm(2.0, 0.3, 1), 0.09, 1e-15, 0.0)); /* n = m: c^m */
}
END_TEST

START_TEST(schlick_fresnel)
{
    static const double f0s[] = {0.0, 0.04, 0.5, 1.0};
    for (int k = 0; k < 4; ++k) {
        double f0 = f0s[k];
        ck_assert(f_schlick(f0, 1.0) == f0);                      /* normal incidence */
        ck_assert(tu_close(f_schlick(f0, 0.0), 1.0, 1e-15, 0.0)); /* grazing */
        ck_assert(tu_close(f_schlick(f0, 0.5), f0 + (1.0 - f0) / 32.0, 1e-15, 0.0));
        ck_assert(f_schlick(f0, 1.5) == f0); /* cos_d clamped */
        ck_assert(tu_close(f_schlick(f0, -0.5), 1.0, 1e-15, 0.0));
    }
}
END_TEST

/* 2 pi int_0^{pi/2} D(theta) cos(theta) sin(theta) dtheta by composite Gauss-Legendre on
 * panels graded towards theta = 0 (where narrow distributions live). */
static const double glx[8] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290,
                              -0.1834346424956498, 0.1834346424956498,  0.5255324099163290,
                              0.7966664774136267,  0.9602898564975363};
static const double glw[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
                              0.3626837833783620, 0.3626837833783620, 0.3137066458778873,
                              0.2223810344533745, 0.1012285362903763};

typedef double (*ndf1)(double ch, double sh2, double a);

static double ndf_integral(ndf1 d, double a)
{
    double sum = 0.0, lo = 0.0;
    for (int k = 40; k >= 0; --k) { /* panels [pi/2 2^-(k+1), pi/2 2^-k] and [0, first] */
        double hi = 0.5 * PI_ * ldexp(1.0, -k);
        for (int sub = 0; sub < 8; ++sub) {
            double a0 = lo + (hi - lo) * sub / 8.0, a1 = lo + (hi - lo) * (sub + 1) / 8.0;
            for (int j = 0; j < 8; ++j) {
                double t = a0 + 0.5 * (a1 - a0) * (glx[j] + 1.0);
                double c = cos(t), s = sin(t);
                sum += 0.5 * (a1 - a0) * glw[j] * d(c, s * s, a) * c * s;
            }
        }
        lo = hi;
    }
    return 2.0 * PI_ * sum;
}

START_TEST(distributions_normalised)
{
    static const double as[] = {0.01, 0.05, 0.3, 1.0};
    for (int k = 0; k < 4; ++k) {
        double a = as[k];
        double g = ndf_integral(d_ggx, a), b = ndf_integral(d_beckmann, a);
        ck_assert_msg(fabs(g - 1.0) < 1e-9, "GGX alpha %g integrates to %.12f", a, g);
        ck_assert_msg(fabs(b - 1.0) < 1e-9, "Beckmann alpha %g integrates to %.12f", a, b);
    }
    static const double cc[] = {0.001, 0.0505, 0.1, 0.5, 0.9};
    for (int k = 0; k < 5; ++k) {
        double v = ndf_integral(d_gtr1, cc[k]);
        ck_assert_msg(fabs(v - 1.0) < 1e-9, "GTR1 alpha %g integrates to %.12f", cc[k], v);
    }
    ck_assert(tu_close(d_gtr1(0.7, 0.51, 1.0), 1.0 / PI_, 1e-15, 0.0)); /* alpha = 1 limit */
    /* hand values (Eq. 6, Beckmann, GTR1) at theta_h = 20 deg */
    double t = 20.0 * PI_ / 180.0, c = cos(t), s2 = sin(t) * sin(t), a = 0.3, a2 = a * a;
    ck_assert(
        tu_close(d_ggx(c, s2, a), a2 / (PI_ * pow(1.0 + (a2 - 1.0) * c * c, 2.0)), 1e-13, 0.0));
    ck_assert(tu_close(d_beckmann(c, s2, a), exp(-tan(t) * tan(t) / a2) / (PI_ * a2 * pow(c, 4.0)),
                       1e-13, 0.0));
    ck_assert(tu_close(d_gtr1(c, s2, a), (a2 - 1.0) / (PI_ * log(a2) * (1.0 + (a2 - 1.0) * c * c)),
                       1e-13, 0.0));
    ck_assert(d_beckmann(0.0, 1.0, 0.3) == 0.0 && d_beckmann(-0.5, 0.75, 0.3) == 0.0);
}
END_TEST

START_TEST(anisotropic_ggx)
{
    /* ax = ay: the isotropic D (Eq. 7 reduces to Eq. 6) */
    double h[3] = {0.3, -0.2, 0.0};
    h[2] = sqrt(1.0 - h[0] * h[0] - h[1] * h[1]);
    double sh2 = h[0] * h[0] + h[1] * h[1];
    ck_assert(tu_close(d_ggx_aniso(h[0], h[1], h[2], 0.2, 0.2), d_ggx(h[2], sh2, 0.2), 1e-13, 0.0));
    ck_assert(tu_close(v1_smith_ggx_aniso(h[0], h[1], h[2], 0.2, 0.2), v1_smith_ggx(h[2], 0.2),
                       1e-13, 0.0));
    /* ax != ay: int D cos dw = 1 by a product rule (GL in theta on graded panels x
     * trapezoid in phi, spectrally accurate for this smooth periodic integrand) */
    double ax = 0.4, ay = 0.1, sum = 0.0, lo = 0.0;
    const int nphi = 256;
    for (int k = 20; k >= 0; --k) {
        double hi = 0.5 * PI_ * ldexp(1.0, -k);
        for (int j = 0; j < 8; ++j) {
            double t = lo + 0.5 * (hi - lo) * (glx[j] + 1.0);
            for (int q = 0; q < nphi; ++q) {
                double p = 2.0 * PI_ * (q + 0.5) / nphi;
                double x = sin(t) * cos(p), y = sin(t) * sin(p), z = cos(t);
                sum += 0.5 * (hi - lo) * glw[j] * (2.0 * PI_ / nphi) *
                       d_ggx_aniso(x, y, z, ax, ay) * z * sin(t);
            }
        }
        lo = hi;
    }
    ck_assert_msg(fabs(sum - 1.0) < 1e-6, "anisotropic GGX integrates to %.10f", sum);
}
END_TEST

START_TEST(smith_and_cook_torrance_g)
{
    static const double as[] = {0.05, 0.3, 1.0}, cs[] = {0.01, 0.3, 0.7, 1.0};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j) {
            double a = as[i], c = cs[j], tan2 = (1.0 - c * c) / (c * c);
            double g1 = 2.0 / (1.0 + sqrt(1.0 + a * a * tan2)); /* Eq. 9 */
            ck_assert(tu_close(g1_smith_ggx(c, a), g1, 1e-13, 0.0));
            ck_assert(tu_close(v1_smith_ggx(c, a), g1 / (2.0 * c), 1e-13, 0.0)); /* G1/(2 cos) */
        }
    ck_assert(g1_smith_ggx(0.0, 0.3) == 0.0 && g1_smith_ggx(-0.2, 0.3) == 0.0);
    ck_assert(tu_close(v1_smith_ggx(0.0, 0.3), 1.0 / 0.3, 1e-15, 0.0)); /* bounded at grazing */
    /* Cook-Torrance V-cavity G = min(1, 2 NH NV / VH, 2 NH NL / VH) */
    abrdf__geo g;
    double wi[3] = {0.6, 0.0, 0.8}, wo[3] = {-0.28, 0.0, 0.96};
    geo_make(&g, wi[0], wi[1], wi[2], wo[0], wo[1], wo[2]);
    double vh = wo[0] * g.hx + wo[1] * g.hy + wo[2] * g.hz;
    double e = fmin(1.0, fmin(2 * g.ch * 0.96 / vh, 2 * g.ch * 0.8 / vh));
    ck_assert(tu_close(g_cook_torrance(&g), e, 1e-14, 0.0));
    double gi[3] = {0.9998, 0.0, 0.02}; /* grazing light: the NL branch wins */
    double n = sqrt(gi[0] * gi[0] + gi[2] * gi[2]);
    geo_make(&g, gi[0] / n, 0.0, gi[2] / n, -0.5, 0.0, sqrt(0.75));
    vh = -0.5 * g.hx + sqrt(0.75) * g.hz;
    ck_assert(tu_close(g_cook_torrance(&g), 2 * g.ch * (gi[2] / n) / vh, 1e-13, 0.0));
}
END_TEST

START_TEST(table5_normalisations)
{
    static const double ns[] = {0.0, 1.0, 10.0, 1000.0};
    for (int k = 0; k < 4; ++k) {
        double n = ns[k];
        ck_assert(tu_close(norm_phe(n), (n + 2) / (2 * PI_), 1e-15, 0.0));
        ck_assert(
            tu_close(norm_be(n), (n + 2) * (n + 4) / (8 * PI_ * (pow(2, -n / 2) + n)), 1e-15, 0.0));
        ck_assert(tu_close(norm_16e(n), (1.063 * n + 1) / (2 * PI_), 1e-15, 0.0));
        ck_assert(tu_close(norm_ge(n), (n + 2) / (4 * PI_ * (2 - pow(2, -n / 2))), 1e-15, 0.0));
        if (n > 0) ck_assert(tu_close(norm_2e(n), 0.111 / n + 0.238 * (0.481 + n), 1e-15, 0.0));
    }
    /* n = 0: f_phe and f_be become Lambert's 1/pi */
    ck_assert(tu_close(norm_phe(0.0), 1.0 / PI_, 1e-15, 0.0));
    ck_assert(tu_close(norm_be(0.0), 1.0 / PI_, 1e-15, 0.0));
}
END_TEST

START_TEST(geometry)
{
    abrdf__geo g;
    double wi[3] = {0.6, 0.0, 0.8}, wo[3] = {0.0, 0.6, 0.8};
    geo_make(&g, wi[0], wi[1], wi[2], wo[0], wo[1], wo[2]);
    double s = sqrt(0.36 + 0.36 + 2.56);
    ck_assert(tu_close(g.hx, 0.6 / s, 1e-15, 0.0) && tu_close(g.hz, 1.6 / s, 1e-15, 0.0));
    ck_assert(
        tu_close(g.cd, wi[0] * g.hx + wi[1] * g.hy + wi[2] * g.hz, 1e-15, 0.0)); /* |L+V|/2 = L.H */
    ck_assert(tu_close(g.sh2, 1.0 - g.ch * g.ch, 1e-15, 0.0));
    ck_assert(tu_close(g.rv, 2 * 0.8 * 0.8 - (0.6 * 0.0 + 0.0 * 0.6 + 0.8 * 0.8), 1e-15, 0.0));
    geo_make(&g, 0.6, 0.0, 0.8, -0.6, 0.0, -0.8); /* wi = -wo: H undefined, rejected */
    ck_assert(g.cd == 0.0 && !geo_front(&g));
}
END_TEST

TCase *closed_form_terms_tcase(void)
{
    TCase *tc = tcase_create("split_terms");
    tcase_add_test(tc, guards);
    tcase_add_test(tc, schlick_fresnel);
    tcase_add_test(tc, distributions_normalised);
    tcase_add_test(tc, anisotropic_ggx);
    tcase_add_test(tc, smith_and_cook_torrance_g);
    tcase_add_test(tc, table5_normalisations);
    tcase_add_test(tc, geometry);
    return tc;
}
