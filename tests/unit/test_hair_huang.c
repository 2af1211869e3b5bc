/* test_hair_huang.c - Huang, Hullin, Hanika 2022 microfacet hair (hair_huang.c): smooth
 * limit of R, quadrature convergence, white furnace vs eccentricity, stability grid. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "hair.h"
#include "hair_test_util.h"
#include "test_util.h"

static const double PI = 3.14159265358979323846;

static void setup(abrdf__huang *m, double melanin, double aspect)
{
    abrdf_params p;
    abrdf_params_init(ABRDF_HUANG, &p);
    p.melanin = melanin;
    p.aspect_ratio = aspect;
    abrdf__huang_setup(&p, m);
}

static void fibre(const void *m, const double wi[3], const double wo[3], unsigned lobes,
                  double s[3])
{
    abrdf__huang_fibre(m, wi, wo, lobes, s);
}

/* Fibre albedo integral S dw_i over the sphere (midpoint nt x 2nt), view at theta_o. */
static double fibre_albedo(const abrdf__huang *m, double theta_o, unsigned lobes, int nt)
{
    return htu_fibre_albedo(fibre, m, theta_o, lobes, nt, 2 * nt);
}

/* Smooth, round, untilted fibre: R tends to Marschner's specular cone, whose albedo is the
 * h-average of the Fresnel reflectance, integral_0^1 F(sqrt(1 - h^2)) dh = 0.0750. The
 * microfacet R approaches it from below (single-scattering GGX loses light at the
 * silhouette, where F is largest): measured 0.0682 with this 90 x 180 sphere grid, 0.0710
 * with 180 x 360. Checked: within 12% below the limit, never above. */
START_TEST(r_smooth_limit)
{
    abrdf__huang m;
    setup(&m, 0.0, 1.0);
    m.alpha = 0.05;
    m.tilt = 0.0;
    m.compensate = 0; /* the single-scattering lobe */
    double fa = 0.0;
    const int n = 20000;
    for (int k = 0; k < n; ++k) {
        double h = (k + 0.5) / n;
        fa += abrdf__fresnel_dielectric(1.55, sqrt(1 - h * h)) / n;
    }
    double a = fibre_albedo(&m, 0.0, 1u, 90), a2 = fibre_albedo(&m, 0.0, 1u, 180);
    printf(
        "huang R albedo, alpha 0.05: %.5f (90 x 180), %.5f (180 x 360), Fresnel h-average %.5f\n",
        a, a2, fa);
    ck_assert_msg(a < fa && a > 0.88 * fa, "R albedo %.5f vs %.5f", a, fa);
    ck_assert_msg(a2 < fa && a2 > 0.88 * fa, "R albedo %.5f vs %.5f", a2, fa);
}
END_TEST

/* The quadrature converges. At one direction pair (default parameters) the Simpson count and
 * the VNDF grids are refined, printed for docs/MODELS.md, "Convergence". The shifted grids
 * make a pair's error vary with the pair, so the check is over 48 pairs, grazing ones among
 * them: the default's relative error against the reference with every grid and the Simpson
 * count doubled, RMS within 12% and the largest within 40% (measured 8.1% and 28%; the
 * unshifted grids of the same size gave 19% and 63%). */
