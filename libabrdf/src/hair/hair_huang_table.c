/* hair_huang_table.c - huang's fibre function tabulated once per material, then read by
 * interpolation (docs/MODELS.md, "A tabulated huang").
 *
 * What costs in huang is the residual, TT + TRT + TRRT+ (hair_huang.c): thousands of VNDF
 * nodes per evaluation, and on an image its quadrature error is spread like noise over the
 * rule's shifts (docs/MODELS.md, "What a converged reference costs"). The residual is a smooth
 * function of four angles, so it is computed here once, on a grid of directions, with the
 * mean of several shift sets at every node (a denser rule than one evaluation can afford), and
 * an evaluation reads it by cubic interpolation. R, cheap and the sharpest lobe, stays the
 * model's own quadrature.
 *
 * The axes. The fibre runs along local +x; a direction w has its longitudinal angle
 * theta = asin(w.x) and its azimuth phi = atan2(w.y, w.z) about the fibre (0 along the
 * cross-section's minor axis, hair_huang.c). The residual depends on the view's theta_v, the
 * light's theta_l, the view's azimuth phi_v and the light's relative azimuth
 * d = phi_l - phi_v. The ellipse is symmetric under y -> -y and z -> -z, which take
 * (phi_v, d) to (-phi_v, -d) and (pi - phi_v, -d): phi_v folds into [0, pi/2].
 *   theta_v, theta_l: nt nodes at the cells' centres, -pi/2 + (k + 1/2) pi / nt;
 *   phi_v:            nv nodes on [0, pi/2], both ends included (nv = 1: a round fibre);
 *   d:                np nodes -pi + k 2 pi / np, periodic.
 * The table holds the residual S times cos(theta_v) (S has 1/cos(theta_v) from the fibre's
 * projected width, hair_huang.c), as v[((((iv nv + jv) nt + il) np + k) 3 + channel], one
 * row (iv, jv) per view node; in the rows at phi_v = 0 and pi/2 (the mirror lines) the mean
 * at d and -d. osl/abrdf_hair.h (abrdf_huang_tabulated) reads the same table as an image.
 * Catmull-Rom (exact at the nodes) along theta_v at fixed theta_v + theta_l, along
 * theta_v + theta_l, and in each azimuth (theta_stencil says why and
 * how the theta ends are read); beyond the end theta nodes the end value repeats; across
 * phi_v's ends the stencil reads the mirrored node with d's sign turned; a negative result
 * (the cubic's overshoot) reads as 0. */
#include <math.h>

#include "hair.h"

static double theta_node(int n, int k) { return -0.5 * ABRDF__PI + (k + 0.5) * ABRDF__PI / n; }
static double phi_v_node(int n, int k) { return n > 1 ? k * 0.5 * ABRDF__PI / (n - 1) : 0.0; }
static double d_node(int n, int k) { return -ABRDF__PI + k * 2.0 * ABRDF__PI / n; }

static void dir_of(double theta, double phi, double w[3])
{
    w[0] = sin(theta);
    w[1] = cos(theta) * sin(phi);
    w[2] = cos(theta) * cos(phi);
}

int abrdf__huang_table_check(const abrdf__huang *m, int nt, int nv, int np, int sets)
{
    if (nt < ABRDF__HUANG_TABLE_NT_MIN || nt > ABRDF__HUANG_TABLE_AXIS_MAX) return 0;
    if (np < ABRDF__HUANG_TABLE_NP_MIN || np > ABRDF__HUANG_TABLE_AXIS_MAX) return 0;
    if (nv < 1 || nv > ABRDF__HUANG_TABLE_AXIS_MAX || (nv == 1 && m->b != 1.0)) return 0;
    /* every index fits a 32-bit long (wasm32, LLP64) */
    if (3.0 * nt * nv * nt * np + ABRDF__HUANG_TABLE_HEADER > ABRDF__HUANG_TABLE_VALUES_MAX)
        return 0;
    return sets >= 1 && sets <= ABRDF__HUANG_TABLE_SETS_MAX;
}

long abrdf__huang_table_count(int nt, int nv, int np) { return 3L * nt * nv * nt * np; }

