/* test_cloth.c - Neubelt-Pettineo (Eq. 10) and Kajiya-Kay (Eq. 11): hand-computed values,
 * normalisation of the velvet D, reciprocity (NP) and its absence (KK), white furnace,
 * scalar == batch, and the stability grid (tangent parallel to L or V, zero tangent). */
#include <math.h>
#include <stdio.h>
#include "cl_quad.h"
#include "test_util.h"

static const double PI = 3.14159265358979323846;

static double dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Neubelt-Pettineo by hand: Ashikhmin-Premoze D (sin^4 form), Schlick F, smooth visibility. */
static double np_hand(const double wi[3], const double wo[3], double kd, double ks, double f0,
                      double r, double k_amp)
{
    double s[3] = {wi[0] + wo[0], wi[1] + wo[1], wi[2] + wo[2]};
    double l = sqrt(dot(s, s)), h[3] = {s[0] / l, s[1] / l, s[2] / l};
    double a = r * r, ch = h[2], sh2 = 1.0 - ch * ch, cot2 = ch * ch / sh2;
    double D = (1.0 + k_amp * exp(-cot2 / (a * a)) / (sh2 * sh2)) / (PI * (1.0 + k_amp * a * a));
    double F = f0 + (1.0 - f0) * pow(1.0 - dot(wi, h), 5.0);
    double ci = wi[2], co = wo[2];
    return (1.0 - F) * kd / PI + ks * F * D / (4.0 * (ci + co - ci * co));
}

START_TEST(np_by_hand)
{
    abrdf_params p;
    abrdf_params_init(ABRDF_NEUBELT_PETTINEO, &p);
    const double rs[] = {0.3, 0.7, 1.0}, ks[] = {0.0, 4.0, 20.0};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            p.r = rs[i];
            p.k_amp = ks[j];
            p.kd[0] = 0.6;
            p.f0[0] = 0.1;
            double wi[3], wo[3];
            tu_dir(40.0, 180.0, wi);
            tu_dir(70.0, 30.0, wo);
            double got = tu_eval1(ABRDF_NEUBELT_PETTINEO, &p, wi, wo);
            double want = np_hand(wi, wo, 0.6, 1.0, 0.1, rs[i], ks[j]);
            ck_assert_msg(tu_close(got, want, 1e-12, 0.0), "r=%g k=%g: %.17g vs %.17g", rs[i],
                          ks[j], got, want);
        }
}
END_TEST

/* The library's velvet D, read back through the API: with kd = 0, ks = 1, f0 = 1 (F = 1)
 * and wi = wo = h, f = D / (4 (2c - c^2)), c = N.h. Then int D(h) cos_h dwh must be 1
 * (MODELS.md B6.1: the normalisation 1/(pi (1 + k_amp alpha^2)) holds for any k_amp). */
START_TEST(np_d_integrates_to_one)
{
    abrdf_params p;
    abrdf_params_init(ABRDF_NEUBELT_PETTINEO, &p);
    p.kd[0] = 0.0;
    p.f0[0] = 1.0;
    p.ks[0] = 1.0;
    const double rs[] = {0.25, 0.5, 0.8, 1.0}, ks[] = {0.0, 1.0, 4.0, 50.0};
    enum { N = 4000 };
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            p.r = rs[i];
            p.k_amp = ks[j];
            double sum = 0.0;
            /* midpoint rule in theta_h (D is isotropic: dwh = 2 pi sin dtheta) */
            for (int k = 0; k < N; ++k) {
                double th = (k + 0.5) * (PI / 2) / N;
                double h[3] = {sin(th), 0.0, cos(th)}, c = h[2];
                double D = tu_eval1(ABRDF_NEUBELT_PETTINEO, &p, h, h) * 4.0 * (2.0 * c - c * c);
                sum += D * c * sin(th) * 2.0 * PI * (PI / 2) / N;
            }
            ck_assert_msg(fabs(sum - 1.0) < 1e-4, "r=%g k_amp=%g: int D cos = %.8f", rs[i], ks[j],
                          sum);
        }
}
END_TEST

