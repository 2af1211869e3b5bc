/* hair_huang.c - Huang, Hullin, Hanika microfacet-based hair, far field (paper Eqs. 12-14).
 *
 * W. Huang, M. B. Hullin, J. Hanika, "A microfacet-based hair scattering model", Computer
 * Graphics Forum 41(4) (EGSR 2022). The fibre is an elliptical cylinder (minor/major axis
 * ratio b) whose surface is a GGX microfacet surface (alpha = r, not squared) with scales
 * tilted by the cuticle angle. Far field: the scattered light is averaged over the
 * fibre's projected width h.
 *   R   = F(wi.wh) / 4 * integral D(wm.wh) G2(wm.wi, wm.wo) arc(gamma) S_E dgamma (Eq. 12)
 *   TT  = integral over gamma and the entry microfacet wh1 of T1 A_t T2 D2 G ... with the
 *         generalised half vector wh2 ~ -wt + wo/eta at the exit                    (Eq. 13)
 *   TRT = the same with an internal reflection at wh2 and the exit half vector
 *         wh3 ~ wtr + wo/eta                                                        (Eq. 14)
 *   plus TRRT+ as a geometric series times Chiang's longitudinal M(v = 4 alpha) / (2 pi),
 *   S = (R + (TT + TRT)/eta^2 + TRRT+) / (2 cos(theta_view) radius).
 * The structure, frame and h-interval logic follow Blender Cycles
 * src/kernel/closure/bsdf_principled_hair_huang.h (MODELS.md B7.3), in double.
 *
 * What differs from Cycles (docs/MODELS.md, "Where abrdf differs from Cycles", has the
 * measurements):
 *  - DETERMINISTIC integration. Cycles draws one GGX visible-normal (VNDF) sample per h node
 *    for the entry microfacet and one for the internal reflection. Here the VNDF sampling
 *    map is integrated on its unit square by an n1 x n1 (entry) and n2 x n2 (internal
 *    reflection) grid of cells, each grid shifted by its own point of the R2 sequence
 *    (grid_shift): the expectation Cycles estimates, computed by quadrature.
 *  - Composite Simpson over the surface parameter gamma instead of h (Cycles' steps,
 *    <= 0.7 alpha for R and <= 0.8 alpha for the rest, divided by a refinement factor):
 *    dgamma/dh is singular at the silhouette and Simpson in h over-weights it.
 *  - TRRT+ is weighted by the projected width |dh/dgamma| cos(theta_view) of each element
 *    instead of Cycles' constant 2/pi, which lets it grow as 1/cos(theta_view).
 *  - The energy compensation S_E = 1/E(sqrt(alpha), mu, eta) reads tables this project
 *    generates by quadrature (tools/gen/gen_hair_tables.c -> hair_tables.c), not Cycles'
 *    Monte Carlo tables.
 *  - Continuous in the directions: R's range is cut where the mesonormal stops facing wo and
 *    where D's argument changes sign (Cycles tests each node), nothing the range guarantees
 *    is re-tested per node, and the Simpson count does not follow the range's length.
 *  - No near field: the whole visible projected width is integrated.
 *  - The cross-section's major axis is the local +y (along the ribbon, B), the minor axis
 *    +z (N); Cycles' local frame (X major axis, Y tangent, Z) is (w.y, w.x, w.z) here.
 *  - cuticle_tilt is Blender's "offset" (degrees); the model's tilt is its negative.
 * For the tests only, cycles_nodes (hair.h) switches to Cycles' quadrature, so that a Cycles
 * render can be checked against the same integrand (docs/MODELS.md, "Cycles as an oracle"). */
#include <float.h>
#include <math.h>

#include "hair.h"
#include "isa.h"

/* The larger of x and a floor, the smaller of x and a ceiling; a NaN x gives the bound (as
 * fmax/fmin do, which are library calls on x86-64 without -ffinite-math-only). */
static double max_of(double x, double floor_) { return x > floor_ ? x : floor_; }

typedef struct v3 {
    double x, y, z;
} v3;

