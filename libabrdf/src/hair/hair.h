/* hair.h - the hair fibre models (Marschner 2003, Huang 2022) and their shared parts.
 *
 * FIBRE ON A SURFACE. The fibre runs along the local +x axis (the frame's tangent T); the
 * surface normal N = +z is the normal of the "ribbon" the fibre is drawn on, as in BRDF
 * Explorer's tangent-field evaluation and pbrt-v4's curve shading frame.
 *   sin(theta) = w.x          longitudinal angle, measured from the normal plane of T
 *   phi = atan2(w.z, w.y)     azimuth around T, phi = 0 along B = +y
 * Every model first computes the fibre scattering function S(wi, wo) in pbrt-v4's
 * convention: the radiance scattered by a unit length of fibre is the integral of
 * S(wi, wo) L(wi) dw_i over the whole sphere, so a lossless fibre has
 * integral S dw_i = 1 (white furnace). abrdf returns f_r = S / |N.wi| (the renderer
 * multiplies by N.wi again), for wi and wo both above the ribbon, and 0 otherwise.
 *
 * Absorption is a cross-section coefficient sigma_a per unit fibre RADIUS (the radius is
 * 1), from the melanin parameters (abrdf__hair_sigma_a). */
#ifndef ABRDF_HAIR_H
#define ABRDF_HAIR_H
#include "abrdf_internal.h"

#define ABRDF__HAIR_DEG (ABRDF__PI / 180.0)

/* ---- shared helpers (hair_common.c) -------------------------------------------------- */

/* Melanin -> absorption sigma_a (RGB, per unit radius), Cycles' mapping (MODELS.md B7.2):
 *   m' = -ln(max(1 - melanin, 1e-4)), eumelanin = m'(1 - redness), pheomelanin = m' redness,
 *   sigma_a = eumelanin (0.506, 0.841, 1.653) + pheomelanin (0.343, 0.733, 1.924). */
void abrdf__hair_sigma_a(double melanin, double redness, double sigma[3]);

/* Exact dielectric Fresnel reflectance for one polarisation, relative index n = n_t / n_i
 * (any n > 0; total internal reflection gives 1), cosine of incidence c in [0, 1]. */
double abrdf__fresnel_s(double n, double c);
double abrdf__fresnel_p(double n, double c);
/* Unpolarised: (F_s + F_p) / 2 with the same index. */
double abrdf__fresnel_dielectric(double n, double c);

/* Unit-area Gaussian of standard deviation sd at x. */
double abrdf__gauss(double x, double sd);

/* Wrap an angle into (-pi, pi]. */
double abrdf__wrap_pi(double a);

/* Longitudinal sine/cosine and azimuth of a local direction (fibre along +x). */
void abrdf__fibre_angles(const double w[3], double *sin_t, double *cos_t, double *phi);

/* ---- Marschner et al. 2003 (hair_marschner.c) -------------------------------------- */

/* Per-lobe constants of the practical model, from the parameters. */
typedef struct abrdf__marschner {
    double eta;        /* index of refraction of the fibre */
    double aspect;     /* cross-section axis ratio a (TRT eccentricity trick) */
    double sigma_a[3]; /* absorption per unit radius */
    double alpha[3];   /* longitudinal shifts alpha_R, alpha_TT, alpha_TRT (rad) */
    double beta[3];    /* longitudinal widths beta_R, beta_TT, beta_TRT (rad) */
} abrdf__marschner;

void abrdf__marschner_setup(const abrdf_params *p, abrdf__marschner *m);

/* Longitudinal function M_p(theta_h) of lobe p (0 = R, 1 = TT, 2 = TRT), normalised as a
 * density in theta_r: integral M_p dtheta_r = 1 (hair_marschner.c explains why). */
double abrdf__marschner_mp(const abrdf__marschner *m, int p, double theta_h);

/* Attenuation A_p(h) (RGB) for Bravais indices eta1 (eta'), eta2 (eta'') and the
 * refracted longitudinal cosine cos_theta_t. */
void abrdf__marschner_ap(const abrdf__marschner *m, int p, double h, double eta1, double eta2,
                         double cos_theta_t, double a[3]);

/* Azimuthal function N_p(phi) (RGB) at longitudinal half-difference theta_d;
 * cos_phi_sum = cos(phi_i + phi_o) orients the elliptical cross-section (TRT only).
 * glint = 0 disables the TRT caustic smoothing (tests: the bare root sum). */
