/* test_stability.c - the hard cases of every registered model, in double (scalar) and float
 * (batch): grazing (cos = 0, +-1e-8), cos slightly above 1 (unnormalised input), wi = wo,
 * wi = -wo, back-facing, zero/NaN/Inf/huge/tiny vectors, the parameter extremes
 * (r in {0, 1e-8, 1e-4, 1}, n in {0, 1, 1e4, 1e6}, F0 in {0, 1}, full anisotropy with
 * r -> 0, ...) plus random and near-mirror directions: >= 10^6 evaluations per precision,
 * every result finite and non-negative. Parameters outside a model's range are rejected
 * with ABRDF_E_RANGE and f = 0. Prints the counts. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test_grid.h"
#include "test_util.h"

#define MAX_SETS 96
#define MAX_REPORT 8
#define TARGET_EVALS 1100000L /* per precision, over the closed-form models */
#define MAXDIR 64
#define MAXPAIRS 8192

static int ndir;
static double dirs[MAXDIR][3];

static void add_dir(double x, double y, double z)
{
    dirs[ndir][0] = x;
    dirs[ndir][1] = y;
    dirs[ndir][2] = z;
    ++ndir;
}

static void make_dirs(void)
{
    static const double graze[] = {0.0, 1e-8, -1e-8};
    static const double gphi[] = {0.0, 90.0, 180.0, 235.0};
    const double d2r = 3.14159265358979323846 / 180.0;
    ndir = 0;
    for (int i = 0; i < 3; ++i) /* grazing: cos = 0, +-1e-8 */
        for (int j = 0; j < 4; ++j) {
            double z = graze[i], s = sqrt(1.0 - z * z);
            add_dir(s * cos(gphi[j] * d2r), s * sin(gphi[j] * d2r), z);
        }
    add_dir(0, 0, 1); /* normal incidence and cos slightly above 1 (unnormalised) */
    add_dir(0, 0, 1.0 + 1e-7);
    add_dir(1e-9, 0, 1.0 + 1e-7);
    add_dir(1e-8, 0, 1.0);
    add_dir(0.0, 1e-12, 1.0 - 1e-16);
    for (int t = 0; t < 3; ++t) /* ordinary directions */
        for (int j = 0; j < 2; ++j) {
            double th = (t == 0 ? 30.0 : t == 1 ? 60.0 : 85.0) * d2r, ph = (j ? 120.0 : 0.0) * d2r;
            add_dir(sin(th) * cos(ph), sin(th) * sin(ph), cos(th));
        }
    add_dir(0.3, 0.2, -0.93); /* back-facing */
    add_dir(0, 0, -1);
    add_dir(1, 0, -1e-8);
    add_dir(0, 0, 0); /* degenerate */
    add_dir(NAN, 0, 1);
    add_dir(0, 0, NAN);
    add_dir(INFINITY, 0, 1);
    add_dir(0, 0, INFINITY);
    add_dir(-INFINITY, -INFINITY, -INFINITY);
    add_dir(1e-300, 0, 1e-300);
    add_dir(1e300, 0, 1e300);
    add_dir(4.9e-324, 0, 0);
    add_dir(0, 0, 4.9e-324);
    add_dir(3e-39, 0, 3e-39); /* float denormals */
}

typedef struct pairset {
    int count;
    double wi[MAXPAIRS][3], wo[MAXPAIRS][3];
} pairset;

static void push(pairset *ps, const double a[3], const double b[3])
{
    if (ps->count >= MAXPAIRS) return;
    memcpy(ps->wi[ps->count], a, sizeof(double) * 3);
    memcpy(ps->wo[ps->count], b, sizeof(double) * 3);
    ++ps->count;
}

/* Every ordered pair of the hard directions (wi = wo included), wi = -wo, the mirror pair
 * (H = N exactly: the peak of every half-vector lobe), then `extra` random pairs: half
 * uniform on the sphere (back-facing included), half near the mirror direction at angles
 * 10^-U(0, 9) (inside the sharpest lobes, n = 1e6 or alpha_g = 1e-6). */
