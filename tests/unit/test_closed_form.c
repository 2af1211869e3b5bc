/* test_closed_form.c - every model against an independent hand computation, written out term
 * by term here from the published formula (docs/MODELS.md), not through the library's
 * kernels: the half vector, mirror vector, angles and every factor are recomputed in this
 * file, often in a different but equivalent form (angles and trigonometry where the kernel
 * uses dot products, the monomial cubic where the kernel uses the form about c = 1, Smith's
 * Lambda form where the kernel uses the visibility form). Also abrdf_shade and
 * abrdf_frame_make. The split terms are tested in closed_form_terms.c, the roughness
 * converters in test_converters.c.
 *
 * Tolerance: 1e-11 relative. Both sides are double and differ only in rounding order; the
 * largest amplification on these configurations is c^n with n = 1000 (1e-16 * n / (1 - c)). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "abrdf_internal.h"
#include "test_util.h"

TCase *closed_form_terms_tcase(void); /* closed_form_terms.c */

static const double PI = 3.14159265358979323846;
#define REL 1e-11

/* ---- hand geometry ------------------------------------------------------------------ */

static double dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

typedef struct hand {
    double wi[3], wo[3];
    double ci, co; /* cos theta_i, cos theta_o */
    double h[3];   /* half vector */
    double ch, cd; /* N.H, L.H */
    double rv;     /* (2 (N.L) N - L) . V */
} hand;

/* The configurations every model is checked on: (theta_i, phi_i, theta_o, phi_o) in
 * degrees. Near-mirror pairs keep sharp lobes away from 0; one pair lies almost at grazing;
 * two lie on the light's side, where retro-reflective terms live. */
static const double configs[][4] = {
    {30, 180, 50, 20},  /* generic */
    {10, 0, 15, 170},   /* close to the mirror direction */
    {40, 30, 40, 212},  /* 2 deg from the mirror direction */
    {70, 45, 60, 200},  /* oblique */
    {0, 0, 0, 0},       /* wi = wo = N: every lobe at its peak */
    {85, 90, 80, 275},  /* near grazing, near mirror */
    {30, 0, 50, 20},    /* back-scattering side (Oren-Nayar's B term is non-zero) */
    {60, 100, 45, 130}, /* back-scattering, oblique */
};
#define NCONF ((int)(sizeof configs / sizeof configs[0]))

static hand hand_make(int k)
{
    hand g;
    tu_dir(configs[k][0], configs[k][1], g.wi);
    tu_dir(configs[k][2], configs[k][3], g.wo);
    g.ci = g.wi[2];
    g.co = g.wo[2];
    double s[3] = {g.wi[0] + g.wo[0], g.wi[1] + g.wo[1], g.wi[2] + g.wo[2]};
    double l = sqrt(dot(s, s));
    for (int c = 0; c < 3; ++c) g.h[c] = s[c] / l;
    g.ch = g.h[2];
    g.cd = dot(g.wi, g.h);
    double mir[3] = {-g.wi[0], -g.wi[1], g.wi[2]}; /* 2 (N.L) N - L with N = z */
    g.rv = dot(mir, g.wo);
    return g;
}

static double schlick(double f0, double cd)
{
    return f0 + (1.0 - f0) * pow(1.0 - cd, 5.0);
} /* Eq. 8 */

/* Compares channel 0 of the library against `expect` for model m with params p. */
static void expect_eq(abrdf_model m, const abrdf_params *p, const hand *g, double expect,
                      double rel, const char *what)
{
    double got = tu_eval1(m, p, g->wi, g->wo);
    ck_assert_msg(tu_close(got, expect, rel, 1e-300), "%s %s: library %.17g, hand %.17g",
                  abrdf_model_get(m)->name, what, got, expect);
}

static abrdf_params params(abrdf_model m)
{
    abrdf_params p;
    ck_assert_int_eq(abrdf_params_init(m, &p), ABRDF_OK);
    return p;
}

/* ---- diffuse ------------------------------------------------------------------------ */