static v3 mk(double x, double y, double z)
{
    v3 r = {x, y, z};
    return r;
}
static v3 add(v3 a, v3 b) { return mk(a.x + b.x, a.y + b.y, a.z + b.z); }
static v3 scl(v3 a, double s) { return mk(a.x * s, a.y * s, a.z * s); }
static v3 neg(v3 a) { return mk(-a.x, -a.y, -a.z); }
static double dot(v3 a, v3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static double len(v3 a) { return sqrt(dot(a, a)); }
static v3 cross(v3 a, v3 b)
{
    return mk(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}

/* ---- fibre coordinates (Cycles' local frame: y along the fibre) --------------------- */
static double sin_theta(v3 w) { return w.y; }
static double cos_theta(v3 w) { return sqrt(w.x * w.x + w.z * w.z); }
static double dir_phi(v3 w) { return atan2(w.x, w.z); }

/* Azimuth on the ellipse x = sin(gamma), z = b cos(gamma) <-> direction of its normal. */
static double to_gamma(double phi, double b) { return atan2(sin(phi), b * cos(phi)); }

/* Offset h (in units of the projected radius) of the ray from wi through the surface point
 * whose normal has azimuth phi: h = -cos(phi_i) sin(gamma) + b sin(phi_i) cos(gamma). */
static double phi_to_h(double phi, double b, double sp_i, double cp_i)
{
    double g = to_gamma(phi, b);
    return -cp_i * sin(g) + b * sp_i * cos(g);
}

/* Inverse of the above for h pre-divided by the projected radius. */
static double h_to_gamma(double h_div_r, double b, v3 wi)
{
    return atan2(wi.z, -b * wi.x) - acos(abrdf__clamp(-h_div_r, -1.0, 1.0));
}

/* An angle by its sine and cosine: the paths through the fibre turn by angles whose sine
 * and cosine are algebra in the directions, so they need no trigonometric calls. */
typedef struct sc {
    double s, c;
} sc;

static sc sc_of(double a)
{
    sc r = {sin(a), cos(a)};
    return r;
}

/* Two pieces of the fibre's geometry that the vector loops (entry_base, internal_exit) write
 * out without a branch, by sines and cosines:
 *   to_phi(w)        to_phi(dir_phi(w), b) = atan2(b w.x, w.z), the ellipse parameter of the
 *                    normal that faces w's azimuth: (b w.x, w.z) over its length, (0, 1) for
 *                    a direction along the fibre (as atan2(0, 0));
 *   twice_minus(a, g)  2a - g, where a path that leaves the surface point g at the normal
 *                    azimuth a meets it again (the chord's other end): the double angle of a
 *                    turned back by g.
 * The point at gamma is (sin gamma, 0, b cos gamma). */

/* Unit (meso)normal at ellipse parameter gamma, tilted by theta along the fibre (st = sin
 * theta, ct = cos theta), and, if flat is not NULL, the untilted one: both from one sine and
 * cosine of gamma. The point at gamma is (sin gamma, b cos gamma), its tangent (cos gamma,
 * -b sin gamma), so the normal is (b sin gamma, cos gamma) over the tangent's length
 * sqrt(cos^2 + b^2 sin^2) = sqrt(1 - (1 - b^2) sin^2 gamma), which is also the relative arc
 * length there: returned, as the integrals weigh each node by it. */
static double sphg_pair(double st, double ct, sc gamma, double b, v3 *tilted, v3 *flat)
{
    double sp = gamma.s, cp = gamma.c, arc = 1.0;
    if (b != 1.0) {
        sp *= b;
        arc = sqrt(sp * sp + cp * cp); /* >= b >= 0.01 (the registry's bound) */
        double inv = 1.0 / arc;
        sp *= inv, cp *= inv;
    }
    *tilted = mk(sp * ct, st, cp * ct);
    if (flat) *flat = mk(sp, 0.0, cp);
    return arc;
}

/* ---- GGX pieces (alpha2 = alpha^2), height-correlated Smith ----------------------- */
/* GGX D from the squared cosine, for a normal known to face the half vector. */
static double ggx_d_sq(double alpha2, double c2)
{
    double k = 1.0 + (alpha2 - 1.0) * c2;
    return alpha2 / (ABRDF__PI * k * k);
}

/* Without a branch: entry_base's vector loop inlines it. */
static inline double ggx_lambda(double alpha2, double c)
{
    double c2 = c * c, l = 0.5 * (sqrt(1.0 + alpha2 * (1.0 - c2) / c2) - 1.0);
    return c2 > 0.0 ? l : ABRDF__HUANG_LAMBDA_GRAZING; /* grazing: fully shadowed */
}

static double ggx_g(double alpha2, double ci, double co)
{
    return 1.0 / (1.0 + ggx_lambda(alpha2, ci) + ggx_lambda(alpha2, co));
}

/* G2 / G1(in), the masking of the outgoing side given the incoming side is visible, is
 * (1 + Lambda_in) / (1 + Lambda_in + Lambda_out); the entry keeps Lambda_in of its mesonormal
 * (ring_node.lam1), the exits keep c and s = sqrt(c^2 + alpha^2 (1 - c^2)) of theirs
 * (Lambda = (s/c - 1)/2: entry_path.c2, s2; internal_nodes.c3, s3), so it is written out
 * where it is used (entry_base, internal_exit, exit_factor). */

/* Heitz 2018, "Sampling the GGX distribution of visible normals": maps (u1, u2) in the unit
 * square to a microfacet normal distributed as the VNDF of direction wi about normal wm.
 * Used here as a change of variables for deterministic quadrature, not for sampling. */
/* What the map of one (wi, wm) pair shares between its nodes: the basis around wm and the
 * stretched view direction. A quadrature over many nodes of one pair builds it once. */
typedef struct vndf_frame {
    double alpha;
    v3 wm;         /* the mean normal */
    v3 vh, t1, t2; /* stretched wi and the basis around it, in the basis s, t, wm */
    v3 q1, q2, q3; /* alpha (s t1.x + t t1.y), the same for t2 and vh: the map's */
    double sh;     /* 0.5 (1 + vh.z)                             linear part */
} vndf_frame;

static void vndf_frame_make(double alpha, v3 wi, v3 wm, vndf_frame *f);
static v3 vndf_frame_node(const vndf_frame *f, const double p[3]);

/* The disc point of node (u1, u2), r = sqrt(u1) at angle 2 pi u2, and sqrt(1 - p1^2): what
 * vndf_frame_node takes (the quadrature's grids make theirs in grid_points). */
static void vndf_disc(double u1, double u2, double p[3])
{
    double r = sqrt(u1), ph = 2.0 * ABRDF__PI * u2;
    p[0] = r * cos(ph);
    p[1] = r * sin(ph);
    p[2] = abrdf__safe_sqrt(1.0 - p[0] * p[0]);
}

static v3 vndf_map(double alpha, v3 wi, v3 wm, double u1, double u2)
{
    double p[3];
    vndf_frame f;
    vndf_disc(u1, u2, p);
    vndf_frame_make(alpha, wi, wm, &f);
    return vndf_frame_node(&f, p);
}

/* THE VNDF GRIDS, SHIFTED. Each VNDF square is integrated on an n x n grid of cells, node
 * j at ((j / n + 1/2 + d1) / n, (j % n + 1/2 + d2) / n), and every grid of an evaluation is
 * shifted by its own (d1, d2): the entry grid of Simpson node i by shift i, the internal
 * grid of the path through entry node j1 there by shift i n1^2 + j1. The integrand is cut by
 * total internal reflection and visibility, and TRT's exit is a narrow peak in the square;
 * on one unshifted grid the nodes of neighbouring paths fall on the same side of a cut or of
 * the peak and their errors add up (the default's image was 1.8e-2 from the converged one),
 * on shifted grids they average out (6.8e-5 with the same nodes, and 2.3e-4 on average over
 * rotations of the shifts: docs/MODELS.md, "Convergence on an image" and "What a converged
 * reference costs"). Shift k is the k-th point of the R2 sequence (M. Roberts 2018:
 * k (1/g, 1/g^2) modulo 1, g the plastic number) minus 1/2, with the steps in 16-bit fixed
 * point (hair.h: the first one's period) and k taken modulo 2^15 so that the OSL and POV-Ray
 * twins compute the same shifts exactly (32-bit integers, doubles). */
static void grid_shift(long k, long set, double d[2])
{
    /* the set's offset after the model's wrap: every shift of the evaluation turns by the
     * same vector (hair.h, shift_set) */
    unsigned long kk = (unsigned long)(k % 32768) + (unsigned long)set;
    d[0] = (double)((32768ul + kk * ABRDF__HUANG_R2_A1) % 65536ul) / 65536.0 - 0.5;
    d[1] = (double)((32768ul + kk * ABRDF__HUANG_R2_A2) % 65536ul) / 65536.0 - 0.5;
}

/* The angles of an n x n grid's columns, 2 pi (b + 1/2) / n, as cosines and sines: a shift
 * turns them all by 2 pi d2 / n (grid_points). */
typedef struct grid_angles {
    int n;
    double c[ABRDF__HUANG_GRID_MAX], s[ABRDF__HUANG_GRID_MAX];
} grid_angles;

static void grid_angles_make(int n, grid_angles *a)
{
    a->n = n;
    for (int b = 0; b < n; ++b) {
        double ph = 2.0 * ABRDF__PI * (b + 0.5) / n;
        a->c[b] = cos(ph), a->s[b] = sin(ph);
    }
}

/* The disc points (vndf_disc) of the grid with shift k (of the shift set whose offset is set:
 * 0 in the model): point j in p0[j], p1[j], p2[j] (p2:
 * sqrt(1 - p0^2), not written if NULL: the internal grids' loop takes it itself). The angle of
 * a column is its unshifted one turned by 2 pi d2 / n: one sine and cosine per grid, the same
 * values as vndf_disc's up to rounding. */
static void grid_points(const grid_angles *a, long k, long set, double *p0, double *p1, double *p2)
{
    const int n = a->n;
    double d[2];
    grid_shift(k, set, d);
    double dph = 2.0 * ABRDF__PI * d[1] / n, cd = cos(dph), sd = sin(dph);
    for (int i = 0; i < n; ++i) {
        double r = sqrt((i + 0.5 + d[0]) / n);
        for (int b = 0; b < n; ++b) {
            int j = i * n + b;
            p0[j] = r * (a->c[b] * cd - a->s[b] * sd);
            p1[j] = r * (a->s[b] * cd + a->c[b] * sd);
            if (p2) p2[j] = abrdf__safe_sqrt(1.0 - p0[j] * p0[j]);
        }
    }
}

/* An evaluation's disc points and column angles, in one block whose layout is fixed. Each
 * row of points is 8 KiB (ABRDF__HUANG_NODES_MAX doubles), so every row starts at the same
 * address modulo 4 KiB; the angles lie 2 KiB past it, beyond the points of any grid up to
 * 16 x 16. grid_points reads the angles while it stores points: an angle 4 KiB (or a
 * multiple) from a point stored just before waits for that store (the processor compares
 * the addresses' low 12 bits first), which made huang's per-call evaluation 25 % slower
 * on the mixed scene's lock when another change moved the angles to such a place. */
typedef struct grid_block {
    double p1s[3][ABRDF__HUANG_NODES_MAX], p2s[2][ABRDF__HUANG_NODES_MAX];
    char gap[2048];
    grid_angles ang1, ang2;
} grid_block;
typedef char grid_rows_are_4k[(ABRDF__HUANG_NODES_MAX * sizeof(double)) % 4096 == 0 ? 1 : -1];

static void vndf_frame_make(double alpha, v3 wi, v3 wm, vndf_frame *f)
{
    /* orthonormal basis s, t around wm (Duff et al. 2017). It flips where wm.z changes
     * sign, but the map does not depend on it: t1, t2 below are built from wi's projection,
     * so the nodes are the same in any basis (checked: identical S to 12 digits). */
    double sg = wm.z >= 0.0 ? 1.0 : -1.0;
    double a = -1.0 / (sg + wm.z), bb = wm.x * wm.y * a;
    v3 s = mk(1.0 + sg * wm.x * wm.x * a, sg * bb, -sg * wm.x);
    v3 t = mk(bb, sg + wm.y * wm.y * a, -wm.y);
    v3 l = mk(dot(wi, s), dot(wi, t), dot(wi, wm));
    v3 vh = mk(alpha * l.x, alpha * l.y, l.z);
    vh = scl(vh, 1.0 / len(vh));
    double lensq = vh.x * vh.x + vh.y * vh.y;
    v3 t1 = lensq > 0.0 ? scl(mk(-vh.y, vh.x, 0.0), 1.0 / sqrt(lensq)) : mk(1, 0, 0);
    f->alpha = alpha;
    f->wm = wm;
    f->vh = vh, f->t1 = t1, f->t2 = cross(vh, t1);
    f->sh = 0.5 * (1.0 + vh.z);
    /* the normal in the basis, (alpha nh.x, alpha nh.y, nh.z), then to the world: the x and y
     * parts are linear in the node's p1, p2, p3 */
    v3 as = scl(s, alpha), at = scl(t, alpha);
    f->q1 = add(scl(as, f->t1.x), scl(at, f->t1.y));
    f->q2 = add(scl(as, f->t2.x), scl(at, f->t2.y));
    f->q3 = add(scl(as, vh.x), scl(at, vh.y));
}

/* The microfacet normal h of the disc point (p1, p2') (vndf_disc: p2' = (1 - sh) sqrt(1 -
 * p1^2) + sh p2, the warp onto the projected hemisphere of the stretched view vh), Heitz's map:
 * lifted, unstretched. Without a branch: the vector loops (entry_base, internal_base) inline
 * it. */
static inline void vndf_lift(const vndf_frame *f, double p1, double p2, double *hx, double *hy,
                             double *hz)
{
    const double al = f->alpha;
    double d = 1.0 - p1 * p1 - p2 * p2, p3 = d > 0.0 ? sqrt(d) : 0.0;
    double nx = f->t1.x * p1 + f->t2.x * p2 + f->vh.x * p3;
    double ny = f->t1.y * p1 + f->t2.y * p2 + f->vh.y * p3;
    double nz = f->t2.z * p2 + f->vh.z * p3; /* t1.z = 0 */
    nz = nz > 0.0 ? nz : 0.0;
    double inv = 1.0 / sqrt(al * al * (nx * nx + ny * ny) + nz * nz);
    *hx = (f->q1.x * p1 + f->q2.x * p2 + f->q3.x * p3 + f->wm.x * nz) * inv;
    *hy = (f->q1.y * p1 + f->q2.y * p2 + f->q3.y * p3 + f->wm.y * nz) * inv;
    *hz = (f->q1.z * p1 + f->q2.z * p2 + f->q3.z * p3 + f->wm.z * nz) * inv;
}

/* The microfacet normal of the disc point p (vndf_disc). */
static v3 vndf_frame_node(const vndf_frame *f, const double p[3])
{
    v3 h;
    vndf_lift(f, p[0], (1.0 - f->sh) * p[2] + f->sh * p[1], &h.x, &h.y, &h.z);
    return h;
}

/* Fresnel for unpolarised light at cosine c (sign ignored) and relative index eta; the
 * cosine of the refracted ray (negative: on the other side) through cos_t. */
static double fresnel(double c, double eta, double *cos_t)
{
    c = fabs(c);
    double q = eta * eta - (1.0 - c * c);
    if (q <= 0.0) {
        if (cos_t) *cos_t = 0.0;
        return 1.0;
    }
    if (cos_t) *cos_t = -sqrt(q) / eta;
    return abrdf__fresnel_dielectric(eta, c);
}

static v3 refract_dir(v3 wi, v3 n, double cos_t, double inv_eta)
{
    return add(scl(n, inv_eta * dot(n, wi) + cos_t), scl(wi, -inv_eta));
}

static v3 reflect_dir(v3 i, v3 n) { return add(i, scl(n, -2.0 * dot(i, n))); }

static int visible1(v3 v, v3 m, v3 h) { return dot(v, h) > 0.0 && dot(v, m) > 0.0; }
static int visible2(v3 a, v3 b, v3 m, v3 h) { return visible1(a, m, h) && visible1(b, m, h); }

/* ---- Chiang et al. 2016 longitudinal function, for TRRT+ ------------------------------ */
static double bessel_i0(double x)
{
    double x2 = 0.25 * x * x, term = 1.0, sum = 1.0;
    for (int k = 1; k < ABRDF__HUANG_I0_TERMS && term > ABRDF__HUANG_I0_REL_TOL * sum; ++k) {
        term *= x2 / ((double)k * k);
        sum += term;
    }
    return sum;
}

static double log_bessel_i0(double x)
{
    if (x > ABRDF__HUANG_I0_ASYMPTOTIC) /* asymptotic expansion */
        return x + 0.5 * (1.0 / (8.0 * x) - log(2.0 * ABRDF__PI) - log(x));
    return log(bessel_i0(x));
}

static double longitudinal_m(double si, double ci, double so, double co, double v)
{
    double a = ci * co / v, bsin = si * so / v;
    if (v <= ABRDF__HUANG_M_LOG_V)
        return exp(log_bessel_i0(a) - bsin - 1.0 / v + log(2.0) + log(0.5 / v));
    return exp(-bsin) * bessel_i0(a) / (sinh(1.0 / v) * 2.0 * v);
}

/* ---- energy compensation (Cycles' ggx_glass_E tables, regenerated) ------------------ */

/* Single-scattering albedo (reflection + transmission) of a rough GGX dielectric interface
 * of relative index eta, lit at cosine mu: the VNDF expectation of
 * F G2(i, o_r)/G1(i) + (1 - F) G2(i, o_t)/G1(i), by an n x n midpoint rule on the VNDF
 * square (tools/gen/gen_hair_tables.c tabulates it; hair_tables.c). */
double abrdf__ggx_glass_albedo(double alpha, double mu, double eta, int n)
{
    v3 wi = mk(abrdf__safe_sqrt(1.0 - mu * mu), 0.0, mu), nz = mk(0, 0, 1);
    double a2 = alpha * alpha, li = ggx_lambda(a2, mu), sum = 0.0;
    for (int j = 0; j < n * n; ++j) {
        v3 h = vndf_map(alpha, wi, nz, (j / n + 0.5) / n, (j % n + 0.5) / n);
        double c = dot(wi, h);
        if (!(c > 0.0)) continue;
        double cos_t;
        double f = fresnel(c, eta, &cos_t);
        v3 o_r = reflect_dir(neg(wi), h);
        if (o_r.z > 0.0) sum += f * (1.0 + li) / (1.0 + li + ggx_lambda(a2, o_r.z));
        if (f < 1.0) {
            v3 o_t = refract_dir(wi, h, cos_t, 1.0 / eta);
            if (o_t.z < 0.0) sum += (1.0 - f) * (1.0 + li) / (1.0 + li + ggx_lambda(a2, o_t.z));
        }
    }
    return sum / (n * n);
}

/* Trilinear lookup with Cycles' conventions (lookup_table_read_3D): the table's grid
 * nodes sit at x, y, z = k/(N - 1), coordinates are clamped to [0, 1]. */
static double table_read(const double *t, double x, double y, double z)
{
    const int n = ABRDF__HAIR_E_N;
    double c[3] = {x, y, z};
    int i0[3], i1[3];
    double f[3];
    for (int k = 0; k < 3; ++k) {
        double u = abrdf__clamp(c[k], 0.0, 1.0) * (n - 1);
        i0[k] = (int)u < n - 1 ? (int)u : n - 1;
        i1[k] = i0[k] + 1 < n ? i0[k] + 1 : n - 1;
        f[k] = u - i0[k];
    }
    double v = 0.0;
    for (int k = 0; k < 8; ++k) {
        int ix = k & 1 ? i1[0] : i0[0], iy = k & 2 ? i1[1] : i0[1], iz = k & 4 ? i1[2] : i0[2];
        double w =
            (k & 1 ? f[0] : 1 - f[0]) * (k & 2 ? f[1] : 1 - f[1]) * (k & 4 ? f[2] : 1 - f[2]);
        v += w * t[(iz * n + iy) * n + ix];
    }
    return v;
}

/* 1/E: the factor that lifts a single microfacet interaction to the energy of all its
 * bounces (Cycles' bsdf_hair_huang_energy_scale); 1 when compensation is off. The table's x
 * and z axes depend only on alpha and eta, so abrdf__huang_tables collapses it once per
 * material to a 1-D table in mu, node k at k/(N - 1) (the same bilinear weights in x and z
 * as table_read's, so the same values up to rounding); energy_scale_at interpolates it. */
static void energy_collapse(const double *t, double alpha, double eta, double out[])
{
    const int n = ABRDF__HAIR_E_N;
    double x = sqrt(alpha), z = sqrt(fabs((eta - 1.0) / (eta + 1.0)));
    for (int k = 0; k < n; ++k) out[k] = table_read(t, x, (double)k / (n - 1), z);
}

void abrdf__huang_tables(abrdf__huang *m)
{
    double inv = 1.0 / m->eta;
    energy_collapse(m->eta < 1.0 ? abrdf__hair_glass_inv_e : abrdf__hair_glass_e, m->alpha, m->eta,
                    m->e_in);
    energy_collapse(inv < 1.0 ? abrdf__hair_glass_inv_e : abrdf__hair_glass_e, m->alpha, inv,
                    m->e_out);
}

typedef const double *energy_axes; /* the collapsed table: m->e_in or m->e_out */

/* E at cosine mu from a collapsed table t, floored at ABRDF__HAIR_E_MIN; mu clamped to
 * [0, 1] (NaN to 0). Without a branch: the vector loops (entry_base, internal_exit) inline
 * it. */
static inline double energy_e(const double *t, double mu)
{
    const int n = ABRDF__HAIR_E_N;
    double u = abrdf__clamp(mu, 0.0, 1.0) * (n - 1);
    int i0 = (int)u < n - 1 ? (int)u : n - 1, i1 = i0 + 1 < n ? i0 + 1 : n - 1;
    double f = u - i0, e = (1.0 - f) * t[i0] + f * t[i1];
    return e > ABRDF__HAIR_E_MIN ? e : ABRDF__HAIR_E_MIN;
}

static double energy_scale_at(const abrdf__huang *m, const energy_axes *a, double mu)
{
    return m->compensate ? 1.0 / energy_e(*a, mu) : 1.0;
}

/* ---- the model ------------------------------------------------------------------------ */
void abrdf__huang_setup(const abrdf_params *p, abrdf__huang *m)
{
    m->eta = p->eta;
    m->alpha = abrdf__clamp(p->r, ABRDF__HUANG_ALPHA_MIN, 1.0);
    m->tilt = -p->cuticle_tilt * ABRDF__HAIR_DEG;
    m->b = fmin(p->aspect_ratio, 1.0);
    abrdf__hair_sigma_a(p->melanin, p->redness, m->sigma_a);
    m->refine = 1;
    m->n1 = p->entry_grid;
    m->n2 = p->internal_grid;
    m->compensate = 1;
    m->cycles_nodes = 0;
    m->shift_set = 0;
    m->table = (abrdf__huang_table){0, 0, 0, 0, NULL};
    abrdf__huang_tables(m);
}

/* Simpson intervals (an even count) for a range of gamma with step at most res/refine.
 * The count is that of the LARGEST range, pi (the visible half of the section), not of the
 * actual one: a count that follows the range changes by 2 where the range crosses a
 * multiple of the step, and S would jump there by the quadrature error. */
static int simpson_intervals(double res, int refine)
{
    return 2 * (int)ceil(ABRDF__PI / res * 0.5) * refine;
}

/* Composite Simpson of Eq. 12's integrand over [lo, hi] with the fixed count n. wm.wh >= 0
 * holds there up to rounding, and the end nodes have wm.wh = 0 (D = alpha^2/pi, not 0):
 * hence D from the square. */
static double simpson_r(const abrdf__huang *m, v3 wi, v3 wo, v3 wh, double lo, double hi, int n)
{
    double b = m->b, a2 = m->alpha * m->alpha;
    double res = (hi - lo) / n, sum = 0.0;
    energy_axes ax = m->e_in;
    const double st = sin(m->tilt), ct = cos(m->tilt);
    for (int i = 0; i <= n; ++i) {
        double gm = lo + i * res;
        v3 wm;
        sc g = sc_of(gm);
        double arc = sphg_pair(st, ct, g, b, &wm, NULL);
        double w = (i == 0 || i == n) ? 0.5 : (i % 2 + 1);
        double c = dot(wm, wh);
        sum += w * ggx_d_sq(a2, c * c) * ggx_g(a2, dot(wm, wi), dot(wm, wo)) * arc *
               energy_scale_at(m, &ax, dot(wm, wi));
    }
    return sum * 2.0 / 3.0 * res;
}

/* Eq. 12 over [g0, g0 + gr], the gamma range whose mesonormals face the viewer wi. The
 * integrand is cut where the projected mesonormal stops facing wo and where D's argument
 * wm.wh changes sign (GGX D does not vanish at 90 deg). Both cuts are made on the RANGE,
 * not node by node: with a node on a cut (in a coplanar configuration the cuts fall on the
 * end nodes), a 1e-16 rounding of wi or wo decided whether it counted, and S jumped by up
 * to 4%; with the cuts between nodes, S jumped wherever one crossed a node. */
static double lobe_r(const abrdf__huang *m, v3 wi, v3 wo, double g0, double gr)
{
    const double pi = ABRDF__PI, b = m->b;
    v3 wh = add(wi, wo);
    double l = len(wh);
    if (!(l > 0.0)) return 0.0;
    wh = scl(wh, 1.0 / l);
    /* The projected mesonormal at gamma is along (b sin gamma, 0, cos gamma): it faces a
     * direction w for gamma within pi/2 of atan2(b w.x, w.z). h_to_gamma centres the viewer's
     * range on gc; the branch of wo's centre nearest to it gives the single overlap. */
    double gc = atan2(wi.z, -b * wi.x) - 0.5 * pi;
    double go = gc + abrdf__wrap_pi(atan2(b * wo.x, wo.z) - gc);
    double lo = fmax(g0, go - 0.5 * pi), hi = fmin(g0 + gr, go + 0.5 * pi);
    if (!(hi > lo)) return 0.0;
    /* wm.wh = cos(tilt) |wh_xz| cos(phi - phi_h) + sin(tilt) wh.y, phi the normal's azimuth:
     * >= 0 on the arc |phi - phi_h| <= a, a = acos(c0), mapped to gamma by to_gamma
     * (monotone, phi + pi -> gamma + pi). */
    double hxz = sqrt(wh.x * wh.x + wh.z * wh.z), ct = cos(m->tilt), st = sin(m->tilt);
    double num = -st * wh.y, den = ct * hxz;
    double arc_lo = lo - 1.0, arc_hi = hi + 1.0; /* default: the arc covers the range */
    if (num >= den) return 0.0;                  /* wm.wh <= 0 everywhere */
    if (num > -den) {
        double ph = atan2(wh.x, wh.z), a = acos(num / den), gh = to_gamma(ph, b);
        double d1 = abrdf__wrap_pi(gh - to_gamma(ph - a, b));
        double d2 = abrdf__wrap_pi(to_gamma(ph + a, b) - gh);
        /* each half-arc maps into (0, pi); a negative wrap is rounding (or, past pi/2, the
         * other side of pi) */
        if (d1 < 0.0) d1 = a > 0.5 * pi ? d1 + 2.0 * pi : 0.0;
        if (d2 < 0.0) d2 = a > 0.5 * pi ? d2 + 2.0 * pi : 0.0;
        arc_lo = gh - d1;
        arc_hi = gh + d2;
        double k = floor((lo - arc_hi) / (2.0 * pi)); /* first shift reaching the range */
        arc_lo += 2.0 * pi * k;
        arc_hi += 2.0 * pi * k;
    }
    int n = simpson_intervals(0.7 * m->alpha, m->refine);
    double sum = 0.0;
    /* the range (<= pi) meets at most two shifted copies of the arc (its gap is > 0) */
    for (int k = 0; k < 3 && arc_lo <= hi; ++k) {
        double p0 = fmax(lo, arc_lo), p1 = fmin(hi, arc_hi);
        if (p1 > p0) sum += simpson_r(m, wi, wo, wh, p0, p1, n);
        arc_lo += 2.0 * pi;
        arc_hi += 2.0 * pi;
    }
    return 0.25 * fresnel(dot(wi, wh), m->eta, NULL) * sum; /* Eq. 12 */
}

/* dgamma/dh at gamma for the viewer's azimuth (sp_i, cp_i), h in units of the projected
 * radius (as the nodes are): the radius over the projected width per unit gamma. Cycles'
 * quadrature weights its h nodes by it (cycles_nodes). */
static double dgamma_dh(sc g, double b, double sp_i, double cp_i)
{
    double radius = sqrt(fmax(ABRDF__HUANG_RADIUS2_MIN, 1.0 - (1.0 - b * b) * sp_i * sp_i));
    return radius / fabs(cp_i * g.c + b * sp_i * g.s);
}

/* Eq. 12 in Cycles' quadrature (cycles_nodes, tests only): Simpson over h in [h0, h1] (units
 * of the projected radius) with steps <= 0.7 alpha / refine, each node weighted by dgamma/dh
 * and counted when wi and wo see the half vector and the untilted normal; D from the squared
 * cosine, as Cycles. */
static double lobe_r_cycles(const abrdf__huang *m, v3 wi, v3 wo, double h0, double h1, double sp_i,
                            double cp_i)
{
    const double b = m->b, a2 = m->alpha * m->alpha;
    v3 wh = add(wi, wo);
    double l = len(wh);
    if (!(l > 0.0)) return 0.0;
    wh = scl(wh, 1.0 / l);
    int n = 2 * (int)ceil((h1 - h0) / (0.7 * m->alpha) * 0.5) * m->refine;
    double res = (h1 - h0) / n, sum = 0.0;
    energy_axes ax = m->e_in;
    const double st = sin(m->tilt), ct = cos(m->tilt);
    for (int i = 0; i <= n; ++i) {
        sc g = sc_of(h_to_gamma(h0 + i * res, b, wi));
        v3 wm, flat;
        double arc = sphg_pair(st, ct, g, b, &wm, NULL);
        flat = mk(wm.x, 0.0, wm.z);
        if (!visible2(wi, wo, flat, wh)) continue;
        double w = ((i == 0 || i == n) ? 0.5 : (i % 2 + 1)) * dgamma_dh(g, b, sp_i, cp_i);
        double c = dot(wm, wh);
        sum += w * ggx_d_sq(a2, c * c) * ggx_g(a2, dot(wm, wi), dot(wm, wo)) * arc *
               energy_scale_at(m, &ax, dot(wm, wi));
    }
    return 0.25 * fresnel(dot(wi, wh), m->eta, NULL) * sum * 2.0 / 3.0 * res;
}

/* ---- TT, TRT, TRRT+: the view's paths, then each light's exit --------------------------
 *
 * In Cycles' convention the viewer is "wi" and the light "wo". Everything up to the last
 * interface depends on the viewer only: the visible range, the entry mesonormals, the entry
 * microfacets and their refracted rays, the chords and their absorption, TRT's internal
 * reflection. The light enters at the exit alone (the half vector through which it leaves,
 * its Fresnel, D and masking, the total internal reflection test) and in TRRT+'s
 * longitudinal M. So the paths of one view are built once and every light of a run
 * (abrdf__huang_fibre_run: the lights of one shading point) takes only its exits. */

/* fresnel1: the unpolarised dielectric Fresnel reflectance at cosine c (sign ignored, clamped
 * to 1) for relative index eta, with one square root, as the vector loops write it: t = eta
 * cos(theta_t) = sqrt(eta^2 - sin^2), R_s = ((c - t)/(c + t))^2, R_p = ((eta^2 c - t)/(eta^2
 * c + t))^2, over one denominator; total internal reflection gives 1 and the refracted
 * cosine -t / eta (0 under total internal reflection). */

/* The lights of a run, in the fibre frame, with what their exits reuse and their sums: the
 * caller's arrays (LIGHT_STORE), room for as many lights as the run has. Each light's
 * directions are held twice: as vectors (R, TT) and as one array per component, which the
 * light-major loops (internal_lights) read. */
typedef struct light_run {
    int n;
    v3 *wo;               /* light directions (Cycles' "wo") */
    v3 *wos;              /* wo / eta: the light's part of the exit half vectors */
    double *x, *y, *z;    /* wo, per component */
    double *sx, *sy, *sz; /* wo / eta, per component */
    double *s_tt[3], *s_trt[3], *s_trrt[3]; /* each light's sums of TT, TRT and TRRT+, one
                                             * array per channel */
    double *fl, *v; /* a chunk's internal nodes' values for every light (trt_add): node j's
                     * from j * cap on */
    int cap;        /* room for lights */
} light_run;

/* Runs of LIGHT_MAJOR_MIN lights and more take the light-major loops (internal_lights,
 * lights_add), whose lanes run over the lights: a table's build hands over
 * hundreds. lights_add takes them LIGHTS_BLOCK at a time (a vector's lanes with AVX-512, two
 * with AVX2), and the room for lights is whole blocks. */
#define LIGHT_MAJOR_MIN 8
#define LIGHTS_BLOCK 8
typedef char light_room_is_blocks[ABRDF__HUANG_RUN_MAX % LIGHTS_BLOCK == 0 &&
                                          ABRDF__HUANG_WIDE_MAX % LIGHTS_BLOCK == 0
                                      ? 1
                                      : -1];

/* The arrays of a light_run for up to N lights, with fibre_run's own (slot, res), and
 * LIGHT_BIND(lr, st, N) pointing lr at them: a run of ABRDF__HUANG_RUN_MAX lights takes 14 KiB
 * of stack, a wide one (abrdf__huang_fibre_wide) 57 KiB. */
#define LIGHT_STORE(N)                                                                             \
    struct {                                                                                       \
        v3 wo[N], wos[N];                                                                          \
        double x[N], y[N], z[N], sx[N], sy[N], sz[N], s_tt[3][N], s_trt[3][N], s_trrt[3][N];       \
        double fl[INTERNAL_CHUNK * (N)], v[INTERNAL_CHUNK * (N)], res[N][3];                       \
        int slot[N];                                                                               \
    }
#define LIGHT_BIND(lr, st, N)                                                                      \
    ((lr).n = 0, (lr).wo = (st).wo, (lr).wos = (st).wos, (lr).x = (st).x, (lr).y = (st).y,         \
     (lr).z = (st).z, (lr).sx = (st).sx, (lr).sy = (st).sy, (lr).sz = (st).sz,                     \
     (lr).s_tt[0] = (st).s_tt[0], (lr).s_tt[1] = (st).s_tt[1], (lr).s_tt[2] = (st).s_tt[2],        \
     (lr).s_trt[0] = (st).s_trt[0], (lr).s_trt[1] = (st).s_trt[1], (lr).s_trt[2] = (st).s_trt[2],  \
     (lr).s_trrt[0] = (st).s_trrt[0], (lr).s_trrt[1] = (st).s_trrt[1],                             \
     (lr).s_trrt[2] = (st).s_trrt[2], (lr).fl = (st).fl, (lr).v = (st).v, (lr).cap = (N))

/* What the terms share: the fibre, the view, the run's lights (and their sums),
 * per-evaluation constants. */
typedef struct residual_ctx {
    const abrdf__huang *m;
    v3 wi;
    const light_run *lr;
    double b, inv_eta, inv_eta2, a2;
    double st, ct;      /* sin and cos of the cuticle tilt; the exit's: -st, ct */
    energy_axes ax_out; /* the energy table leaving the fibre (m->e_out) */
    unsigned lobes;
} residual_ctx;

/* A Simpson node on the fibre's cross-section: the entry mesonormals at gamma gmi. */
typedef struct ring_node {
    sc gmi; /* the entry point's ellipse parameter */
    v3 wmi, wmi_;
    double cos_mi1, proj, scale1; /* wi's cosine, projected width (TRRT+), entry energy scale */
    double lam1;                  /* Smith Lambda of the entry mesonormal seen from wi */
    double weight;                /* Simpson weight */
} ring_node;

/* A path entering the fibre through the microfacet wh1 and crossing it to the mesonormal
 * pair at gmt. */
typedef struct entry_path {
    v3 wt, wmt, wmt_; /* refracted direction, exit mesonormals */
    sc gmt;           /* the exit point's ellipse parameter */
    double t1, scale2, g1o, cos_mo1, cos_mi2;
    double c2, s2; /* |cos_mi2| and sqrt(c2^2 + alpha^2 (1 - c2^2)): its Lambda is (s2/c2 - 1)/2 */
    int flat_seen; /* the refracted ray sees the untilted exit mesonormal */
    double tt_pre; /* TT's factors that do not depend on the light */
    double at[3];  /* absorption along the chord */
    double wgt;    /* Simpson weight times the entry node's */
} entry_path;

/* The paths through a chunk of an entry grid's nodes, what each needs before its lights, for
 * every node without a branch (entry_base, compiled per instruction-set level): the entry
 * microfacet wh1 (Heitz's map from the disc point, vndf_lift), the transmission
 * (fresnel1), the refracted ray wt (refract_dir), the exit point gmt = twice_minus(to_phi(wt),
 * gamma_mi) and its mesonormals (sphg_pair, one root for the normal and
 * the arc length), the masking G2/G1 toward the refracted ray, the exit's energy scale and
 * Smith terms, the chord over cos(theta_t), TT's factors without the light. ok = 0 where
 * light does not enter (wi does not see wh1) or the refracted ray does not see wh1 or either
 * entry mesonormal. wi sees both mesonormals on [g0, g0 + gr]: that range is built from
 * them, so testing wi.wmi_ > 0 again only let a 1e-16 rounding drop the end nodes, where it
 * is 0 (S jumped). */
#define ENTRY_CHUNK 32

typedef struct entry_nodes {
    double ok[ENTRY_CHUNK], t1[ENTRY_CHUNK], wx[ENTRY_CHUNK], wy[ENTRY_CHUNK], wz[ENTRY_CHUNK];
    double gs[ENTRY_CHUNK], gc[ENTRY_CHUNK];                                   /* gmt */
    double mx[ENTRY_CHUNK], mz[ENTRY_CHUNK], fx[ENTRY_CHUNK], fz[ENTRY_CHUNK]; /* y: -st */
    double cos_mo1[ENTRY_CHUNK], cos_mi2[ENTRY_CHUNK], g1o[ENTRY_CHUNK], scale2[ENTRY_CHUNK];
    double c2[ENTRY_CHUNK], s2[ENTRY_CHUNK], flat[ENTRY_CHUNK], ka[ENTRY_CHUNK];
    double tt[ENTRY_CHUNK]; /* tt_pre over the path's weight */
} entry_nodes;

/* What the chunk reads: the entry VNDF frame, the view, eta, the fibre (b, the exit's tilt
 * -st, ct), alpha^2, the exit energy table (e_none: no compensation), and the Simpson node's
 * entry point gmi, mesonormals, Lambda, energy scale and cosine. */
typedef struct entry_consts {
    const vndf_frame *f;
    double wx, wy, wz, eta, eta2, inv_eta, b, st, ct, a2;
    const double *etab;
    double gis, gic, mix, miy, miz, mfx, mfz, lam1, scale1, cos_mi1;
} entry_consts;

#define ENTRY_BASE(L)                                                                              \
    ABRDF__NOINLINE ABRDF__ISA_ATTR_##L static void entry_base_##L(                                \
        const entry_consts *restrict q, const double *restrict p1, const double *restrict p2,      \
        const double *restrict p3, int n, entry_nodes *restrict o)                                 \
    {                                                                                              \
        const vndf_frame *f = q->f;                                                                \
        const double sh = f->sh, b = q->b, a2 = q->a2, eta2 = q->eta2;                             \
        const int round_ = b == 1.0;                                                               \
        /* every constant read before the loop: a read under a condition would be a masked load */ \
        const double eta = q->eta, inv_eta = q->inv_eta, st = q->st, ct = q->ct;                   \
        const double vx = q->wx, vy = q->wy, vz = q->wz, gis = q->gis, gic = q->gic;               \
        const double mix = q->mix, miy = q->miy, miz = q->miz, mfx = q->mfx, mfz = q->mfz;         \
        const double lam1 = q->lam1, k1 = q->scale1 * q->cos_mi1;                                  \
        const double *et = q->etab;                                                                \
        for (int j = 0; j < n; ++j) {                                                              \
            double hx, hy, hz;                                                                     \
            vndf_lift(f, p1[j], (1.0 - sh) * p3[j] + sh * p2[j], &hx, &hy, &hz);                   \
            double chi = vx * hx + vy * hy + vz * hz; /* fresnel1(chi, eta) */                     \
            double c = chi < 1.0 ? chi : 1.0, qq = eta2 - (1.0 - c * c);                           \
            double t = sqrt(qq > 0.0 ? qq : 0.0), ds = c + t, dp = eta2 * c + t;                   \
            double ns = (c - t) * dp, np = (eta2 * c - t) * ds, dd = ds * dp;                      \
            double fr = 0.5 * (ns * ns + np * np) / (dd * dd);                                     \
            int tr = (qq > 0.0) & (ds > 0.0) & (dp > 0.0);                                         \
            double t1 = 1.0 - (tr ? fr : 1.0), ct1 = tr ? -t / eta : 0.0;                          \
            double k = inv_eta * chi + ct1; /* refract_dir */                                      \
            double wx = hx * k - vx * inv_eta, wy = hy * k - vy * inv_eta;                         \
            double wz = hz * k - vz * inv_eta;                                                     \
            double x = b * wx, r2 = x * x + wz * wz, ir = 1.0 / sqrt(r2 > 0.0 ? r2 : 1.0);         \
            double as = r2 > 0.0 ? x * ir : 0.0, ac = r2 > 0.0 ? wz * ir : 1.0; /* to_phi */       \
            double cc = ac * ac - as * as, ss = 2.0 * as * ac;                                     \
            double gs = ss * gic - cc * gis, gc = cc * gic + ss * gis;                             \
            double sp = b * gs, cp = gc; /* sphg_pair */                                           \
            double arc = round_ ? 1.0 : sqrt(sp * sp + cp * cp), ia = 1.0 / arc;                   \
            sp *= ia, cp *= ia;                                                                    \
            double mx = sp * ct, my = -st, mz = cp * ct;                                           \
            double cmo1 = -(wx * mix + wy * miy + wz * miz);                                       \
            double cmi2 = -(wx * mx + wy * my + wz * mz);                                          \
            int ok = (chi > 0.0) & (-(wx * hx + wy * hy + wz * hz) > 0.0) & (cmo1 > 0.0) &         \
                     (-(wx * mfx + wz * mfz) > 0.0);                                               \
            o->ok[j] = ok ? 1.0 : 0.0;                                                             \
            o->t1[j] = t1, o->wx[j] = wx, o->wy[j] = wy, o->wz[j] = wz, o->gs[j] = gs;             \
            o->gc[j] = gc, o->mx[j] = mx, o->mz[j] = mz, o->fx[j] = sp;                            \
            o->fz[j] = cp, o->cos_mo1[j] = cmo1, o->cos_mi2[j] = cmi2;                             \
            o->flat[j] = -(wx * sp + wz * cp) > 0.0 ? 1.0 : 0.0;                                   \
            double g1o = (1.0 + lam1) / (1.0 + lam1 + ggx_lambda(a2, cmo1));                       \
            double sc2 = 1.0 / energy_e(et, cmi2);                                                 \
            o->g1o[j] = g1o, o->scale2[j] = sc2;                                                   \
            double c2 = cmi2 < 0.0 ? -cmi2 : cmi2;                                                 \
            o->c2[j] = c2, o->s2[j] = sqrt(c2 * c2 + a2 * (1.0 - c2 * c2));                        \
            double ctt = sqrt(wx * wx + wz * wz), dx = gis + gs, dz = b * (gic + gc);              \
            o->ka[j] = sqrt(dx * dx + dz * dz) /                                                   \
                       (ctt > ABRDF__HAIR_COS_MIN ? ctt : ABRDF__HAIR_COS_MIN); /* exit: gmt+pi */ \
            o->tt[j] = t1 * sc2 * g1o / cmo1 * k1 * arc;                                           \
        }                                                                                          \
    }
ABRDF__ISA_LEVELS(ENTRY_BASE)

typedef void (*entry_base_fn)(const entry_consts *restrict, const double *restrict,
                              const double *restrict, const double *restrict, int,
                              entry_nodes *restrict);
#define ENTRY_BASE_ENTRY(L) entry_base_##L,
static entry_base_fn entry_base_at(int level)
{
    static const entry_base_fn fns[] = {ABRDF__ISA_LEVELS(ENTRY_BASE_ENTRY)};
    const int n = (int)(sizeof fns / sizeof fns[0]);
    return fns[level < 0 ? 0 : level < n ? level : n - 1];
}

/* Entry node j of the chunk as a path (its absorption along the chord taken here), weight wgt:
 * 1, or 0 when light does not enter there. */
static int entry_path_at(const residual_ctx *c, const entry_nodes *o, int j, double wgt,
                         entry_path *e)
{
    if (!(o->ok[j] > 0.0)) return 0;
    e->wt = mk(o->wx[j], o->wy[j], o->wz[j]);
    e->wmt = mk(o->mx[j], -c->st, o->mz[j]), e->wmt_ = mk(o->fx[j], 0.0, o->fz[j]);
    e->gmt.s = o->gs[j], e->gmt.c = o->gc[j];
    e->t1 = o->t1[j], e->scale2 = o->scale2[j], e->g1o = o->g1o[j];
    e->cos_mo1 = o->cos_mo1[j], e->cos_mi2 = o->cos_mi2[j], e->c2 = o->c2[j], e->s2 = o->s2[j];
    e->flat_seen = o->flat[j] > 0.0;
    for (int k = 0; k < 3; ++k) {
        double s = c->m->sigma_a[k];
        e->at[k] = s > 0.0 ? exp(-s * o->ka[j]) : 1.0;
    }
    e->wgt = wgt;
    e->tt_pre = wgt * o->tt[j];
    return 1;
}

/* A light's factors of an exit through the microfacet whose half vector is h / |h| (h not
 * normalised, l = |h|^2), from the cosines of h (not normalised either) to the ray inside
 * (u_i), to the light (u_o) and to the exit mesonormal (u_m > 0): (1 - F) D G2 cos_i cos_o
 * rn^2, the last factor the generalised half vector's Jacobian, at index e2 = (1/eta)^2. Each
 * cosine to h / |h| is u / sqrt(l): the Fresnel ratios are scale-free in (u_i, sqrt(l) eta'
 * cos_t), D = alpha^2 / (pi k^2) with k l = l + (alpha^2 - 1) u_m^2 =: K, and cos_i cos_o
 * rn^2 = u_i u_o / l^2 cancels D's l^2: no normalisation. The masking is height-correlated,
 * G2 = 1 / (1 + Lambda_in + Lambda_o), with Lambda = (s/c - 1)/2 for a cosine c to the
 * mesonormal and s = sqrt(c^2 + alpha^2 (1 - c^2)): G2 = 2 c_in c_o / (s_in c_o + s_o c_in).
 * c_in, s_in: the ray inside's (c_in = |cosine|); cos_om: the light's cosine. 0 when the light
 * is totally reflected there or either direction grazes the mesonormal. Two roots and one
 * division, and no branch: it is inlined into the vectorised loops (light_exit). */
static inline double exit_factor(double u_i, double u_o, double u_m, double l, double e2, double a2,
                                 double c_in, double s_in, double cos_om)
{
    double u = fabs(u_i), q = (e2 - 1.0) * l + u * u;
    double t = sqrt(q > 0.0 ? q : 0.0), ds = u + t, dp = e2 * u + t;
    double ns = (u - t) * dp, np = (e2 * u - t) * ds, dd2 = ds * dp * ds * dp;
    double k = l + (a2 - 1.0) * u_m * u_m;
    double c = fabs(cos_om), c2 = c * c, s = sqrt(c2 + a2 * (1.0 - c2));
    double v = (dd2 - 0.5 * (ns * ns + np * np)) * a2 * u_i * u_o * 2.0 * c_in * c /
               (ABRDF__PI * k * k * dd2 * (s_in * c + s * c_in));
    return q > 0.0 ? v : 0.0; /* else 1 - F = 0 */
}

/* TT: each light exits through the microfacet with generalised half vector wh2 (Eq. 13). */
static void tt_add(residual_ctx *c, const entry_path *e)
{
    const double a2 = c->a2, inv_eta = c->inv_eta;
    v3 wt = e->wt;
    for (int l = 0; l < c->lr->n; ++l) {
        v3 wo = c->lr->wo[l];
        /* exit possible only if wo is within the critical cone */
        if (!(dot(wo, wt) >= inv_eta - ABRDF__HUANG_CRITICAL_TOL)) continue;
        v3 wh2 = add(neg(wt), c->lr->wos[l]); /* not normalised: l2 = |wh2|^2 */
        double l2 = dot(wh2, wh2);
        if (!(l2 > ABRDF__HUANG_HALF_LEN2_MIN)) continue;
        double u_mh = dot(e->wmt, wh2), u_o = dot(neg(wo), wh2);
        if (!(u_mh > 0.0)) continue; /* a microfacet at 90 degrees or beyond faces away (chi+) */
        /* u_o = wo.wt - 1/eta: below 0 within the tolerance above, where no light exits (its
         * term would be negative) */
        if (!(u_o > 0.0)) continue;
        double v = e->tt_pre * exit_factor(dot(neg(wt), wh2), u_o, u_mh, l2, c->inv_eta2, a2, e->c2,
                                           e->s2, dot(neg(wo), e->wmt));
        if (isfinite(v))
            for (int k = 0; k < 3; ++k) c->lr->s_tt[k][l] += v * e->at[k]; /* Eq. 13 */
    }
}

/* ---- the internal reflections of one entry path, a chunk of nodes at a time -------------
 * TRRT+ is Cycles' geometric series of further internal bounces,
 * t1 r2^2 tavg a^3 / (1 - a (1 - tavg)) per channel (absorption a), tavg = max(1 - r2, 1e-5);
 * its three channels share one division (each denominator is >= tavg).
 * What every internal node needs before its light-dependent tests, without a branch: its
 * microfacet wh2 (Heitz's map from the disc point, vndf_lift), the cosine to the
 * refracted ray, the reflectance there (fresnel1 at 1/eta), the reflected ray wtr and TRRT+'s
 * three channels (trrt3). The compiler vectorises the loop; it is compiled once per
 * instruction-set level (isa.h). A node with cos_hi2 <= 0 is masked out by internal_light. */
#define INTERNAL_CHUNK 16

typedef struct internal_nodes {
    double hx[INTERNAL_CHUNK], hy[INTERNAL_CHUNK], hz[INTERNAL_CHUNK]; /* wh2 */
    double ci[INTERNAL_CHUNK];                                         /* cos_hi2 */
    double r2f[INTERNAL_CHUNK];                                        /* F(cos_hi2) at 1/eta */
    double tx[INTERNAL_CHUNK], ty[INTERNAL_CHUNK], tz[INTERNAL_CHUNK]; /* wtr */
    double rr[3][INTERNAL_CHUNK];                                      /* TRRT+ (RGB) */
    /* TRT's exit, the view's part (internal_exit) */
    double mx[INTERNAL_CHUNK], my[INTERNAL_CHUNK], mz[INTERNAL_CHUNK]; /* exit mesonormal */
    double fx[INTERNAL_CHUNK], fz[INTERNAL_CHUNK]; /* the untilted one (y = 0) */
    double c3[INTERNAL_CHUNK], s3[INTERNAL_CHUNK]; /* wtr's cosine to it, and its s (G2) */
    double kab[INTERNAL_CHUNK];                    /* the second chord over cos(theta_tr) */
    double refl[INTERNAL_CHUNK]; /* 1 where -wtr sees wh2 and the mesonormals at gmt */
    double pre[INTERNAL_CHUNK];  /* Eq. 14's factors without the light; 0: exit not seen */
} internal_nodes;

/* The path's constants the chunk reads: the frame of the map, the refracted ray, TRRT+'s
 * weight w (node weight times projected width), t1 and absorption, (1/eta)^2; for TRT's exit
 * (internal_exit): the exit point gmt and its mesonormals, b (round: 1), the tilt, alpha^2,
 * the energy table (e_none: no compensation), the path's c2 and s2, and kp, the factors of
 * Eq. 14 that are the path's; whether the ray sees the untilted exit mesonormal, whether TRT
 * is wanted. */
/* E = 1 at every node: energy_scale_at without compensation (16 nodes, checked below) */
static const double e_none[] = {1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1};
typedef char e_none_has_every_node[sizeof e_none / sizeof e_none[0] == ABRDF__HAIR_E_N ? 1 : -1];

typedef struct internal_path {
    const vndf_frame *f;
    double wx, wy, wz;
    double w, t1, at[3], e2;
    double gs, gc, mtx, mty, mtz, mfx, mfz;
    double b, st, ct, a2, c2, s2, kp;
    const double *etab;
    int flat_seen, trt;
} internal_path;

#define INTERNAL_BASE(L)                                                                           \
    ABRDF__NOINLINE ABRDF__ISA_ATTR_##L static void internal_base_##L(                             \
        const internal_path *restrict q, const double *restrict p1, const double *restrict p2,     \
        int n, internal_nodes *restrict o)                                                         \
    {                                                                                              \
        const vndf_frame *f = q->f;                                                                \
        const double sh = f->sh, e2 = q->e2;                                                       \
        for (int j = 0; j < n; ++j) {                                                              \
            double a = p1[j], qa = 1.0 - a * a, pq = qa > 0.0 ? sqrt(qa) : 0.0; /* vndf_disc */    \
            double hx, hy, hz;                                                                     \
            vndf_lift(f, a, (1.0 - sh) * pq + sh * p2[j], &hx, &hy, &hz);                          \
            o->hx[j] = hx, o->hy[j] = hy, o->hz[j] = hz;                                           \
            double ci = -(q->wx * hx + q->wy * hy + q->wz * hz);                                   \
            o->ci[j] = ci; /* fresnel1(ci, 1/eta) */                                               \
            double c = fabs(ci) < 1.0 ? fabs(ci) : 1.0, qq = e2 - (1.0 - c * c);                   \
            double t = sqrt(qq > 0.0 ? qq : 0.0), ds = c + t, dp = e2 * c + t;                     \
            double ns = (c - t) * dp, np = (e2 * c - t) * ds, dd = ds * dp;                        \
            double dd2 = dd > 0.0 ? dd * dd : 1.0;                                                 \
            double r2 = qq > 0.0 && dd > 0.0 ? 0.5 * (ns * ns + np * np) / dd2 : 1.0;              \
            o->r2f[j] = r2; /* wtr = -(wt - 2 (wt.wh2) wh2) */                                     \
            double k2 = 2.0 * ci;                                                                  \
            o->tx[j] = -(q->wx + k2 * hx), o->ty[j] = -(q->wy + k2 * hy);                          \
            o->tz[j] = -(q->wz + k2 * hz); /* trrt3 */                                             \
            double tavg = 1.0 - r2 > ABRDF__HUANG_TAVG_MIN ? 1.0 - r2 : ABRDF__HUANG_TAVG_MIN;     \
            double kk = q->w * q->t1 * r2 * r2 * tavg;                                             \
            double a0 = q->at[0], a1 = q->at[1], a2 = q->at[2];                                    \
            double d0 = 1.0 - a0 * (1.0 - tavg), d1 = 1.0 - a1 * (1.0 - tavg);                     \
            double dd3 = 1.0 - a2 * (1.0 - tavg), iv = kk / (d0 * d1 * dd3);                       \
            o->rr[0][j] = a0 * a0 * a0 * (d1 * dd3) * iv;                                          \
            o->rr[1][j] = a1 * a1 * a1 * (d0 * dd3) * iv;                                          \
            o->rr[2][j] = a2 * a2 * a2 * (d0 * d1) * iv;                                           \
        }                                                                                          \
    }
