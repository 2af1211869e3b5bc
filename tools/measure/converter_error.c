/* converter_error.c - measures the error of the roughness converters (docs/MODELS.md,
 * "Roughness converters").
 *
 *   converter_error            prints the Markdown tables of docs/MODELS.md
 *
 * 1. alpha_g -> Blinn-Phong exponent n = abrdf_alpha_g_to_n(alpha_g). The normalised
 *    Blinn-Phong NDF D_bp = (n + 2)/(2 pi) cos^n(theta_h) is compared with GGX and Beckmann D
 *    of the same alpha_g (all three integrate to 1 over the hemisphere as D cos dw):
 *      peak ratio     D_bp(0) / D_ref(0)
 *      rel50, rel1    max |D_bp - D_ref| / D_ref where D_ref >= 50 % / 1 % of its peak
 *      L1             integral |D_bp - D_ref| cos dw  (0 = identical, 2 = disjoint)
 *    The integrals use composite Simpson on panels that double in width away from the peak,
 *    so even alpha_g = 1e-3 is resolved; the "norm" columns print each D's integral.
 * 2. POV-Ray roughness: abrdf_n_to_pov_roughness(n), stored by POV-Ray 3.7 in single
 *    precision and inverted back to the exponent it applies: max relative exponent error.
 * 3. Round trips of every converter pair over a grid: max relative error. */
#include <float.h>
#include <math.h>
#include <stdio.h>

#include "abrdf.h"

static const double PI = 3.14159265358979323846;

typedef double (*ndf_fn)(double theta, double alpha_g, double n);

static double d_blinn_phong(double t, double a, double n)
{
    (void)a;
    return (n + 2.0) / (2.0 * PI) * pow(cos(t), n);
}

static double d_ggx(double t, double a, double n)
{
    (void)n;
    double c = cos(t), s = sin(t), a2 = a * a;
    double k = s * s + a2 * c * c; /* 1 + (a2 - 1) c^2 without cancellation */
    return a2 / (PI * k * k);
}

static double d_beckmann(double t, double a, double n)
{
    (void)n;
    double c = cos(t), tn = tan(t);
    if (!(c > 0.0)) return 0.0;
    return exp(-tn * tn / (a * a)) / (PI * a * a * c * c * c * c);
}

typedef struct stats {
    double norm_bp, norm_ref; /* integrals of D cos dw */
    double l1;                /* integral |D_bp - D_ref| cos dw */
    double rel50, rel1;       /* max relative error in the 50 % / 1 % zones */
} stats;

#define PANEL_STEPS 2000 /* Simpson intervals per panel (even) */

static void compare(ndf_fn ref, double a, double n, stats *s)
{
    double peak = ref(0.0, a, n);
    s->norm_bp = s->norm_ref = s->l1 = s->rel50 = s->rel1 = 0.0;
    /* Panels [0, w], [w, 2w], [2w, 4w], ... up to pi/2 with w = alpha_g / 64. */
    double lo = 0.0, hi = fmin(a / 64.0, PI / 2);
    while (lo < PI / 2) {
        double h = (hi - lo) / PANEL_STEPS;
        for (int i = 0; i <= PANEL_STEPS; ++i) {
            double t = lo + h * i;
            double w = (i == 0 || i == PANEL_STEPS) ? 1.0 : (i % 2 ? 4.0 : 2.0);
            double jac = 2.0 * PI * cos(t) * sin(t) * h / 3.0; /* cos dw, azimuth integrated */
            double db = d_blinn_phong(t, a, n), dr = ref(t, a, n);
            s->norm_bp += w * jac * db;
            s->norm_ref += w * jac * dr;
            s->l1 += w * jac * fabs(db - dr);
            double rel = fabs(db - dr) / dr;
            if (dr >= 0.5 * peak && rel > s->rel50) s->rel50 = rel;
            if (dr >= 0.01 * peak && rel > s->rel1) s->rel1 = rel;
        }
        lo = hi;
        hi = fmin(2.0 * hi, PI / 2);
    }
}

