/* gen_belcour_tables.c - computes the precomputed tables of Belcour's layered model from
 * first principles and writes libabrdf/src/layered/belcour_tables.c. Re-running it reproduces that
 * file byte for byte (a test does).
 *
 *   gen_belcour_tables [--order N] [out.c]     write the tables (default order 32, stdout)
 *   gen_belcour_tables --check [--order N] [--tol T]
 *                                              max |table(N) - table(2N)| over the nodes;
 *                                              exit status 1 if it exceeds T
 *
 * L. Belcour, "Efficient rendering of layered materials using an atomic decomposition with
 * statistical operators", ACM TOG 37(4), 2018, Sec. 5 and its supplemental code; MODELS.md
 * B8.2. The axes are in libabrdf/src/layered/belcour_tables.h.
 *
 * FGD(cos, alpha, eta, kappa) = int F(wi.h) D(h) G(wi, wo) / (4 cos_i cos_o) cos_o dwo,
 *   the directional albedo of a GGX reflection (separable Smith G, exact Fresnel of the
 *   complex relative index eta + i kappa, as the runtime lobes use). Changing variables to
 *   the half vector (dwo = 4 (wi.h) dwh) and to the GGX cumulative u in theta_h,
 *   tan^2(theta_h) = alpha^2 u / (1 - u), for which D(h) cos(theta_h) dwh = du dphi / (2 pi):
 *     FGD = 1/(2 pi) int_0^1 int_0^2pi F G (wi.h) / (cos_i cos_h) dphi du.
 *   Quadrature (each step removes what would slow Gauss-Legendre down to first order):
 *   - u = 1 - (1 - v)^2 cancels the 1/cos_h ~ 1/sqrt(1 - u) of grazing facets;
 *   - the integrand is even in phi, and for each u the phi interval ends where wo crosses
 *     the horizon, so the cut-off is not inside the quadrature;
 *   - the theta_h at which that interval opens or closes split v into smooth pieces;
 *   - for a dielectric with eta < 1, F = 1 beyond the critical angle and has an infinite
 *     slope there: FGD = E_ss + int (F - 1) over the facets below the critical angle only.
 *   Gauss-Legendre of order N in v and in phi per piece (at most MAX_PIECES pieces).
 * TIR(cos, alpha, eta): light at cos inside the denser medium meets the rough interface,
 *   relative index eta = n_outside / n_inside < 1; the fraction of the visible-normal
 *   distribution D_wi(h) = G1(wi) (wi.h)+ D(h) / cos_i whose facets do not totally reflect
 *   (1 - (wi.h)^2 < eta^2), normalised by the quadrature's own integral of D_wi; here too
 *   the phi interval ends at the TIR boundary. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "belcour_tables.h"
#include "layered_optics.h"
#include "out_file.h"
#include "quad.h"

#define ORDER_DEFAULT 32
#define ORDER_MAX 128

#define MAX_PIECES 8
#define ROOT_SCAN 512 /* theta_h samples when looking for the breakpoints */

typedef struct quad {
    int order;
    double xu[ORDER_MAX], wu[ORDER_MAX];           /* Gauss-Legendre on [0, 1] */
    double c, a;                                   /* incidence cosine and roughness */
    int n;                                         /* points */
    double cd[MAX_PIECES * ORDER_MAX * ORDER_MAX]; /* wi.h per point */
    double wv[MAX_PIECES * ORDER_MAX * ORDER_MAX]; /* visible-normal weight per point */
    double wf[MAX_PIECES * ORDER_MAX * ORDER_MAX]; /* FGD weight per point (F excluded) */
} quad;

/* The facets taken are those with wi.h > thr(theta_h) = max(t0, t1 / cos(theta_h)). For a
 * given theta_h, wi.h = s sh cos(phi) + c ch decreases with phi on [0, pi], so they form
 * phi in [0, limit]; integrating up to the limit keeps the step out of the quadrature. */
static double thr(double t0, double t1, double ch) { return fmax(t0, t1 / ch); }