/* FNV-1a (32 bits) over bytes. */
static unsigned fnv(unsigned h, const void *p, size_t n)
{
    const unsigned char *b = p;
    for (size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 16777619u;
    return h;
}

/* Two 32-bit keys (FNV-1a from two offset bases: 64 bits between two tables) of what the
 * residual depends on: the setup's eta, alpha, tilt, b, sigma_a (each + 0.0, so that -0 is 0),
 * grids, Simpson refinement, compensation and energy tables, and the quadrature's revision
 * (ABRDF__HUANG_REVISION), so that a table kept in a file by an older library, whose
 * quadrature gave other values, is refused. Not the test-only fields. */
static void table_keys(const abrdf__huang *m, double key[2])
{
    const double d[7] = {m->eta + 0.0,        m->alpha + 0.0,      m->tilt + 0.0,      m->b + 0.0,
                         m->sigma_a[0] + 0.0, m->sigma_a[1] + 0.0, m->sigma_a[2] + 0.0};
    const int k[5] = {m->n1, m->n2, m->refine, m->compensate, ABRDF__HUANG_REVISION};
    const unsigned basis[2] = {2166136261u, 3735928559u};
    for (int i = 0; i < 2; ++i) {
        unsigned h = fnv(fnv(basis[i], d, sizeof d), k, sizeof k);
        h = fnv(fnv(h, m->e_in, sizeof m->e_in), m->e_out, sizeof m->e_out);
        key[i] = (double)h;
    }
}

/* The header: a mark, the format, the sizes and the two keys. */
#define TABLE_MARK 1633776744.0 /* "abth" */

void abrdf__huang_table_header(const abrdf__huang *m, const abrdf__huang_table *t, double *h)
{
    double key[2];
    table_keys(m, key);
    const double v[ABRDF__HUANG_TABLE_HEADER] = {TABLE_MARK, 1.0,     t->nt,  t->nv,
                                                 t->np,      t->sets, key[0], key[1]};
    for (int i = 0; i < ABRDF__HUANG_TABLE_HEADER; ++i) h[i] = v[i];
}

int abrdf__huang_table_header_ok(const abrdf__huang *m, const abrdf__huang_table *t,
                                 const double *h)
{
    double want[ABRDF__HUANG_TABLE_HEADER];
    abrdf__huang_table_header(m, t, want);
    for (int i = 0; i < ABRDF__HUANG_TABLE_HEADER; ++i)
        if (!(h[i] == want[i])) return 0;
    return 1;
}

void abrdf__huang_table_rows(const abrdf__huang *m, const abrdf__huang_table *t, int row0, int row1,
                             double *v)
{
    const int nt = t->nt, nv = t->nv, np = t->np;
    const long row_len = 3L * nt * np;
    abrdf__huang ms = *m;
    for (int row = row0; row < row1; ++row) {
        const int iv = row / nv, jv = row % nv;
        const double tv = theta_node(nt, iv), pv = phi_v_node(nv, jv), k = cos(tv) / t->sets;
        double wo[3];
        dir_of(tv, pv, wo);
        double *out = v + (long)row * row_len;
        for (long i = 0; i < row_len; ++i) out[i] = 0.0;
        for (int s = 0; s < t->sets; ++s) {
            ms.shift_set = s;
            /* the row's lights (il, kd), il * np + kd, up to ABRDF__HUANG_WIDE_MAX at once */
            for (int k0 = 0; k0 < nt * np; k0 += ABRDF__HUANG_WIDE_MAX) {
                const int n =
                    nt * np - k0 < ABRDF__HUANG_WIDE_MAX ? nt * np - k0 : ABRDF__HUANG_WIDE_MAX;
                double wi[ABRDF__HUANG_WIDE_MAX][3], sr[ABRDF__HUANG_WIDE_MAX][3];
                for (int j = 0; j < n; ++j)
                    dir_of(theta_node(nt, (k0 + j) / np), pv + d_node(np, (k0 + j) % np), wi[j]);
                abrdf__huang_fibre_wide(&ms, n, (const double(*)[3])wi, wo, 14u, sr);
                for (int j = 0; j < n; ++j)
                    for (int c = 0; c < 3; ++c) out[(k0 + j) * 3 + c] += sr[j][c] * k;
            }
        }
        /* The view azimuths 0 and pi/2 lie on the ellipse's mirror lines: there the model is
         * the same at d and -d, and the read folds across them onto -d (residual), so it is
         * continuous only if these rows are. The shift sets' noise is not symmetric; the mean
         * of the two is the model's symmetry kept (and twice the nodes' samples, but at d = 0
         * and pi, their own mirror images). */
        if (jv == 0 || jv == nv - 1)
            for (int il = 0; il < nt; ++il)
                for (int k = 1; 2 * k < np; ++k) {
                    double *a = out + (il * np + k) * 3, *b = out + (il * np + np - k) * 3;
                    for (int c = 0; c < 3; ++c) a[c] = b[c] = 0.5 * (a[c] + b[c]);
                }
        /* Every lobe's term is >= 0 (TT's exits within ABRDF__HUANG_CRITICAL_TOL below the
         * critical cone gave negative terms until revision 2); the table holds S >= 0 whatever
         * the quadrature gives, so that prepare never refuses a table this build wrote. */
        for (long i = 0; i < row_len; ++i) out[i] = out[i] > 0.0 ? out[i] : 0.0;
    }
}

/* Catmull-Rom weights at t in [0, 1) between the stencil's second and third nodes. */
static void catmull_rom(double t, double w[4])
{
    double t2 = t * t, t3 = t2 * t;
    w[0] = 0.5 * (-t3 + 2.0 * t2 - t);
    w[1] = 0.5 * (3.0 * t3 - 5.0 * t2 + 2.0);
    w[2] = 0.5 * (-3.0 * t3 + 4.0 * t2 + t);
    w[3] = 0.5 * (t3 - t2);
}

static int clamp_node(int j, int n) { return j < 0 ? 0 : j > n - 1 ? n - 1 : j; }

/* A theta's position in node units: node k at k. */
static double theta_x(int n, double theta)
{
    return (theta + 0.5 * ABRDF__PI) * n / ABRDF__PI - 0.5;
}

/* The two theta axes' stencil: up to 32 (view node, light node, weight) triples.
 *
 * Every lobe is a ridge along theta_v + theta_l = const (a specular cone: theta_l near
 * -theta_v, shifted by the cuticle tilt), sharp across it and smooth along it. The view and
 * light nodes have one spacing, so node (iv, il) lies on the sheared grid (iv, j = iv + il),
 * and the table is read by Catmull-Rom along theta_v at fixed theta_v + theta_l (along the
 * ridge) and along j: at (iv, j) it reads the light node j - iv. That stencil reaches two
 * nodes further along theta_l than the axis-aligned one (Catmull-Rom along theta_v and
 * theta_l), so near the theta ends the two are blended: e is the distance, in nodes, to the
 * nearest end node of either axis; e <= 2 reads along the axes alone, e >= 4 along the ridge
 * alone, and between them the weight moves linearly (where 2 < e < 3 the ridge read's share,
 * below a half, still reads held end values). Both reads are exact at the nodes and
 * continuous, and so is the blend. */
static int theta_stencil(int nt, double tv, double tl, int iv[32], int il[32], double w[32])
{
    const double xv = theta_x(nt, tv), xl = theta_x(nt, tl), xj = xv + xl;
    const double fv = floor(xv), fl = floor(xl), fj = floor(xj);
    double wv[4], wl[4], wj[4];
    catmull_rom(xv - fv, wv);
    catmull_rom(xl - fl, wl);
    catmull_rom(xj - fj, wj);
    double e = fmin(fmin(xv, nt - 1 - xv), fmin(xl, nt - 1 - xl)); /* nodes from an end */
    double s = fmin(fmax(0.5 * (e - 2.0), 0.0), 1.0);              /* the sheared read's share */
    int n = 0;
    for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) {
            const int v = (int)fv - 1 + a;
            if (s > 0.0) {
                iv[n] = clamp_node(v, nt), il[n] = clamp_node((int)fj - 1 + b - v, nt);
                w[n++] = s * wv[a] * wj[b];
            }
            if (s < 1.0) {
                iv[n] = clamp_node(v, nt), il[n] = clamp_node((int)fl - 1 + b, nt);
                w[n++] = (1.0 - s) * wv[a] * wl[b];
            }
        }
    return n;
}