void abrdf__marschner_np(const abrdf__marschner *m, int p, double phi, double theta_d,
                         double cos_phi_sum, int glint, double n[3]);

/* The fibre scattering function S (pbrt convention, see the top of this file) for local
 * directions wi, wo anywhere on the sphere; lobes is a bit mask of R (1), TT (2), TRT (4). */
void abrdf__marschner_fibre(const abrdf__marschner *m, const double wi[3], const double wo[3],
                            unsigned lobes, double s[3]);

/* f_r for the surface from the model's setup (the dispatch entry, special.c). */
void abrdf__marschner_eval(const abrdf__marschner *m, const double wi[3], const double wo[3],
                           double f[3]);

/* ---- Huang, Hullin, Hanika 2022 (hair_huang.c) -------------------------------------- */

/* Default quadrature (the defaults of the entry_grid and internal_grid parameters): the
 * entry microfacet normal on an N1 x N1 grid of the VNDF square, the internal-reflection
 * normal (TRT) on N2 x N2 per entry node, each grid shifted by its own point of the R2
 * sequence (hair_huang.c, grid_shift; docs/MODELS.md, "Convergence" and "Convergence on an
 * image", gives their convergence, at one direction pair and on an image). */
#define ABRDF__HUANG_N1 6
#define ABRDF__HUANG_N2 3
/* Largest VNDF grid abrdf__huang_fibre takes: n1, n2 <= ABRDF__HUANG_GRID_MAX = 32 (the
 * range of the entry_grid and internal_grid parameters), so the convergence study
 * (docs/MODELS.md, "Convergence", 4x the default grids) fits; the grids' disc points then
 * take 40 KiB of stack. */
#define ABRDF__HUANG_GRID_MAX 32
#define ABRDF__HUANG_NODES_MAX (ABRDF__HUANG_GRID_MAX * ABRDF__HUANG_GRID_MAX)
/* The R2 sequence's steps 1/g and 1/g^2 (g = 1.32471795724474602596, the plastic number) in
 * units of 2^-16, which shift each VNDF grid (hair_huang.c, grid_shift). The first,
 * 49472 = 2^6 773, takes 1024 values modulo 2^16, so d1 repeats every 1024 grids (d2 still
 * differs): not within one evaluation at the default grids and r >= 0.16 (k < 1024), but at
 * entry grids of 9 and more (15 n1^2 internal grids at r = 0.3) and at r = 0.05 (k up to
 * 2915). An odd step (49471) measured no better on the convergence cylinder (docs/MODELS.md,
 * "What a converged reference costs"), and changing it changes every value of the model. */
#define ABRDF__HUANG_R2_A1 49472ul
#define ABRDF__HUANG_R2_A2 37345ul

/* Energy compensation tables (hair_tables.c, GENERATED by tools/gen/gen_hair_tables.c): the
 * single-scattering albedo E of a GGX dielectric interface, N^3 nodes indexed
 * [(z N + y) N + x] with x = sqrt(alpha), y = mu (cosine of incidence), z = F0^(1/4) of the
 * interface, every axis k/(N - 1); _e for eta > 1 (from outside), _inv_e for 1/eta. */
#define ABRDF__HAIR_E_N 16
extern const double abrdf__hair_glass_e[ABRDF__HAIR_E_N * ABRDF__HAIR_E_N * ABRDF__HAIR_E_N];
extern const double abrdf__hair_glass_inv_e[ABRDF__HAIR_E_N * ABRDF__HAIR_E_N * ABRDF__HAIR_E_N];

/* The albedo the tables hold, by an n x n midpoint rule over the GGX VNDF square. */
double abrdf__ggx_glass_albedo(double alpha, double mu, double eta, int n);

/* A tabulated residual (hair_huang_table.c, below): its sizes and the caller's values. */
typedef struct abrdf__huang_table {
    int nt, nv, np, sets;
    const double *v; /* abrdf__huang_table_count(nt, nv, np) values; NULL: no table */
} abrdf__huang_table;