START_TEST(diffuse_models)
{
    abrdf_params p;
    for (int k = 0; k < NCONF; ++k) {
        hand g = hand_make(k);
        p = params(ABRDF_LAMBERT);
        p.kd[0] = 0.7;
        expect_eq(ABRDF_LAMBERT, &p, &g, 0.7 / PI, REL, "Eq. 1"); /* kd / pi */

        static const double f0s[] = {0.0, 0.04, 1.0};
        for (int j = 0; j < 3; ++j) {
            p = params(ABRDF_LAMBERT_FRESNEL);
            p.kd[0] = 0.8;
            p.f0[0] = f0s[j];
            expect_eq(ABRDF_LAMBERT_FRESNEL, &p, &g, 0.8 / PI * (1.0 - schlick(f0s[j], g.cd)), REL,
                      "Eq. 2");
        }

        static const double rs[] = {0.0, 0.5, 1.0};
        for (int j = 0; j < 3; ++j) {
            p = params(ABRDF_DISNEY_DIFFUSE);
            p.kd[0] = 0.6;
            p.r = rs[j];
            double fd90 = 0.5 + 2.0 * rs[j] * g.cd * g.cd; /* F_D90 = 0.5 + 2 r cos^2(theta_d) */
            double e = 0.6 / PI * (1.0 + (fd90 - 1.0) * pow(1.0 - g.ci, 5.0)) *
                       (1.0 + (fd90 - 1.0) * pow(1.0 - g.co, 5.0)); /* Eq. 3 */
            expect_eq(ABRDF_DISNEY_DIFFUSE, &p, &g, e, REL, "Eq. 3");
        }

        /* Oren-Nayar 1994 qualitative model with its angles, as printed:
         * (rho/pi)(A + B max(0, cos(phi_i - phi_o)) sin(alpha) tan(beta)). */
        static const double sig[] = {0.0, 0.3, 1.2};
        for (int j = 0; j < 3; ++j) {
            p = params(ABRDF_OREN_NAYAR);
            p.kd[0] = 0.9;
            p.sigma = sig[j];
            double s2 = sig[j] * sig[j];
            double A = 1.0 - 0.5 * s2 / (s2 + 0.33), B = 0.45 * s2 / (s2 + 0.09);
            double ti = acos(g.ci), to = acos(g.co);
            double pi_xy = hypot(g.wi[0], g.wi[1]), po_xy = hypot(g.wo[0], g.wo[1]);
            double cphi = (pi_xy > 0 && po_xy > 0)
                              ? (g.wi[0] * g.wo[0] + g.wi[1] * g.wo[1]) / (pi_xy * po_xy)
                              : 0.0;
            double alpha = fmax(ti, to), beta = fmin(ti, to);
            double e = 0.9 / PI * (A + B * fmax(0.0, cphi) * sin(alpha) * tan(beta));
            expect_eq(ABRDF_OREN_NAYAR, &p, &g, e, 1e-10, "qualitative ON");
        }
    }
}
END_TEST

/* ---- empirical lobes ---------------------------------------------------------------- */

static const double exps[] = {1.0, 2.0, 10.0, 100.0, 1000.0};
#define NEXP 5

START_TEST(phong_blinn_phong)
{
    for (int k = 0; k < NCONF; ++k) {
        hand g = hand_make(k);
        for (int j = 0; j < NEXP; ++j) {
            abrdf_params p = params(ABRDF_PHONG);
            p.ks[0] = 0.5;
            p.n = exps[j];
            expect_eq(ABRDF_PHONG, &p, &g, 0.5 * pow(fmax(0.0, g.rv), exps[j]), REL, "cos^n gamma");
            expect_eq(ABRDF_BLINN_PHONG, &p, &g, 0.5 * pow(g.ch, exps[j]), REL, "Eq. 4");
        }
    }
}
END_TEST