START_TEST(quadrature_convergence)
{
    abrdf__huang m;
    setup(&m, 0.3, 0.85);
    double wi[3], wo[3];
    htu_fdir(0.3, 2.2, wi);
    htu_fdir(-0.1, 0.2, wo);
    double s[6][3];
    static const int rf[6][3] = {{1, 1, 1}, {2, 1, 1}, {1, 2, 2}, {4, 1, 1}, {8, 1, 1}, {1, 4, 4}};
    for (int k = 0; k < 6; ++k) {
        m.refine = rf[k][0];
        m.n1 = rf[k][1] * ABRDF__HUANG_N1;
        m.n2 = rf[k][2] * ABRDF__HUANG_N2;
        abrdf__huang_fibre(&m, wi, wo, 15u, s[k]);
    }
    printf("huang convergence: S %.6g, Simpson x2 %.6g, VNDF grids x2 %.6g\n", s[0][0], s[1][0],
           s[2][0]);
    printf("huang convergence: Simpson x4 %.6g, Simpson x8 %.6g, VNDF grids x4 %.6g\n", s[3][0],
           s[4][0], s[5][0]);
    double sum2 = 0.0, worst = 0.0;
    int count = 0;
    for (int k = 0; k < 48; ++k) {
        htu_fdir(-1.2 + 2.4 * ((k * 7) % 48 + 0.5) / 48, 2.0 * PI * (k + 0.5) / 48, wi);
        htu_fdir(-0.9 + 1.8 * ((k * 13) % 48 + 0.5) / 48, 0.7, wo);
        double a[3], r[3];
        m.refine = 1, m.n1 = ABRDF__HUANG_N1, m.n2 = ABRDF__HUANG_N2;
        abrdf__huang_fibre(&m, wi, wo, 15u, a);
        m.refine = 2, m.n1 = 2 * ABRDF__HUANG_N1, m.n2 = 2 * ABRDF__HUANG_N2;
        abrdf__huang_fibre(&m, wi, wo, 15u, r);
        if (!(r[0] > 1e-4)) continue;
        double e = fabs(a[0] - r[0]) / r[0];
        sum2 += e * e, ++count;
        if (e > worst) worst = e;
    }
    double rms = sqrt(sum2 / count);
    printf("huang convergence over %d pairs: RMS relative error %.4f, largest %.4f\n", count, rms,
           worst);
    ck_assert_msg(count >= 24 && rms <= 0.12 && worst <= 0.4, "%d pairs, RMS %.4f, largest %.4f",
                  count, rms, worst);
}
END_TEST

/* ---- convergence on an image ---------------------------------------------------------
 * One S value (above) does not say what a grid's error looks like in a render. This renders
 * the default hair (the melanin of data/materials.csv's hair_brown) on the convergence
 * cylinder (htu_cylinder_image). Per grid (n1, n2) and Simpson refinement it prints the image
 * NMSE (Table 8's measure) against the default and against the reference, and the work per
 * evaluation in VNDF nodes relative to the default, n1^2 (1 + n2^2) refine / (6^2 (1 + 3^2))
 * (TT visits n1^2 nodes, TRT n2^2 more per node), beside the CPU time of the image relative to
 * the default's (a one-off timing, not checked). tools/bench/hair_convergence measures the
 * same image against a denser reference. */
static void eval_fn(const void *m, const double wi[3], const double wo[3], double f[3])
{
    abrdf__huang_eval(m, wi, wo, f);
}

/* The cylinder's directions, as its pixels hand them to the model: unit vectors in the
 * local frame (T, B, N) = ((0, 1, 0), N x T, (x, 0, z)) of the pixel at x, the view
 * (V.T, V.B, V.N) = (0, x, z) for the orthographic camera along -z, so x = wo[1] is a pixel
 * centre -1 + (k + 1/2) 2 / HTU_CYL_SAMPLES; the light one of scenes/mixed.scene's two
 * directional lights L, whose frame-free invariants are wi.wo = L.V = L_z / |L| and
 * wi[0] = L.T = L_y / |L|. */
typedef struct frame_probe {
    int calls, bad;
    double lo, hi; /* the pixel centres seen */
} frame_probe;

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void probe_fn(const void *m, const double wi[3], const double wo[3], double f[3])
{
    static const double dir[2][3] = {{-0.45, 0.75, 0.55}, {0.7, 0.25, 0.45}};
    frame_probe *p = (frame_probe *)m;
    double li = sqrt(dot3(wi, wi)), lo = sqrt(dot3(wo, wo));
    double k = (wo[1] + 1.0) * HTU_CYL_SAMPLES / 2.0 - 0.5, d = dot3(wi, wo);
    int light = 0;
    for (int l = 0; l < 2; ++l) {
        double n = sqrt(dot3(dir[l], dir[l]));
        if (fabs(d - dir[l][2] / n) < 1e-12 && fabs(wi[0] - dir[l][1] / n) < 1e-12) light = 1;
    }
    if (fabs(li - 1.0) > 1e-12 || fabs(lo - 1.0) > 1e-12 || wo[0] != 0.0 || !(wo[2] > 0.0) ||
        fabs(k - floor(k + 0.5)) > 1e-9 || !light)
        ++p->bad;
    p->lo = fmin(p->lo, wo[1]), p->hi = fmax(p->hi, wo[1]);
    ++p->calls;
    f[0] = f[1] = f[2] = 0.0;
}

