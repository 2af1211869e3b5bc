/* test_fmath.c - the float transcendentals of the batch path (fmath.h) against the C
 * library in double: the error in ulp of the float result over every 1021st float of each
 * domain (about 4.2 million inputs, both signs, subnormals, the clamped ranges), printed
 * (docs quote it), and held to the bounds fmath.h states; the special values exact. */
#include <math.h>
#include <stdio.h>

#include "fmath.h"
#include "test_util.h"

/* |got - want| in units of the last place of want as a float (subnormal spacing below
 * FLT_MIN). */
static double ulps(float got, double want)
{
    double a = fabs(want);
    double ulp = a < 1.17549435e-38 ? ldexp(1.0, -149) : ldexp(1.0, ilogb(a) - 23);
    return fabs((double)got - want) / ulp;
}

typedef struct worst {
    double ulp;
    float at;
} worst;

static void note(worst *w, double e, float x)
{
    if (!(e <= w->ulp)) w->ulp = e, w->at = x;
}

START_TEST(exp2_and_log2_within_their_bounds)
{
    worst e2 = {0.0, 0.0f}, l2 = {0.0, 0.0f}, ln = {0.0, 0.0f}, ex = {0.0, 0.0f};
    for (uint64_t u = 0; u <= 0xFFFFFFFFu; u += 1021) {
        float x = abrdf__bitsf((uint32_t)u);
        if (!isfinite(x)) continue;
        double want2 = exp2((double)x);
        if (want2 >= 1.17549435e-38 && want2 < 3.4028234e38)
            note(&e2, ulps(abrdf__exp2f(x), want2), x);
        double we = exp((double)x);
        if (we >= 1.17549435e-38 && x < 88.375f) note(&ex, ulps(abrdf__expf(x), we), x);
        if (x > 0.0f) note(&l2, ulps(abrdf__log2f(x), log2((double)x)), x);
        if (x >= 1.17549435e-38f) note(&ln, ulps(abrdf__log2f_normal(x, 0.0f), log2((double)x)), x);
    }
    /* both sides of the reduction's switch at sqrt(2) and sqrt(1/2), and binades' tops */
    static const float edge[] = {0x1.6a09e6p0f, 0x1.6a09e8p0f,  0x1.6a09e6p-1f,  0x1.6a09e8p-1f,
                                 0x1.fffffep0f, 0x1.fffffep-1f, 0x1.6a09e6p100f, 0x1.6a09e8p-100f};
    for (size_t k = 0; k < sizeof edge / sizeof *edge; ++k)
        note(&ln, ulps(abrdf__log2f_normal(edge[k], 0.0f), log2((double)edge[k])), edge[k]);
    printf("fmath: abrdf__exp2f max error %.2f ulp (at %a), abrdf__log2f %.2f ulp (at %a), "
           "abrdf__log2f_normal %.2f ulp (at %a), abrdf__expf %.2f ulp (at %a)\n",
           e2.ulp, e2.at, l2.ulp, l2.at, ln.ulp, ln.at, ex.ulp, ex.at);
    ck_assert_msg(e2.ulp <= 2.0, "exp2 %.3g ulp at %a", e2.ulp, e2.at);
    ck_assert_msg(l2.ulp <= 3.5, "log2 %.3g ulp at %a", l2.ulp, l2.at);
    ck_assert_msg(ln.ulp <= 3.5, "log2_normal %.3g ulp at %a", ln.ulp, ln.at);
    ck_assert_msg(ex.ulp <= 2.0, "exp %.3g ulp at %a", ex.ulp, ex.at);
}
END_TEST

/* x^e over the batch path's range: bases in (0, 1], exponents of the models (n in [0, 1e6]),
 * relative to the double result: within what the rounding of y = e log2(x) costs through 2^y
 * (ln 2 times half an ulp of y plus e times log2's 2.8 ulp of log2 x) and 2 ulp of 2^y. */