static double phi_limit(double c, double ch, double sh, double t)
{
    double s = sqrt(fmax(0.0, 1.0 - c * c)) * sh;
    if (!(s > 0.0)) return c * ch > t ? ABRDF__LO_PI : 0.0;
    double x = (t - c * ch) / s;
    return x <= -1.0 ? ABRDF__LO_PI : (x >= 1.0 ? 0.0 : acos(x));
}

/* The limit is not smooth in theta_h where it reaches 0 or pi, i.e. where
 * cos(theta_i -+ theta_h) = thr: those theta_h split the u integral into smooth pieces. */
static double edge(double ti, double sign, double t0, double t1, double th)
{
    return cos(ti + sign * th) - thr(t0, t1, cos(th));
}

static int breakpoints(double c, double a, double t0, double t1, double *u)
{
    int n = 0;
    if (!(a > 0.0)) return 0;
    double ti = acos(c), hi = 0.5 * ABRDF__LO_PI;
    for (int sgn = -1; sgn <= 1; sgn += 2)
        for (int k = 0; k + 1 < ROOT_SCAN; ++k) {
            double lo_t = hi * k / ROOT_SCAN, hi_t = hi * (k + 1) / ROOT_SCAN;
            double flo = edge(ti, sgn, t0, t1, lo_t), fhi = edge(ti, sgn, t0, t1, hi_t);
            if ((flo > 0.0) == (fhi > 0.0) || n == MAX_PIECES - 1) continue;
            for (int it = 0; it < 80; ++it) {
                double m = 0.5 * (lo_t + hi_t), fm = edge(ti, sgn, t0, t1, m);
                if ((fm > 0.0) == (flo > 0.0))
                    lo_t = m, flo = fm;
                else
                    hi_t = m;
            }
            double t2 = tan(0.5 * (lo_t + hi_t));
            t2 *= t2;
            u[n++] = 1.0 - sqrt(a * a / (a * a + t2)); /* v of u = t2 / (a^2 + t2) */
        }
    if (t0 > 0.0 && t1 > 0.0 && t1 < t0 && n < MAX_PIECES - 1) { /* thr switches branch */
        double c2 = (t1 / t0) * (t1 / t0), t2 = (1.0 - c2) / c2;
        u[n++] = 1.0 - sqrt(a * a / (a * a + t2));
    }
    for (int i = 1; i < n; ++i) /* insertion sort, n is tiny */
        for (int j = i; j > 0 && u[j] < u[j - 1]; --j) {
            double t = u[j];
            u[j] = u[j - 1];
            u[j - 1] = t;
        }
    return n;
}

/* Quadrature points over the facets with wi.h > thr, for incidence cos c, roughness a:
 * u in GGX-cumulative pieces between the breakpoints, phi in [0, limit(u)], order N each.
 * D(h) cos(theta_h) dwh = du dphi / (2 pi) and phi is even: weight du dphi / pi. The
 * integrands carry 1/cos(theta_h) ~ 1/sqrt(1 - u) near grazing facets; u = 1 - (1 - v)^2
 * cancels it, so the Gauss-Legendre nodes are placed in v (breakpoints are in v too). */
static void quad_make(quad *q, int order, double c, double a, double t0, double t1)
{
    q->order = order;
    q->c = c;
    q->a = a;
    quad_gauss_legendre01(order, q->xu, q->wu);
    double br[MAX_PIECES + 1];
    int nb = breakpoints(c, a, t0, t1, br + 1);
    br[0] = 0.0;
    br[nb + 1] = 1.0;
    q->n = 0;
    for (int p = 0; p <= nb; ++p) {
        double v0 = br[p], dv = br[p + 1] - br[p];
        for (int i = 0; i < order; ++i) {
            double v = v0 + dv * q->xu[i], m = 1.0 - v;
            double du = 2.0 * m * dv; /* u = 1 - (1 - v)^2 */
            double t2 = a * a * (1.0 - m * m) / (m * m);
            double ch = 1.0 / sqrt(1.0 + t2), sh = sqrt(t2) * ch;
            double lim = phi_limit(c, ch, sh, thr(t0, t1, ch));
            for (int j = 0; j < order; ++j) {
                double cd = sqrt(fmax(0.0, 1.0 - c * c)) * sh * cos(lim * q->xu[j]) + c * ch;
                double co = 2.0 * cd * ch - c;
                double w = du * q->wu[i] * q->wu[j] * lim / ABRDF__LO_PI;
                int k = q->n++;
                q->cd[k] = cd;
                q->wv[k] = cd > 0.0 ? w * cd / (c * ch) : 0.0;
                q->wf[k] = co > 0.0 ? q->wv[k] * abrdf__lo_g1(c, a) * abrdf__lo_g1(co, a) : 0.0;
            }
        }
    }
}