START_TEST(table1_approximations)
{
    static const abrdf_model fm[] = {ABRDF_F2, ABRDF_F4, ABRDF_F8, ABRDF_F16};
    static const double ms[] = {2.0, 4.0, 8.0, 16.0};
    for (int k = 0; k < NCONF; ++k) {
        hand g = hand_make(k);
        double c = g.ch;
        for (int j = 0; j < NEXP; ++j) {
            double n = exps[j];
            abrdf_params p = params(ABRDF_F2);
            p.ks[0] = 0.75;
            p.n = n;
            for (int q = 0; q < 4; ++q) { /* ((n/m)(c - 1) + 1)^m, zero where the base < 0 */
                double base = (n / ms[q]) * (c - 1.0) + 1.0;
                expect_eq(fm[q], &p, &g, 0.75 * (base > 0 ? pow(base, ms[q]) : 0.0), REL,
                          "Table 1");
            }
            expect_eq(ABRDF_FS, &p, &g, 0.75 * c / (n - n * c + c), REL, "Schlick");
            double a = 0.786 * n;
            expect_eq(ABRDF_FKV, &p, &g, 0.75 * fmax(0.0, a * c * c + (1.0 - a) * c), REL, "fkv");
        }
    }
    /* f_m with n = m is exactly c^m. */
    for (int k = 0; k < NCONF; ++k) {
        hand g = hand_make(k);
        for (int q = 0; q < 4; ++q) {
            abrdf_params p = params(fm[q]);
            p.ks[0] = 1.0;
            p.n = ms[q];
            expect_eq(fm[q], &p, &g, pow(g.ch, ms[q]), 1e-13, "n = m");
        }
    }
}
END_TEST

/* fkub: the documented monomial form A c^3 + B c^2 + C c with A = -d, B = b + 3d,
 * C = -a - 2b - 3d from the table's (a, b, d), clamped to [0, 1], zero below x0. */
START_TEST(fkub_cubic)
{
    static const double ns[] = {2.0, 5.0, 10.0, 37.0, 100.0};
    for (int j = 0; j < 5; ++j) {
        double abd[3], x0;
        abrdf__fkub_coeffs(ns[j], abd, &x0);
        double A = -abd[2], B = abd[1] + 3.0 * abd[2], C = -abd[0] - 2.0 * abd[1] - 3.0 * abd[2];
        ck_assert_msg(fabs(A + B + C - 1.0) < 1e-9, "fkub n=%g: f(1) = A + B + C = %.17g", ns[j],
                      A + B + C);
        /* the zone starts where c^n falls to a fixed fraction of its peak, for every n */
        double abd2[3], x02;
        abrdf__fkub_coeffs(1.0, abd2, &x02);
        ck_assert_msg(x0 > 0.0 && x0 < 1.0 && fabs(pow(x0, ns[j]) - x02) < 1e-12,
                      "fkub n=%g zone start %.17g", ns[j], x0);
        for (int k = 0; k < NCONF; ++k) {
            hand g = hand_make(k);
            double c = g.ch;
            double v = c >= x0 ? fmin(1.0, fmax(0.0, ((A * c + B) * c + C) * c)) : 0.0;
            abrdf_params p = params(ABRDF_FKUB);
            p.ks[0] = 0.9;
            p.n = ns[j];
            /* monomial vs. the kernel's form about c = 1: coefficients ~n^2 cancel */
            expect_eq(ABRDF_FKUB, &p, &g, 0.9 * v, 1e-9, "monomial form");
        }
    }
    /* exact at n = 2 (c^2 on the zone c >= x0, 0 below), f(1) = 1 for every n */
    abrdf_params p = params(ABRDF_FKUB);
    p.ks[0] = 1.0;
    p.n = 2.0;
    double abd[3], x0;
    abrdf__fkub_coeffs(2.0, abd, &x0);
    for (int k = 0; k < NCONF; ++k) {
        hand g = hand_make(k);
        expect_eq(ABRDF_FKUB, &p, &g, g.ch >= x0 ? g.ch * g.ch : 0.0, 1e-12, "n = 2 is c^2");
    }
    hand g = hand_make(4); /* wi = wo = N: c = 1 */
    static const double any[] = {0.25, 1.0, 3.3, 100.0, 12345.0, 1e6};
    for (int j = 0; j < 6; ++j) {
        p.n = any[j];
        expect_eq(ABRDF_FKUB, &p, &g, 1.0, 1e-12, "f(1) = 1");
    }
}
END_TEST

