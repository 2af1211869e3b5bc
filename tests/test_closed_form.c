/* test_closed_form.c - every model against an independent closed-form hand computation at
 * fixed directions (written out term by term here, not via the library's kernels). */
#include <math.h>
#include "test_util.h"

static const double PI = 3.14159265358979323846;

/* wi at 30 deg, wo at 50 deg on the other side with a 20 deg azimuth offset. */
static void dirs(double wi[3], double wo[3])
{
    tu_dir(30.0, 180.0, wi);
    tu_dir(50.0, 20.0, wo);
}

static void half(const double wi[3], const double wo[3], double h[3])
{
    double s[3] = {wi[0] + wo[0], wi[1] + wo[1], wi[2] + wo[2]};
    double l = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
    for (int c = 0; c < 3; ++c) h[c] = s[c] / l;
}

static double dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

START_TEST(ggx_schlick_smith_by_hand)
{
    double wi[3], wo[3], h[3];
    dirs(wi, wo);
    half(wi, wo, h);
    abrdf_params p;
    abrdf_params_init(ABRDF_DISNEY_SPECULAR, &p);
    p.r = 0.4;
    p.f0[0] = p.f0[1] = p.f0[2] = 0.9;
    double ag = 0.16, a2 = ag * ag;
    double ch = h[2], ci = wi[2], co = wo[2], cd = dot(wi, h);
    double D = a2 / (PI * pow(1.0 + (a2 - 1.0) * ch * ch, 2));                /* Eq. 6 */
    double F = 0.9 + 0.1 * pow(1.0 - cd, 5);                                   /* Eq. 8 */
    double G1i = 2.0 / (1.0 + sqrt(1.0 + a2 * (1.0 - ci * ci) / (ci * ci)));  /* Eq. 9 */
    double G1o = 2.0 / (1.0 + sqrt(1.0 + a2 * (1.0 - co * co) / (co * co)));
    double expect = F * D * G1i * G1o / (4.0 * ci * co);                       /* Eq. 5 */
    double got = tu_eval1(ABRDF_DISNEY_SPECULAR, &p, wi, wo);
    ck_assert_msg(tu_close(got, expect, 1e-9, 0.0), "GGX %.17g vs hand %.17g", got, expect);
}
END_TEST

START_TEST(lambert_is_kd_over_pi)
{
    double wi[3], wo[3];
    dirs(wi, wo);
    abrdf_params p;
    abrdf_params_init(ABRDF_LAMBERT, &p);
    p.kd[0] = 0.5;
    ck_assert(tu_close(tu_eval1(ABRDF_LAMBERT, &p, wi, wo), 0.5 / PI, 1e-15, 0.0));
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("closed_form");
    TCase *tc = tcase_create("models");
    tcase_add_test(tc, ggx_schlick_smith_by_hand);
    tcase_add_test(tc, lambert_is_kd_over_pi);
    suite_add_tcase(s, tc);
    return s;
}

int main(void) { return tu_run(suite()); }