START_TEST(cylinder_directions)
{
    frame_probe p = {0, 0, 1.0, -1.0};
    static double img[HTU_CYL_SAMPLES][3];
    htu_cylinder_image(probe_fn, &p, img);
    printf("huang convergence cylinder: %d directions handed over, %d not as the frame gives, "
           "views across x in [%.3f, %.3f]\n",
           p.calls, p.bad, p.lo, p.hi);
    ck_assert_int_gt(p.calls, HTU_CYL_SAMPLES);
    ck_assert_int_eq(p.bad, 0);
    ck_assert(p.lo < -0.95 && p.hi > 0.95);
}
END_TEST

/* The default's error on the image, against a reference with every grid doubled and the
 * Simpson count doubled (30 times the work), and what each grid buys. The VNDF grids are
 * shifted per grid (hair_huang.c, grid_shift); at one grid the error depends on where the
 * shifts fall, and it does not fall steadily with the work below about 30 times it. Checked:
 * the default and every grid at least as dense in each dimension within Table 8's "slight"
 * (2.5e-4) of the reference (measured 6.8e-5 and at most 1.9e-4; with every grid unshifted,
 * the reference's too, the default is 2.2e-2 away), and each coarser grid further from the
 * reference than the default (figures in docs/MODELS.md, "Convergence on an image"). */
START_TEST(image_convergence)
{
    static const int grid[][3] = {{6, 3, 1}, {12, 6, 2}, {6, 3, 2}, {12, 3, 1}, {6, 6, 1},
                                  {8, 4, 1}, {5, 3, 1},  {4, 3, 1}, {3, 3, 1},  {4, 2, 1}};
    enum { NG = (int)(sizeof grid / sizeof grid[0]) };
    static double img[NG][HTU_CYL_SAMPLES][3];
    double cpu[NG];
    abrdf__huang m;
    setup(&m, 0.73, 0.85);
    for (int g = 0; g < NG; ++g) {
        m.n1 = grid[g][0];
        m.n2 = grid[g][1];
        m.refine = grid[g][2];
        clock_t t0 = clock();
        htu_cylinder_image(eval_fn, &m, img[g]);
        cpu[g] = (double)(clock() - t0) / CLOCKS_PER_SEC;
    }
    double def_work = 36.0 * 10.0;
    for (int g = 0; g < NG; ++g) {
        double work =
            grid[g][0] * grid[g][0] * (1.0 + grid[g][1] * grid[g][1]) * grid[g][2] / def_work;
        printf("huang image grids %d,%d, Simpson x%d: NMSE vs the default %.2e, vs the reference "
               "%.2e, work %.2f (CPU time %.2f, one-off)\n",
               grid[g][0], grid[g][1], grid[g][2], htu_image_nmse(img[0], img[g]),
               htu_image_nmse(img[1], img[g]), work, cpu[g] / cpu[0]);
    }
    const double def_err = htu_image_nmse(img[1], img[0]);
    ck_assert_msg(def_err < 2.5e-4, "default vs reference: %g", def_err);
    for (int g = 2; g < NG; ++g) {
        double e = htu_image_nmse(img[1], img[g]);
        if (grid[g][0] >= 6 && grid[g][1] >= 3)
            ck_assert_msg(e < 2.5e-4, "grids %d,%d x%d vs reference: %g", grid[g][0], grid[g][1],
                          grid[g][2], e);
        else
            ck_assert_msg(e > def_err,
                          "coarser grids %d,%d x%d (%g) no further than the default (%g)",
                          grid[g][0], grid[g][1], grid[g][2], e, def_err);
    }
}
END_TEST

/* The grids' shift sets (hair.h, shift_set; tools/bench/hair_convergence --shifts): setup
 * picks set 0, the model's (its image is a freshly set up model's, bit for bit), and every set
 * gives an image of its own. Their errors against the reference (12, 6, x2) are spread by where
 * the shifts fall, so the mean of the set images must be nearer to it than the sets are on
 * average (the errors partly cancel: no common bias of their size), and their mean error stays
 * below 4e-4 (it is 2.3e-4: a rule whose expected error doubled would fail). Printed for
 * docs/MODELS.md, "Convergence on an image" and "What a converged reference costs". */