ABRDF__ISA_LEVELS(INTERNAL_BASE)

typedef void (*internal_base_fn)(const internal_path *restrict, const double *restrict,
                                 const double *restrict, int, internal_nodes *restrict);
#define INTERNAL_BASE_ENTRY(L) internal_base_##L,
static internal_base_fn internal_base_at(int level)
{
    static const internal_base_fn fns[] = {ABRDF__ISA_LEVELS(INTERNAL_BASE_ENTRY)};
    const int n = (int)(sizeof fns / sizeof fns[0]);
    return fns[level < 0 ? 0 : level < n ? level : n - 1];
}

/* TRT's exit, the view's part, for each node of a chunk (after internal_base): whether the
 * reflected ray wtr leaves through the exit mesonormals (visible2(-wt, -wtr, wmt, wh2) and the
 * same for wmt_: -wt's halves are the node's cos_hi2 > 0, the path's cos_mi2 > 0 and
 * flat_seen), where (gamma_mi - 2 (to_phi(phi_t) - to_phi(phi_tr)) + pi = (2 to_phi(phi_tr) -
 * gmt) + pi), its mesonormals there and whether wtr sees them, the second chord, and Eq. 14's
 * factors that do not see the light: (1 - F)'s and the masking's inner halves, the exit's
 * energy scale, the arc length. Written without a branch for every node (to_phi, twice_minus,
 * sphg_pair); pre = 0 where the exit is not seen. The
 * internal masking (1 + Lambda_2) / (1 + Lambda_2 + Lambda_mo2) / cos_mo2 is
 * (c2 + s2) / (s2 cos_mo2 + s_mo2 c2). */