/* ---- Table 5 ------------------------------------------------------------------------ */

static double k_phe(double n) { return (n + 2.0) / (2.0 * PI); }
static double k_be(double n)
{
    return (n + 2.0) * (n + 4.0) / (8.0 * PI * (pow(2.0, -n / 2.0) + n));
}
static double k_2e(double n) { return 0.111 / n + 0.238 * (0.481 + n); }
static double k_16e(double n) { return (1.063 * n + 1.0) / (2.0 * PI); }
static double k_ge(double n) { return (n + 2.0) / (4.0 * PI * (2.0 - pow(2.0, -n / 2.0))); }
static double lobe(double n, double m, double c) /* ((n/m)(c - 1) + 1)^m, clamped */
{
    double b = (n / m) * (c - 1.0) + 1.0;
    return b > 0.0 ? pow(b, m) : 0.0;
}

START_TEST(table5_energy_conserving)
{
    static const double f0s[] = {0.0, 0.04, 1.0};
    for (int k = 0; k < NCONF; ++k) {
        hand g = hand_make(k);
        double rv = fmax(0.0, g.rv);
        for (int j = 0; j < NEXP; ++j) {
            double n = exps[j];
            abrdf_params p = params(ABRDF_F_PHE);
            p.ks[0] = 0.6;
            p.n = n;
            /* lobes about R (cos gamma): f_phe, f_2e, f_16e; about H: f_be, f_ge */
            expect_eq(ABRDF_F_PHE, &p, &g, 0.6 * k_phe(n) * pow(rv, n), REL, "f_phe");
            expect_eq(ABRDF_F_BE, &p, &g, 0.6 * k_be(n) * pow(g.ch, n), REL, "f_be");
            expect_eq(ABRDF_F_2E, &p, &g, 0.6 * k_2e(n) * lobe(n, 2, g.rv), REL, "f_2e");
            expect_eq(ABRDF_F_16E, &p, &g, 0.6 * k_16e(n) * lobe(n, 16, g.rv), REL, "f_16e");
            for (int q = 0; q < 3; ++q) {
                p.f0[0] = f0s[q];
                double F = schlick(f0s[q], g.cd);
                expect_eq(ABRDF_F_GE, &p, &g, 0.6 * k_ge(n) * F * pow(g.ch, n) / fmax(g.ci, g.co),
                          REL, "f_ge");
                double den = 4.0 * g.ci * g.co; /* G = 1; D on N.H */
                expect_eq(ABRDF_F_CTPHE, &p, &g, 0.6 * k_phe(n) * pow(g.ch, n) * F / den, REL,
                          "f_ctphe");
                expect_eq(ABRDF_F_CT2E, &p, &g, 0.6 * k_2e(n) * lobe(n, 2, g.ch) * F / den, REL,
                          "f_ct2e");
                expect_eq(ABRDF_F_CT16E, &p, &g, 0.6 * k_16e(n) * lobe(n, 16, g.ch) * F / den, REL,
                          "f_ct16e");
            }
        }
    }
    /* G = 1 forms clamp each cosine at 1e-4 (ABRDF__COS_MIN_NO_G): at cos_o = 1e-6 the
     * denominator is 4 cos_i 1e-4. */
    double wi[3] = {0.6, 0.0, 0.8}, wo[3] = {-sqrt(1.0 - 1e-12), 0.0, 1e-6};
    abrdf_params p = params(ABRDF_F_CTPHE);
    p.ks[0] = 1.0;
    p.n = 10.0;
    p.f0[0] = 1.0;
    double s[3] = {wi[0] + wo[0], 0.0, wi[2] + wo[2]};
    double ch = s[2] / sqrt(s[0] * s[0] + s[2] * s[2]);
    double e = k_phe(10.0) * pow(ch, 10.0) / (4.0 * 0.8 * 1e-4);
    double got = tu_eval1(ABRDF_F_CTPHE, &p, wi, wo);
    ck_assert_msg(tu_close(got, e, 1e-9, 0.0), "f_ctphe cosine clamp: %.17g vs %.17g", got, e);
}
END_TEST