START_TEST(shift_sets)
{
    enum { NS = ABRDF__HUANG_SHIFT_SETS };
    static double ref[HTU_CYL_SAMPLES][3], fresh[HTU_CYL_SAMPLES][3];
    static double img[NS][HTU_CYL_SAMPLES][3], avg[HTU_CYL_SAMPLES][3];
    abrdf__huang m;
    setup(&m, 0.73, 0.85);
    ck_assert_int_eq(m.shift_set, 0);
    htu_cylinder_image(eval_fn, &m, fresh);
    m.n1 = 12, m.n2 = 6, m.refine = 2;
    htu_cylinder_image(eval_fn, &m, ref);
    setup(&m, 0.73, 0.85);
    double sum = 0.0;
    for (int s = 0; s < NS; ++s) {
        m.shift_set = s;
        htu_cylinder_image(eval_fn, &m, img[s]);
        for (int t = 0; t < s; ++t)
            ck_assert_msg(memcmp(img[s], img[t], sizeof img[s]) != 0,
                          "shift sets %d and %d give the same image", t, s);
        sum += htu_image_nmse(ref, img[s]);
        for (int p = 0; p < HTU_CYL_SAMPLES; ++p)
            for (int c = 0; c < 3; ++c) avg[p][c] = (s ? avg[p][c] : 0.0) + img[s][p][c] / NS;
    }
    ck_assert_msg(memcmp(img[0], fresh, sizeof fresh) == 0, "shift set 0 is not the model");
    double first = htu_image_nmse(ref, img[0]), mean = sum / NS, of_mean = htu_image_nmse(ref, avg);
    printf("huang shift sets: the default vs (12, 6, x2): set 0 %.2e, mean of %d sets %.2e, their "
           "mean image %.2e\n",
           first, NS, mean, of_mean);
    ck_assert_msg(mean < 4e-4, "mean over shift sets %g", mean);
    ck_assert_msg(of_mean < 0.5 * mean, "mean image %g vs mean error %g", of_mean, mean);
}
END_TEST

/* White furnace, melanin 0, WITHOUT energy compensation: R + TT + TRT (the paper's
 * Eqs. 12-14) stay below 1 and lose more energy as the section gets more eccentric; TRRT+
 * takes up part of it. The total stays <= 1 for the round and the default fibre (b = 1 and
 * 0.85, theta_o = 0, 45, 80 deg) and exceeds 1 for eccentric ones (converged, grids (12, 6):
 * 1.046 at b = 0.5, 1.039 at b = 0.2; the test's (4, 2) grid gives 1.034 and 1.061): TRRT+ is
 * Cycles' closed-form estimate of the further bounces, not an integral over their paths, and
 * nothing bounds it by what the first three lobes leave. Bounded at 1.01 and 1.08. Printed for
 * docs/MODELS.md, "White furnace". */
START_TEST(white_furnace_uncompensated)
{
    const double asp[] = {1.0, 0.85, 0.5, 0.2};
    double prev = 2.0;
    for (int k = 0; k < 4; ++k) {
        abrdf__huang m;
        setup(&m, 0.0, asp[k]);
        m.n1 = 4;
        m.n2 = 2;
        m.compensate = 0;
        double e = fibre_albedo(&m, 0.0, 7u, 12), t = fibre_albedo(&m, 0.0, 8u, 12);
        printf("huang white furnace, no compensation, b=%.2f theta_o=0: R+TT+TRT %.4f, TRRT+ %.4f, "
               "total %.4f\n",
               asp[k], e, t, e + t);
        ck_assert_msg(e <= 1.0 && e > 0.2, "R+TT+TRT albedo %.4f", e);
        if (k >= 1) ck_assert_msg(e <= prev + 5e-3, "loss must grow with eccentricity: %.4f", e);
        prev = e;
        ck_assert_msg(e + t <= (asp[k] >= 0.85 ? 1.01 : 1.08) && e + t > 0.7, "total albedo %.4f",
                      e + t);
    }
    const double deg[] = {45.0, 80.0};
    for (int k = 0; k < 2; ++k) {
        abrdf__huang m;
        setup(&m, 0.0, 0.85);
        m.n1 = 4;
        m.n2 = 2;
        m.compensate = 0;
        double a = fibre_albedo(&m, deg[k] * PI / 180, 15u, 12);
        printf("huang white furnace, no compensation, b=0.85 theta_o=%.0f: total %.4f\n", deg[k],
               a);
        ck_assert_msg(a <= 1.01 && a > 0.6, "total albedo %.4f at %g deg", a, deg[k]);
    }
}
END_TEST