#define INTERNAL_EXIT(L)                                                                           \
    ABRDF__NOINLINE ABRDF__ISA_ATTR_##L static void internal_exit_##L(                             \
        const internal_path *restrict q, int n, internal_nodes *restrict o)                        \
    {                                                                                              \
        const double b = q->b, a2 = q->a2, st = q->st, ct = q->ct;                                 \
        const int round_ = b == 1.0;                                                               \
        for (int j = 0; j < n; ++j) {                                                              \
            double tx = o->tx[j], ty = o->ty[j], tz = o->tz[j];                                    \
            double cmo2 = -(q->mtx * tx + q->mty * ty + q->mtz * tz);                              \
            int ok = (-(tx * o->hx[j] + ty * o->hy[j] + tz * o->hz[j]) > 0.0) & (cmo2 > 0.0) &     \
                     (-(q->mfx * tx + q->mfz * tz) > 0.0);                                         \
            double x = b * tx, r2 = x * x + tz * tz, ir = 1.0 / sqrt(r2 > 0.0 ? r2 : 1.0);         \
            double as = r2 > 0.0 ? x * ir : 0.0, ac = r2 > 0.0 ? tz * ir : 1.0; /* to_phi */       \
            double cc = ac * ac - as * as, ss = 2.0 * as * ac;                                     \
            double gs = -(ss * q->gc - cc * q->gs), gc = -(cc * q->gc + ss * q->gs);               \
            double sp = b * gs, cp = gc; /* sphg_pair */                                           \
            double arc = round_ ? 1.0 : sqrt(sp * sp + cp * cp), ia = 1.0 / arc;                   \
            sp *= ia, cp *= ia;                                                                    \
            double mx = sp * ct, my = -st, mz = cp * ct;                                           \
            o->mx[j] = mx, o->my[j] = my, o->mz[j] = mz, o->fx[j] = sp, o->fz[j] = cp;             \
            double c3 = mx * tx + my * ty + mz * tz;                                               \
            double dx = gs - q->gs, dz = b * (gc - q->gc), ctr = sqrt(tx * tx + tz * tz);          \
            double ka =                                                                            \
                sqrt(dx * dx + dz * dz) / (ctr > ABRDF__HAIR_COS_MIN ? ctr : ABRDF__HAIR_COS_MIN); \
            o->kab[j] = ka;                                                                        \
            o->c3[j] = c3, o->s3[j] = sqrt(c3 * c3 + a2 * (1.0 - c3 * c3));                        \
            double smo = sqrt(cmo2 * cmo2 + a2 * (1.0 - cmo2 * cmo2));                             \
            double e = energy_e(q->etab, c3);                                                      \
            double pre = q->kp * o->r2f[j] * arc / ((q->s2 * cmo2 + smo * q->c2) * e);             \
            o->refl[j] = (ok & q->flat_seen) ? 1.0 : 0.0;                                          \
            ok = ok & (c3 > 0.0) & (tx * sp + tz * cp > 0.0);                                      \
            o->pre[j] = (ok & q->flat_seen & q->trt) ? pre : 0.0;                                  \
        }                                                                                          \
    }
