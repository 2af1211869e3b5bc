/* test_grid.h - what the property suites (invariants, stability) share: parameter sets built
 * from each model's registry metadata (so models added later are covered without editing
 * the tests), direct access to parameter fields (to write out-of-range values that
 * abrdf_param_set would refuse), a deterministic random source, and the directional-albedo
 * quadrature of the white-furnace test. */
#ifndef ABRDF_TEST_GRID_H
#define ABRDF_TEST_GRID_H
#include "abrdf.h"

/* Which values a parameter set draws from (per parameter name, tg_values in test_grid.c). */
typedef enum tg_kind {
    TG_TYPICAL, /* values a renderer uses: invariants (reciprocity, float == double) */
    TG_FURNACE, /* unit weights, lobes the quadrature resolves: white furnace */
    TG_HARD     /* the range ends and the hard values: stability */
} tg_kind;

typedef struct tg_set {
    abrdf_params p;
    char label[160]; /* "n=100 f0=1": the parameters that differ between the sets */
} tg_set;

/* Every combination of the kind's values of the parameters `model` uses (values outside the
 * model's range dropped). If the product exceeds max, the first max combinations of a
 * one-parameter-at-a-time walk followed by deterministic random combinations. Returns the
 * number of sets written. */
int tg_param_sets(abrdf_model model, tg_kind kind, tg_set *out, int max);

/* Address of parameter `id` inside p (double or int, see abrdf_param_info.kind); NULL for a
 * parameter this helper does not know (then the test says so and fails). */
void *tg_param_ptr(abrdf_params *p, int id);

/* xorshift64*: deterministic, reproducible on every platform. */
typedef struct tg_rng {
    unsigned long long s;
} tg_rng;
double tg_uniform(tg_rng *r);                 /* [0, 1) */
void tg_sphere(tg_rng *r, double out[3]);     /* uniform on the unit sphere */
void tg_hemisphere(tg_rng *r, double out[3]); /* uniform on the upper hemisphere */

/* Mirror of w about the normal +z. */
void tg_mirror(const double w[3], double out[3]);

/* Directional albedo rho(wi) = int f_r(wi, wo) cos_o dw_o over the upper hemisphere, largest
 * RGB channel, by a product rule: composite 8-point Gauss-Legendre in mu = cos(theta_o)
 * (`panels` uniform panels on [0, 1] plus panels graded geometrically towards the mirror
 * direction's mu) times the trapezoid rule in a smooth periodic reparametrisation of phi_o
 * that clusters `nphi` points around the mirror azimuth (spectrally accurate for smooth
 * lobes).
 * Returns -1 if an evaluation fails. `evals` (if not NULL) is increased by the count. */
double tg_albedo(abrdf_model model, const abrdf_params *p, const double wi[3], int panels, int nphi,
                 long *evals);

/* tg_albedo refined (panels, nphi doubled) until two successive levels agree to within
 * `tol`, starting at (4, 32), at most `max_level` doublings. Returns the finer value;
 * *diff receives the last difference (converged if <= tol), *level the doublings used. */
double tg_albedo_converged(abrdf_model model, const abrdf_params *p, const double wi[3], double tol,
                           int max_level, double *diff, int *level, long *evals);

#endif