/* ---- microfacet --------------------------------------------------------------------- */

static double g1_lambda(double a2tan2)
{
    return 2.0 / (1.0 + sqrt(1.0 + a2tan2));
} /* Smith, Eq. 9 */

START_TEST(cook_torrance_beckmann)
{
    static const double rs[] = {0.2, 0.5, 1.0};
    for (int k = 0; k < NCONF; ++k) {
        hand g = hand_make(k);
        for (int j = 0; j < 3; ++j) {
            abrdf_params p = params(ABRDF_COOK_TORRANCE);
            p.r = rs[j];
            p.ks[0] = 1.0;
            p.f0[0] = 0.5;
            double a = rs[j] * rs[j];
            double tan2 = (1.0 - g.ch * g.ch) / (g.ch * g.ch);
            double D = exp(-tan2 / (a * a)) / (PI * a * a * pow(g.ch, 4.0)); /* Beckmann */
            double vh = dot(g.wo, g.h);
            double G = fmin(1.0, fmin(2.0 * g.ch * g.co / vh, 2.0 * g.ch * g.ci / vh));
            double e = schlick(0.5, g.cd) * D * G / (4.0 * g.ci * g.co); /* Eq. 5 */
            expect_eq(ABRDF_COOK_TORRANCE, &p, &g, e, 1e-10, "Eq. 5, Beckmann");
        }
    }
}
END_TEST

START_TEST(disney_specular_ggx)
{
    static const double rs[] = {0.05, 0.4, 1.0};
    for (int k = 0; k < NCONF; ++k) {
        hand g = hand_make(k);
        for (int j = 0; j < 3; ++j) {
            abrdf_params p = params(ABRDF_DISNEY_SPECULAR);
            p.r = rs[j];
            p.ks[0] = 1.0;
            p.f0[0] = 0.9;
            double ag = rs[j] * rs[j], a2 = ag * ag;
            double D = a2 / (PI * pow(1.0 + (a2 - 1.0) * g.ch * g.ch, 2.0)); /* Eq. 6 */
            double ti2 = (1.0 - g.ci * g.ci) / (g.ci * g.ci),
                   to2 = (1.0 - g.co * g.co) / (g.co * g.co);
            double G = g1_lambda(a2 * ti2) * g1_lambda(a2 * to2);        /* Eq. 9 */
            double e = schlick(0.9, g.cd) * D * G / (4.0 * g.ci * g.co); /* Eq. 5 */
            /* 1e-9: 1 + (a2 - 1) ch^2 cancels near the peak for r = 0.05 in this form */
            expect_eq(ABRDF_DISNEY_SPECULAR, &p, &g, e, 1e-9, "Eqs. 5, 6, 8, 9");
        }
    }
}
END_TEST