START_TEST(np_reciprocal)
{
    abrdf_params p;
    abrdf_params_init(ABRDF_NEUBELT_PETTINEO, &p);
    unsigned s = 7u;
    for (int i = 0; i < 20000; ++i) {
        double a[3], b[3];
        quad_rand_dir(&s, 0.001, a);
        quad_rand_dir(&s, 0.001, b);
        double f1 = tu_eval1(ABRDF_NEUBELT_PETTINEO, &p, a, b),
               f2 = tu_eval1(ABRDF_NEUBELT_PETTINEO, &p, b, a);
        ck_assert_msg(tu_close(f1, f2, 1e-12, 0.0), "%.17g vs %.17g", f1, f2);
    }
    ck_assert(abrdf_model_get(ABRDF_NEUBELT_PETTINEO)->props & ABRDF_PROP_RECIPROCAL);
}
END_TEST

/* White furnace. kd = 1, f0 = 0: Fresnel (1 - cos_d)^5 moves energy from the Lambert term to
 * the sheen lobe, which returns less than it takes, so rho <= 1 and close to 1 (measured
 * 0.990-1.000). f0 = 1: sheen alone, rho <= 1 at the default k_amp = 4 (it grows toward
 * grazing: 0.13-0.25 at 0 deg, up to 0.77 at 89 deg for r = 0.6). Tolerance 2e-3 covers the
 * quadrature (orders 96 vs 192 agree to 1e-3). NP is not energy-conserving in general:
 * for large k_amp at grazing light its sheen albedo approaches sqrt(k_amp)/(2 sqrt(pi)). */
START_TEST(np_white_furnace)
{
    abrdf_params p;
    abrdf_params_init(ABRDF_NEUBELT_PETTINEO, &p);
    const double rs[] = {0.3, 0.6, 1.0}, th[] = {0.0, 45.0, 80.0, 89.0};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j) {
            p.r = rs[i];
            p.kd[0] = 1.0;
            p.f0[0] = 0.0;
            double a =
                quad_albedo(ABRDF_NEUBELT_PETTINEO, &p, th[j], fmax(0.05, rs[i] * rs[i]), 96, 0);
            ck_assert_msg(a <= 1.0 + 2e-3 && a > 0.97, "r=%g th=%g: rho = %.6f", rs[i], th[j], a);
            p.kd[0] = 0.0;
            p.f0[0] = 1.0;
            a = quad_albedo(ABRDF_NEUBELT_PETTINEO, &p, th[j], fmax(0.05, rs[i] * rs[i]), 96, 0);
            ck_assert_msg(a <= 1.0, "sheen only r=%g th=%g: rho = %.6f", rs[i], th[j], a);
        }
    /* the grazing limit sqrt(k_amp) / (2 sqrt(pi)) = 2.82 at k_amp = 100, alpha = 0.1 */
    p.k_amp = 100.0;
    p.r = sqrt(0.1);
    double g = quad_albedo(ABRDF_NEUBELT_PETTINEO, &p, 89.9, 0.05, 128, 0);
    ck_assert_msg(g > 2.5 && g < 3.0, "k_amp 100 at 89.9 deg: rho = %.4f", g);
    ck_assert(!(abrdf_model_get(ABRDF_NEUBELT_PETTINEO)->props & ABRDF_PROP_ENERGY_CONSERVING));
}
END_TEST

/* Kajiya-Kay by hand in a world frame with an explicit tangent. */
START_TEST(kk_by_hand)
{
    abrdf_params p;
    abrdf_params_init(ABRDF_KAJIYA_KAY, &p);
    p.kd[0] = 0.3;
    p.ks[0] = 0.7;
    p.n = 20.0;
    double n[3] = {0, 0, 1}, t[3] = {0.6, 0.8, 0.0};
    abrdf_frame fr;
    ck_assert_int_eq(abrdf_frame_make(n, t, &fr), ABRDF_OK);
    double L[3], V[3];
    tu_dir(35.0, 200.0, L);
    tu_dir(60.0, 10.0, V);
    double tl = dot(t, L), tv = dot(t, V);
    double sl = sqrt(1 - tl * tl), sv = sqrt(1 - tv * tv);
    double want = 0.3 * sl + 0.7 * pow(fmax(0.0, sl * sv - tl * tv), 20.0);
    double f[3];
    ck_assert_int_eq(abrdf_eval(ABRDF_KAJIYA_KAY, &p, &fr, L, V, f), ABRDF_OK);
    ck_assert_msg(tu_close(f[0], want, 1e-12, 0.0), "%.17g vs %.17g", f[0], want);
}
END_TEST

/* The specular peak lies on the mirror cone T.V = -T.L (sign-correct form, MODELS.md B6.4):
 * scanning V in the T-N plane, the maximum of the specular term is at theta_V = -theta_L. */
