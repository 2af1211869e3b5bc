/* hair_convergence.c - what huang's quadrature grids cost and how far each is from the
 * converged model, on the convergence cylinder of docs/MODELS.md ("What a converged reference
 * costs"): the hair of data/materials.csv's hair_brown on a fibre cylinder under the two
 * directional lights of scenes/mixed.scene (tests/unit/hair_test_util.c, htu_cylinder_image;
 * test_hair_huang renders the same image). Each grid's image NMSE against a reference grid, and
 * its work per evaluation relative to the default's, n1^2 (1 + n2^2) refine / (6^2 (1 + 3^2)).
 *
 *   hair_convergence [--lobes] [--backlit] [--r R] [--shifts K] [--reference N1,N2,REFINE]
 *                    [--reference-sets K] [--table NT,NV,NP,SETS [--parts] [--pairs N]]
 *                    [N1,N2,REFINE ...]
 *
 * The reference defaults to 16,8,4 (185 times the default's work: a few seconds at r = 0.3,
 * about 15 at r = 0.1, as the Simpson steps shrink with r); the grids to the table of the page.
 * The reference is its grids with shift set 0 (the model's shifts), or with --reference-sets K
 * the mean image of its shift sets 0 to K - 1 (K <= ABRDF__HUANG_SHIFT_SETS, K times the
 * time): one set of (16, 8, x4) is itself a few 1e-6 from the converged model, and correlated
 * with the model's own set 0 (docs/MODELS.md, "A tabulated huang", "The reference").
 * REFINE divides the Simpson steps (not a parameter of the model). --lobes adds, under each
 * grid, each lobe's part of its error (R, TT, TRT, TRRT+); --r sets the fibre's roughness, in
 * [0.05, 1] (default 0.3, hair_brown's). --backlit moves the second light behind the cylinder
 * (hair_test_util.h, htu_cylinder_image_lit), so that TT is in the image. --shifts K adds,
 * under each grid, its NMSE with the shift sets 0 to K - 1 (hair.h, shift_set; K <=
 * ABRDF__HUANG_SHIFT_SETS), their mean and range, the error of the sets' mean image and the
 * nearest set: the model's grids are shifted by one fixed set (set 0), and its error on this
 * image depends on where those shifts fall; the mean over the sets tells the rule's error from
 * that luck. The reference keeps its own (set 0, or the mean of --reference-sets). --table
 * adds the tabulated huang (hair.h, abrdf__huang_table_rows) built from the default grids with
 * NT theta nodes, NV view azimuths, NP light azimuths and the mean of SETS shift sets per
 * node: its image's NMSE, the seconds its table took to build (one thread), and the
 * microseconds per evaluation of the image's pairs, the table's beside the quadrature's,
 * measured in this run. --parts adds, under the
 * table, where its error comes from: the NMSE of the rule its nodes hold (the mean of the SETS
 * shift sets) at the image's own directions, no interpolation; and, on that same mean, the
 * NMSE of the Catmull-Rom interpolation along each axis the table reads along, alone (theta_v
 * along the lobes' ridge, theta_v + theta_l across it, phi_v, d), the other three exact,
 * between nodes placed as hair_huang_table.c places them (away from the theta ends, where the
 * table blends into reading along theta_v and theta_l). --pairs N adds the table's residual
 * lobes against the reference grids' at N random direction pairs (table_pairs; with their set
 * 0 whatever --reference-sets). */

#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "hair.h"
#include "hair_test_util.h"

typedef struct grids {
    int n1, n2, refine;
} grids;

static int parse(const char *s, grids *g)
{
    char tail;
    if (sscanf(s, "%d,%d,%d%c", &g->n1, &g->n2, &g->refine, &tail) != 3 || g->n1 < 1 ||
        g->n1 > ABRDF__HUANG_GRID_MAX || g->n2 < 1 || g->n2 > ABRDF__HUANG_GRID_MAX ||
        g->refine < 1 || g->refine > 16) {
        fprintf(stderr, "hair_convergence: '%s' is not N1,N2,REFINE (grids 1-%d, refine 1-16)\n", s,
                ABRDF__HUANG_GRID_MAX);
        return 0;
    }
    return 1;
}

/* The model of one grid, and the lobes its image keeps (hair.h: R 1, TT 2, TRT 4, TRRT+ 8) */
typedef struct lobed {
    abrdf__huang m;
    unsigned lobes;
} lobed;