/* The residual S of one light wi seen from wo, from the table. */
static void residual(const abrdf__huang_table *t, const double wi[3], const double wo[3],
                     double s[3])
{
    const int nt = t->nt, nv = t->nv, np = t->np;
    s[0] = s[1] = s[2] = 0.0;
    double cv = sqrt(fmax(1.0 - wo[0] * wo[0], 0.0));
    if (!(cv > ABRDF__HAIR_COS_MIN)) return;
    double tv = asin(fmax(-1.0, fmin(1.0, wo[0]))), tl = asin(fmax(-1.0, fmin(1.0, wi[0])));
    double pv = atan2(wo[1], wo[2]);
    double d = remainder(atan2(wi[1], wi[2]) - pv, 2.0 * ABRDF__PI);
    if (pv < 0.0) pv = -pv, d = -d;                        /* y -> -y */
    if (pv > 0.5 * ABRDF__PI) pv = ABRDF__PI - pv, d = -d; /* z -> -z */
    int iv[32], il[32];
    double wt[32], wp[4] = {0.0, 1.0, 0.0, 0.0};
    const int nth = theta_stencil(nt, tv, tl, iv, il, wt);
    int ip = 0;
    if (nv > 1) {
        double x = pv * (nv - 1) / (0.5 * ABRDF__PI), f = floor(x);
        ip = (int)f < nv - 2 ? (int)f : nv - 2;
        catmull_rom(x - ip, wp);
    }
    double acc[3] = {0.0, 0.0, 0.0};
    for (int q = 0; q < 4; ++q) {
        if (wp[q] == 0.0) continue;
        int jv = nv > 1 ? ip - 1 + q : 0;
        double dd = d;
        if (jv < 0) jv = -jv, dd = -dd;                    /* across phi_v = 0 */
        if (jv > nv - 1) jv = 2 * (nv - 1) - jv, dd = -dd; /* across phi_v = pi/2 */
        double x = (dd + ABRDF__PI) * np / (2.0 * ABRDF__PI), f = floor(x);
        double wd[4];
        catmull_rom(x - f, wd);
        int kd[4];
        for (int k = 0; k < 4; ++k) kd[k] = (((int)f - 1 + k) % np + np) % np;
        for (int a = 0; a < nth; ++a) {
            const double *row = t->v + (((long)iv[a] * nv + jv) * nt + il[a]) * np * 3;
            double w = wp[q] * wt[a];
            for (int k = 0; k < 4; ++k) {
                const double *x3 = row + kd[k] * 3;
                double ww = w * wd[k];
                acc[0] += ww * x3[0], acc[1] += ww * x3[1], acc[2] += ww * x3[2];
            }
        }
    }
    for (int c = 0; c < 3; ++c) s[c] = acc[c] > 0.0 ? acc[c] / cv : 0.0;
}