static void ndf_table(void)
{
    static const double alphas[] = {0.0015, 0.005, 0.01, 0.05, 0.1, 0.2, 0.3, 0.5, 0.7, 0.9, 1.0};
    printf("| alpha_g | n | ref | peak ratio | max rel. err (D >= 50%% peak) | max rel. err (D >= "
           "1%% peak) | L1 | norm D_bp | norm D_ref |\n");
    printf("|---|---|---|---|---|---|---|---|---|\n");
    for (size_t i = 0; i < sizeof alphas / sizeof alphas[0]; ++i) {
        double a = alphas[i], n = abrdf_alpha_g_to_n(a);
        static const struct {
            const char *name;
            ndf_fn fn;
        } refs[] = {{"GGX", d_ggx}, {"Beckmann", d_beckmann}};
        for (int r = 0; r < 2; ++r) {
            stats s;
            compare(refs[r].fn, a, n, &s);
            double ratio = d_blinn_phong(0.0, a, n) / refs[r].fn(0.0, a, n);
            printf("| %g | %.6g | %s | %.6f | %.2f%% | %.2f%% | %.4f | %.6f | %.6f |\n", a, n,
                   refs[r].name, ratio, 100.0 * s.rel50, 100.0 * s.rel1, s.l1, s.norm_bp,
                   s.norm_ref);
        }
    }
}

/* POV-Ray 3.7 parses roughness as a double, stores it as a float (SNGL), stores 1/roughness
 * as the float exponent (parstxtr.cpp), and raises N.H to it (trace.cpp). */
static double pov_exponent(double rough)
{
    float stored = (float)rough;
    return stored != 0.0f ? (double)(float)(1.0 / stored) : 0.0;
}

static void pov_table(void)
{
    double worst = 0.0, worst_n = 0.0, worst_lobe = 0.0;
    for (double e = 0.0; e <= 6.0 + 1e-9; e += 0.001) {
        double n = pow(10.0, e);
        double np = pov_exponent(abrdf_n_to_pov_roughness(n));
        double rel = fabs(np - n) / n;
        if (rel > worst) worst = rel, worst_n = n;
        /* Lobe error where c^n >= 1 % of the peak: |c^np / c^n - 1| is largest at the
         * zone edge c = 0.01^(1/n), where it equals |0.01^((np - n)/n) - 1|. */
        double lobe = fabs(pow(0.01, (np - n) / n) - 1.0);
        if (lobe > worst_lobe) worst_lobe = lobe;
    }
    printf("| mapping | grid | max rel. error of the exponent | at n | max rel. lobe error (c^n >= "
           "1%% peak) |\n");
    printf("|---|---|---|---|---|\n");
    printf("| n -> POV-Ray roughness -> exponent POV-Ray applies | n = 10^(0..6), 6001 points | "
           "%.3g | %.6g | %.3g |\n",
           worst, worst_n, worst_lobe);
}

static void round_trips(void)
{
    double e_r = 0, e_a = 0, e_n = 0, e_p = 0;
    for (int i = 0; i <= 10000; ++i) {
        double x = i / 10000.0; /* r and alpha_g in [0, 1] */
        double r = abrdf_alpha_g_to_r(abrdf_r_to_alpha_g(x));
        e_r = fmax(e_r, fabs(r - x) / fmax(x, 1e-300));
        double a = fmax(x, 0.0015); /* alpha_g with n <= 1e6 */
        double a2 = abrdf_n_to_alpha_g(abrdf_alpha_g_to_n(a));
        e_a = fmax(e_a, fabs(a2 - a) / a);
        double n = pow(10.0, -3.0 + 9.0 * x); /* n in [1e-3, 1e6] */
        double n2 = abrdf_alpha_g_to_n(abrdf_n_to_alpha_g(n));
        e_n = fmax(e_n, fabs(n2 - n) / n);
        double n3 = abrdf_pov_roughness_to_n(abrdf_n_to_pov_roughness(n));
        e_p = fmax(e_p, fabs(n3 - n) / n);
    }
    printf("| round trip | grid | max rel. error |\n|---|---|---|\n");
    printf("| r -> alpha_g -> r | r in [0, 1], 10001 points | %.3g |\n", e_r);
    printf("| alpha_g -> n -> alpha_g | alpha_g in [0.0015, 1], 10001 points | %.3g |\n", e_a);
    printf("| n -> alpha_g -> n | n = 10^(-3..6), 10001 points | %.3g |\n", e_n);
    printf("| n -> POV-Ray roughness -> n (double) | n = 10^(-3..6), 10001 points | %.3g |\n", e_p);
}

int main(void)
{
    printf("Blinn-Phong NDF with n = abrdf_alpha_g_to_n(alpha_g) against GGX and Beckmann D:\n\n");
    ndf_table();
    printf("\nPOV-Ray `roughness` (single precision inside POV-Ray 3.7):\n\n");
    pov_table();
    printf("\nRound trips:\n\n");
    round_trips();
    return 0;
}