/* f_r = S / cos(theta_i) of the kept lobes, as abrdf__huang_eval gives it for all of them */
static void eval_fn(const void *l, const double wi[3], const double wo[3], double f[3])
{
    const lobed *x = l;
    f[0] = f[1] = f[2] = 0.0;
    if (!(wi[2] > 0.0) || !(wo[2] > 0.0)) return;
    abrdf__huang_fibre(&x->m, wi, wo, x->lobes, f);
    for (int c = 0; c < 3; ++c) f[c] /= wi[2];
}

static int backlit; /* --backlit: the image's second light behind the cylinder */

/* The model of hair_brown at roughness r (grids: the model's defaults). */
static void model(double r, abrdf__huang *m)
{
    abrdf_params p;
    abrdf_params_init(ABRDF_HUANG, &p);
    p.melanin = 0.73; /* hair_brown */
    p.r = r;
    abrdf__huang_setup(&p, m);
}

static void image(const grids *g, double r, unsigned lobes, int set, double img[HTU_CYL_SAMPLES][3])
{
    lobed x;
    model(r, &x.m);
    x.m.n1 = g->n1, x.m.n2 = g->n2, x.m.refine = g->refine;
    x.m.shift_set = set;
    x.lobes = lobes;
    htu_cylinder_image_lit(eval_fn, &x, backlit, img);
}

/* The reference image of the lobes: the mean of the reference grids' shift sets 0 to sets - 1
 * (--reference-sets; set 0 alone by default). */
static void reference(const grids *g, double r, unsigned lobes, int sets,
                      double img[HTU_CYL_SAMPLES][3])
{
    static double one[HTU_CYL_SAMPLES][3];
    image(g, r, lobes, 0, img);
    for (int s = 1; s < sets; ++s) {
        image(g, r, lobes, s, one);
        for (int k = 0; k < HTU_CYL_SAMPLES; ++k)
            for (int c = 0; c < 3; ++c) img[k][c] += one[k][c];
    }
    for (int k = 0; k < HTU_CYL_SAMPLES; ++k)
        for (int c = 0; c < 3; ++c) img[k][c] /= sets;
}

/* Each lobe's part of a grid's error: the squared difference of that lobe's image from the
 * reference's (ref_lobe[l], lobe bit 1 << l), over the whole reference image's squared sum
 * (so the parts add up to about the NMSE), and each lobe's share of the reference's squared
 * sum. */
static void by_lobe(const grids *g, double r, const double want[HTU_CYL_SAMPLES][3],
                    double ref_lobe[4][HTU_CYL_SAMPLES][3])
{
    static const char *name[4] = {"R", "TT", "TRT", "TRRT+"};
    static double b[HTU_CYL_SAMPLES][3];
    double den = 0.0;
    for (int k = 0; k < HTU_CYL_SAMPLES; ++k)
        for (int c = 0; c < 3; ++c) den += want[k][c] * want[k][c];
    printf("  by lobe (error, share of the reference):");
    for (int l = 0; l < 4; ++l) {
        image(g, r, 1u << l, 0, b);
        double num = 0.0, own = 0.0;
        for (int k = 0; k < HTU_CYL_SAMPLES; ++k)
            for (int c = 0; c < 3; ++c) {
                double a = ref_lobe[l][k][c];
                num += (b[k][c] - a) * (b[k][c] - a);
                own += a * a;
            }
        printf("%s %s %.1e (%.0f %%)", l ? "," : "", name[l], num / den, 100.0 * own / den);
    }
    printf("\n");
}

/* A grid's NMSE with each of the shift sets 0 to k - 1, their mean and range, the error of
 * their mean image, and which set is the nearest (by the full values, not the printed ones). */