static void make_pairs(pairset *ps, int extra, tg_rng *rng)
{
    ps->count = 0;
    for (int i = 0; i < ndir; ++i)
        for (int j = 0; j < ndir; ++j) push(ps, dirs[i], dirs[j]);
    for (int i = 0; i < ndir; ++i) {
        double neg[3] = {-dirs[i][0], -dirs[i][1], -dirs[i][2]}, m[3];
        tg_mirror(dirs[i], m);
        push(ps, dirs[i], neg);
        push(ps, dirs[i], m);
    }
    for (int k = 0; k < extra; ++k) {
        double a[3], b[3];
        if (k & 1) {
            tg_sphere(rng, a);
            tg_sphere(rng, b);
        } else {
            double m[3], d[3];
            tg_hemisphere(rng, a);
            tg_mirror(a, m);
            tg_sphere(rng, d);
            double eps = pow(10.0, -9.0 * tg_uniform(rng));
            for (int c = 0; c < 3; ++c) b[c] = m[c] + eps * d[c];
        }
        push(ps, a, b);
    }
}

static int good3(const double f[3])
{
    return f[0] >= 0.0 && f[1] >= 0.0 && f[2] >= 0.0 && isfinite(f[0]) && isfinite(f[1]) &&
           isfinite(f[2]);
}

static int goodf(float f) { return f >= 0.0f && isfinite(f); }

static pairset ps;
static float bx[6][MAXPAIRS], bout[3][MAXPAIRS];

/* Evaluates one parameter set on ps in both precisions, through a prepared object (what a
 * renderer uses; abrdf_eval and abrdf_eval_batch are the same calls, test_invariants holds
 * them to it bit for bit); returns the number of bad results. */
static long run_set(const abrdf_model_info *m, const tg_set *set, long *nd, long *nf, tg_rng *rng)
{
    long bad = 0;
    abrdf_prepared prep;
    int pst = abrdf_prepare(m->id, &set->p, &prep);
    if (pst != ABRDF_OK) {
        printf("BAD prepare %s [%s]: status %d\n", m->name, set->label, pst);
        return 1;
    }
    for (int k = 0; k < ps.count; ++k) {
        double f[3] = {NAN, NAN, NAN};
        int st = abrdf_eval_prepared(&prep, NULL, ps.wi[k], ps.wo[k], f);
        ++*nd;
        if (st != ABRDF_OK || !good3(f)) {
            if (bad++ < MAX_REPORT)
                printf("BAD double %s [%s] wi=(%g,%g,%g) wo=(%g,%g,%g): status %d f=%g,%g,%g\n",
                       m->name, set->label, ps.wi[k][0], ps.wi[k][1], ps.wi[k][2], ps.wo[k][0],
                       ps.wo[k][1], ps.wo[k][2], st, f[0], f[1], f[2]);
        }
        if ((k & 15) == 0) { /* world space through a random (or broken) frame */
            double n[3], t[3];
            abrdf_frame fr;
            tg_sphere(rng, n);
            tg_sphere(rng, t);
            abrdf_frame_make(n, (k & 32) ? t : NULL, &fr);
            if ((k & 63) == 0) fr.t[1] = NAN; /* a hand-made frame with a NaN: f = 0 */
            st = abrdf_eval_prepared(&prep, &fr, ps.wi[k], ps.wo[k], f);
            ++*nd;
            if (st != ABRDF_OK || !good3(f)) {
                if (bad++ < MAX_REPORT)
                    printf("BAD double/frame %s [%s]: status %d f=%g\n", m->name, set->label, st,
                           f[0]);
            }
        }
    }
    for (int k = 0; k < ps.count; ++k)
        for (int c = 0; c < 3; ++c) {
            bx[c][k] = (float)ps.wi[k][c];
            bx[3 + c][k] = (float)ps.wo[k][c];
        }
    for (int c = 0; c < 3; ++c)
        for (int k = 0; k < ps.count; ++k) bout[c][k] = NAN;
    abrdf_batch b = {(size_t)ps.count, bx[0],   bx[1],  bx[2], bx[3], bx[4], bx[5],
                     bout[0],          bout[1], bout[2]};
    int st = abrdf_eval_prepared_batch(&prep, &b);
    *nf += ps.count;
    if (st != ABRDF_OK) {
        printf("BAD batch %s [%s]: status %d\n", m->name, set->label, st);
        return bad + ps.count;
    }
    for (int k = 0; k < ps.count; ++k)
        if (!goodf(bout[0][k]) || !goodf(bout[1][k]) || !goodf(bout[2][k])) {
            if (bad++ < MAX_REPORT)
                printf("BAD float %s [%s] wi=(%g,%g,%g) wo=(%g,%g,%g): f=%g,%g,%g\n", m->name,
                       set->label, bx[0][k], bx[1][k], bx[2][k], bx[3][k], bx[4][k], bx[5][k],
                       bout[0][k], bout[1][k], bout[2][k]);
        }
    return bad;
}

