/* belcour_tables.h - axes of the precomputed tables of Belcour's layered model, shared by
 * the generator (tools/gen/gen_belcour_tables.c) and the library (layered_belcour.c), so that
 * the two cannot disagree. The data live in belcour_tables.c (generated).
 *
 * FGD[cos][alpha][eta][kappa]  directional albedo of one GGX reflection with exact Fresnel
 * TIR[cos][alpha][eta]         fraction of visible microfacets that let light out of the
 *                              dense side (eta = n_outside / n_inside < 1; 1 for eta >= 1)
 * Axes (node i of N):
 *   cos    cell centres (i + 0.5) / N            (uniform in cos theta)
 *   alpha  i / (N - 1), alpha = alpha_g in [0, 1] (uniform; 0 is a smooth interface)
 *   eta    FGD: ETA_MIN (ETA_MAX/ETA_MIN)^(i/(N-1)), log-uniform, eta = 1 is the middle node
 *          TIR: TIR_ETA_MIN + (1 - TIR_ETA_MIN) i / (N - 1)
 *   kappa  KAPPA_MAX (i / (N - 1))^2              (dense near the dielectric kappa = 0)
 * Interpolation is multilinear with indices clamped to the table (as Belcour's code). */
#ifndef ABRDF_BELCOUR_TABLES_H
#define ABRDF_BELCOUR_TABLES_H
#include <math.h>

#define ABRDF__FGD_NCOS 24
#define ABRDF__FGD_NALPHA 16
#define ABRDF__FGD_NETA 25
#define ABRDF__FGD_NKAPPA 12
#define ABRDF__FGD_ETA_MIN 0.25
#define ABRDF__FGD_ETA_MAX 4.0
#define ABRDF__FGD_KAPPA_MAX 10.0
#define ABRDF__FGD_SIZE (ABRDF__FGD_NCOS * ABRDF__FGD_NALPHA * ABRDF__FGD_NETA * ABRDF__FGD_NKAPPA)

#define ABRDF__TIR_NCOS 24
#define ABRDF__TIR_NALPHA 16
#define ABRDF__TIR_NETA 16
#define ABRDF__TIR_ETA_MIN 0.25
#define ABRDF__TIR_SIZE (ABRDF__TIR_NCOS * ABRDF__TIR_NALPHA * ABRDF__TIR_NETA)

/* Row-major: index = ((i_cos * NALPHA + i_alpha) * NETA + i_eta) * NKAPPA + i_kappa. */
extern const float abrdf__fgd_table[ABRDF__FGD_SIZE];
extern const float abrdf__tir_table[ABRDF__TIR_SIZE];

/* Node values of each axis (the generator evaluates there). */
static inline double abrdf__bt_cos(int i, int n) { return (i + 0.5) / n; }
static inline double abrdf__bt_alpha(int i, int n) { return (double)i / (n - 1); }
static inline double abrdf__bt_fgd_eta(int i)
{
    return ABRDF__FGD_ETA_MIN *
           pow(ABRDF__FGD_ETA_MAX / ABRDF__FGD_ETA_MIN, (double)i / (ABRDF__FGD_NETA - 1));
}
static inline double abrdf__bt_fgd_kappa(int i)
{
    double u = (double)i / (ABRDF__FGD_NKAPPA - 1);
    return ABRDF__FGD_KAPPA_MAX * u * u;
}
static inline double abrdf__bt_tir_eta(int i)
{
    return ABRDF__TIR_ETA_MIN + (1.0 - ABRDF__TIR_ETA_MIN) * i / (ABRDF__TIR_NETA - 1);
}

/* Continuous index of a value on each axis (inverse of the node maps). */
static inline double abrdf__bt_x_cos(double c, int n) { return c * n - 0.5; }
static inline double abrdf__bt_x_alpha(double a, int n) { return a * (n - 1); }
static inline double abrdf__bt_x_fgd_eta(double eta)
{
    return log(eta / ABRDF__FGD_ETA_MIN) / log(ABRDF__FGD_ETA_MAX / ABRDF__FGD_ETA_MIN) *
           (ABRDF__FGD_NETA - 1);
}
static inline double abrdf__bt_x_fgd_kappa(double k)
{
    return sqrt(k > 0.0 ? k / ABRDF__FGD_KAPPA_MAX : 0.0) * (ABRDF__FGD_NKAPPA - 1);
}
static inline double abrdf__bt_x_tir_eta(double eta)
{
    return (eta - ABRDF__TIR_ETA_MIN) / (1.0 - ABRDF__TIR_ETA_MIN) * (ABRDF__TIR_NETA - 1);
}

#endif