START_TEST(pow_within_the_rounding_of_its_exponent)
{
    static const float es[] = {0.5f, 1.0f, 2.0f, 7.3f, 10.0f, 100.0f, 1000.0f, 1e4f, 1e5f, 1e6f};
    double worst_excess = 0.0;
    for (size_t k = 0; k < sizeof es / sizeof *es; ++k) {
        for (uint32_t u = 0x00800000u; u <= 0x3F800000u; u += 4099) {
            float x = abrdf__bitsf(u), e = es[k];
            double want = pow((double)x, (double)e);
            if (!(want >= 1e-30)) continue;
            double l = fabs(log2((double)x)), y = e * l;
            double ulp_y = y > 0.0 ? ldexp(1.0, ilogb(y) - 23) : 0.0;
            double ulp_l = l > 0.0 ? ldexp(1.0, ilogb(l) - 23) : 0.0;
            double bound =
                (log(2.0) * (0.5 * ulp_y + e * 2.8 * ulp_l) + 2.0 * ldexp(1.0, -23)) * want;
            double got = abrdf__powf_pos(x, e), excess = fabs(got - want) / bound;
            if (excess > worst_excess) worst_excess = excess;
            ck_assert_msg(excess <= 1.0, "%a^%g: %.9g, want %.9g", x, e, got, want);
        }
    }
    printf("fmath: abrdf__powf_pos's error at most %.2f of its bound\n", worst_excess);
}
END_TEST

START_TEST(special_values)
{
    ck_assert(abrdf__exp2f(0.0f) == 1.0f);
    ck_assert(abrdf__exp2f(-126.2f) == 0.0f); /* no subnormal results */
    ck_assert(abrdf__exp2f(-1e30f) == 0.0f);
    ck_assert(abrdf__exp2f(-INFINITY) == 0.0f);
    ck_assert(abrdf__exp2f(NAN) == 0.0f);
    ck_assert(isinf(abrdf__exp2f(128.0f)) && abrdf__exp2f(128.0f) > 0.0f);
    ck_assert(isinf(abrdf__exp2f(INFINITY)));
    ck_assert(isfinite(abrdf__exp2f(127.99f)));
    ck_assert(abrdf__log2f(1.0f) == 0.0f);
    ck_assert(abrdf__log2f(0.5f) == -1.0f);
    ck_assert(fabs(abrdf__log2f(0x1p-149f) + 149.0) < 1e-5); /* smallest subnormal */
    ck_assert(fabs(abrdf__log2f(0x1.8p-140f) - log2(0x1.8p-140)) < 1e-5);
    ck_assert(abrdf__powf_pos(0.0f, 0.0f) == 1.0f);
    ck_assert(abrdf__powf_pos(0.0f, 3.0f) == 0.0f);
    ck_assert(abrdf__powf_pos(-0.5f, 2.0f) == 0.0f); /* the base is clamped, no spurious lobe */
    ck_assert(abrdf__powf_pos(NAN, 2.0f) == 0.0f);
    /* a subnormal base is raised as FLT_MIN = 2^-126 */
    ck_assert(abrdf__powf_pos(0x1p-140f, 0.5f) == 0x1p-63f);
    ck_assert(abrdf__powf_pos(0x1p-149f, 2.0f) == 0.0f);
    ck_assert(abrdf__powf_pos(0x1p-149f, 0.0f) == 1.0f);
    for (int k = -126; k <= 127; ++k) /* a power of 2 has m = 1, t = 0: exact */
        ck_assert(abrdf__log2f_normal(ldexpf(1.0f, k), 0.0f) == (float)k);
    ck_assert(abrdf__log2f_normal(8.0f, 24.0f) == -21.0f);
    ck_assert(abrdf__powf_pos(1.0f, 1e6f) == 1.0f); /* the peak of every lobe exactly */
    ck_assert(abrdf__powf_pos(0.25f, 0.0f) == 1.0f);
    ck_assert(abrdf__powf_pos(0.5f, 2.0f) == 0.25f);
    ck_assert(abrdf__expf(0.0f) == 1.0f);
    ck_assert(abrdf__expf(-1e4f) == 0.0f);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("fmath");
    TCase *tc = tcase_create("fmath");
    tcase_set_timeout(tc, 600);
    tcase_add_test(tc, exp2_and_log2_within_their_bounds);
    tcase_add_test(tc, pow_within_the_rounding_of_its_exponent);
    tcase_add_test(tc, special_values);
    suite_add_tcase(s, tc);
    return tu_run(s);
}