START_TEST(hard_cases_never_nan_inf_negative)
{
    static tg_set sets[MAX_SETS];
    tg_rng rng = {20240601};
    make_dirs();
    /* Random pairs per set so that the closed-form models reach TARGET_EVALS. */
    long nsets = 0;
    for (int mi = 0; mi < abrdf_model_count(); ++mi) {
        const abrdf_model_info *m = tu_param_model(mi);
        if (m && !(m->needs & ABRDF_NEEDS_INTEGRATION))
            nsets += tg_param_sets(m->id, TG_HARD, sets, MAX_SETS);
    }
    make_pairs(&ps, 0, &rng);
    long hard_pairs = ps.count;
    long extra = nsets ? (TARGET_EVALS + nsets - 1) / nsets - hard_pairs : 0;
    if (extra < 64) extra = 64;
    if (extra > MAXPAIRS - hard_pairs) extra = MAXPAIRS - hard_pairs;
    long nd = 0, nf = 0, bad = 0, nd_int = 0, nf_int = 0;
    for (int mi = 0; mi < abrdf_model_count(); ++mi) {
        const abrdf_model_info *m = tu_param_model(mi);
        if (!m) continue;
        int slow = (m->needs & ABRDF_NEEDS_INTEGRATION) != 0;
        /* Models that integrate inside eval get the hard pairs and 4 parameter sets. */
        int ns = tg_param_sets(m->id, TG_HARD, sets, slow ? 4 : MAX_SETS);
        long b0 = bad;
        for (int s = 0; s < ns; ++s) {
            make_pairs(&ps, slow ? 0 : (int)extra, &rng);
            bad += run_set(m, &sets[s], slow ? &nd_int : &nd, slow ? &nf_int : &nf, &rng);
        }
        printf("stability %-22s %3d parameter sets%s%s\n", m->name, ns,
               slow ? " (integrating model: hard pairs only)" : "", bad > b0 ? "  BAD" : "");
    }
    printf("stability: %ld double evals, %ld float evals, %ld bad (closed-form models, %ld "
           "hard + %ld random direction pairs per parameter set)\n",
           nd, nf, bad, hard_pairs, extra);
    if (nd_int || nf_int)
        printf("stability: integrating models: %ld double evals, %ld float evals\n", nd_int,
               nf_int);
    ck_assert_msg(bad == 0, "%ld NaN/Inf/negative or failed evaluations", bad);
    ck_assert_msg(nd >= 1000000 && nf >= 1000000, "only %ld double / %ld float evaluations", nd,
                  nf);
}
END_TEST

/* Outside a model's range (below min, above max, NaN, +-Inf) every parameter it uses is
 * rejected: ABRDF_E_RANGE from check, eval and batch, with f = 0 (never NaN). */
static int rejected(const abrdf_model_info *m, const abrdf_params *p, const char *what)
{
    double wi[3] = {0.3, 0.1, 0.9}, wo[3] = {-0.2, 0.3, 0.8}, f[3] = {NAN, NAN, NAN};
    float x[1] = {0.3f}, y[1] = {0.1f}, z[1] = {0.9f}, ox[1] = {-0.2f}, oy[1] = {0.3f},
          oz[1] = {0.8f}, fr[1] = {NAN}, fg[1] = {NAN}, fb[1] = {NAN};
    abrdf_batch b = {1, x, y, z, ox, oy, oz, fr, fg, fb};
    char msg[256];
    int s1 = abrdf_params_check(m->id, p, msg, sizeof msg);
    int s2 = abrdf_eval(m->id, p, NULL, wi, wo, f);
    int s3 = abrdf_eval_batch(m->id, p, &b);
    /* prepare refuses too, and the object it leaves is "not prepared" */
    abrdf_prepared prep;
    double g[3] = {NAN, NAN, NAN};
    int s4 = abrdf_prepare(m->id, p, &prep);
    int s5 = abrdf_eval_prepared(&prep, NULL, wi, wo, g);
    int ok = s1 == ABRDF_E_RANGE && s2 == ABRDF_E_RANGE && s3 == ABRDF_E_RANGE && f[0] == 0.0 &&
             f[1] == 0.0 && f[2] == 0.0 && fr[0] == 0.0f && fg[0] == 0.0f && fb[0] == 0.0f &&
             msg[0] != '\0' && s4 == ABRDF_E_RANGE && s5 == ABRDF_E_MODEL && g[0] == 0.0 &&
             abrdf_prepared_model(&prep) == ABRDF_MODEL_NONE;
    if (!ok)
        printf("NOT REJECTED %s %s: check %d eval %d batch %d prepare %d eval_prepared %d f=%g "
               "float=%g msg='%s'\n",
               m->name, what, s1, s2, s3, s4, s5, f[0], fr[0], msg);
    return ok;
}