static void by_shifts(const grids *g, double r, int k, const double want[HTU_CYL_SAMPLES][3])
{
    static double img[HTU_CYL_SAMPLES][3], avg[HTU_CYL_SAMPLES][3];
    double e[ABRDF__HUANG_SHIFT_SETS], sum = 0.0, lo = 0.0, hi = 0.0;
    int best = 0;
    for (int s = 0; s < k; ++s) {
        image(g, r, 15u, s, img);
        e[s] = htu_image_nmse(want, img);
        for (int p = 0; p < HTU_CYL_SAMPLES; ++p)
            for (int c = 0; c < 3; ++c) avg[p][c] = (s ? avg[p][c] : 0.0) + img[p][c] / k;
        sum += e[s];
        if (s == 0 || e[s] < lo) best = s;
        lo = s == 0 || e[s] < lo ? e[s] : lo;
        hi = s == 0 || e[s] > hi ? e[s] : hi;
    }
    printf("  over %d shift sets: mean %.1e, from %.1e to %.1e (", k, sum / k, lo, hi);
    for (int s = 0; s < k; ++s) printf("%s%.1e", s ? " " : "", e[s]);
    printf("); their mean image %.1e; nearest: set %d\n", htu_image_nmse(want, avg), best);
}

static double seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

typedef struct tabled {
    abrdf__huang m;
    abrdf__huang_table t;
} tabled;

static void eval_table(const void *l, const double wi[3], const double wo[3], double f[3])
{
    const tabled *x = l;
    double fl[1][3];
    abrdf__huang_table_eval_run(&x->m, &x->t, 1, (const double(*)[3])wi, wo, fl);
    for (int c = 0; c < 3; ++c) f[c] = fl[0][c];
}

static void eval_model(const void *m, const double wi[3], const double wo[3], double f[3])
{
    abrdf__huang_eval(m, wi, wo, f);
}

/* Microseconds per evaluation of eval over the image's pairs (two lights per pixel, the
 * unlit ones skipped), the image rendered reps times. */
static double image_us(htu_eval_fn eval, const void *m, int reps)
{
    static double img[HTU_CYL_SAMPLES][3];
    double t0 = seconds();
    for (int i = 0; i < reps; ++i) htu_cylinder_image_lit(eval, m, backlit, img);
    return (seconds() - t0) * 1e6 / (reps * 2.0 * HTU_CYL_SAMPLES);
}

/* --parts: the rule a table's nodes hold, the mean of shift sets 0 to sets - 1 of the model's
 * grids, as a function of (theta_v, theta_l, phi_v, d): the residual lobes' S cos(theta_v),
 * as the table stores it, and R. One of the axes the table reads along (0-3, below) is read
 * by Catmull-Rom between the table's nodes; axis -1 reads none. */
typedef struct parted {
    abrdf__huang m;
    int sets, axis, dims[3]; /* NT, NV, NP */
} parted;

/* S of the lobes (hair.h bits) at the angles a, the mean of the sets, times k. */
static void mean_at(const parted *x, const double a[4], unsigned lobes, double k, double out[3])
{
    double wo[3], wi[1][3], s[1][3];
    htu_table_dir(a[0], a[2], wo);
    htu_table_dir(a[1], a[2] + a[3], wi[0]);
    abrdf__huang m = x->m;
    for (int c = 0; c < 3; ++c) out[c] = 0.0;
    for (int j = 0; j < x->sets; ++j) {
        m.shift_set = j;
        abrdf__huang_fibre_run(&m, 1, (const double(*)[3])wi, wo, lobes, s);
        for (int c = 0; c < 3; ++c) out[c] += s[0][c] * k / x->sets;
    }
}