ABRDF__ISA_LEVELS(INTERNAL_EXIT)

typedef void (*internal_exit_fn)(const internal_path *restrict, int, internal_nodes *restrict);
#define INTERNAL_EXIT_ENTRY(L) internal_exit_##L,
static internal_exit_fn internal_exit_at(int level)
{
    static const internal_exit_fn fns[] = {ABRDF__ISA_LEVELS(INTERNAL_EXIT_ENTRY)};
    const int n = (int)(sizeof fns / sizeof fns[0]);
    return fns[level < 0 ? 0 : level < n ? level : n - 1];
}

/* The light's part of TRT and TRRT+ for each node of a chunk (after internal_exit), one light
 * at a time, without a branch: fl[j] = 1 where the node's TRRT+ counts for the light, v[j]
 * Eq. 14's value before absorption (0 where the light does not leave through the node's
 * exit). TRRT+ counts where the light is totally reflected at the exit (the path stays
 * inside), and where it is not but the internal reflection is seen (refl) and the exit's
 * half vector wh3 = wtr + wo / eta has a length. The exit needs visible2(wtr, -wo, wmtr, wh3)
 * and the same for wmtr_ (wtr's half is in pre), on the signs of the unnormalised cosines. */
typedef struct light_consts {
    double wx, wy, wz, sx, sy, sz; /* the light wo, and wo / eta */
    double cut, e2, a2;            /* the critical cosine (1/eta less a tolerance), (1/eta)^2 */
} light_consts;

