/* fit_internal.h - what the fit (fit.c), the prediction (predict.c) and the budget selection
 * (budget.c) share: a BRDF of one or two lobes, the workspace carved into arrays, the
 * reference's highlight width, and the two stages each public call is made of (prepare for
 * a reference, then evaluate candidates), so that the budget fits many candidates against
 * one reference without repeating the reference's work. */
#ifndef ABRDF_FIT_INTERNAL_H
#define ABRDF_FIT_INTERNAL_H

#include "abrdf_fit.h"
#include "abrdf_internal.h"
#include "prepared.h"

/* ---- one lobe prepared for many evaluations (lobes.c) -------------------------------- */

/* A lobe prepared as abrdf_prepare does (prepared.h), double path only. */
typedef struct abrdf__lobe_prep {
    abrdf_model model; /* ABRDF_MODEL_NONE: evaluates to 0 */
    abrdf__prep pr;    /* the prepared model (a copy of the block) */
} abrdf__lobe_prep;

/* Prepare lobe m with block p (this library's layout, validated by the caller; copied). */
void abrdf__lobe_prepare(abrdf__lobe_prep *lp, abrdf_model m, const abrdf_params *p);
/* f_r of the prepared lobe at local-frame unit directions; finite and >= 0. */
void abrdf__lobe_eval(const abrdf__lobe_prep *lp, const double wi[3], const double wo[3],
                      double f[3]);

/* ---- a BRDF: up to two lobes summed over one parameter block ---------------------------- */

typedef struct abrdf__brdf {
    abrdf_model lobe[2]; /* diffuse, specular; ABRDF_MODEL_NONE = absent */
    abrdf_params p;      /* this library's full layout, validated for both lobes */
    /* A caller's prepared object standing for the whole BRDF (abrdf_fit_to's reference; NULL
     * for every other BRDF): lobe = (none, its model), p = its parameters, and it is evaluated
     * as prepared, which is how a measured table (no parameter block) is a reference. */
    const abrdf__prep *prepared;
} abrdf__brdf;

/* Set b from the caller's models and block (any struct_size): ABRDF_OK, or an error with a
 * message naming the problem (no lobe, unknown model, parameter out of range). */
int abrdf__brdf_make(abrdf__brdf *b, abrdf_model diffuse, abrdf_model specular,
                     const abrdf_params *p, char *msg, size_t msg_size);
/* The BRDF of a caller's prepared object (abrdf__brdf.prepared): ABRDF_OK, or ABRDF_E_NULL /
 * ABRDF_E_MODEL (not prepared) with a message. The object must outlive b. */
int abrdf__brdf_from_prepared(abrdf__brdf *b, const abrdf_prepared *prepared, char *msg,
                              size_t msg_size);
/* f_r of the sum of the lobes, local frame, unit vectors, no checks (b was made valid), with
 * both lobes prepared once (a copy of b's block: b may change or go away afterwards; a
 * `prepared` object is pointed at, not copied). */
typedef struct abrdf__brdf_prep {
    abrdf__lobe_prep lobe[2];
    const abrdf__prep *prepared; /* b's prepared object, or NULL */
} abrdf__brdf_prep;
void abrdf__brdf_prepare(const abrdf__brdf *b, abrdf__brdf_prep *bp);
void abrdf__brdf_prep_eval(const abrdf__brdf_prep *bp, const double wi[3], const double wo[3],
                           double f[3]);
/* Union of the lobes' ABRDF_NEEDS_* flags. */
unsigned abrdf__brdf_needs(const abrdf__brdf *b);
/* Does a lobe read the tangent frame at these parameters (fibres; anisotropy > 0)? */
int abrdf__brdf_uses_tangent(const abrdf__brdf *b);
/* Is a lobe a fibre model (Kajiya-Kay, Marschner, Huang), whose highlight is a cone about
 * the tangent rather than a lobe about the mirror direction? */
int abrdf__brdf_is_fibre(const abrdf__brdf *b);

/* Angular half-width (radians, in the half vector) of the reference's highlight about the
 * mirror direction: where f cos falls to half its mirror value, in [ABRDF__FIT_WIDTH_MIN, 1];
 * 1 if f does not peak at the mirror direction (diffuse, fibres, sheen). */
double abrdf__brdf_highlight_width(const abrdf__brdf *b);

/* Narrowest highlight the direction sets and the sphere resolve, radians: below it a lobe is
 * treated as this wide. 2e-4 is the half-width of f_2e at n = 1e5; sharper lobes (up to the
 * parameter's n = 1e6) are covered by the nodes nearest the mirror direction. */
#define ABRDF__FIT_WIDTH_MIN 2e-4

/* ---- the caller's workspace ------------------------------------------------------------ */

typedef struct abrdf__arena {
    char *base;
    size_t size, used;
    int failed; /* a request did not fit */
} abrdf__arena;

void abrdf__arena_init(abrdf__arena *a, void *base, size_t size);
/* n doubles (8-byte aligned), or NULL (and a->failed) if the workspace is too small. */
double *abrdf__arena_doubles(abrdf__arena *a, size_t n);

