/* sample.h - importance sampling, the internals: elementary direction samplers ("lobes"),
 * the per-model mixtures built from them (one-sample MIS), in double, in the local frame
 * (N = +z, T = +x, B = +y; wo toward the viewer, wi toward the light, as in abrdf.h).
 *
 * A model's sampler is a MIXTURE of components, each with a selection probability that may
 * depend on wo (never on wi). abrdf_sample picks a component with u1 (then reuses u1, rescaled
 * to [0, 1), as pbrt-v4 does), draws wi from it, and returns the pdf of the whole mixture at
 * wi, sum_k P_k pdf_k(wi), so the weight f cos / pdf is exact whichever component drew the
 * sample (Veach 1997, Sec. 9.2.4: one-sample MIS, balance heuristic). Every component is a
 * density over the whole sphere that integrates to 1; directions below the surface are
 * returned with weight 0 (f_r = 0 there). docs/RENDERER.md, "Importance sampling" lists the
 * components per model, with the citations. */
#ifndef ABRDF_SAMPLE_H
#define ABRDF_SAMPLE_H
#include "abrdf_internal.h"
#include "measured.h"

/* ---- 1-D densities of the cosine c to an axis -----------------------------------------
 * Each is a density p(c) over c in [1 - T, 1], written in t = 1 - c (the angle to the axis
 * is theta with c = cos theta); a direction with azimuth uniform around the axis then has
 * the solid-angle density p(c) / (2 pi). */
typedef enum abrdf__dist_kind {
    ABRDF__DIST_UNIFORM,  /* p = 1/T on t in [0, T] */
    ABRDF__DIST_POW,      /* p = (n + 1) c^n on c in [0, 1]: Phong, Blinn-Phong */
    ABRDF__DIST_FM,       /* p ~ ((n/m)(c - 1) + 1)^m where the base is > 0: Table-1 power form */
    ABRDF__DIST_SCHLICK,  /* p ~ 1 / (1 + n t) on t in [0, 1]: Schlick's rational form */
    ABRDF__DIST_LINEAR,   /* p ~ 1 - a t on t in [0, min(1, 1/a)]: fkv */
    ABRDF__DIST_BECKMANN, /* p = 2 pi D_Beckmann(c) c (Walter et al. 2007) */
    ABRDF__DIST_GTR1      /* p = 2 pi D_GTR1(c) c (Burley 2012, App. B) */
} abrdf__dist_kind;

typedef struct abrdf__dist {
    abrdf__dist_kind kind;
    double n;     /* exponent (POW, FM, SCHLICK) */
    int m;        /* degree of the power form (FM) */
    double a;     /* slope (LINEAR), roughness alpha (BECKMANN, GTR1) */
    double t_max; /* support in t: [0, t_max] (set by abrdf__dist_setup) */
    double norm;  /* normalisation (set by abrdf__dist_setup) */
    double q;     /* FM: 1 - b_end^(m+1) */
} abrdf__dist;

/* Fill the derived fields for a density on c in [lo, 1] (lo = -1: the whole sphere about
 * the axis, lo = 0: a hemisphere). A lobe so flat over its support that its own inversion
 * would cancel (POW with n = 0; FM, SCHLICK and LINEAR varying by less than
 * ABRDF__SAMPLE_FLAT) becomes UNIFORM, the density it then equals to that accuracy. */
void abrdf__dist_setup(abrdf__dist *d, double lo);
/* Draw t = 1 - c from u in [0, 1); *s receives sin(theta) = sqrt(t (2 - t)). */
double abrdf__dist_sample(const abrdf__dist *d, double u, double *s);
/* Density p(c) at c with s2 = sin^2(theta) (passed separately: 1 - c^2 cancels near the
 * axis, where the peaked lobes live). */
double abrdf__dist_pdf(const abrdf__dist *d, double c, double s2);

/* ---- trimmed logistic (pbrt-v4's azimuthal density for hair, here also longitudinal) ---
 * Logistic density of scale s restricted to [a, b] and renormalised. */
double abrdf__tlogistic_sample(double s, double a, double b, double u);
double abrdf__tlogistic_pdf(double x, double s, double a, double b);
/* The untrimmed density and the mass of [a, b] under it (tlogistic_pdf is their ratio). */
double abrdf__logistic_pdf(double x, double s);
double abrdf__tlogistic_mass(double s, double a, double b);

/* ---- hair (sample_hair.c) ------------------------------------------------------------ */
#define ABRDF__HAIR_NODES 32 /* offsets h_k of the far-field proposal */