/* f_r of the mean of the sets, one axis read between its nodes (x->axis) or none (-1). */
static void eval_parted(const void *l, const double wi[3], const double wo[3], double f[3])
{
    const parted *x = l;
    f[0] = f[1] = f[2] = 0.0;
    if (!(wi[2] > 0.0) || !(wo[2] > 0.0)) return;
    const double a[4] = {asin(wo[0]), asin(wi[0]), atan2(wo[1], wo[2]),
                         remainder(atan2(wi[1], wi[2]) - atan2(wo[1], wo[2]), 2.0 * ABRDF__PI)};
    double res[3] = {0.0, 0.0, 0.0}, r[3];
    if (x->axis < 0) {
        mean_at(x, a, 14u, cos(a[0]), res);
    } else {
        const int ax = x->axis;
        /* The axis' coordinate at a, its node spacing h and its first node o, as
         * hair_huang_table.c reads it: theta_v along the ridge (at fixed theta_v + theta_l),
         * theta_v + theta_l across it (at fixed theta_v), phi_v, d. */
        const double c = ax == 1 ? a[0] + a[1] : a[ax];
        const double h = ax < 2    ? ABRDF__PI / x->dims[0]
                         : ax == 2 ? 0.5 * ABRDF__PI / (x->dims[1] - 1)
                                   : 2.0 * ABRDF__PI / x->dims[2];
        const double o = ax == 0   ? -0.5 * ABRDF__PI + 0.5 * h
                         : ax == 1 ? -ABRDF__PI + h
                         : ax == 2 ? 0.0
                                   : -ABRDF__PI;
        double t = (c - o) / h, i = floor(t), u = t - i, u2 = u * u, u3 = u2 * u;
        const double w[4] = {0.5 * (-u3 + 2.0 * u2 - u), 0.5 * (3.0 * u3 - 5.0 * u2 + 2.0),
                             0.5 * (-3.0 * u3 + 4.0 * u2 + u), 0.5 * (u3 - u2)};
        for (int q = 0; q < 4; ++q) {
            double b[4] = {a[0], a[1], a[2], a[3]}, v[3];
            const double node = o + (i - 1 + q) * h;
            if (ax == 0)
                b[0] = node, b[1] = a[0] + a[1] - node;
            else if (ax == 1)
                b[1] = node - a[0];
            else
                b[ax] = node;
            mean_at(x, b, 14u, cos(b[0]), v);
            for (int c = 0; c < 3; ++c) res[c] += w[q] * v[c];
        }
    }
    mean_at(x, a, 1u, 1.0, r); /* R is never read from the table */
    for (int c = 0; c < 3; ++c) f[c] = (res[c] / cos(a[0]) + r[c]) / wi[2];
}

/* --parts: the table's error in parts (above). */
static void table_parts(const int dims[4], double r, const double want[HTU_CYL_SAMPLES][3])
{
    static const char *name[4] = {"theta_v along the ridge", "theta_v + theta_l", "phi_v", "d"};
    static double img[HTU_CYL_SAMPLES][3], mean[HTU_CYL_SAMPLES][3];
    parted x = {.sets = dims[3], .axis = -1, .dims = {dims[0], dims[1], dims[2]}};
    model(r, &x.m);
    htu_cylinder_image_lit(eval_parted, &x, backlit, mean);
    printf("  its nodes' rule (the mean of %d shift sets) at the image's own directions: NMSE vs "
           "the reference %.1e\n",
           dims[3], htu_image_nmse(want, mean));
    printf("  each axis alone read between its nodes, on that mean: NMSE vs the mean");
    for (x.axis = 0; x.axis < 4; ++x.axis) {
        if (x.axis == 2 && dims[1] == 1) continue; /* a round fibre: no phi_v axis */
        htu_cylinder_image_lit(eval_parted, &x, backlit, img);
        printf("%s %s %.1e", x.axis ? "," : "", name[x.axis], htu_image_nmse(mean, img));
    }
    printf("\n");
}

/* --pairs: the table's residual lobes (TT + TRT + TRRT+) against the reference grids' at
 * random direction pairs, both uniform on the sphere within 85 degrees of the fibre's normal
 * plane: the NMSE over all of them, over those with both theta within 60 degrees and over the
 * others. */
static void table_pairs(const tabled *x, const grids *ref, int pairs)
{
    abrdf__huang rm = x->m;
    rm.n1 = ref->n1, rm.n2 = ref->n2, rm.refine = ref->refine;
    unsigned seed = 12345u;
    double num[2] = {0.0, 0.0}, den[2] = {0.0, 0.0};
    for (int i = 0; i < pairs;) {
        double a[4];
        htu_uniforms(&seed, a);
        double zo = 2.0 * a[0] - 1.0, zi = 2.0 * a[2] - 1.0;
        if (fabs(zo) > sin(85.0 * ABRDF__PI / 180.0) || fabs(zi) > sin(85.0 * ABRDF__PI / 180.0))
            continue;
        double wo[3], wi[1][3], s[1][3], sr[1][3];
        htu_table_dir(asin(zo), 2.0 * ABRDF__PI * a[1], wo);
        htu_table_dir(asin(zi), 2.0 * ABRDF__PI * a[3], wi[0]);
        abrdf__huang_table_fibre_run(&x->m, &x->t, 1, (const double(*)[3])wi, wo, 14u, s);
        abrdf__huang_fibre_run(&rm, 1, (const double(*)[3])wi, wo, 14u, sr);
        int far = fabs(zo) > sin(ABRDF__PI / 3.0) || fabs(zi) > sin(ABRDF__PI / 3.0);
        for (int c = 0; c < 3; ++c) {
            num[far] += (s[0][c] - sr[0][c]) * (s[0][c] - sr[0][c]);
            den[far] += sr[0][c] * sr[0][c];
        }
        ++i;
    }
    char part[2][32];
    for (int k = 0; k < 2; ++k) /* a bucket with no pair (or no residual) has no NMSE */
        if (den[k] > 0.0)
            snprintf(part[k], sizeof part[k], "%.1e", num[k] / den[k]);
        else
            snprintf(part[k], sizeof part[k], "none");
    printf(
        "  its residual lobes at %d random direction pairs (theta within 85 degrees) against the "
        "reference's: NMSE %.1e; both theta within 60 degrees %s, the others %s\n",
        pairs, (num[0] + num[1]) / (den[0] + den[1]), part[0], part[1]);
}