typedef struct abrdf__huang {
    double eta;        /* index of refraction */
    double alpha;      /* GGX roughness (not squared), [0.001, 1] */
    double tilt;       /* cuticle tilt of the mesonormals (rad), = -cuticle_tilt */
    double b;          /* minor/major axis ratio, (0, 1] */
    double sigma_a[3]; /* absorption per unit (major) radius */
    int refine;        /* Simpson step divisor in h (1 = Cycles' steps) */
    int n1, n2;        /* VNDF grid sizes per dimension (entry, internal; shifted), <= 32
                          (ABRDF__HUANG_NODES_MAX; larger grids give no TT/TRT/TRRT+) */
    int compensate;    /* 1: divide each interaction by the glass albedo E (Cycles) */
    /* The energy tables at this alpha and eta: for a fixed roughness and index the 3-D
     * tables are 1-D in mu, node k at mu = k/(N - 1) (abrdf__huang_setup; a caller that
     * changes alpha or eta afterwards calls abrdf__huang_tables). */
    double e_in[ABRDF__HAIR_E_N];  /* entering the fibre (eta) */
    double e_out[ABRDF__HAIR_E_N]; /* leaving it (1/eta) */
    /* Tests only (the Cycles oracle, tests/ports/hair_huang_lobes.c): parts of Blender 5.0
     * Cycles' far-field quadrature, a bit mask. ABRDF__HUANG_CYCLES_H: Simpson nodes uniform
     * in h over the visible width clipped to +-ABRDF__HUANG_CYCLES_H_CLIP, weighted by
     * dgamma/dh, R's visibility tested per node (steps divided by refine). ABRDF__HUANG_CYCLES_TRRT:
     * TRRT+ weighted by the constant 2/pi. 0 (setup's value): the model. */
    unsigned cycles_nodes;
    /* Tests (tools/bench/hair_convergence.c, --shifts; test_hair_huang, shift_sets) and the
     * table's build (abrdf__huang_table_rows): which set of grid shifts. Set k adds
     * ABRDF__HUANG_SHIFT_SET_STEP k to every grid's index into the R2 sequence, after the
     * index's own wrap at 2^15. The sequence is additive
     * (shift(i + D) = shift(i) + shift(D) modulo 1, exactly in its 16-bit fixed point), so this
     * turns every shift of an evaluation by one vector: a Cranley-Patterson rotation of the
     * whole rule, which tells the error of the rule from the luck of where its shifts fall.
     * 0 (setup's value): the model. The tabulated huang averages sets 0 to sets - 1. */
    int shift_set;
    /* The residual read from a table (abrdf_prepare_huang_table) instead of integrated:
     * abrdf__huang_prepared_run reads it when table.v is set (setup: NULL); every other
     * function of hair_huang.c integrates. */
    abrdf__huang_table table;
} abrdf__huang;
/* The step 4111 turns the 8 sets by 8 different vectors in both coordinates (a step of 4096
 * would turn d2 alone: 4096 ABRDF__HUANG_R2_A1 is a multiple of 2^16). */
#define ABRDF__HUANG_SHIFT_SET_STEP 4111L
#define ABRDF__HUANG_SHIFT_SETS 8
#define ABRDF__HUANG_CYCLES_H 1u
#define ABRDF__HUANG_CYCLES_TRRT 2u

/* Lights per run: abrdf__huang_fibre_run and abrdf__huang_eval_run take up to this many
 * lights of one view (a shading point's lights; the batch path hands them over as runs). */
#define ABRDF__HUANG_RUN_MAX 32
/* abrdf__huang_fibre_wide takes up to this many: a table's build hands over its lights of one
 * view this many at a time, so the view's paths are built once for them (hair_huang_table.c;
 * at the default sizes 6 runs per row and shift set instead of 24 runs of 32). Their arrays
 * take 57 KiB of stack, a build about 124 KiB in all (256 lights were 3 % faster than 128
 * and take twice the arrays; 64, 12 % slower: one-off, the default table's build). */
#define ABRDF__HUANG_WIDE_MAX 128

void abrdf__huang_setup(const abrdf_params *p, abrdf__huang *m);
/* Fill m->e_in and m->e_out from m->alpha and m->eta (abrdf__huang_setup calls it). */
void abrdf__huang_tables(abrdf__huang *m);
/* Fibre function S (hair.h convention); lobes: R (1), TT (2), TRT (4), TRRT+ (8). */
void abrdf__huang_fibre(const abrdf__huang *m, const double wi[3], const double wo[3],
                        unsigned lobes, double s[3]);