/* White furnace of the default model (Cycles' energy compensation on): the compensation
 * lifts TT and TRT but the TRRT+ series is computed from the uncompensated Fresnel terms
 * (as in Cycles), so a lossless fibre returns more than it receives: 7% for the round fibre
 * and 6% for the default one, 21% and 20% at b = 0.5 and 0.2 (converged, grids (12, 6)).
 * Bounded here at [0.85, 1.25] and documented. */
START_TEST(white_furnace_compensated)
{
    const double asp[] = {1.0, 0.85, 0.5, 0.2, 0.85, 0.85}, deg[] = {0, 0, 0, 0, 45, 80};
    for (int k = 0; k < 6; ++k) {
        abrdf__huang m;
        setup(&m, 0.0, asp[k]);
        m.n1 = 4;
        m.n2 = 2;
        double a = fibre_albedo(&m, deg[k] * PI / 180, 15u, 12);
        printf("huang white furnace, compensated, b=%.2f theta_o=%.0f: total %.4f\n", asp[k],
               deg[k], a);
        ck_assert_msg(a <= 1.25 && a > 0.85, "total albedo %.4f", a);
    }
}
END_TEST

/* The compensation table: at a grid node the lookup is the tabulated quadrature value
 * (rounded to 6 decimals); a smooth interface at normal incidence has E = R + T = 1. */
START_TEST(glass_albedo_table)
{
    const int n = ABRDF__HAIR_E_N;
    int x = 5, y = 9, z = 7;
    double rough = (double)x / (n - 1), mu = (double)y / (n - 1), zz = (double)z / (n - 1);
    double s = zz * zz, eta = (1 + s) / (1 - s);
    double e = abrdf__ggx_glass_albedo(rough * rough, mu, eta, 64);
    ck_assert(fabs(abrdf__hair_glass_e[(z * n + y) * n + x] - e) <= 5e-7);
    double ei = abrdf__ggx_glass_albedo(rough * rough, mu, 1.0 / eta, 64);
    ck_assert(fabs(abrdf__hair_glass_inv_e[(z * n + y) * n + x] - ei) <= 5e-7);
    ck_assert(tu_close(abrdf__ggx_glass_albedo(1e-6, 1.0, 1.55, 16), 1.0, 1e-9, 0));
    ck_assert(e < 1.0 && e > 0.5);
}
END_TEST

/* Hard cases: no NaN, Inf or negative value (counts printed). */
START_TEST(stability_grid)
{
    const double etas[] = {1.0, 1.55, 4.0};
    const double mel[] = {0.0, 1.0};
    const double rr[] = {0.05, 1.0};
    const double tilt[] = {-10, 10};
    const double asp[] = {0.01, 0.85, 1.0};
    const double dirs[][3] = {{1, 0, 1e-12}, {-1, 0, 1e-12},    {0, 0, 1},         {0.6, 0, 0.8},
                              {0, 1, 1e-12}, {0.3, 0.4, 0.866}, {0.99, -0.1, 0.1}, {0, 0, 0}};
    const int nd = (int)(sizeof dirs / sizeof dirs[0]);
    tu_counts cnt = {0, 0, 0, 0};
    abrdf_params p;
    abrdf_params_init(ABRDF_HUANG, &p);
    for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 2; ++b)
            for (int c = 0; c < 2; ++c)
                for (int d = 0; d < 2; ++d)
                    for (int e = 0; e < 3; ++e) {
                        p.eta = etas[a];
                        p.melanin = mel[b];
                        p.r = rr[c];
                        p.cuticle_tilt = tilt[d];
                        p.aspect_ratio = asp[e];
                        for (int i = 0; i < nd; ++i)
                            for (int o = 0; o < nd; ++o) {
                                if (c == 0 && (i + o) % 5)
                                    continue; /* alpha = 0.05 is slow: a fifth */
                                double f[3];
                                ck_assert_int_eq(
                                    abrdf_eval(ABRDF_HUANG, &p, NULL, dirs[i], dirs[o], f),
                                    ABRDF_OK);
                                tu_count(&cnt, f);
                            }
                    }
    const double zero[3] = {0, 0, 0}, n[3] = {0, 0, 1};
    abrdf_frame fr;
    abrdf_frame_make(n, zero, &fr);
    abrdf_params_init(ABRDF_HUANG, &p);
    for (int i = 0; i < nd; ++i)
        for (int o = 0; o < nd; ++o) {
            double f[3];
            ck_assert_int_eq(abrdf_eval(ABRDF_HUANG, &p, &fr, dirs[i], dirs[o], f), ABRDF_OK);
            tu_count(&cnt, f);
        }
    printf("huang stability grid: %ld values, NaN %ld, Inf %ld, negative %ld\n", cnt.evals, cnt.nan,
           cnt.inf, cnt.neg);
    ck_assert(cnt.nan == 0 && cnt.inf == 0 && cnt.neg == 0);
}
END_TEST