START_TEST(kk_highlight_on_mirror_cone)
{
    abrdf_params p;
    abrdf_params_init(ABRDF_KAJIYA_KAY, &p);
    p.kd[0] = 0.0;
    p.ks[0] = 1.0;
    p.n = 100.0;
    double L[3];
    tu_dir(30.0, 180.0, L); /* T.L = -sin 30 */
    double best = -1.0, best_x = 0.0;
    for (int k = -890; k <= 890; ++k) {
        double th = k * 0.1, V[3];
        tu_dir(fabs(th), th < 0 ? 180.0 : 0.0, V);
        double f = tu_eval1(ABRDF_KAJIYA_KAY, &p, L, V);
        if (f > best) best = f, best_x = th;
    }
    ck_assert_msg(fabs(best_x - 30.0) < 0.051, "peak at %g deg, want 30", best_x);
    ck_assert(tu_close(best, 1.0, 1e-9, 0.0));
}
END_TEST

/* The specular bracket is symmetric in L and V; the diffuse sin(T, L) is not, so the model
 * is reciprocal only for kd = 0, and its metadata says "not reciprocal". */
START_TEST(kk_reciprocity)
{
    abrdf_params p;
    abrdf_params_init(ABRDF_KAJIYA_KAY, &p);
    p.kd[0] = 0.0;
    unsigned s = 11u;
    for (int i = 0; i < 20000; ++i) {
        double a[3], b[3];
        quad_rand_dir(&s, 0.001, a);
        quad_rand_dir(&s, 0.001, b);
        ck_assert(tu_close(tu_eval1(ABRDF_KAJIYA_KAY, &p, a, b),
                           tu_eval1(ABRDF_KAJIYA_KAY, &p, b, a), 1e-12, 0.0));
    }
    p.kd[0] = 0.5;
    double a[3], b[3];
    tu_dir(10.0, 0.0, a);
    tu_dir(80.0, 0.0, b);
    ck_assert(!tu_close(tu_eval1(ABRDF_KAJIYA_KAY, &p, a, b), tu_eval1(ABRDF_KAJIYA_KAY, &p, b, a),
                        1e-3, 0.0));
    ck_assert(!(abrdf_model_get(ABRDF_KAJIYA_KAY)->props & ABRDF_PROP_RECIPROCAL));
    ck_assert(!(abrdf_model_get(ABRDF_KAJIYA_KAY)->props & ABRDF_PROP_ENERGY_CONSERVING));
    ck_assert(abrdf_model_get(ABRDF_KAJIYA_KAY)->needs & ABRDF_NEEDS_TANGENT);
}
END_TEST

/* Kajiya-Kay is an unnormalised lobe: its diffuse albedo is kd sin(T, L) pi, which exceeds 1
 * for kd > 1/pi. Closed form for the diffuse part: rho = pi kd sin(T, L). */
START_TEST(kk_diffuse_albedo_closed_form)
{
    abrdf_params p;
    abrdf_params_init(ABRDF_KAJIYA_KAY, &p);
    p.kd[0] = 1.0;
    p.ks[0] = 0.0;
    const double th[] = {0.0, 45.0, 80.0};
    for (int j = 0; j < 3; ++j) {
        double a = quad_albedo(ABRDF_KAJIYA_KAY, &p, th[j], 1.0, 96, 0);
        double want = PI * sqrt(1.0 - pow(sin(th[j] * PI / 180.0), 2)); /* T = +x, wi in x-z */
        ck_assert_msg(tu_close(a, want, 1e-3, 0.0), "th=%g: %.6f vs %.6f", th[j], a, want);
    }
}
END_TEST

/* Float batch path == double scalar path. */
START_TEST(cloth_batch_matches_scalar)
{
    const abrdf_model ms[] = {ABRDF_NEUBELT_PETTINEO, ABRDF_KAJIYA_KAY};
    clq_batch_matches_scalar(ms, 2, 2000, 3u, 2e-4, 1e-6);
}
END_TEST

/* Hard cases: grazing and back-facing directions, L = V, L = -V, tangent parallel to L or
 * to V, zero tangent (the frame then picks one), extreme parameters; scalar and batch. */
