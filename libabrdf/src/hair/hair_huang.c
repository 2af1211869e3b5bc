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
 *    map is integrated by an n1 x n1 (entry) and n2 x n2 (internal reflection) midpoint
 *    product rule on its unit square: the expectation Cycles estimates, computed by
 *    quadrature.
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
#include <math.h>

#include "hair.h"

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
static double to_phi(double gamma, double b) { return atan2(b * sin(gamma), cos(gamma)); }
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

static v3 to_point(double gamma, double b) { return mk(sin(gamma), 0.0, b * cos(gamma)); }

/* Unit (meso)normal at ellipse parameter gamma, tilted by theta along the fibre (st = sin
 * theta, ct = cos theta), and, if flat is not NULL, the untilted one: both from one sine and
 * cosine of gamma. */
static void sphg_pair(double st, double ct, double gamma, double b, v3 *tilted, v3 *flat)
{
    double sg = sin(gamma), cg = cos(gamma);
    double sp = sg, cp = cg;
    if (b != 1.0 && fabs(cg) >= ABRDF__HUANG_ELLIPSE_COS_MIN) {
        double tp = b * sg / cg;
        cp = (cg > 0.0 ? 1.0 : -1.0) / sqrt(tp * tp + 1.0);
        sp = cp * tp;
    }
    *tilted = mk(sp * ct, st, cp * ct);
    if (flat) *flat = mk(sp, 0.0, cp);
}

/* Relative arc length of the ellipse at gamma (e2 = 1 - b^2). */
static double arc_length(double e2, double gamma)
{
    double s = sin(gamma);
    return abrdf__safe_sqrt(1.0 - e2 * s * s);
}

/* ---- GGX pieces (alpha2 = alpha^2), height-correlated Smith ----------------------- */
/* GGX D from the squared cosine, for a normal known to face the half vector. */
static double ggx_d_sq(double alpha2, double c2)
{
    double k = 1.0 + (alpha2 - 1.0) * c2;
    return alpha2 / (ABRDF__PI * k * k);
}

static double ggx_d(double alpha2, double c) { return c > 0.0 ? ggx_d_sq(alpha2, c * c) : 0.0; }

static double ggx_lambda(double alpha2, double c)
{
    double c2 = c * c;
    if (!(c2 > 0.0)) return ABRDF__HUANG_LAMBDA_GRAZING; /* grazing: fully shadowed */
    return 0.5 * (sqrt(1.0 + alpha2 * (1.0 - c2) / c2) - 1.0);
}

static double ggx_g(double alpha2, double ci, double co)
{
    return 1.0 / (1.0 + ggx_lambda(alpha2, ci) + ggx_lambda(alpha2, co));
}

/* G2 / G1(in): the masking of the outgoing side given the incoming side is visible. */
static double ggx_go(double alpha2, double ci, double co)
{
    double li = ggx_lambda(alpha2, ci), lo = ggx_lambda(alpha2, co);
    return (1.0 + li) / (1.0 + li + lo);
}

/* Heitz 2018, "Sampling the GGX distribution of visible normals": maps (u1, u2) in the unit
 * square to a microfacet normal distributed as the VNDF of direction wi about normal wm.
 * Used here as a change of variables for deterministic quadrature, not for sampling. */
/* What the map of one (wi, wm) pair shares between its nodes: the basis around wm and the
 * stretched view direction. A quadrature over many nodes of one pair builds it once. */
typedef struct vndf_frame {
    double alpha;
    v3 s, t, wm;   /* orthonormal basis around wm */
    v3 vh, t1, t2; /* stretched wi and the basis around it */
    double sh;     /* 0.5 (1 + vh.z) */
} vndf_frame;

static void vndf_frame_make(double alpha, v3 wi, v3 wm, vndf_frame *f);
static v3 vndf_frame_node(const vndf_frame *f, double p1, double p2);

/* The disc point of node (u1, u2), r = sqrt(u1) at angle 2 pi u2: what vndf_map_node takes.
 * A quadrature evaluates it once per node (vndf_nodes), not once per use. */
static void vndf_disc(double u1, double u2, double p[2])
{
    double r = sqrt(u1), ph = 2.0 * ABRDF__PI * u2;
    p[0] = r * cos(ph);
    p[1] = r * sin(ph);
}