START_TEST(out_of_range_parameters_rejected)
{
    long cases = 0, fails = 0;
    for (int mi = 0; mi < abrdf_model_count(); ++mi) {
        const abrdf_model_info *m = tu_param_model(mi);
        if (!m) continue;
        for (int i = 0; i < m->param_count; ++i) {
            const abrdf_model_param *mp = &m->params[i];
            const abrdf_param_info *pi = abrdf_param_get(mp->id);
            int is_int = pi->kind == ABRDF_PARAM_INT;
            double bad[5] = {mp->min - (is_int ? 1.0 : fmax(1e-9, fabs(mp->min) * 1e-9)),
                             mp->max + (is_int ? 1.0 : fmax(1e-9, fabs(mp->max) * 1e-9)), NAN,
                             INFINITY, -INFINITY};
            for (int k = 0; k < (is_int ? 2 : 5); ++k) {
                abrdf_params p;
                abrdf_params_init(m->id, &p);
                void *ptr = tg_param_ptr(&p, mp->id);
                ck_assert_msg(ptr != NULL, "parameter %s unknown to tg_param_ptr", pi->name);
                if (is_int)
                    *(int *)ptr = (int)bad[k];
                else if (pi->kind == ABRDF_PARAM_RGB)
                    ((double *)ptr)[1] = bad[k];
                else
                    *(double *)ptr = bad[k];
                char what[96];
                snprintf(what, sizeof what, "%s=%g", pi->name, bad[k]);
                ++cases;
                fails += !rejected(m, &p, what);
            }
        }
    }
    /* The exponent and roughness values: in range they are evaluated by the hard-case
     * test above; outside a model's range (f_2e, f_ct2e need n >= 1) they must be rejected. */
    static const double ns[] = {0.0, 1.0, 1e4, 1e6}, rs[] = {0.0, 1e-8, 1e-4, 1.0};
    for (int mi = 0; mi < abrdf_model_count(); ++mi) {
        const abrdf_model_info *m = tu_param_model(mi);
        if (!m) continue;
        for (int i = 0; i < m->param_count; ++i) {
            const char *nm = abrdf_param_get(m->params[i].id)->name;
            const double *vals = !strcmp(nm, "n") ? ns : !strcmp(nm, "r") ? rs : NULL;
            for (int k = 0; vals && k < 4; ++k) {
                if (vals[k] >= m->params[i].min && vals[k] <= m->params[i].max) continue;
                abrdf_params p;
                abrdf_params_init(m->id, &p);
                *(double *)tg_param_ptr(&p, m->params[i].id) = vals[k];
                char what[96];
                snprintf(what, sizeof what, "%s=%g (issue value)", nm, vals[k]);
                ++cases;
                fails += !rejected(m, &p, what);
            }
        }
    }
    printf("out of range: %ld cases, %ld not rejected\n", cases, fails);
    ck_assert_msg(fails == 0, "%ld out-of-range parameters were not rejected cleanly", fails);
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("stability");
    TCase *tc = tcase_create("hard_cases");
    tcase_set_timeout(tc, 600);
    tcase_add_test(tc, hard_cases_never_nan_inf_negative);
    tcase_add_test(tc, out_of_range_parameters_rejected);
    suite_add_tcase(s, tc);
    return s;
}

int main(void)
{
    setvbuf(stdout, NULL, _IOLBF, 0);
    return tu_run(suite());
}