/* Continuity where wi, wo and the fibre T lie in one plane (surface azimuth 0 or 180 deg,
 * fibre azimuths equal): each direction is turned off that plane by +-d degrees, to either
 * side, alone or both, and S must tend to its value in the plane. Before the fix a 1e-16
 * rounding decided whether the Simpson end nodes on the silhouette counted: r = 0.3,
 * theta 85 deg, both at 180 deg gave 0.021276 on one side and 0.021129 on the other (R), and
 * the TRT lobe jumped by 0.3% at theta 40/70; at 85/85 and 60/20, phi 0/180, the cut of
 * GGX D at wm.wh = 0 sat on R's end nodes (4e-4, 2.5e-4 in blue). Measured now: <= 2e-8 relative at d = 1e-6
 * deg, 0 at 1e-13 deg; held to 1e-6. */
START_TEST(coplanar_continuity)
{
    const struct {
        double ti, pi, to, po;
    } cfg[] = {{85, 180, 85, 180}, {85, 0, 85, 0},   {40, 0, 70, 180},
               {40, 180, 70, 0},   {40, 0, 70, 0},   {60, 180, 30, 180},
               {10, 0, 80, 0},     {85, 0, 85, 180}, {60, 0, 20, 180}};
    const double d[] = {1e-13, 1e-9, 1e-6};
    const int sides[][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, 1}, {-1, -1}, {1, -1}, {-1, 1}};
    abrdf_params p;
    abrdf_params_init(ABRDF_HUANG, &p);
    p.r = 0.3;
    double worst = 0.0;
    for (size_t c = 0; c < sizeof cfg / sizeof cfg[0]; ++c) {
        double wi[3], wo[3], f0[3];
        tu_dir(cfg[c].ti, cfg[c].pi, wi);
        tu_dir(cfg[c].to, cfg[c].po, wo);
        ck_assert_int_eq(abrdf_eval(ABRDF_HUANG, &p, NULL, wi, wo, f0), ABRDF_OK);
        ck_assert(f0[0] > 0.0);
        if (c == 0) printf("huang coplanar: r 0.3, theta 85/85, phi 180/180: f %.6f\n", f0[0]);
        for (size_t k = 0; k < sizeof d / sizeof d[0]; ++k)
            for (size_t sd = 0; sd < sizeof sides / sizeof sides[0]; ++sd) {
                double f[3];
                tu_dir(cfg[c].ti, cfg[c].pi + sides[sd][0] * d[k], wi);
                tu_dir(cfg[c].to, cfg[c].po + sides[sd][1] * d[k], wo);
                abrdf_eval(ABRDF_HUANG, &p, NULL, wi, wo, f);
                for (int ch = 0; ch < 3; ++ch) {
                    double rel = fabs(f[ch] - f0[ch]) / f0[ch];
                    worst = fmax(worst, rel);
                    ck_assert_msg(rel <= 1e-6,
                                  "theta %g/%g phi %g/%g turned by (%d, %d) x %g deg: "
                                  "%.9g vs %.9g",
                                  cfg[c].ti, cfg[c].to, cfg[c].pi, cfg[c].po, sides[sd][0],
                                  sides[sd][1], d[k], f[ch], f0[ch]);
                }
            }
    }
    printf("huang coplanar continuity: largest relative change %.3g (d <= 1e-6 deg)\n", worst);
}
END_TEST

