/* prepared.h - what abrdf_prepare computes once per (model, parameters) and every evaluation
 * reads: the layout behind the public abrdf_prepared's opaque bytes (abrdf.h, "prepared
 * evaluation").
 *
 * A prepared object is plain data: no pointer into itself or to the caller's memory (its one
 * pointer is to the library's evaluation of the model, valid in the process that prepared it,
 * as abrdf.h says of the object), so a copy (struct assignment, memcpy) is as good as the
 * original, and a const one may be read by
 * any number of threads. It holds the validated parameters in this library's layout, the
 * closed-form kernels' parameters in both precisions (filled by each model's setup, the
 * functions k_dispatch.h lists) and the setup of the models evaluated in double only. Other
 * per-model operations (sampling, pdf) read the same object: model and params are what they
 * were prepared from, and kd / kf whatever the model's setup precomputed. */
#ifndef ABRDF_PREPARED_H
#define ABRDF_PREPARED_H

#include "abrdf_internal.h"
#include "hair.h"
#include "layered.h"
#include "measured.h"

/* The kernels' parameters, one field list for both precisions (kernel.h: abrdf__kp). */
#define ABRDF__KP_FIELDS(REAL)                                                                     \
    REAL kd[3], ks[3], f0[3]; /* kp_base */                                                        \
    REAL ks_f0[3], ks_f1[3];  /* ks F0 and ks (1 - F0): ks F_Schlick (kp_base, schlick_out) */     \
    REAL n;                   /* exponent (kp_base) */                                             \
    REAL r;                   /* perceptual roughness (kp_base) */                                 \
    REAL ag;                  /* alpha_g = max(r^2, ABRDF__ALPHA_G_MIN) */                         \
    REAL ax, ay;              /* anisotropic alpha_g along T and B */                              \
    REAL on_a, on_b;          /* Oren-Nayar A and B */                                             \
    REAL cc_alpha;            /* clearcoat GTR1 alpha */                                           \
    REAL k_amp;               /* velvet amplitude */                                               \
    REAL norm;                /* the model's normalisation constant (Table 5, velvet) */           \
    REAL fkub[3];             /* a, b, d of the cubic approximation about c = 1 for this n */      \
    REAL fkub_x0;             /* below this cosine the cubic is zero */

typedef struct abrdf__kp_d {
    ABRDF__KP_FIELDS(double)
} abrdf__kp_d;
typedef struct abrdf__kp_f {
    ABRDF__KP_FIELDS(float)
} abrdf__kp_f;

/* "abrp": set by abrdf_prepare on success; a block without it was never prepared. */
#define ABRDF__PREP_MAGIC 0x61627270u

/* The library reads a caller's abrdf_prepared through this type; may_alias tells the compiler
 * that it overlays the public struct's bytes. */
#if defined(__GNUC__)
#define ABRDF__MAY_ALIAS __attribute__((may_alias))
#else
#define ABRDF__MAY_ALIAS
#endif
struct abrdf__prep;
/* The double scalar evaluation of one model (eval_double.c): f_r for unit local-frame wi, wo,
 * finite and >= 0. Returns ABRDF_OK. */
typedef int (*abrdf__eval_d_fn)(const struct abrdf__prep *pr, const double wi[3],
                                const double wo[3], double f[3]);
typedef struct ABRDF__MAY_ALIAS abrdf__prep {
    unsigned magic;      /* ABRDF__PREP_MAGIC */
    abrdf_model model;   /* the prepared model */
    abrdf_params params; /* the validated parameters, this library's layout (struct_size) */
    abrdf__kp_d kd;      /* the closed-form kernels' parameters, double (scalar path) */
    abrdf__kp_f kf;      /* ... float (batch path) */
    union {
        abrdf__marschner marschner;
        abrdf__huang huang;
        abrdf__belcour belcour;
        abrdf__ww ww;
        abrdf__measured measured;
    } special; /* setup of a model evaluated in double only (special.c) */
} abrdf__prep;

/* Which precisions abrdf__prep_make fills (abrdf_eval needs only double), and ONCE for an
 * object that serves a single evaluation (abrdf_eval, abrdf_sample): a setup may then leave
 * out what only pays over many evaluations, as long as the results keep their bits. */