static v3 vndf_map(double alpha, v3 wi, v3 wm, double u1, double u2)
{
    double p[2];
    vndf_frame f;
    vndf_disc(u1, u2, p);
    vndf_frame_make(alpha, wi, wm, &f);
    return vndf_frame_node(&f, p[0], p[1]);
}

/* The disc points of the n x n midpoint grid, node j at ((j / n + 0.5) / n, (j % n + 0.5) / n). */
static void vndf_nodes(int n, double (*p)[2])
{
    for (int j = 0; j < n * n; ++j) vndf_disc((j / n + 0.5) / n, (j % n + 0.5) / n, p[j]);
}

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
    f->s = s, f->t = t, f->wm = wm;
    f->vh = vh, f->t1 = t1, f->t2 = cross(vh, t1);
    f->sh = 0.5 * (1.0 + vh.z);
}

static v3 vndf_frame_node(const vndf_frame *f, double p1, double p2)
{
    const double alpha = f->alpha, sh = f->sh;
    p2 = (1.0 - sh) * abrdf__safe_sqrt(1.0 - p1 * p1) + sh * p2;
    double p3 = abrdf__safe_sqrt(1.0 - p1 * p1 - p2 * p2);
    v3 nh = add(add(scl(f->t1, p1), scl(f->t2, p2)), scl(f->vh, p3));
    v3 ne = mk(alpha * nh.x, alpha * nh.y, fmax(0.0, nh.z));
    ne = scl(ne, 1.0 / len(ne));
    return add(add(scl(f->s, ne.x), scl(f->t, ne.y)), scl(f->wm, ne.z));
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

/* Cycles' TRRT+ estimate: the geometric series of further internal bounces. */
static double trrt(double t1, double r2, double a)
{
    double tavg = fmax(1.0 - r2, ABRDF__HUANG_TAVG_MIN);
    return t1 * r2 * r2 * tavg * a * a * a / (1.0 - a * (1.0 - tavg));
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
 * and z axes depend only on alpha and eta: energy_axes_of computes them once per
 * evaluation, energy_scale_at looks up one cosine mu. */
typedef struct energy_axes {
    const double *t; /* the table for this relative index */
    double x, z;     /* sqrt(alpha), the table's z axis for this relative index */
} energy_axes;

static energy_axes energy_axes_of(const abrdf__huang *m, double eta)
{
    energy_axes a;
    a.t = eta < 1.0 ? abrdf__hair_glass_inv_e : abrdf__hair_glass_e;
    a.x = sqrt(m->alpha);
    a.z = sqrt(fabs((eta - 1.0) / (eta + 1.0)));
    return a;
}

static double energy_scale_at(const abrdf__huang *m, const energy_axes *a, double mu)
{
    if (!m->compensate) return 1.0;
    double e = table_read(a->t, a->x, mu, a->z);
    return 1.0 / fmax(e, ABRDF__HAIR_E_MIN);
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
    double b = m->b, a2 = m->alpha * m->alpha, e2 = 1.0 - b * b;
    double res = (hi - lo) / n, sum = 0.0;
    energy_axes ax = energy_axes_of(m, m->eta);
    const double st = sin(m->tilt), ct = cos(m->tilt);
    for (int i = 0; i <= n; ++i) {
        double gm = lo + i * res;
        v3 wm;
        sphg_pair(st, ct, gm, b, &wm, NULL);
        double w = (i == 0 || i == n) ? 0.5 : (i % 2 + 1);
        double c = dot(wm, wh);
        sum += w * ggx_d_sq(a2, c * c) * ggx_g(a2, dot(wm, wi), dot(wm, wo)) * arc_length(e2, gm) *
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
static double dgamma_dh(double g, double b, double sp_i, double cp_i)
{
    double radius = sqrt(fmax(ABRDF__HUANG_RADIUS2_MIN, 1.0 - (1.0 - b * b) * sp_i * sp_i));
    return radius / fabs(cp_i * cos(g) + b * sp_i * sin(g));
}

/* Eq. 12 in Cycles' quadrature (cycles_nodes, tests only): Simpson over h in [h0, h1] (units
 * of the projected radius) with steps <= 0.7 alpha / refine, each node weighted by dgamma/dh
 * and counted when wi and wo see the half vector and the untilted normal; D from the squared
 * cosine, as Cycles. */
static double lobe_r_cycles(const abrdf__huang *m, v3 wi, v3 wo, double h0, double h1, double sp_i,
                            double cp_i)
{
    const double b = m->b, a2 = m->alpha * m->alpha, e2 = 1.0 - b * b;
    v3 wh = add(wi, wo);
    double l = len(wh);
    if (!(l > 0.0)) return 0.0;
    wh = scl(wh, 1.0 / l);
    int n = 2 * (int)ceil((h1 - h0) / (0.7 * m->alpha) * 0.5) * m->refine;
    double res = (h1 - h0) / n, sum = 0.0;
    energy_axes ax = energy_axes_of(m, m->eta);
    const double st = sin(m->tilt), ct = cos(m->tilt);
    for (int i = 0; i <= n; ++i) {
        double g = h_to_gamma(h0 + i * res, b, wi);
        v3 wm, flat;
        sphg_pair(st, ct, g, b, &wm, NULL);
        flat = mk(wm.x, 0.0, wm.z);
        if (!visible2(wi, wo, flat, wh)) continue;
        double w = ((i == 0 || i == n) ? 0.5 : (i % 2 + 1)) * dgamma_dh(g, b, sp_i, cp_i);
        double c = dot(wm, wh);
        sum += w * ggx_d_sq(a2, c * c) * ggx_g(a2, dot(wm, wi), dot(wm, wo)) * arc_length(e2, g) *
               energy_scale_at(m, &ax, dot(wm, wi));
    }
    return 0.25 * fresnel(dot(wi, wh), m->eta, NULL) * sum * 2.0 / 3.0 * res;
}

/* What lobes_residual's terms share: the fibre, the directions and per-evaluation constants. */
typedef struct residual_ctx {
    const abrdf__huang *m;
    v3 wi, wo;
    double b, inv_eta, a2, e2; /* e2 = 1 - b^2 */
    double st, ct;             /* sin and cos of the cuticle tilt; the exit's: -st, ct */
    energy_axes ax_out;        /* the energy table's axes leaving the fibre */
    unsigned lobes;
} residual_ctx;

/* A Simpson node on the fibre's cross-section: the entry mesonormals at gamma gmi. */
typedef struct ring_node {
    double gmi;
    v3 wmi, wmi_;
    double cos_mi1, proj, scale1; /* wi's cosine, projected width (TRRT+), entry energy scale */
    double weight;                /* Simpson weight */
} ring_node;

/* A path entering the fibre through the microfacet wh1 and crossing it to the mesonormal
 * pair at gmt. */
typedef struct entry_path {
    v3 wt, wmt, wmt_; /* refracted direction, exit mesonormals */
    double gmt, phi_t;
    double t1, scale2, g1o, cos_mo1, cos_mi2;
    double at[3]; /* absorption along the chord */
    double wgt;   /* Simpson weight times the entry node's */
} entry_path;

/* The path through the entry microfacet wh1: 1, or 0 when light does not enter there. */
static int entry_path_make(const residual_ctx *c, const ring_node *r, v3 wh1, double w1,
                           entry_path *e)
{
    const abrdf__huang *m = c->m;
    const double b = c->b;
    v3 wi = c->wi;
    double cos_hi1 = dot(wi, wh1);
    if (!(cos_hi1 > 0.0)) return 0;
    double cos_t1;
    e->t1 = 1.0 - fresnel(cos_hi1, m->eta, &cos_t1);
    v3 wt = e->wt = refract_dir(wi, wh1, cos_t1, c->inv_eta);
    e->phi_t = dir_phi(wt);
    e->gmt = 2.0 * to_phi(e->phi_t, b) - r->gmi;
    sphg_pair(-c->st, c->ct, e->gmt, b, &e->wmt, &e->wmt_);
    e->cos_mo1 = dot(neg(wt), r->wmi), e->cos_mi2 = dot(neg(wt), e->wmt);
    /* wi sees wh1 (cos_hi1 > 0) and, on [g0, g0 + gr], both mesonormals: that range
     * is built from them, so testing wi.wmi_ > 0 again only let a 1e-16 rounding drop
     * the end nodes, where it is 0 (S jumped). The refracted ray is tested here. */
    if (!(dot(neg(wt), wh1) > 0.0 && dot(neg(wt), r->wmi) > 0.0 && dot(neg(wt), r->wmi_) > 0.0))
        return 0;
    e->g1o = ggx_go(c->a2, r->cos_mi1, e->cos_mo1);
    e->scale2 = energy_scale_at(m, &c->ax_out, e->cos_mi2);
    double ct_t = fmax(cos_theta(wt), ABRDF__HAIR_COS_MIN);
    double chord = len(add(to_point(r->gmi, b), neg(to_point(e->gmt + ABRDF__PI, b))));
    for (int k = 0; k < 3; ++k)
        e->at[k] = m->sigma_a[k] > 0.0 ? exp(-m->sigma_a[k] / ct_t * chord) : 1.0;
    e->wgt = r->weight * w1;
    return 1;
}

/* TT: exit through the microfacet with generalised half vector wh2 (Eq. 13). */
static void tt_add(const residual_ctx *c, const ring_node *r, const entry_path *e, double s_tt[3])
{
    const double a2 = c->a2, inv_eta = c->inv_eta;
    v3 wt = e->wt, wo = c->wo;
    /* exit possible only if wo is within the critical cone */
    if (!(dot(wo, wt) >= inv_eta - ABRDF__HUANG_CRITICAL_TOL)) return;
    v3 wh2 = add(neg(wt), scl(wo, inv_eta));
    double l2 = dot(wh2, wh2);
    if (!(l2 > ABRDF__HUANG_HALF_LEN2_MIN)) return;
    double rn = 1.0 / sqrt(l2);
    wh2 = scl(wh2, rn);
    double cos_mh2 = dot(e->wmt, wh2);
    if (!(cos_mh2 >= 0.0)) return;
    double cos_hi2 = dot(neg(wt), wh2), cos_ho2 = dot(neg(wo), wh2);
    double t2 = (1.0 - fresnel(cos_hi2, inv_eta, NULL)) * e->scale2;
    double v = e->wgt * e->t1 * r->scale1 * t2 * ggx_d(a2, cos_mh2) * e->g1o *
               ggx_g(a2, e->cos_mi2, dot(neg(wo), e->wmt)) / e->cos_mo1 * r->cos_mi1 * cos_hi2 *
               cos_ho2 * rn * rn * arc_length(c->e2, e->gmt);
    if (isfinite(v))
        for (int k = 0; k < 3; ++k) s_tt[k] += v * e->at[k]; /* Eq. 13 */
}

/* TRT through the internal microfacet wh2, exit at wh3 (Eq. 14), and TRRT+ where the path
 * stays inside; wgt2: the node's weight. */
static void trt_add(const residual_ctx *c, const ring_node *r, const entry_path *e, v3 wh2,
                    double wgt2, double s_trt[3], double s_trrt[3])
{
    const abrdf__huang *m = c->m;
    const double a2 = c->a2, b = c->b, inv_eta = c->inv_eta;
    v3 wt = e->wt, wo = c->wo;
    double cos_hi2 = dot(neg(wt), wh2);
    if (!(cos_hi2 > 0.0)) return;
    double r2f = fresnel(cos_hi2, inv_eta, NULL), r2 = r2f * e->scale2;
    v3 wtr = neg(reflect_dir(wt, wh2));
    double rr[3];
    for (int k = 0; k < 3; ++k) rr[k] = wgt2 * r->proj * trrt(e->t1, r2f, e->at[k]);
    /* total internal reflection */
    if (dot(neg(wtr), wo) < inv_eta - ABRDF__HUANG_CRITICAL_TOL) {
        for (int k = 0; k < 3; ++k) s_trrt[k] += rr[k];
        return;
    }
    if (!visible2(neg(wt), neg(wtr), e->wmt, wh2) || !visible2(neg(wt), neg(wtr), e->wmt_, wh2))
        return;
    double phi_tr = dir_phi(wtr);
    double gmtr = r->gmi - 2.0 * (to_phi(e->phi_t, b) - to_phi(phi_tr, b)) + ABRDF__PI;
    v3 wmtr, wmtr_;
    sphg_pair(-c->st, c->ct, gmtr, b, &wmtr, &wmtr_);
    v3 wh3 = add(wtr, scl(wo, inv_eta));
    double l3 = dot(wh3, wh3);
    if (!(l3 > ABRDF__HUANG_HALF_LEN2_MIN)) return;
    double rn3 = 1.0 / sqrt(l3);
    wh3 = scl(wh3, rn3);
    double cos_mh3 = dot(wmtr, wh3);
    if (cos_mh3 < 0.0 || !visible2(wtr, neg(wo), wmtr, wh3) ||
        !visible2(wtr, neg(wo), wmtr_, wh3)) {
        for (int k = 0; k < 3; ++k) s_trrt[k] += rr[k];
        return;
    }
    double cos_hi3 = dot(wh3, wtr), cos_ho3 = dot(wh3, neg(wo));
    double cos_mi3 = dot(wmtr, wtr), cos_mo2 = dot(e->wmt, neg(wtr));
    double t3 = (1.0 - fresnel(cos_hi3, inv_eta, NULL)) * energy_scale_at(m, &c->ax_out, cos_mi3);
    double ct_tr = fmax(cos_theta(wtr), ABRDF__HAIR_COS_MIN);
    double chord2 = len(add(to_point(gmtr, b), neg(to_point(e->gmt, b))));
    double v = wgt2 * e->t1 * r->scale1 * r2 * t3 * ggx_d(a2, cos_mh3) * e->g1o *
               ggx_go(a2, e->cos_mi2, cos_mo2) * ggx_g(a2, cos_mi3, dot(wmtr, neg(wo))) /
               (e->cos_mo1 * cos_mo2) * r->cos_mi1 * e->cos_mi2 * cos_hi3 * cos_ho3 * rn3 * rn3 *
               arc_length(c->e2, gmtr);
    if (isfinite(v) && (c->lobes & 4u))
        for (int k = 0; k < 3; ++k) {
            double atr = m->sigma_a[k] > 0.0 ? exp(-m->sigma_a[k] / ct_tr * chord2) : 1.0;
            s_trt[k] += v * e->at[k] * atr; /* Eq. 14 */
        }
    for (int k = 0; k < 3; ++k) s_trrt[k] += rr[k];
}

/* TT + TRT + TRRT+ (RGB): Simpson over h, nested midpoint rules over the VNDF squares. */
static void lobes_residual(const abrdf__huang *m, v3 wi, v3 wo, double g0, double gr, double h0,
                           double h1, double sp_i, double cp_i, unsigned lobes, double out[3])
{
    const double b = m->b, eta = m->eta, inv_eta = 1.0 / eta, al = m->alpha;
    const int n1 = m->n1, n2 = m->n2;
    const double w1 = 1.0 / (n1 * n1), w2 = 1.0 / (n2 * n2);
    double s_tt[3] = {0, 0, 0}, s_trt[3] = {0, 0, 0}, s_trrt[3] = {0, 0, 0};
    out[0] = out[1] = out[2] = 0.0;
    if (n1 * n1 > ABRDF__HUANG_NODES_MAX || n2 * n2 > ABRDF__HUANG_NODES_MAX) return;
    /* Per evaluation, not per node: the VNDF grids' disc points and the energy tables' axes. */
    double node1[ABRDF__HUANG_NODES_MAX][2], node2[ABRDF__HUANG_NODES_MAX][2];
    vndf_nodes(n1, node1);
    vndf_nodes(n2, node2);
    energy_axes ax_in = energy_axes_of(m, eta);
    residual_ctx c = {.m = m,
                      .wi = wi,
                      .wo = wo,
                      .b = b,
                      .inv_eta = inv_eta,
                      .a2 = al * al,
                      .e2 = 1.0 - b * b,
                      .st = sin(m->tilt),
                      .ct = cos(m->tilt),
                      .ax_out = energy_axes_of(m, inv_eta),
                      .lobes = lobes};
    /* Cycles' quadrature (tests only): Simpson over h, not gamma */
    const int ch = (m->cycles_nodes & ABRDF__HUANG_CYCLES_H) != 0;
    int n = ch ? 2 * (int)ceil((h1 - h0) / (0.8 * al) * 0.5) * m->refine
               : simpson_intervals(0.8 * al, m->refine);
    double res = ch ? (h1 - h0) / n : gr / n;
    for (int i = 0; i <= n; ++i) {
        ring_node r;
        r.gmi = ch ? h_to_gamma(h0 + i * res, b, wi) : g0 + i * res;
        sphg_pair(c.st, c.ct, r.gmi, b, &r.wmi, &r.wmi_);
        /* The range is built so that wi sees every tilted mesonormal on it: cos_mi1 >= 0,
         * and 0 at the ends when the tilt hides the silhouette. Skipping cos_mi1 <= 0 let a
         * 1e-16 rounding drop an end node, whose TRRT+ (weighted by proj, not cos_mi1) is
         * not 0: S jumped. The VNDF map is continuous through cos_mi1 = 0. */
        r.cos_mi1 = fmax(dot(wi, r.wmi), 0.0);
        r.weight = (i == 0 || i == n) ? 0.5 : (i % 2 + 1);
        if (ch) r.weight *= dgamma_dh(r.gmi, b, sp_i, cp_i);
        /* Projected width of this surface element seen from wi, |dh/dgamma| cos(theta_i):
         * the light TRRT+ receives here (R, TT, TRT carry it through cos_mi1). */
        r.proj = (m->cycles_nodes & ABRDF__HUANG_CYCLES_TRRT)
                     ? 2.0 / ABRDF__PI
                     : fabs(cp_i * cos(r.gmi) + b * sp_i * sin(r.gmi)) * cos_theta(wi);
        r.scale1 = energy_scale_at(m, &ax_in, r.cos_mi1); /* depends on the entry node only */
        vndf_frame f1;
        vndf_frame_make(al, wi, r.wmi, &f1);
        for (int j1 = 0; j1 < n1 * n1; ++j1) {
            entry_path e;
            if (!entry_path_make(&c, &r, vndf_frame_node(&f1, node1[j1][0], node1[j1][1]), w1, &e))
                continue;
            if (lobes & 2u) tt_add(&c, &r, &e, s_tt);
            if (!(lobes & 12u) || !(e.cos_mi2 > 0.0)) continue;
            /* TRT and TRRT+: internal reflection at wh2 (n2 x n2 VNDF nodes) */
            vndf_frame f2;
            vndf_frame_make(al, neg(e.wt), e.wmt, &f2);
            for (int j2 = 0; j2 < n2 * n2; ++j2)
                trt_add(&c, &r, &e, vndf_frame_node(&f2, node2[j2][0], node2[j2][1]), e.wgt * w2,
                        s_trt, s_trrt);
        }
    }
    double mlong =
        longitudinal_m(sin_theta(wi), cos_theta(wi), sin_theta(wo), cos_theta(wo), 4.0 * al);
    double k = 2.0 / 3.0 * res;
    for (int i = 0; i < 3; ++i) {
        double trrt_term = (lobes & 8u) ? s_trrt[i] * mlong / (2.0 * ABRDF__PI) : 0.0;
        out[i] = ((s_tt[i] + s_trt[i]) * inv_eta * inv_eta + trrt_term) * k;
    }
}

void abrdf__huang_fibre(const abrdf__huang *m, const double wi_[3], const double wo_[3],
                        unsigned lobes, double s[3])
{
    s[0] = s[1] = s[2] = 0.0;
    /* Cycles' convention: its "wi" is the viewer (our wo), its "wo" the light (our wi). */
    v3 wi = mk(wo_[1], wo_[0], wo_[2]), wo = mk(wi_[1], wi_[0], wi_[2]);
    double ci = cos_theta(wi);
    if (!(ci > ABRDF__HAIR_COS_MIN) || !(cos_theta(wo) > 0.0)) return;
    double b = m->b, e2 = 1.0 - b * b;
    double tan_tilt = tan(m->tilt);
    if (tan_tilt * sin_theta(wo) / cos_theta(wo) < -1.0) return; /* exit mesonormal hidden */
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
    double r = !(lobes & 1u) ? 0.0
               : (m->cycles_nodes & ABRDF__HUANG_CYCLES_H)
                   ? lobe_r_cycles(m, wi, wo, hmin, hmax, sp_i, cp_i)
                   : lobe_r(m, wi, wo, g0, g1 - g0);
    double res[3] = {0, 0, 0};
    if (lobes & 14u) lobes_residual(m, wi, wo, g0, g1 - g0, hmin, hmax, sp_i, cp_i, lobes, res);
    for (int c = 0; c < 3; ++c) s[c] = (r + res[c]) / area;
}

void abrdf__huang_eval(const abrdf__huang *m, const double wi[3], const double wo[3], double f[3])
{
    f[0] = f[1] = f[2] = 0.0;
    if (!(wi[2] > 0.0 && wo[2] > 0.0)) return;
    double s[3];
    abrdf__huang_fibre(m, wi, wo, 15u, s);
    for (int c = 0; c < 3; ++c) f[c] = s[c] / wi[2]; /* f_r = S / |N.wi| */
}
