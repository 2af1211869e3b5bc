/* layered.h - the layered models, evaluated in double through special.c. */
#ifndef ABRDF_LAYERED_H
#define ABRDF_LAYERED_H
#include "abrdf_internal.h"
#include "belcour_tables.h"

/* What Weidlich-Wilkie's evaluation takes from the parameters alone (abrdf__ww_setup). */
enum { ABRDF__WW_MATCHED, ABRDF__WW_DIELECTRIC, ABRDF__WW_CONDUCTOR }; /* abrdf__ww.kind */
typedef struct abrdf__ww {
    int count; /* interfaces used: min(layer_count, ABRDF_MAX_LAYERS), none below a conductor */
    int kind[ABRDF_MAX_LAYERS];   /* eta = 1 and kappa = 0 (F = 0), kappa = 0, kappa > 0 */
    double eta[ABRDF_MAX_LAYERS]; /* eta and kappa per interface */
    double kappa[ABRDF_MAX_LAYERS];
    double eta2[ABRDF_MAX_LAYERS];    /* eta^2 */
    double a2[ABRDF_MAX_LAYERS];      /* alpha_g^2, alpha_g = max(r^2, ABRDF__ALPHA_G_MIN) */
    double inv_eta[ABRDF_MAX_LAYERS]; /* 1 / eta per interface */
    double sd[ABRDF_MAX_LAYERS][3];   /* sigma_a depth of the medium below each interface */
    int absorbs[ABRDF_MAX_LAYERS];    /* some channel of sd is > 0 */
    int grey[ABRDF_MAX_LAYERS];       /* its three channels are equal: one exp serves them */
    double base[3];                   /* the Lambert base kd / pi */
} abrdf__ww;
void abrdf__ww_setup(const abrdf_params *p, abrdf__ww *w);

/* Local-frame f_r of the Weidlich-Wilkie stack set up in w (Eq. 15), and of the Belcour stack
 * (Eq. 16) described by p->layer_count and p->layers[]; f = 0 for back-facing pairs. */
void abrdf__eval_weidlich_wilkie(const abrdf__ww *w, const double wi[3], const double wo[3],
                                 double f[3]);
/* The float batch b (abrdf_eval_prepared_batch's contract) at instruction-set level `level`
 * (isa.h), vectorised over the pairs; the double path's values to float rounding. */
void abrdf__ww_batch(const abrdf__ww *w, const abrdf_batch *b, int level);
/* A value's place on a table axis: the lower node i and the weight t of node i + 1. */
typedef struct abrdf__belcour_cell {
    int i;
    double t;
} abrdf__belcour_cell;

/* The corners of a table's trailing axes (FGD: eta and kappa; TIR: eta) fixed by one
 * interface, premixed: their n offsets from a (cos, alpha) node and their weights. */
typedef struct abrdf__belcour_mix {
    int n;
    int off[4];
    double w[4];
} abrdf__belcour_mix;

/* What Belcour's evaluation takes from the parameters alone, per interface, computed once
 * by abrdf__belcour_setup, not per evaluation: the variances of its reflection and of its
 * two transmissions, s(alpha) of the roughness (a pow each); its index and extinction on the
 * FGD table's axes and the index ratio of the interface above on the TIR table's (a log and
 * a sqrt); the two top interfaces' tables along cos at the roughness they are seen with. */
typedef struct abrdf__belcour {
    double s_r12[ABRDF_MAX_LAYERS], s_t12[ABRDF_MAX_LAYERS], s_t21[ABRDF_MAX_LAYERS];
    double inv_eta2[ABRDF_MAX_LAYERS];        /* 1 / eta^2 (Snell's law of the mean direction) */
    abrdf__belcour_mix fgd[ABRDF_MAX_LAYERS]; /* eta_k, kappa_k */
    abrdf__belcour_mix tir[ABRDF_MAX_LAYERS]; /* 1 / eta_{k-1}, for k >= 1 */
    int tir_dense[ABRDF_MAX_LAYERS];          /* 1 / eta_{k-1} < 1: TIR can occur (else 1) */
    /* Interfaces 0 and 1 are seen with a fixed roughness a_top: the variance through the
     * stack above them is 0 and s_T12 of interface 0 (the empty stack reflects nothing back,
     * so the direction drops out). Their FGD (and interface 1's TIR) then vary with cos
     * alone: the tables interpolated in every other axis, at each cos node. */
    double alpha_top0;                  /* a(s_R12) of interface 0 */
    double fgd_top[2][ABRDF__FGD_NCOS]; /* FGD(cos node, a_top, eta_k, kappa_k), k = 0, 1 */
    double tir_top1[ABRDF__TIR_NCOS];   /* TIR(cos node, a_top, 1 / eta_0) of interface 1 */
    int tops;     /* fgd_top and tir_top1 are filled (else their values come from the tables) */
    int channels; /* 1 when every medium absorbs the same in R, G and B (one channel is
                     carried and broadcast), else 3 */
} abrdf__belcour;
/* tables = 0 leaves out the tables along cos (tops = 0), which take longer to fill than
 * they save on one evaluation; evaluations give the same bits either way. */
void abrdf__belcour_setup(const abrdf_params *p, abrdf__belcour *b, int tables);
void abrdf__eval_belcour(const abrdf__belcour *b, const abrdf_params *p, const double wi[3],
                         const double wo[3], double f[3]);

/* Belcour's lobes (Eq. 16) for the mean direction of cosine cos_theta: energies e[k] (RGB)
 * and GGX roughnesses alpha[k] (alpha_g, floored at ABRDF__ALPHA_G_MIN), the same pass as
 * abrdf__eval_belcour makes at cos = H.L; returns the count (<= ABRDF_MAX_LAYERS). The
 * sampler calls it at cos = N.wo. */
int abrdf__belcour_lobes(const abrdf_params *p, double cos_theta, double e[][3], double alpha[]);

/* Belcour's precomputed tables, interpolated (belcour_tables.h gives their axes):
 * FGD = directional albedo of one GGX reflection with exact Fresnel, TIR = fraction of the
 * visible microfacets through which light can leave a rough interface from the dense side. */
double abrdf__belcour_fgd(double cos_theta, double alpha_g, double eta, double kappa);
double abrdf__belcour_tir(double cos_theta, double alpha_g, double eta);

#endif