START_TEST(disney_specular_anisotropic)
{
    static const double an[] = {0.0, 0.5, 1.0}, rs[] = {0.3, 0.7};
    for (int k = 0; k < NCONF; ++k) {
        hand g = hand_make(k);
        for (int j = 0; j < 3; ++j)
            for (int q = 0; q < 2; ++q) {
                abrdf_params p = params(ABRDF_DISNEY_SPECULAR_ANISO);
                p.r = rs[q];
                p.anisotropic = an[j];
                p.ks[0] = 1.0;
                p.f0[0] = 0.3;
                double aspect = sqrt(1.0 - 0.9 * an[j]);
                double ax = rs[q] * rs[q] / aspect, ay = rs[q] * rs[q] * aspect;
                double u = g.h[0] / ax, v = g.h[1] / ay;
                double D = 1.0 / (PI * ax * ay * pow(u * u + v * v + g.ch * g.ch, 2.0)); /* Eq. 7 */
                double li =
                    (ax * ax * g.wi[0] * g.wi[0] + ay * ay * g.wi[1] * g.wi[1]) / (g.ci * g.ci);
                double lo =
                    (ax * ax * g.wo[0] * g.wo[0] + ay * ay * g.wo[1] * g.wo[1]) / (g.co * g.co);
                double G = g1_lambda(li) * g1_lambda(lo);
                double e = schlick(0.3, g.cd) * D * G / (4.0 * g.ci * g.co);
                expect_eq(ABRDF_DISNEY_SPECULAR_ANISO, &p, &g, e, 1e-10, "Eq. 7");
                if (an[j] == 0.0) { /* anisotropic = 0 is the isotropic model */
                    abrdf_params pi = params(ABRDF_DISNEY_SPECULAR);
                    pi.r = rs[q];
                    pi.ks[0] = 1.0;
                    pi.f0[0] = 0.3;
                    double iso = tu_eval1(ABRDF_DISNEY_SPECULAR, &pi, g.wi, g.wo);
                    expect_eq(ABRDF_DISNEY_SPECULAR_ANISO, &p, &g, iso, 1e-12, "= isotropic");
                }
            }
    }
}
END_TEST

START_TEST(disney_clearcoat_gtr1)
{
    static const double gloss[] = {0.0, 0.5, 1.0};
    for (int k = 0; k < NCONF; ++k) {
        hand g = hand_make(k);
        for (int j = 0; j < 3; ++j) {
            abrdf_params p = params(ABRDF_DISNEY_CLEARCOAT);
            p.ks[0] = 0.8;
            p.clearcoat_gloss = gloss[j];
            double a = 0.1 + (0.001 - 0.1) * gloss[j], a2 = a * a;
            double D = (a2 - 1.0) / (PI * log(a2) * (1.0 + (a2 - 1.0) * g.ch * g.ch)); /* GTR1 */
            double ti2 = (1.0 - g.ci * g.ci) / (g.ci * g.ci),
                   to2 = (1.0 - g.co * g.co) / (g.co * g.co);
            double G = g1_lambda(0.0625 * ti2) * g1_lambda(0.0625 * to2); /* alpha_g = 0.25 */
            double e = 0.8 * 0.25 * schlick(0.04, g.cd) * D * G / (4.0 * g.ci * g.co);
            expect_eq(ABRDF_DISNEY_CLEARCOAT, &p, &g, e, 1e-9, "GTR1 clearcoat");
        }
    }
}
END_TEST

/* ---- RGB channels are independent ------------------------------------------------------ */

START_TEST(rgb_channels)
{
    hand g = hand_make(0);
    for (int mi = 0; mi < abrdf_model_count(); ++mi) {
        const abrdf_model_info *m = tu_param_model(mi);
        if (!m) continue;
        abrdf_params p = params(m->id), q;
        double w[3] = {0.2, 0.5, 1.0}, f[3], f1[3];
        for (int c = 0; c < 3; ++c) p.kd[c] = p.ks[c] = w[c];
        ck_assert_int_eq(abrdf_eval(m->id, &p, NULL, g.wi, g.wo, f), ABRDF_OK);
        for (int c = 0; c < 3; ++c) { /* channel c equals channel c of a grey evaluation with
                                        * weight w[c] (models may colour channels themselves) */
            q = p;
            for (int d = 0; d < 3; ++d) {
                q.kd[d] = q.ks[d] = w[c];
                q.f0[d] = p.f0[c];
            }
            ck_assert_int_eq(abrdf_eval(m->id, &q, NULL, g.wi, g.wo, f1), ABRDF_OK);
            ck_assert_msg(tu_close(f[c], f1[c], 1e-14, 0.0), "%s channel %d: %.17g vs %.17g",
                          m->name, c, f[c], f1[c]);
        }
    }
}
END_TEST

/* ---- shading, frames, converters ---------------------------------------------------- */