/* The R/TT/TRT proposal of a hair fibre for one wo: the probability of each (offset h_k,
 * lobe p) pair, per lobe the logistic centres and widths (sample_hair.c). */
typedef struct abrdf__hair_sampler {
    double theta_o, phi_o;             /* fibre angles of wo (hair.h) */
    double eta;                        /* index of refraction */
    double mu[3], s_theta[3];          /* theta_i centre and logistic scale per lobe */
    double s_phi[3];                   /* azimuthal logistic scale per lobe */
    double asin_h[ABRDF__HAIR_NODES];  /* asin(h_k) */
    double prob[ABRDF__HAIR_NODES][3]; /* P(node k, lobe p), summing to 1 */
} abrdf__hair_sampler;

/* Setup for marschner or huang (their parameters' meaning differs) and local wo above the
 * ribbon. The proposal only draws directions above it (wi.z >= 0). */
void abrdf__hair_sampler_setup(abrdf_model model, const abrdf_params *p, const double wo[3],
                               abrdf__hair_sampler *h);
void abrdf__hair_sampler_sample(const abrdf__hair_sampler *h, double u1, double u2, double wi[3]);
double abrdf__hair_sampler_pdf(const abrdf__hair_sampler *h, const double wi[3]);

/* ---- components and mixtures (sample_mix.c) ------------------------------------------ */
typedef enum abrdf__lobe_kind {
    ABRDF__LOBE_COSINE,     /* cos(theta)/pi about N (Malley's method) */
    ABRDF__LOBE_UNIFORM,    /* 1/(2 pi) on the hemisphere above N */
    ABRDF__LOBE_MIRROR,     /* dist about R = mirror of wo, the whole sphere */
    ABRDF__LOBE_HALF,       /* dist for the half vector about N, wi = reflect(wo, h) */
    ABRDF__LOBE_GGX_VNDF,   /* GGX visible normals of wo (Heitz 2018; Dupuy, Benyoub 2023) */
    ABRDF__LOBE_FIBRE_SIN,  /* Kajiya-Kay diffuse: density ~ sin(T, wi) N.wi, exact */
    ABRDF__LOBE_FIBRE_CONE, /* Kajiya-Kay specular: trimmed logistic about the cone */
    ABRDF__LOBE_HAIR        /* R/TT/TRT far-field proposal (abrdf__hair_sampler) */
} abrdf__lobe_kind;

typedef struct abrdf__lobe {
    abrdf__lobe_kind kind;
    double prob;      /* selection probability */
    abrdf__dist dist; /* MIRROR, HALF */
    double ax, ay;    /* GGX_VNDF: alpha_g along T and B */
    double n;         /* FIBRE_CONE: exponent */
} abrdf__lobe;

#define ABRDF__MIX_MAX (ABRDF_MAX_LAYERS + 1)

typedef struct abrdf__mixture abrdf__mixture;

/* One component (sample_lobe.c): draw wi from u1, u2 in [0, 1), 0 if the draw degenerated;
 * the component's density at wi. */
int abrdf__lobe_sample(const abrdf__lobe *l, const abrdf__mixture *mx, double u1, double u2,
                       double wi[3]);
double abrdf__lobe_pdf(const abrdf__lobe *l, const abrdf__mixture *mx, const double wi[3]);

struct abrdf__mixture {
    int count;
    abrdf__lobe lobe[ABRDF__MIX_MAX];
    double wo[3];             /* local, unit, above the surface */
    abrdf__hair_sampler hair; /* the LOBE_HAIR component's data */
};

/* Build the mixture of `model` (validated parameters in this library's layout) for the
 * local unit wo with wo[2] > 0. */
void abrdf__mixture_setup(abrdf_model model, const abrdf_params *p, const double wo[3],
                          abrdf__mixture *mx);
/* The mixture of the `measured` model: cosine and a GGX visible-normal lobe with the
 * roughness and share its setup fitted to the table (measured.h). */
void abrdf__mixture_setup_measured(const abrdf__measured *m, const double wo[3],
                                   abrdf__mixture *mx);
/* Draw wi (local, unit) with u1, u2 in [0, 1); returns 0 if the draw degenerated (a set of
 * measure zero: the half vector orthogonal to wo), then wi is +z and carries no weight. */
int abrdf__mixture_sample(const abrdf__mixture *mx, double u1, double u2, double wi[3]);
/* Mixture density at the local unit wi, 1/sr (0 where no component reaches). */
double abrdf__mixture_pdf(const abrdf__mixture *mx, const double wi[3]);

#endif /* ABRDF_SAMPLE_H */