/* A direction from a linear congruential sequence: theta in [0, 180), phi in [0, 360) deg. */
static void lcg_dir(unsigned long long *seed, double w[3])
{
    double u[2];
    for (int k = 0; k < 2; ++k) {
        *seed = *seed * 6364136223846793005ULL + 1442695040888963407ULL;
        u[k] = (double)(*seed >> 11) / 9007199254740992.0;
    }
    tu_dir(180.0 * u[0], 360.0 * u[1], w);
}

/* A run of lights sharing one view (abrdf__huang_fibre_run, and the batch path that hands
 * runs of equal wo to it) gives each light what a call of its own gives: lobe by lobe in
 * double, the same bits (runs of 1, 2, 5, 7 and ABRDF__HUANG_RUN_MAX lights, of which light
 * 5 is hidden by the tilt, and of 7, 8 and 16 lit ones: hair_huang.c's two loops over the
 * lights, below and from LIGHT_MAJOR_MIN = 8 lit lights on, and a last block of LIGHTS_BLOCK
 * that is full; through abrdf__huang_fibre_wide, which a table's build calls, of 5, 13, 100
 * and ABRDF__HUANG_WIDE_MAX), and through abrdf_eval_prepared_batch against
 * abrdf_eval_prepared in float, with lights below the ribbon, lights the tilt hides and a
 * degenerate vector inside the runs, and runs longer than ABRDF__HUANG_RUN_MAX (split). */
START_TEST(light_runs_match_single_calls)
{
    abrdf_params p;
    abrdf_params_init(ABRDF_HUANG, &p);
    p.cuticle_tilt = 8.0; /* hides some grazing lights */
    p.melanin = 0.4;
    abrdf__huang m;
    abrdf__huang_setup(&p, &m);
    unsigned long long seed = 7;
    double worst = 0.0;
    for (int v = 0; v < 6; ++v) {
        double wo[3], wi[ABRDF__HUANG_WIDE_MAX][3], s_run[ABRDF__HUANG_WIDE_MAX][3];
        lcg_dir(&seed, wo);
        wo[2] = fabs(wo[2]) + 0.05;
        for (int l = 0; l < ABRDF__HUANG_WIDE_MAX; ++l) {
            lcg_dir(&seed, wi[l]);
            if (l == 2) wi[l][2] = -fabs(wi[l][2]);                          /* below the ribbon */
            if (l == 5) wi[l][0] = 0.999, wi[l][1] = 0.0, wi[l][2] = 0.0447; /* grazing, along T */
            double yz = hypot(wi[l][1], wi[l][2]);
            if (l > 5 && fabs(wi[l][0]) > 0.9) { /* from light 6 on, every light is lit */
                wi[l][0] = copysign(0.9, wi[l][0]);
                if (yz > 0.0)
                    wi[l][1] *= sqrt(0.19) / yz, wi[l][2] *= sqrt(0.19) / yz;
                else
                    wi[l][1] = sqrt(0.19);
            }
        }
        /* runs: (first light, lights, wide) */
        static const int runs[][3] = {{0, 1, 0},
                                      {0, 2, 0},
                                      {0, 5, 0},
                                      {0, 7, 0},
                                      {0, ABRDF__HUANG_RUN_MAX, 0},
                                      {6, 7, 0},
                                      {6, 8, 0},
                                      {6, 16, 0},
                                      {0, 5, 1},
                                      {0, 13, 1},
                                      {0, 100, 1},
                                      {0, ABRDF__HUANG_WIDE_MAX, 1}};
        for (unsigned lobes = 1; lobes < 16; lobes = lobes * 2 + 1)
            for (int k = 0; k < (v < 2 ? 12 : 8); ++k) { /* the wide runs from two views */
                const int n = runs[k][1];
                const double(*w)[3] = (const double(*)[3])wi + runs[k][0];
                if (runs[k][2])
                    abrdf__huang_fibre_wide(&m, n, w, wo, lobes, s_run);
                else
                    abrdf__huang_fibre_run(&m, n, w, wo, lobes, s_run);
                for (int l = 0; l < n; ++l) {
                    double s1[3];
                    abrdf__huang_fibre(&m, w[l], wo, lobes, s1);
                    for (int c = 0; c < 3; ++c) {
                        double d = fabs(s_run[l][c] - s1[c]) / fmax(fabs(s1[c]), 1e-300);
                        worst = fmax(worst, s1[c] == 0.0 ? (s_run[l][c] != 0.0) : d);
                    }
                }
            }
    }
    printf("huang light runs vs single calls: largest relative difference %.3g\n", worst);
    ck_assert_msg(worst == 0.0, "a run differs from single calls by %.3g", worst);

    /* the batch path: 3 views x 11 lights each (a run of 8 and one of 3), one degenerate */
    abrdf_prepared pr;
    ck_assert_int_eq(abrdf_prepare(ABRDF_HUANG, &p, &pr), ABRDF_OK);
    enum { V = 3, L = 11, N = V * L };
    float in[6][N], out[3][N];
    for (int v = 0; v < V; ++v) {
        double wo[3];
        lcg_dir(&seed, wo);
        wo[2] = fabs(wo[2]) + 0.05;
        for (int l = 0; l < L; ++l) {
            double wi[3];
            lcg_dir(&seed, wi);
            if (l % 4 == 3) wi[2] = -wi[2];
            for (int k = 0; k < 3; ++k)
                in[k][v * L + l] = (float)wi[k], in[3 + k][v * L + l] = (float)wo[k];
        }
    }
    in[0][5] = in[1][5] = in[2][5] = 0.0f; /* a zero light vector inside the first run */
    abrdf_batch b = {N, in[0], in[1], in[2], in[3], in[4], in[5], out[0], out[1], out[2]};
    ck_assert_int_eq(abrdf_eval_prepared_batch(&pr, &b), ABRDF_OK);
    double bworst = 0.0;
    for (int i = 0; i < N; ++i) {
        double wi[3] = {in[0][i], in[1][i], in[2][i]}, wo[3] = {in[3][i], in[4][i], in[5][i]};
        double f[3] = {0, 0, 0};
        if (i != 5) ck_assert_int_eq(abrdf_eval_prepared(&pr, NULL, wi, wo, f), ABRDF_OK);
        for (int c = 0; c < 3; ++c) {
            ck_assert_msg(isfinite(out[c][i]) && out[c][i] >= 0.0f, "pair %d: %g", i, out[c][i]);
            if (f[c] == 0.0)
                ck_assert_msg(out[c][i] == 0.0f, "pair %d: %g where 0", i, out[c][i]);
            else
                bworst = fmax(bworst, fabs(out[c][i] - f[c]) / f[c]);
        }
    }
    printf("huang batch runs vs abrdf_eval_prepared: largest relative difference %.3g\n", bworst);
    ck_assert_msg(bworst <= 1e-6, "the batch differs from per-pair calls by %.3g", bworst);
}
END_TEST