static double fgd(const quad *q, double eta, double kappa)
{
    double s = 0.0;
    for (int k = 0; k < q->n; ++k)
        if (q->wf[k] > 0.0) s += q->wf[k] * abrdf__fresnel_exact(q->cd[k], eta, kappa);
    return s;
}

/* The single-scattering albedo (F = 1) of the points' facets. */
static double e_ss(const quad *q)
{
    double s = 0.0;
    for (int k = 0; k < q->n; ++k) s += q->wf[k];
    return s;
}

static double visible(const quad *q)
{
    double s = 0.0;
    for (int k = 0; k < q->n; ++k) s += q->wv[k];
    return s;
}

/* Facets let light out when 1 - (wi.h)^2 < eta^2, i.e. wi.h > sqrt(1 - eta^2). */
static double tir(quad *q, int order, double c, double a, double eta)
{
    if (eta >= 1.0) return 1.0;
    quad_make(q, order, c, a, 0.0, 0.0);
    double all = visible(q);
    quad_make(q, order, c, a, sqrt(1.0 - eta * eta), 0.0);
    return all > 0.0 ? fmin(1.0, visible(q) / all) : 1.0;
}

/* Fill both tables at quadrature order `order`. */
static void compute(int order, float *fgd_t, float *tir_t, quad *q, quad *q2)
{
    for (int ic = 0; ic < ABRDF__FGD_NCOS; ++ic)
        for (int ia = 0; ia < ABRDF__FGD_NALPHA; ++ia) {
            double c = abrdf__bt_cos(ic, ABRDF__FGD_NCOS);
            quad_make(q, order, c, abrdf__bt_alpha(ia, ABRDF__FGD_NALPHA), 0.0, 0.5 * c);
            double e_all = e_ss(q);
            for (int ie = 0; ie < ABRDF__FGD_NETA; ++ie)
                for (int ik = 0; ik < ABRDF__FGD_NKAPPA; ++ik) {
                    double eta = abrdf__bt_fgd_eta(ie), kappa = abrdf__bt_fgd_kappa(ik), v;
                    if (kappa == 0.0 && eta < 1.0) {
                        /* F = 1 on the facets beyond the critical angle and has an infinite
                         * slope there: integrate F - 1 only where it is not 0. */
                        quad_make(q2, order, c, abrdf__bt_alpha(ia, ABRDF__FGD_NALPHA),
                                  sqrt(1.0 - eta * eta), 0.5 * c);
                        v = e_all + fgd(q2, eta, kappa) - e_ss(q2);
                    } else {
                        v = fgd(q, eta, kappa);
                    }
                    fgd_t[((ic * ABRDF__FGD_NALPHA + ia) * ABRDF__FGD_NETA + ie) *
                              ABRDF__FGD_NKAPPA +
                          ik] = (float)(v < 0.0 ? 0.0 : (v > 1.0 ? 1.0 : v));
                }
        }
    for (int ic = 0; ic < ABRDF__TIR_NCOS; ++ic)
        for (int ia = 0; ia < ABRDF__TIR_NALPHA; ++ia)
            for (int ie = 0; ie < ABRDF__TIR_NETA; ++ie)
                tir_t[(ic * ABRDF__TIR_NALPHA + ia) * ABRDF__TIR_NETA + ie] =
                    (float)tir(q, order, abrdf__bt_cos(ic, ABRDF__TIR_NCOS),
                               abrdf__bt_alpha(ia, ABRDF__TIR_NALPHA), abrdf__bt_tir_eta(ie));
}

static void write_array(FILE *f, const char *name, const char *size, const float *v, int n)
{
    fprintf(f, "const float %s[%s] = {\n", name, size);
    for (int i = 0; i < n; ++i)
        fprintf(f, "%.5f,%s", (double)v[i], (i % 10 == 9 || i == n - 1) ? "\n" : " ");
    fprintf(f, "};\n");
}