/* ---- the prediction (predict.c) -------------------------------------------------------- */

/* The sphere is sampled on this many grids, shifted by half a sample spacing in x, y and
 * both; the prediction is the largest of their NMSEs (predict.c explains why). */
#define ABRDF__PRED_SHIFTS 4

/* The view resolved into shading terms in each term's local frame, and the reference's
 * image over them. */
typedef struct abrdf__pred {
    int samples; /* image samples, of every image */
    int images;  /* the sphere: ABRDF__PRED_SHIFTS sampling grids; caller's terms: 1 */
    int image_end[ABRDF__PRED_SHIFTS]; /* samples [image_end[k-1], image_end[k]) form image k */
    int terms;                         /* shading terms */
    double *li, *lo;                   /* 3 * terms: local-frame wi, wo */
    double *ec;                        /* 3 * terms: irradiance * cos(theta_i) */
    int *sample_of; /* terms: the sample each adds to (stored as doubles' space) */
    double *weight; /* samples: 1 (pixels of equal area) */
    double *ref;    /* 3 * samples: the reference's images */
    double *img;    /* 3 * samples: scratch for a candidate's images */
    double ref_energy[ABRDF__PRED_SHIFTS]; /* per image: sum weight * ref^2 */
} abrdf__pred;

/* Bytes the prediction needs for `view` (NULL = default sphere); 0 if the view is invalid.
 * `integrating`: a lobe of the reference or candidates integrates numerically (the sphere's
 * default resolution is then lower). */
size_t abrdf__pred_bytes(const abrdf_view *view, int integrating);
/* Check the caller's view (struct_size, ranges); ABRDF_OK or an error with a message. */
int abrdf__view_check(const abrdf_view *view, abrdf_view *full, char *msg, size_t msg_size);
/* Resolve the view (NULL = default) for the reference and render the reference's image. */
int abrdf__pred_prepare(abrdf__pred *pr, const abrdf_view *view, const abrdf__brdf *ref,
                        int integrating, abrdf__arena *a, char *msg, size_t msg_size);
/* NMSE of b's image against the reference's (0 when both are black). */
double abrdf__pred_nmse(abrdf__pred *pr, const abrdf__brdf *b);

/* ---- the fit (fit.c) ------------------------------------------------------------------- */

/* The direction set and the reference's values on it. */
typedef struct abrdf__fit_set {
    int n;        /* direction pairs */
    int groups;   /* incidence directions; pair j belongs to group[j] */
    double *wi;   /* 3n, local frame */
    double *wo;   /* 3n */
    double *q;    /* n: solid-angle weight * cos^2(theta_i) cos(theta_o) */
    double *cosi; /* n */
    int *group;   /* n */
    double *yref; /* 3n: the reference's f_r */
    double width; /* the reference's highlight width (abrdf__brdf_highlight_width) */
    int tangent;  /* the set varies the tangent azimuth */
    int fibre;    /* outgoing directions uniform over the hemisphere (fibres) */
} abrdf__fit_set;

/* Bytes of the direction set and the fit's scratch at a resolution option (its level for a
 * closed-form reference), for the largest of the sets. */
size_t abrdf__fit_bytes(int resolution);
/* The direction-set level, [0, 4], of a resolution option, [0, 5]: 1 to 5 are levels 0 to 4;
 * 0 is the default, level 2. */
int abrdf__fit_level(int resolution, int integrating);
/* Build the set of a level (abrdf__fit_level) for the reference (tangent: whether the
 * candidate or the reference reads the tangent frame; fibre: whether either is a fibre model)
 * and evaluate the reference on it. */
int abrdf__fit_set_make(abrdf__fit_set *s, const abrdf__brdf *ref, int tangent, int fibre,
                        int level, abrdf__arena *a);

/* Fit cand (lobes set, cand->p holding the starting block: abrdf__fit_start) with `metric`
 * (not AUTO) on the set; cand->p receives the fit. keep_shared: a lobe of the reference's
 * model keeps the reference's parameters (abrdf_fit_options). pr (may be NULL) predicts the
 * NMSE. res receives the metrics. Uses scratch from `a` (released on return). */
void abrdf__fit_run(const abrdf__fit_set *s, const abrdf__brdf *ref, abrdf__brdf *cand,
                    abrdf_fit_metric metric, int keep_shared, abrdf__pred *pr,
                    abrdf_fit_result *res, abrdf__arena *a);
/* The candidate's starting block: its defaults, with every parameter the reference's lobes
 * also read copied from the reference (clamped into the candidate's range). */
void abrdf__fit_start(const abrdf__brdf *ref, abrdf__brdf *cand);
/* Errors of cand against the reference on the set (rel_l2, max_rel_pct, max_abs). */
void abrdf__fit_errors(const abrdf__fit_set *s, const abrdf__brdf *cand, abrdf_fit_result *res);

#endif /* ABRDF_FIT_INTERNAL_H */