/* One node's exit toward one light, for both loops below (the same arithmetic, so the same
 * bits, whichever runs): *fl and the returned v as above. The node: its reflected ray t, its
 * cos_hi2 ci, refl, pre, the exit mesonormals m and f (y = 0), c3 and s3. */
static inline double light_exit(double tx, double ty, double tz, double ci, double refl, double pre,
                                double mx, double my, double mz, double fx, double fz, double c3,
                                double s3, double wx, double wy, double wz, double sx, double sy,
                                double sz, double cut, double e2, double a2, double *fl)
{
    int in = ci > 0.0, tir = -(tx * wx + ty * wy + tz * wz) < cut;
    double hx = tx + sx, hy = ty + sy, hz = tz + sz;
    double l3 = hx * hx + hy * hy + hz * hz;
    int pass = (refl > 0.0) & (l3 > ABRDF__HUANG_HALF_LEN2_MIN);
    *fl = (in & (tir | pass)) ? 1.0 : 0.0;
    double com = -(mx * wx + my * wy + mz * wz), cof = -(fx * wx + fz * wz);
    double umh = mx * hx + my * hy + mz * hz, uhi = hx * tx + hy * ty + hz * tz;
    double uho = -(hx * wx + hy * wy + hz * wz);
    int ok = in & !tir & pass & (pre > 0.0) & (com > 0.0) & (cof > 0.0) & (umh > 0.0) &
             (uhi > 0.0) & (uho > 0.0);
    double f = pre * exit_factor(uhi, uho, umh, l3, e2, a2, c3, s3, com);
    return ok ? f : 0.0;
}

/* Node-major: one light, every node of the chunk (the loop runs over the nodes). */
#define INTERNAL_LIGHT(L)                                                                          \
    ABRDF__NOINLINE ABRDF__ISA_ATTR_##L static void internal_light_##L(                            \
        const internal_nodes *restrict o, int n, const light_consts *restrict lc,                  \
        double *restrict fl, double *restrict v)                                                   \
    {                                                                                              \
        const double wx = lc->wx, wy = lc->wy, wz = lc->wz, sx = lc->sx, sy = lc->sy;              \
        const double sz = lc->sz, cut = lc->cut, e2 = lc->e2, a2 = lc->a2;                         \
        for (int j = 0; j < n; ++j)                                                                \
            v[j] = light_exit(o->tx[j], o->ty[j], o->tz[j], o->ci[j], o->refl[j], o->pre[j],       \
                              o->mx[j], o->my[j], o->mz[j], o->fx[j], o->fz[j], o->c3[j],          \
                              o->s3[j], wx, wy, wz, sx, sy, sz, cut, e2, a2, fl + j);              \
    }
ABRDF__ISA_LEVELS(INTERNAL_LIGHT)

typedef void (*internal_light_fn)(const internal_nodes *restrict, int, const light_consts *restrict,
                                  double *restrict, double *restrict);
#define INTERNAL_LIGHT_ENTRY(L) internal_light_##L,
static internal_light_fn internal_light_at(int level)
{
    static const internal_light_fn fns[] = {ABRDF__ISA_LEVELS(INTERNAL_LIGHT_ENTRY)};
    const int n = (int)(sizeof fns / sizeof fns[0]);
    return fns[level < 0 ? 0 : level < n ? level : n - 1];
}