START_TEST(cloth_stability_grid)
{
    const abrdf_model ms[] = {ABRDF_NEUBELT_PETTINEO, ABRDF_KAJIYA_KAY};
    const double rs[] = {0.0, 1e-3, 0.5, 1.0}, kamp[] = {0.0, 4.0, 100.0}, f0s[] = {0.0, 1.0};
    const double ns[] = {0.0, 1.0, 1e6};
    for (int mi = 0; mi < 2; ++mi) {
        tu_counts k = {0, 0, 0, 0}, kb = {0, 0, 0, 0};
        abrdf_params p;
        abrdf_params_init(ms[mi], &p);
        unsigned s = 99u;
        for (int pi = 0; pi < 72; ++pi) {
            p.r = rs[pi % 4];
            p.k_amp = kamp[(pi / 4) % 3];
            p.f0[0] = p.f0[1] = p.f0[2] = f0s[(pi / 12) % 2];
            p.n = ns[(pi / 24) % 3];
            for (int i = 0; i < 400; ++i) {
                double L[3], V[3], n[3] = {0, 0, 1}, t[3];
                quad_rand_dir(&s, i % 4 == 0 ? 0.0 : -0.2, L);
                if (i % 4 == 0) L[2] = 1e-9 * (i % 3); /* grazing */
                quad_rand_dir(&s, -0.2, V);
                if (i % 7 == 0)
                    for (int c = 0; c < 3; ++c) V[c] = L[c]; /* L = V */
                if (i % 11 == 0)
                    for (int c = 0; c < 3; ++c) V[c] = -L[c]; /* L = -V */
                int tk = i % 4; /* tangent: parallel to L, parallel to V, zero, random */
                for (int c = 0; c < 3; ++c)
                    t[c] = tk == 0 ? L[c] : tk == 1 ? V[c] : tk == 2 ? 0.0 : V[c] - L[c];
                abrdf_frame fr;
                abrdf_frame_make(n, t, &fr);
                double f[3];
                ck_assert_int_eq(abrdf_eval(ms[mi], &p, &fr, L, V, f), ABRDF_OK);
                tu_count(&k, f);
                /* the same pair with T = L or T = V exactly in the local frame */
                double Ll[3] = {1, 0, 0}, Vl[3];
                for (int c = 0; c < 3; ++c) Vl[c] = V[c];
                abrdf_eval(ms[mi], &p, NULL, Ll, Vl, f);
                tu_count(&k, f);
                abrdf_eval(ms[mi], &p, NULL, Vl, Ll, f);
                tu_count(&k, f);
                float bx[2] = {(float)L[0], 1.0f}, by[2] = {(float)L[1], 0.0f},
                      bz[2] = {(float)L[2], 1e-30f};
                float cx[2] = {(float)V[0], (float)V[0]}, cy[2] = {(float)V[1], (float)V[1]},
                      cz[2] = {(float)V[2], (float)V[2]};
                float o0[2], o1[2], o2[2];
                abrdf_batch bt = {2, bx, by, bz, cx, cy, cz, o0, o1, o2};
                abrdf_eval_batch(ms[mi], &p, &bt);
                for (int j = 0; j < 2; ++j) {
                    double fb[3] = {o0[j], o1[j], o2[j]};
                    tu_count(&kb, fb);
                }
            }
        }
        printf("stability %s: scalar %ld values (NaN %ld, Inf %ld, negative %ld); batch %ld (NaN "
               "%ld, Inf %ld, negative %ld)\n",
               abrdf_model_get(ms[mi])->name, k.evals, k.nan, k.inf, k.neg, kb.evals, kb.nan,
               kb.inf, kb.neg);
        ck_assert(k.evals >= 100000);
        ck_assert(k.nan == 0 && k.inf == 0 && k.neg == 0);
        ck_assert(kb.nan == 0 && kb.inf == 0 && kb.neg == 0);
    }
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("cloth");
    TCase *tc = tcase_create("cloth");
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, np_by_hand);
    tcase_add_test(tc, np_d_integrates_to_one);
    tcase_add_test(tc, np_reciprocal);
    tcase_add_test(tc, np_white_furnace);
    tcase_add_test(tc, kk_by_hand);
    tcase_add_test(tc, kk_highlight_on_mirror_cone);
    tcase_add_test(tc, kk_reciprocity);
    tcase_add_test(tc, kk_diffuse_albedo_closed_form);
    tcase_add_test(tc, cloth_batch_matches_scalar);
    tcase_add_test(tc, cloth_stability_grid);
    suite_add_tcase(s, tc);
    return s;
}

int main(void) { return tu_run(suite()); }