int main(int argc, char **argv)
{
    int order = ORDER_DEFAULT, check = 0;
    double tol = 1.0;
    const char *out = NULL;
    for (int i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--order") && i + 1 < argc) {
            order = atoi(argv[++i]);
        } else if (!strcmp(argv[i], "--tol") && i + 1 < argc) {
            tol = atof(argv[++i]);
        } else if (!strcmp(argv[i], "--check")) {
            check = 1;
        } else if (argv[i][0] == '-') {
            fprintf(stderr, "usage: gen_belcour_tables [--order N] [--check [--tol T]] [out.c]\n");
            return 2;
        } else {
            out = argv[i];
        }
    }
    if (order < 2 || order * (check ? 2 : 1) > ORDER_MAX) { /* also rejects atoi's 0 */
        fprintf(stderr, "gen_belcour_tables: --order must be in [2, %d]\n",
                ORDER_MAX / (check ? 2 : 1));
        return 2;
    }
    int status = 0;
    quad *q = malloc(sizeof *q), *q2 = malloc(sizeof *q2);
    float *fgd_t = malloc(sizeof(float) * ABRDF__FGD_SIZE);
    float *tir_t = malloc(sizeof(float) * ABRDF__TIR_SIZE);
    if (!q || !q2 || !fgd_t || !tir_t) return 1;
    if (check) {
        float *fgd2 = malloc(sizeof(float) * ABRDF__FGD_SIZE);
        float *tir2 = malloc(sizeof(float) * ABRDF__TIR_SIZE);
        if (!fgd2 || !tir2) return 1;
        compute(order, fgd_t, tir_t, q, q2);
        compute(2 * order, fgd2, tir2, q, q2);
        double mf = 0.0, mt = 0.0;
        for (int i = 0; i < ABRDF__FGD_SIZE; ++i) mf = fmax(mf, fabs((double)fgd_t[i] - fgd2[i]));
        for (int i = 0; i < ABRDF__TIR_SIZE; ++i) mt = fmax(mt, fabs((double)tir_t[i] - tir2[i]));
        printf("order %d vs %d: max |dFGD| = %.3g, max |dTIR| = %.3g\n", order, 2 * order, mf, mt);
        free(fgd2);
        free(tir2);
        if (!(mf <= tol && mt <= tol)) {
            fprintf(stderr, "gen_belcour_tables: not converged to %g\n", tol);
            status = 1;
        }
    } else {
        /* The output exists (as a temporary file) before the long computation. */
        out_file o;
        FILE *f = out_file_or_stdout(&o, out, "gen_belcour_tables");
        if (!f) return 1;
        compute(order, fgd_t, tir_t, q, q2);
        fprintf(
            f,
            "/* belcour_tables.c - GENERATED by tools/gen/gen_belcour_tables.c --order %d; do not\n"
            " * edit. Tables of Belcour's layered model (belcour_tables.h gives the axes):\n"
            " * FGD %dx%dx%dx%d (cos x alpha x eta x kappa), TIR %dx%dx%d (cos x alpha x eta),\n"
            " * Gauss-Legendre order %d x %d per smooth piece in (v, phi), values rounded to 1e-5. "
            "*/\n"
            "#include \"belcour_tables.h\"\n\n",
            order, ABRDF__FGD_NCOS, ABRDF__FGD_NALPHA, ABRDF__FGD_NETA, ABRDF__FGD_NKAPPA,
            ABRDF__TIR_NCOS, ABRDF__TIR_NALPHA, ABRDF__TIR_NETA, order, order);
        write_array(f, "abrdf__fgd_table", "ABRDF__FGD_SIZE", fgd_t, ABRDF__FGD_SIZE);
        fprintf(f, "\n");
        write_array(f, "abrdf__tir_table", "ABRDF__TIR_SIZE", tir_t, ABRDF__TIR_SIZE);
        status = out_file_finish(&o, "gen_belcour_tables"); /* whole or not at all */
    }
    free(q);
    free(q2);
    free(fgd_t);
    free(tir_t);
    return status;
}