START_TEST(shade_pixel_intensity)
{
    double n[3] = {0.2, -0.3, 0.9}, t[3] = {1, 0, 0};
    abrdf_frame fr;
    ck_assert_int_eq(abrdf_frame_make(n, t, &fr), ABRDF_OK);
    double wi[3] = {0.5, 0.1, 0.8}, wo[3] = {-0.3, -0.2, 0.9};
    abrdf_params p = params(ABRDF_BLINN_PHONG);
    double kd[3] = {0.1, 0.5, 0.9}, ks[3] = {0.3, 0.2, 0.1};
    memcpy(p.kd, kd, sizeof kd);
    memcpy(p.ks, ks, sizeof ks);
    p.n = 20.0;
    double light[3] = {2.0, 1.0, 0.5}, amb[3] = {0.01, 0.02, 0.03}, out[3];
    ck_assert_int_eq(
        abrdf_shade(ABRDF_LAMBERT, ABRDF_BLINN_PHONG, &p, &fr, wi, wo, light, amb, out), ABRDF_OK);
    /* by hand, in world space: I = ka Ia + Il max(0, N.L) (kd/pi + ks (N.H)^n) */
    double nn = sqrt(dot(n, n)), li = sqrt(dot(wi, wi)), lo = sqrt(dot(wo, wo));
    double N[3] = {n[0] / nn, n[1] / nn, n[2] / nn}, L[3], V[3], H[3];
    for (int c = 0; c < 3; ++c) {
        L[c] = wi[c] / li;
        V[c] = wo[c] / lo;
        H[c] = L[c] + V[c];
    }
    double hl = sqrt(dot(H, H));
    for (int c = 0; c < 3; ++c) H[c] /= hl;
    for (int c = 0; c < 3; ++c) {
        double e = amb[c] + light[c] * dot(N, L) * (kd[c] / PI + ks[c] * pow(dot(N, H), 20.0));
        ck_assert_msg(tu_close(out[c], e, 1e-12, 0.0), "shade channel %d: %.17g vs %.17g", c,
                      out[c], e);
    }
    /* omitted terms, light from behind: ambient only */
    double back[3] = {-wi[0], -wi[1], -wi[2]};
    ck_assert_int_eq(
        abrdf_shade(ABRDF_MODEL_NONE, ABRDF_BLINN_PHONG, &p, &fr, back, wo, light, amb, out),
        ABRDF_OK);
    for (int c = 0; c < 3; ++c) ck_assert(out[c] == amb[c]);
    ck_assert_int_eq(abrdf_shade(ABRDF_LAMBERT, ABRDF_MODEL_NONE, &p, &fr, wi, wo, light, amb, out),
                     ABRDF_OK);
    for (int c = 0; c < 3; ++c)
        ck_assert(tu_close(out[c], amb[c] + light[c] * dot(N, L) * kd[c] / PI, 1e-12, 0.0));
    /* an invalid parameter is an error and the output is 0 */
    p.n = -1.0;
    ck_assert_int_eq(
        abrdf_shade(ABRDF_LAMBERT, ABRDF_BLINN_PHONG, &p, &fr, wi, wo, light, amb, out),
        ABRDF_E_RANGE);
    for (int c = 0; c < 3; ++c) ck_assert(out[c] == 0.0);
    ck_assert_int_eq(
        abrdf_shade(ABRDF_LAMBERT, ABRDF_BLINN_PHONG, NULL, &fr, wi, wo, light, amb, out),
        ABRDF_E_NULL);
    /* "none" is ABRDF_MODEL_NONE: a *_COUNT is not a model, whatever the header's count */
    p.n = 20.0;
    ck_assert_int_eq(
        abrdf_shade(ABRDF_MODEL_COUNT, ABRDF_BLINN_PHONG, &p, &fr, wi, wo, light, amb, out),
        ABRDF_E_MODEL);
}
END_TEST

static void assert_orthonormal(const abrdf_frame *f)
{
    ck_assert(fabs(dot(f->n, f->n) - 1.0) < 1e-14);
    ck_assert(fabs(dot(f->t, f->t) - 1.0) < 1e-14);
    ck_assert(fabs(dot(f->b, f->b) - 1.0) < 1e-14);
    ck_assert(fabs(dot(f->n, f->t)) < 1e-14);
    double x[3] = {f->n[1] * f->t[2] - f->n[2] * f->t[1], f->n[2] * f->t[0] - f->n[0] * f->t[2],
                   f->n[0] * f->t[1] - f->n[1] * f->t[0]};
    for (int c = 0; c < 3; ++c) ck_assert(fabs(x[c] - f->b[c]) < 1e-14); /* B = N x T */
}