#define ABRDF__PREP_DOUBLE 1u
#define ABRDF__PREP_FLOAT 2u
#define ABRDF__PREP_ONCE 4u

/* Fill *pr for a model whose parameters p (this library's layout) passed abrdf_params_check;
 * p is copied. what: ABRDF__PREP_DOUBLE | ABRDF__PREP_FLOAT | ABRDF__PREP_ONCE (api.c). */
void abrdf__prep_make(abrdf__prep *pr, abrdf_model model, const abrdf_params *p, unsigned what);

/* Validate params for model (abrdf_params_check's status) and, if valid, abrdf__prep_make
 * from them in this library's layout (api.c). */
int abrdf__prep_checked(abrdf_model model, const abrdf_params *params, abrdf__prep *pr,
                        unsigned what);
/* The library's view of a caller's prepared object, or NULL if it is NULL or not prepared. */
const abrdf__prep *abrdf__prep_of(const abrdf_prepared *prepared);

/* The setups, per precision (eval_double.c, eval_float.c, special.c). */
void abrdf__prep_setup_d(abrdf__prep *pr);
void abrdf__prep_setup_f(abrdf__prep *pr);
void abrdf__prep_setup_special(abrdf__prep *pr, unsigned what);

/* Each model's double scalar evaluation, indexed by model id (eval_double.c): constant data,
 * so the prepared object itself holds no pointer (abrdf.h); abrdf__prep_of admits only
 * objects whose model indexes it. The closed-form models have one each, the double-only
 * models share the dispatch of special.c. */
extern const abrdf__eval_d_fn abrdf__scalar_of[ABRDF_MODEL_COUNT];

/* Local-frame evaluation of a prepared model; wi, wo unit (the scalar path normalises before
 * calling). f is finite and >= 0; returns ABRDF_OK. One indirect call through the table: no
 * switch over the models per sample. */
static inline int abrdf__eval_prepared_d(const abrdf__prep *pr, const double wi[3],
                                         const double wo[3], double f[3])
{
    return abrdf__scalar_of[pr->model](pr, wi, wo, f);
}
/* The float batch (eval_float.c), with the batch loops of the instruction-set level the CPU
 * supports (abrdf__isa_best). */
void abrdf__eval_prepared_f(const abrdf__prep *pr, const abrdf_batch *b);

/* Instruction-set levels of the batch loops (eval_float.c): 0 the build's baseline, 1 AVX2 +
 * FMA, 2 AVX-512 (x86-64 only; elsewhere only 0). abrdf__isa_best is the highest level this
 * CPU runs; abrdf__eval_prepared_f_isa runs a given level (tests compare the levels) and
 * returns -1, writing nothing, if the CPU cannot run it. */
#define ABRDF__ISA_COUNT 3
int abrdf__isa_best(void);
const char *abrdf__isa_name(int level);
int abrdf__eval_prepared_f_isa(const abrdf__prep *pr, const abrdf_batch *b, int level);
/* The same over interleaved rows (abrdf_eval_prepared_rows), bit for bit the batch's values. */
void abrdf__eval_prepared_rows(const abrdf__prep *pr, size_t n, const float *wi, const float *wo,
                               float *f);
int abrdf__eval_prepared_rows_isa(const abrdf__prep *pr, size_t n, const float *wi, const float *wo,
                                  float *f, int level);
/* One pair on the float path (abrdf_eval_prepared_float) at a given level: the rows entry's
 * value for that pair, bit for bit; -1, writing nothing, if the CPU cannot run the level. */
int abrdf__eval_prepared_one_f(const abrdf__prep *pr, const float wi[3], const float wo[3],
                               float f[3], int level);
void abrdf__eval_prepared_one(const abrdf__prep *pr, const float wi[3], const float wo[3],
                              float f[3]); /* at the best level */

/* Special-surface models (special.c), from their prepared setup: f = 0 for another model. */
void abrdf__eval_special_prepared(const abrdf__prep *pr, const double wi[3], const double wo[3],
                                  double f[3]);

#endif /* ABRDF_PREPARED_H */