/* Light-major: node j of the chunk toward every light of the run (the loop runs over the
 * lights, whose number fills the vector lanes where a chunk's n2^2 = 9 nodes do not), the
 * same light_exit; fl and v are 0 from the last light to the end of its block. Returns how
 * many lights leave through the node (v finite and not 0). */
#define INTERNAL_LIGHTS(L)                                                                         \
    ABRDF__NOINLINE ABRDF__ISA_ATTR_##L static int internal_lights_##L(                            \
        const internal_nodes *restrict o, int j, const light_run *restrict lr, double cut,         \
        double e2, double a2, double *restrict fl, double *restrict v)                             \
    {                                                                                              \
        const double tx = o->tx[j], ty = o->ty[j], tz = o->tz[j], ci = o->ci[j];                   \
        const double refl = o->refl[j], pre = o->pre[j], mx = o->mx[j], my = o->my[j];             \
        const double mz = o->mz[j], fx = o->fx[j], fz = o->fz[j], c3 = o->c3[j], s3 = o->s3[j];    \
        const double *restrict x = lr->x, *restrict y = lr->y, *restrict z = lr->z;                \
        const double *restrict sx = lr->sx, *restrict sy = lr->sy, *restrict sz = lr->sz;          \
        const int n = lr->n;                                                                       \
        int out = 0;                                                                               \
        for (int l = 0; l < n; ++l) {                                                              \
            double vl = light_exit(tx, ty, tz, ci, refl, pre, mx, my, mz, fx, fz, c3, s3, x[l],    \
                                   y[l], z[l], sx[l], sy[l], sz[l], cut, e2, a2, fl + l);          \
            v[l] = vl;                                                                             \
            out += (vl != 0.0) & (fabs(vl) <= DBL_MAX);                                            \
        }                                                                                          \
        for (int l = n; l % LIGHTS_BLOCK; ++l) fl[l] = v[l] = 0.0; /* the last block's rest */     \
        return out;                                                                                \
    }
ABRDF__ISA_LEVELS(INTERNAL_LIGHTS)

typedef int (*internal_lights_fn)(const internal_nodes *restrict, int, const light_run *restrict,
                                  double, double, double, double *restrict, double *restrict);
#define INTERNAL_LIGHTS_ENTRY(L) internal_lights_##L,
static internal_lights_fn internal_lights_at(int level)
{
    static const internal_lights_fn fns[] = {ABRDF__ISA_LEVELS(INTERNAL_LIGHTS_ENTRY)};
    const int n = (int)(sizeof fns / sizeof fns[0]);
    return fns[level < 0 ? 0 : level < n ? level : n - 1];
}

/* Light-major: the chunk's n nodes, in their order, to every light: node j's TRRT+ rr[.][j]
 * (RGB) where its fl lets the light through, and its TRT v times its absorption att[j]
 * where the light leaves (v finite and not 0); fl and v of node j from j * cap on. Each
 * light's six sums stay in registers over the chunk. A skipped term adds +0, which leaves a
 * sum as it is (the sums start at +0), so these are the node-major loop's bits. */
#define LIGHTS_ADD(L)                                                                              \
    ABRDF__NOINLINE ABRDF__ISA_ATTR_##L static void lights_add_##L(                                \
        const light_run *restrict lr, int n, const double(*restrict rr)[INTERNAL_CHUNK],           \
        const double(*restrict att)[3])                                                            \
    {                                                                                              \
        double *const *s = lr->s_trrt, *const *t = lr->s_trt;                                      \
        const double *restrict fl = lr->fl, *restrict v = lr->v;                                   \
        const int nl = lr->n, cap = lr->cap;                                                       \
        for (int l0 = 0; l0 < nl; l0 += LIGHTS_BLOCK) {                                            \
            const int m = nl - l0 < LIGHTS_BLOCK ? nl - l0 : LIGHTS_BLOCK;                         \
            double q[3][LIGHTS_BLOCK], u[3][LIGHTS_BLOCK];                                         \
            for (int k = 0; k < 3; ++k)                                                            \
                for (int i = 0; i < LIGHTS_BLOCK; ++i)                                             \
                    q[k][i] = i < m ? s[k][l0 + i] : 0.0, u[k][i] = i < m ? t[k][l0 + i] : 0.0;    \
            for (int j = 0; j < n; ++j) {                                                          \
                const double *fj = fl + (long)j * cap + l0, *vj = v + (long)j * cap + l0;          \
                const double p0 = rr[0][j], p1 = rr[1][j], p2 = rr[2][j];                          \
                const double a0 = att[j][0], a1 = att[j][1], a2 = att[j][2];                       \
                for (int i = 0; i < LIGHTS_BLOCK; ++i) {                                           \
                    int f = fj[i] > 0.0;                                                           \
                    double vl = vj[i];                                                             \
                    int ok = (vl != 0.0) & (fabs(vl) <= DBL_MAX);                                  \
                    q[0][i] += f ? p0 : 0.0, q[1][i] += f ? p1 : 0.0, q[2][i] += f ? p2 : 0.0;     \
                    u[0][i] += ok ? vl * a0 : 0.0, u[1][i] += ok ? vl * a1 : 0.0;                  \
                    u[2][i] += ok ? vl * a2 : 0.0;                                                 \
                }                                                                                  \
            }                                                                                      \
            for (int k = 0; k < 3; ++k) /* a whole block: the room is blocks (below) */            \
                for (int i = 0; i < LIGHTS_BLOCK; ++i)                                             \
                    s[k][l0 + i] = q[k][i], t[k][l0 + i] = u[k][i];                                \
        }                                                                                          \
    }
ABRDF__ISA_LEVELS(LIGHTS_ADD)

typedef void (*lights_add_fn)(const light_run *restrict, int,
                              const double (*restrict)[INTERNAL_CHUNK],
                              const double (*restrict)[3]);
#define LIGHTS_ADD_ENTRY(L) lights_add_##L,
static lights_add_fn lights_add_at(int level)
{
    static const lights_add_fn fns[] = {ABRDF__ISA_LEVELS(LIGHTS_ADD_ENTRY)};
    const int n = (int)(sizeof fns / sizeof fns[0]);
    return fns[level < 0 ? 0 : level < n ? level : n - 1];
}

/* The light loops of one evaluation, at the CPU's level. */
typedef struct light_fns {
    internal_light_fn one;
    internal_lights_fn many;
    lights_add_fn add;
} light_fns;

/* TRT (Eq. 14) and TRRT+ of a chunk's nodes for every light of the run, in the order of the
 * nodes; each node's absorption along its second chord is taken once, if some light leaves
 * through it. Runs of LIGHT_MAJOR_MIN lights and more take the light-major loops. */
static void trt_add(residual_ctx *c, const entry_path *e, const internal_nodes *in, int n,
                    const light_fns *lf)
{
    const light_run *lr = c->lr;
    const int nl = lr->n;
    const double cut = c->inv_eta - ABRDF__HUANG_CRITICAL_TOL;
    if (nl >= LIGHT_MAJOR_MIN) {
        double att[INTERNAL_CHUNK][3];
        for (int j = 0; j < n; ++j) {
            const long o = (long)j * lr->cap;
            int out = lf->many(in, j, lr, cut, c->inv_eta2, c->a2, lr->fl + o, lr->v + o);
            for (int k = 0; k < 3; ++k) {
                double s = c->m->sigma_a[k];
                att[j][k] = !out ? 0.0 : e->at[k] * (s > 0.0 ? exp(-s * in->kab[j]) : 1.0);
            }
        }
        lf->add(lr, n, (const double(*)[INTERNAL_CHUNK])in->rr, (const double(*)[3])att);
        return;
    }
    double fl[LIGHT_MAJOR_MIN][INTERNAL_CHUNK], v[LIGHT_MAJOR_MIN][INTERNAL_CHUNK];
    for (int l = 0; l < nl; ++l) {
        v3 wo = lr->wo[l], ws = lr->wos[l];
        light_consts lc = {wo.x, wo.y, wo.z, ws.x, ws.y, ws.z, cut, c->inv_eta2, c->a2};
        lf->one(in, n, &lc, fl[l], v[l]);
    }
    for (int j = 0; j < n; ++j) {
        double att[3] = {0, 0, 0};
        int att_made = 0;
        for (int l = 0; l < nl; ++l) {
            if (fl[l][j] > 0.0)
                for (int k = 0; k < 3; ++k) lr->s_trrt[k][l] += in->rr[k][j];
            double vj = v[l][j];
            if (!(vj != 0.0) || !isfinite(vj)) continue;
            if (!att_made) { /* once per node, for the first light that leaves */
                for (int k = 0; k < 3; ++k) {
                    double s = c->m->sigma_a[k];
                    att[k] = e->at[k] * (s > 0.0 ? exp(-s * in->kab[j]) : 1.0);
                }
                att_made = 1;
            }
            for (int k = 0; k < 3; ++k) lr->s_trt[k][l] += vj * att[k];
        }
    }
}

/* TT + TRT + TRRT+ (RGB) of every light of the run: Simpson over gamma, nested shifted grids
 * over the VNDF squares (grid_points); out[l] for light l. */