/* Absorption darkens: melanin 0.8 scatters less than melanin 0 (TT and TRT carry it). */
START_TEST(absorption_darkens)
{
    abrdf_params p;
    abrdf_params_init(ABRDF_HUANG, &p);
    double wi[3], wo[3], f0[3], f1[3];
    htu_fdir(0.2, 2.5, wi);
    htu_fdir(-0.1, 0.4, wo);
    wi[2] = fabs(wi[2]);
    wo[2] = fabs(wo[2]);
    p.melanin = 0.0;
    abrdf_eval(ABRDF_HUANG, &p, NULL, wi, wo, f0);
    p.melanin = 0.8;
    abrdf_eval(ABRDF_HUANG, &p, NULL, wi, wo, f1);
    ck_assert(f1[0] < f0[0] && f1[2] < f1[0] && f0[0] > 0.0);
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("hair_huang");
    TCase *tc = tcase_create("huang");
    tcase_set_timeout(tc, 1200);
    tcase_add_test(tc, r_smooth_limit);
    tcase_add_test(tc, quadrature_convergence);
    tcase_add_test(tc, cylinder_directions);
    tcase_add_test(tc, image_convergence);
    tcase_add_test(tc, shift_sets);
    tcase_add_test(tc, white_furnace_uncompensated);
    tcase_add_test(tc, white_furnace_compensated);
    tcase_add_test(tc, glass_albedo_table);
    tcase_add_test(tc, stability_grid);
    tcase_add_test(tc, absorption_darkens);
    tcase_add_test(tc, coplanar_continuity);
    tcase_add_test(tc, light_runs_match_single_calls);
    suite_add_tcase(s, tc);
    return s;
}

int main(void)
{
    setvbuf(stdout, NULL, _IONBF, 0); /* measurements print even if a check aborts */
    return tu_run(suite());
}