/* --table: the tabulated huang's image against the reference, its build and its cost. */
static int table_row(const int dims[4], double r, const grids *ref, int pairs,
                     const double want[HTU_CYL_SAMPLES][3])
{
    tabled x;
    model(r, &x.m);
    if (!abrdf__huang_table_check(&x.m, dims[0], dims[1], dims[2], dims[3])) {
        fprintf(stderr, "hair_convergence: --table %d,%d,%d,%d is out of range (hair.h)\n", dims[0],
                dims[1], dims[2], dims[3]);
        return 0;
    }
    long count = abrdf__huang_table_count(dims[0], dims[1], dims[2]);
    double *v = malloc((size_t)count * sizeof *v);
    if (!v) {
        fprintf(stderr, "hair_convergence: no memory for a table of %ld values\n", count);
        return 0;
    }
    x.t = (abrdf__huang_table){dims[0], dims[1], dims[2], dims[3], v};
    double t0 = seconds();
    abrdf__huang_table_rows(&x.m, &x.t, 0, dims[0] * dims[1], v);
    double build = seconds() - t0;
    static double img[HTU_CYL_SAMPLES][3];
    htu_cylinder_image_lit(eval_table, &x, backlit, img);
    double us_table = image_us(eval_table, &x, 200), us_model = image_us(eval_model, &x.m, 4);
    printf("table (%d, %d, %d), %d shift sets of grids (%d, %d): NMSE vs the reference %.1e; "
           "built in %.1f s (%ld values); %.2f us per evaluation, the quadrature's %.1f (%.0fx)\n",
           dims[0], dims[1], dims[2], dims[3], x.m.n1, x.m.n2, htu_image_nmse(want, img), build,
           count, us_table, us_model, us_model / us_table);
    if (pairs > 0) table_pairs(&x, ref, pairs);
    free(v);
    return 1;
}