/* Where the model's S is 0 whatever the quadrature (abrdf__huang_fibre_run): the view along
 * the fibre, or a mesonormal the cuticle tilt (its tangent tan_tilt) hides from the view or
 * the light. */
static int view_lit(double tan_tilt, const double wo[3])
{
    double c = sqrt(wo[1] * wo[1] + wo[2] * wo[2]);
    return c > ABRDF__HAIR_COS_MIN && !(-tan_tilt * wo[0] / c > 1.0);
}
static int light_lit(double tan_tilt, const double wi[3])
{
    double c = sqrt(wi[1] * wi[1] + wi[2] * wi[2]);
    return c > 0.0 && !(tan_tilt * wi[0] / c < -1.0);
}

void abrdf__huang_table_fibre_run(const abrdf__huang *m, const abrdf__huang_table *t, int count,
                                  const double (*wi)[3], const double wo[3], unsigned lobes,
                                  double (*s)[3])
{
    for (int l = 0; l < count; ++l) s[l][0] = s[l][1] = s[l][2] = 0.0;
    const double tan_tilt = tan(m->tilt); /* once per view, not per light */
    if (count < 1 || count > ABRDF__HUANG_RUN_MAX || !view_lit(tan_tilt, wo)) return;
    if (lobes & 1u) abrdf__huang_fibre_run(m, count, wi, wo, 1u, s);
    if (!(lobes & 14u)) return;
    for (int l = 0; l < count; ++l) {
        if (!light_lit(tan_tilt, wi[l])) continue;
        double r[3];
        residual(t, wi[l], wo, r);
        for (int c = 0; c < 3; ++c) s[l][c] += r[c];
    }
}