static void lobes_residual(const abrdf__huang *m, v3 wi, const light_run *lr, double g0, double gr,
                           double h0, double h1, double sp_i, double cp_i, unsigned lobes,
                           double (*out)[3])
{
    const double b = m->b, eta = m->eta, inv_eta = 1.0 / eta, al = m->alpha;
    const int n1 = m->n1, n2 = m->n2;
    const double w1 = 1.0 / (n1 * n1), w2 = 1.0 / (n2 * n2);
    const long set = ABRDF__HUANG_SHIFT_SET_STEP * m->shift_set; /* 0 but in the tests (hair.h) */
    for (int l = 0; l < lr->n; ++l) {
        out[l][0] = out[l][1] = out[l][2] = 0.0;
        for (int k = 0; k < 3; ++k) lr->s_tt[k][l] = lr->s_trt[k][l] = lr->s_trrt[k][l] = 0.0;
    }
    if (n1 * n1 > ABRDF__HUANG_NODES_MAX || n2 * n2 > ABRDF__HUANG_NODES_MAX) return;
    /* The VNDF grids' column angles once per evaluation; each grid's disc points (as arrays,
     * for the vectorised loop: 43 KiB of stack, grid_block) per Simpson node (entry)
     * and per path (internal) */
    grid_block g;
    double(*p1s)[ABRDF__HUANG_NODES_MAX] = g.p1s, (*p2s)[ABRDF__HUANG_NODES_MAX] = g.p2s;
    grid_angles *ang1 = &g.ang1, *ang2 = &g.ang2;
    grid_angles_make(n1, ang1);
    grid_angles_make(n2, ang2);
    const internal_base_fn base = internal_base_at(abrdf__isa_best());
    const internal_exit_fn exit_view = internal_exit_at(abrdf__isa_best());
    const light_fns lf = {internal_light_at(abrdf__isa_best()),
                          internal_lights_at(abrdf__isa_best()), lights_add_at(abrdf__isa_best())};
    const entry_base_fn entry = entry_base_at(abrdf__isa_best());
    energy_axes ax_in = m->e_in;
    residual_ctx c = {.m = m,
                      .wi = wi,
                      .lr = lr,
                      .b = b,
                      .inv_eta = inv_eta,
                      .inv_eta2 = inv_eta * inv_eta,
                      .a2 = al * al,
                      .st = sin(m->tilt),
                      .ct = cos(m->tilt),
                      .ax_out = m->e_out,
                      .lobes = lobes};
    /* Cycles' quadrature (tests only): Simpson over h, not gamma */
    const int ch = (m->cycles_nodes & ABRDF__HUANG_CYCLES_H) != 0;
    int n = ch ? 2 * (int)ceil((h1 - h0) / (0.8 * al) * 0.5) * m->refine
               : simpson_intervals(0.8 * al, m->refine);
    double res = ch ? (h1 - h0) / n : gr / n;
    for (int i = 0; i <= n; ++i) {
        ring_node r;
        r.gmi = sc_of(ch ? h_to_gamma(h0 + i * res, b, wi) : g0 + i * res);
        sphg_pair(c.st, c.ct, r.gmi, b, &r.wmi, &r.wmi_);
        /* The range is built so that wi sees every tilted mesonormal on it: cos_mi1 >= 0,
         * and 0 at the ends when the tilt hides the silhouette. Skipping cos_mi1 <= 0 let a
         * 1e-16 rounding drop an end node, whose TRRT+ (weighted by proj, not cos_mi1) is
         * not 0: S jumped. The VNDF map is continuous through cos_mi1 = 0. */
        r.cos_mi1 = max_of(dot(wi, r.wmi), 0.0);
        r.weight = (i == 0 || i == n) ? 0.5 : (i % 2 + 1);
        if (ch) r.weight *= dgamma_dh(r.gmi, b, sp_i, cp_i);
        /* Projected width of this surface element seen from wi, |dh/dgamma| cos(theta_i):
         * the light TRRT+ receives here (R, TT, TRT carry it through cos_mi1). */
        r.proj = (m->cycles_nodes & ABRDF__HUANG_CYCLES_TRRT)
                     ? 2.0 / ABRDF__PI
                     : fabs(cp_i * r.gmi.c + b * sp_i * r.gmi.s) * cos_theta(wi);
        r.scale1 = energy_scale_at(m, &ax_in, r.cos_mi1); /* depends on the entry node only */
        r.lam1 = ggx_lambda(c.a2, r.cos_mi1);
        vndf_frame f1;
        vndf_frame_make(al, wi, r.wmi, &f1);
        grid_points(ang1, i, set, p1s[0], p1s[1], p1s[2]);
        const entry_consts ec = {.f = &f1,
                                 .wx = wi.x,
                                 .wy = wi.y,
                                 .wz = wi.z,
                                 .eta = eta,
                                 .eta2 = eta * eta,
                                 .inv_eta = inv_eta,
                                 .b = b,
                                 .st = c.st,
                                 .ct = c.ct,
                                 .a2 = c.a2,
                                 .etab = m->compensate ? m->e_out : e_none,
                                 .gis = r.gmi.s,
                                 .gic = r.gmi.c,
                                 .mix = r.wmi.x,
                                 .miy = r.wmi.y,
                                 .miz = r.wmi.z,
                                 .mfx = r.wmi_.x,
                                 .mfz = r.wmi_.z,
                                 .lam1 = r.lam1,
                                 .scale1 = r.scale1,
                                 .cos_mi1 = r.cos_mi1};
        entry_nodes en;
        for (int j1 = 0; j1 < n1 * n1; ++j1) {
            const int jc = j1 % ENTRY_CHUNK;
            if (jc == 0) {
                int nc = n1 * n1 - j1 < ENTRY_CHUNK ? n1 * n1 - j1 : ENTRY_CHUNK;
                entry(&ec, p1s[0] + j1, p1s[1] + j1, p1s[2] + j1, nc, &en);
            }
            entry_path e;
            if (!entry_path_at(&c, &en, jc, r.weight * w1, &e)) continue;
            if (lobes & 2u) tt_add(&c, &e);
            if (!(lobes & 12u) || !(e.cos_mi2 > 0.0)) continue;
            /* TRT and TRRT+: internal reflection at wh2 (n2 x n2 VNDF nodes) */
            vndf_frame f2;
            vndf_frame_make(al, neg(e.wt), e.wmt, &f2);
            grid_points(ang2, (long)i * n1 * n1 + j1, set, p2s[0], p2s[1], NULL);
            internal_path ip = {.f = &f2,
                                .wx = e.wt.x,
                                .wy = e.wt.y,
                                .wz = e.wt.z,
                                .w = e.wgt * w2 * r.proj,
                                .t1 = e.t1,
                                .at = {e.at[0], e.at[1], e.at[2]},
                                .e2 = c.inv_eta2,
                                .gs = e.gmt.s,
                                .gc = e.gmt.c,
                                .mtx = e.wmt.x,
                                .mty = e.wmt.y,
                                .mtz = e.wmt.z,
                                .mfx = e.wmt_.x,
                                .mfz = e.wmt_.z,
                                .b = b,
                                .st = c.st,
                                .ct = c.ct,
                                .a2 = c.a2,
                                .c2 = e.c2,
                                .s2 = e.s2,
                                .kp = e.wgt * w2 * e.t1 * r.scale1 * e.scale2 * e.g1o *
                                      (e.c2 + e.s2) * r.cos_mi1 * e.cos_mi2 / e.cos_mo1,
                                .etab = m->compensate ? m->e_out : e_none,
                                .flat_seen = e.flat_seen,
                                .trt = (lobes & 4u) != 0};
            for (int j0 = 0; j0 < n2 * n2; j0 += INTERNAL_CHUNK) {
                int nc = n2 * n2 - j0 < INTERNAL_CHUNK ? n2 * n2 - j0 : INTERNAL_CHUNK;
                internal_nodes in;
                base(&ip, p2s[0] + j0, p2s[1] + j0, nc, &in);
                exit_view(&ip, nc, &in);
                trt_add(&c, &e, &in, nc, &lf);
            }
        }
    }
    double k = 2.0 / 3.0 * res;
    for (int l = 0; l < lr->n; ++l) {
        v3 wo = lr->wo[l];
        double mlong = (lobes & 8u) ? longitudinal_m(sin_theta(wi), cos_theta(wi), sin_theta(wo),
                                                     cos_theta(wo), 4.0 * al)
                                    : 0.0;
        for (int i = 0; i < 3; ++i) {
            double trrt_term = (lobes & 8u) ? lr->s_trrt[i][l] * mlong / (2.0 * ABRDF__PI) : 0.0;
            out[l][i] = ((lr->s_tt[i][l] + lr->s_trt[i][l]) * inv_eta * inv_eta + trrt_term) * k;
        }
    }
}

/* S of a run of count lights (at most the room of lr's arrays; slot and res as long): the
 * lights that can be lit at all go into lr, the others keep S = 0. */
static void fibre_run(const abrdf__huang *m, int count, const double (*wi_)[3], const double wo_[3],
                      unsigned lobes, double (*s)[3], light_run lr, int *slot, double (*res)[3])
{
    for (int l = 0; l < count; ++l) s[l][0] = s[l][1] = s[l][2] = 0.0;
    /* Cycles' convention: its "wi" is the viewer (our wo), its "wo" the light (our wi). */
    v3 wi = mk(wo_[1], wo_[0], wo_[2]);
    double ci = cos_theta(wi);
    if (!(ci > ABRDF__HAIR_COS_MIN)) return;
    double b = m->b, e2 = 1.0 - b * b;
    double tan_tilt = tan(m->tilt);
    /* The lights that can be lit at all; the others keep S = 0. */
    for (int l = 0; l < count; ++l) {
        v3 wo = mk(wi_[l][1], wi_[l][0], wi_[l][2]);
        if (!(cos_theta(wo) > 0.0)) continue;
        if (tan_tilt * sin_theta(wo) / cos_theta(wo) < -1.0) continue; /* exit mesonormal hidden */
        slot[lr.n] = l;
        v3 ws = scl(wo, 1.0 / m->eta);
        lr.wo[lr.n] = wo, lr.wos[lr.n] = ws;
        lr.x[lr.n] = wo.x, lr.y[lr.n] = wo.y, lr.z[lr.n] = wo.z;
        lr.sx[lr.n] = ws.x, lr.sy[lr.n] = ws.y, lr.sz[lr.n] = ws.z;
        ++lr.n;
    }
    if (lr.n == 0) return;
    double x = -tan_tilt * sin_theta(wi) / ci;
    if (x > 1.0) return; /* entry mesonormal hidden */
    double half_span = acos(fmax(x, 0.0));
    double sp_i = wi.x / ci, cp_i = wi.z / ci;
    double radius = sqrt(fmax(ABRDF__HUANG_RADIUS2_MIN, 1.0 - e2 * sp_i * sp_i));
    double phi_i = dir_phi(wi);
    double hmin = phi_to_h(phi_i + half_span, b, sp_i, cp_i) / radius;
    double hmax = phi_to_h(phi_i - half_span, b, sp_i, cp_i) / radius;
    const double hclip =
        (m->cycles_nodes & ABRDF__HUANG_CYCLES_H) ? ABRDF__HUANG_CYCLES_H_CLIP : 1.0;
    hmin = fmax(hmin, -hclip);
    hmax = fmin(hmax, hclip);
    if (!(hmax > hmin)) return;
    /* Integrate over the surface parameter gamma, not h: integral g dgamma/dh dh =
     * integral g dgamma, and dgamma/dh (Cycles' Jacobian) has an integrable singularity at
     * the silhouette that Simpson in h (Cycles clips h to +-0.999) over-weights. h is in
     * units of the projected radius, so dh_abs = radius dh: the 1/radius below. */
    double g0 = h_to_gamma(hmax, b, wi), g1 = h_to_gamma(hmin, b, wi); /* decreasing in h */
    if (!(g1 > g0)) return;
    double area =
        ci * 2.0 * radius; /* projected width 2 (far field) times cos(theta_i), radius from dh */
    for (int l = 0; l < lr.n; ++l) res[l][0] = res[l][1] = res[l][2] = 0.0;
    if (lobes & 14u) lobes_residual(m, wi, &lr, g0, g1 - g0, hmin, hmax, sp_i, cp_i, lobes, res);
    for (int l = 0; l < lr.n; ++l) {
        double r = !(lobes & 1u) ? 0.0
                   : (m->cycles_nodes & ABRDF__HUANG_CYCLES_H)
                       ? lobe_r_cycles(m, wi, lr.wo[l], hmin, hmax, sp_i, cp_i)
                       : lobe_r(m, wi, lr.wo[l], g0, g1 - g0);
        for (int c = 0; c < 3; ++c) s[slot[l]][c] = (r + res[l][c]) / area;
    }
}

void abrdf__huang_fibre_run(const abrdf__huang *m, int count, const double (*wi)[3],
                            const double wo[3], unsigned lobes, double (*s)[3])
{
    if (count < 1 || count > ABRDF__HUANG_RUN_MAX) {
        for (int l = 0; l < count; ++l) s[l][0] = s[l][1] = s[l][2] = 0.0;
        return;
    }
    LIGHT_STORE(ABRDF__HUANG_RUN_MAX) st;
    light_run lr;
    LIGHT_BIND(lr, st, ABRDF__HUANG_RUN_MAX);
    fibre_run(m, count, wi, wo, lobes, s, lr, st.slot, st.res);
}

void abrdf__huang_fibre_wide(const abrdf__huang *m, int count, const double (*wi)[3],
                             const double wo[3], unsigned lobes, double (*s)[3])
{
    if (count < 1 || count > ABRDF__HUANG_WIDE_MAX) {
        for (int l = 0; l < count; ++l) s[l][0] = s[l][1] = s[l][2] = 0.0;
        return;
    }
    LIGHT_STORE(ABRDF__HUANG_WIDE_MAX) st;
    light_run lr;
    LIGHT_BIND(lr, st, ABRDF__HUANG_WIDE_MAX);
    fibre_run(m, count, wi, wo, lobes, s, lr, st.slot, st.res);
}

void abrdf__huang_fibre(const abrdf__huang *m, const double wi[3], const double wo[3],
                        unsigned lobes, double s[3])
{
    double si[1][3];
    abrdf__huang_fibre_run(m, 1, (const double(*)[3])wi, wo, lobes, si);
    for (int c = 0; c < 3; ++c) s[c] = si[0][c];
}