/* S for count (1 to ABRDF__HUANG_RUN_MAX) lights wi[l] seen from one view wo: the same
 * values as count calls of abrdf__huang_fibre (the same bits), with the view's paths built
 * once (hair_huang.c, "the view's paths, then each light's exit"). */
void abrdf__huang_fibre_run(const abrdf__huang *m, int count, const double (*wi)[3],
                            const double wo[3], unsigned lobes, double (*s)[3]);
/* The same for count up to ABRDF__HUANG_WIDE_MAX lights (the same bits again). */
void abrdf__huang_fibre_wide(const abrdf__huang *m, int count, const double (*wi)[3],
                             const double wo[3], unsigned lobes, double (*s)[3]);
/* f_r for the surface from the model's setup, one pair or a run of count lights of one view,
 * integrated (hair_huang_surface.c). */
void abrdf__huang_eval(const abrdf__huang *m, const double wi[3], const double wo[3], double f[3]);
void abrdf__huang_eval_run(const abrdf__huang *m, int count, const double (*wi)[3],
                           const double wo[3], double (*f)[3]);

/* ---- huang tabulated (hair_huang_table.c; docs/MODELS.md, "A tabulated huang") --------
 * The residual TT + TRT + TRRT+ of a prepared huang on a grid of directions, each node the
 * mean of `sets` shift sets (shift_set 0 to sets - 1), read by cubic interpolation; R stays
 * the model's quadrature. The table is the caller's memory, abrdf__huang_table_count doubles
 * for nt theta nodes (view and light), nv azimuths of the view on [0, pi/2] (1: a round
 * fibre only) and np relative azimuths of the light. Rows (one per view node, nt nv of them)
 * are independent: abrdf__huang_table_rows fills [row0, row1), so a caller may split them
 * over threads. */
#define ABRDF__HUANG_TABLE_NT_MIN 4
#define ABRDF__HUANG_TABLE_NP_MIN 4
#define ABRDF__HUANG_TABLE_AXIS_MAX 256
#define ABRDF__HUANG_TABLE_SETS_MAX 64
#define ABRDF__HUANG_TABLE_VALUES_MAX 268435456.0 /* 2^28 values (2 GiB), header included */
/* The revision of what a table holds, in the table's keys: raise it with any change of the
 * values abrdf__huang_fibre_run gives (its rule, constants, Simpson steps) or of how
 * abrdf__huang_table_rows builds a table (its nodes, what it stores, how it averages), so that
 * a table kept in a file by a library before the change is refused (abrdf_prepare_huang_table). */
#define ABRDF__HUANG_REVISION 3

/* The public table's header (abrdf_huang_table_build): ABRDF__HUANG_TABLE_HEADER doubles
 * before the values, holding the sizes and two keys of m's setup; _ok: 1 if h is t's for m. */
#define ABRDF__HUANG_TABLE_HEADER 8
void abrdf__huang_table_header(const abrdf__huang *m, const abrdf__huang_table *t, double *h);
int abrdf__huang_table_header_ok(const abrdf__huang *m, const abrdf__huang_table *t,
                                 const double *h);
/* 1 if the sizes are in range for m (nv = 1 needs b = 1), else 0. */
int abrdf__huang_table_check(const abrdf__huang *m, int nt, int nv, int np, int sets);
long abrdf__huang_table_count(int nt, int nv, int np);
/* Fill rows row0 to row1 - 1 of v (t's sizes; t->v is not read). */
void abrdf__huang_table_rows(const abrdf__huang *m, const abrdf__huang_table *t, int row0, int row1,
                             double *v);
/* abrdf__huang_fibre_run and abrdf__huang_eval_run with the residual read from the table. */
void abrdf__huang_table_fibre_run(const abrdf__huang *m, const abrdf__huang_table *t, int count,
                                  const double (*wi)[3], const double wo[3], unsigned lobes,
                                  double (*s)[3]);
void abrdf__huang_table_eval_run(const abrdf__huang *m, const abrdf__huang_table *t, int count,
                                 const double (*wi)[3], const double wo[3], double (*f)[3]);
/* f_r of a prepared huang (the dispatch entries, special.c and eval_float.c): from m->table
 * when it is set, else abrdf__huang_eval_run (hair_huang_surface.c). */
void abrdf__huang_prepared_run(const abrdf__huang *m, int count, const double (*wi)[3],
                               const double wo[3], double (*f)[3]);

#endif /* ABRDF_HAIR_H */