int main(int argc, char **argv)
{
    static const grids table[] = {{6, 3, 1},  {6, 3, 2},  {8, 3, 2},  {10, 3, 2}, {8, 4, 2},
                                  {12, 3, 2}, {10, 4, 2}, {12, 4, 2}, {12, 6, 1}, {12, 6, 2}};
    grids ref = {16, 8, 4}, list[64];
    int n = 0, lobes = 0, shifts = 0, parts = 0, pairs = 0, table_dims[4] = {0, 0, 0, 0};
    int ref_sets = 1;
    double r = 0.3; /* hair_brown's, the model's default */
    for (int i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--lobes")) {
            lobes = 1;
        } else if (!strcmp(argv[i], "--pairs")) {
            char *end = NULL;
            long k = i + 1 < argc ? strtol(argv[i + 1], &end, 10) : 0;
            if (i + 1 >= argc || *end || end == argv[i + 1] || k < 1 || k > 1000000) {
                fprintf(stderr, "hair_convergence: --pairs needs a count of direction pairs, "
                                "1-1000000\n");
                return 2;
            }
            pairs = (int)k;
            ++i;
        } else if (!strcmp(argv[i], "--parts")) {
            parts = 1;
        } else if (!strcmp(argv[i], "--backlit")) {
            backlit = 1;
        } else if (!strcmp(argv[i], "--r")) {
            if (i + 1 >= argc) {
                fprintf(stderr, "hair_convergence: --r needs a roughness in [0.05, 1]\n");
                return 2;
            }
            char *end = NULL;
            r = strtod(argv[++i], &end);
            if (*end || end == argv[i] || !(r >= 0.05 && r <= 1.0)) {
                fprintf(stderr, "hair_convergence: --r '%s' is not a roughness in [0.05, 1]\n",
                        argv[i]);
                return 2;
            }
        } else if (!strcmp(argv[i], "--shifts")) {
            if (i + 1 >= argc) {
                fprintf(stderr, "hair_convergence: --shifts needs a count of shift sets, 1-%d\n",
                        ABRDF__HUANG_SHIFT_SETS);
                return 2;
            }
            char *end = NULL;
            long k = strtol(argv[++i], &end, 10);
            if (*end || end == argv[i] || k < 1 || k > ABRDF__HUANG_SHIFT_SETS) {
                fprintf(stderr,
                        "hair_convergence: --shifts '%s' is not a count of shift sets, 1-%d\n",
                        argv[i], ABRDF__HUANG_SHIFT_SETS);
                return 2;
            }
            shifts = (int)k;
        } else if (!strcmp(argv[i], "--reference-sets")) {
            char *end = NULL;
            long k = i + 1 < argc ? strtol(argv[i + 1], &end, 10) : 0;
            if (i + 1 >= argc || *end || end == argv[i + 1] || k < 1 ||
                k > ABRDF__HUANG_SHIFT_SETS) {
                fprintf(stderr,
                        "hair_convergence: --reference-sets needs a count of shift sets, "
                        "1-%d\n",
                        ABRDF__HUANG_SHIFT_SETS);
                return 2;
            }
            ref_sets = (int)k;
            ++i;
        } else if (!strcmp(argv[i], "--table")) {
            char tail;
            if (i + 1 >= argc ||
                sscanf(argv[i + 1], "%d,%d,%d,%d%c", &table_dims[0], &table_dims[1], &table_dims[2],
                       &table_dims[3], &tail) != 4) {
                fprintf(stderr, "hair_convergence: --table needs NT,NV,NP,SETS\n");
                return 2;
            }
            ++i;
        } else if (!strcmp(argv[i], "--reference")) {
            if (i + 1 >= argc) {
                fprintf(stderr, "hair_convergence: --reference needs N1,N2,REFINE\n");
                return 2;
            }
            if (!parse(argv[++i], &ref)) return 2;
        } else if (n == (int)(sizeof list / sizeof list[0])) {
            fprintf(stderr, "hair_convergence: at most %d grids\n", n);
            return 2;
        } else if (!parse(argv[i], &list[n++])) {
            return 2;
        }
    }
    if (n == 0 && !table_dims[0])
        for (n = 0; n < (int)(sizeof table / sizeof table[0]); ++n) list[n] = table[n];
    if ((parts || pairs) && !table_dims[0]) {
        fprintf(stderr, "hair_convergence: --parts and --pairs need --table NT,NV,NP,SETS\n");
        return 2;
    }
    static double want[HTU_CYL_SAMPLES][3], img[HTU_CYL_SAMPLES][3];
    reference(&ref, r, 15u, ref_sets, want);
    static double ref_lobe[4][HTU_CYL_SAMPLES][3];
    for (int l = 0; lobes && l < 4; ++l) reference(&ref, r, 1u << l, ref_sets, ref_lobe[l]);
    printf("reference: grids (%d, %d), Simpson x%d", ref.n1, ref.n2, ref.refine);
    if (ref_sets > 1) printf(", the mean of %d shift sets", ref_sets);
    printf(", r %g%s\n", r, backlit ? ", backlit" : "");
    for (int k = 0; k < n; ++k) {
        image(&list[k], r, 15u, 0, img);
        double work =
            list[k].n1 * list[k].n1 * (1.0 + list[k].n2 * list[k].n2) * list[k].refine /
            (ABRDF__HUANG_N1 * ABRDF__HUANG_N1 * (1.0 + ABRDF__HUANG_N2 * ABRDF__HUANG_N2));
        printf("grids (%d, %d), Simpson x%d: work %.1f, NMSE vs the reference %.1e\n", list[k].n1,
               list[k].n2, list[k].refine, work, htu_image_nmse(want, img));
        if (lobes) by_lobe(&list[k], r, want, ref_lobe);
        if (shifts) by_shifts(&list[k], r, shifts, want);
    }
    if (table_dims[0] && !table_row(table_dims, r, &ref, pairs, want)) return 2;
    if (parts) table_parts(table_dims, r, want);
    return 0;
}