START_TEST(frame_make)
{
    abrdf_frame f;
    double n[3] = {1.0, 2.0, 2.0}, t[3] = {1.0, 0.0, 0.0};
    ck_assert_int_eq(abrdf_frame_make(n, t, &f), ABRDF_OK);
    assert_orthonormal(&f);
    /* Gram-Schmidt: T is t - (t.N) N normalised, N is n normalised */
    double N[3] = {1.0 / 3, 2.0 / 3, 2.0 / 3}, d = 1.0 / 3, T[3];
    for (int c = 0; c < 3; ++c) T[c] = t[c] - d * N[c];
    double l = sqrt(dot(T, T));
    for (int c = 0; c < 3; ++c) {
        ck_assert(fabs(f.n[c] - N[c]) < 1e-15);
        ck_assert(fabs(f.t[c] - T[c] / l) < 1e-15);
    }
    /* tangent parallel (or anti-parallel) to the normal, or missing: still a valid frame */
    double par[3] = {-2.0, -4.0, -4.0};
    ck_assert_int_eq(abrdf_frame_make(n, par, &f), ABRDF_OK);
    assert_orthonormal(&f);
    abrdf_frame f2;
    ck_assert_int_eq(abrdf_frame_make(n, NULL, &f2), ABRDF_OK);
    assert_orthonormal(&f2);
    ck_assert(memcmp(&f, &f2, sizeof f) == 0); /* deterministic fallback */
    double nan_t[3] = {NAN, 0, 1};
    ck_assert_int_eq(abrdf_frame_make(n, nan_t, &f), ABRDF_OK);
    assert_orthonormal(&f);
    /* zero / NaN / Inf normal: error and the identity frame */
    static const double bad[3][3] = {{0, 0, 0}, {NAN, 0, 1}, {0, INFINITY, 1}};
    for (int k = 0; k < 3; ++k) {
        ck_assert_int_eq(abrdf_frame_make(bad[k], t, &f), ABRDF_E_GEOMETRY);
        ck_assert(f.n[2] == 1.0 && f.t[0] == 1.0 && f.b[1] == 1.0);
    }
    ck_assert_int_eq(abrdf_frame_make(n, t, NULL), ABRDF_E_NULL);
    /* huge and tiny normals are normalised without overflow or underflow */
    double big[3] = {1e300, 1e300, 0}, tiny[3] = {0, 3e-320, 3e-320};
    ck_assert_int_eq(abrdf_frame_make(big, NULL, &f), ABRDF_OK);
    assert_orthonormal(&f);
    ck_assert_int_eq(abrdf_frame_make(tiny, NULL, &f), ABRDF_OK);
    assert_orthonormal(&f);
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("closed_form");
    TCase *tc = tcase_create("models");
    tcase_add_test(tc, diffuse_models);
    tcase_add_test(tc, phong_blinn_phong);
    tcase_add_test(tc, table1_approximations);
    tcase_add_test(tc, fkub_cubic);
    tcase_add_test(tc, table5_energy_conserving);
    tcase_add_test(tc, cook_torrance_beckmann);
    tcase_add_test(tc, disney_specular_ggx);
    tcase_add_test(tc, disney_specular_anisotropic);
    tcase_add_test(tc, disney_clearcoat_gtr1);
    tcase_add_test(tc, rgb_channels);
    suite_add_tcase(s, tc);
    TCase *api = tcase_create("api");
    tcase_add_test(api, shade_pixel_intensity);
    tcase_add_test(api, frame_make);
    suite_add_tcase(s, api);
    suite_add_tcase(s, closed_form_terms_tcase());
    return s;
}

int main(void) { return tu_run(suite()); }
