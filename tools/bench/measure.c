/* measure.c - timing of the float batch path (measure.h). Warm cache: the direction and
 * output arrays are small (4096 pairs = 144 KiB) and every timed call is preceded by an
 * untimed one. The clock is the thread's CPU-time clock, so time spent descheduled on a
 * busy machine is not counted; the median of the repetitions resists what remains. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "abrdf_inline.h"
#include "cost_file.h"
#include "measure.h"
#include "measured_table.h"

/* Pairs per batch for models that integrate inside eval (hair, layered): enough for a
 * stable mean, small enough to keep a calibration within seconds. */
#define INTEGRATING_PAIRS 256

struct measure_set {
    measured_table table;    /* the measured model's table (bench_table), built on first use */
    abrdf_prepared measured; /* ... prepared */
    size_t pairs;
    float *buf;  /* 9 arrays of `pairs` floats: wi xyz, wo xyz, f rgb */
    double *dir; /* the same directions in double, interleaved wi[3] wo[3] per pair */
};

void measure_defaults(measure_opts *o, int quick)
{
    o->reps = quick ? 3 : 7;
    o->pairs = 4096;
    o->rep_seconds = quick ? 0.005 : 0.02;
    o->integrating_pairs = INTEGRATING_PAIRS;
}

static double now_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* xorshift64*: deterministic, good enough for directions */
static double rnd(uint64_t *s)
{
    *s ^= *s >> 12;
    *s ^= *s << 25;
    *s ^= *s >> 27;
    return (double)((*s * 0x2545F4914F6CDD1DULL) >> 11) * (1.0 / 9007199254740992.0);
}

/* Uniform on the upper hemisphere, kept off the horizon so every pair is front-facing. */
static void hemisphere(uint64_t *s, float *x, float *y, float *z)
{
    double cz = 0.01 + 0.99 * rnd(s), phi = 6.283185307179586 * rnd(s);
    double r = sqrt(1.0 - cz * cz);
    *x = (float)(r * cos(phi));
    *y = (float)(r * sin(phi));
    *z = (float)cz;
}

measure_set *measure_set_new(size_t pairs)
{
    measure_set *s = malloc(sizeof *s);
    if (!s) return NULL;
    memset(&s->table, 0, sizeof s->table);
    s->pairs = pairs;
    s->buf = malloc(9 * pairs * sizeof(float));
    s->dir = malloc(6 * pairs * sizeof(double));
    if (!s->buf || !s->dir) {
        measure_set_free(s);
        return NULL;
    }
    uint64_t seed = 0x9E3779B97F4A7C15ULL;
    float *b = s->buf;
    for (size_t i = 0; i < pairs; ++i) {
        hemisphere(&seed, &b[i], &b[pairs + i], &b[2 * pairs + i]);
        hemisphere(&seed, &b[3 * pairs + i], &b[4 * pairs + i], &b[5 * pairs + i]);
    }
    memset(b + 6 * pairs, 0, 3 * pairs * sizeof(float));
    /* the double paths' directions: the same, normalised again in double (unit to a few
     * 1e-16, as a renderer working in double holds them: abrdf_eval_prepared_unit) */
    for (size_t i = 0; i < pairs; ++i)
        for (int w = 0; w < 2; ++w) {
            double *d = s->dir + 6 * i + 3 * (size_t)w;
            for (int c = 0; c < 3; ++c) d[c] = b[(size_t)(3 * w + c) * pairs + i];
            double inv = 1.0 / sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            for (int c = 0; c < 3; ++c) d[c] *= inv;
        }
    return s;
}

void measure_set_free(measure_set *s)
{
    if (!s) return;
    measured_table_free(&s->table);
    free(s->buf);
    free(s->dir);
    free(s);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Sink for the unit loop's results, so the compiler cannot drop the work. */
static volatile float measure_sink;

typedef int (*batch_fn)(void *ctx, const abrdf_batch *b);

typedef struct model_ctx {
    abrdf_model model;
    abrdf_params params;
    const abrdf_prepared *table; /* the measured model: its prepared table (else NULL) */
    const double *dir;           /* double path: interleaved directions (measure_set.dir) */
} model_ctx;

static int run_model(void *ctx, const abrdf_batch *b)
{
    const model_ctx *c = ctx;
    if (c->table) return abrdf_eval_prepared_batch(c->table, b);
    return abrdf_eval_batch(c->model, &c->params, b);
}

/* The context's model prepared (the measured model: its table's prepared object); 0 or -1. */
static int ctx_prepare(const model_ctx *c, abrdf_prepared *prep)
{
    if (c->table) {
        *prep = *c->table;
        return 0;
    }
    return abrdf_prepare(c->model, &c->params, prep) == ABRDF_OK ? 0 : -1;
}

/* The double scalar path prepared once (abrdf_prepare), one abrdf_eval_prepared call (local
 * frame) per pair, or (unit) one abrdf_eval_prepared_unit call on the same directions, which
 * are unit vectors already: what a renderer pays per sample. */
static int run_prepared(const model_ctx *c, const abrdf_batch *b, int unit)
{
    abrdf_prepared prep;
    if (ctx_prepare(c, &prep)) return -1;
    double f[3], acc = 0.0;
    for (size_t i = 0; i < b->count; ++i) {
        const double *wi = c->dir + 6 * i, *wo = wi + 3;
        if (unit)
            abrdf_eval_prepared_unit(&prep, wi, wo, f);
        else
            abrdf_eval_prepared(&prep, NULL, wi, wo, f);
        acc += f[0];
    }
    measure_sink = (float)acc;
    return 0;
}

static int run_model_prepared(void *ctx, const abrdf_batch *b) { return run_prepared(ctx, b, 0); }

/* The float per-sample paths on the float directions of the batch (prepared once), as a
 * renderer shading in float calls them: abrdf_eval_prepared_float per pair, or with `inlined`
 * the GGX lobe of abrdf_inline.h compiled into the loop (disney_specular only: -1 for another
 * model). Every channel is summed: an inlined lobe's unread channels would be dropped. Always
 * inlined into its two callers, so that `inlined` is a constant there and the loop has no
 * branch on it. */
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline int
run_float_pairs(void *ctx, const abrdf_batch *b, int inlined)
{
    abrdf_prepared prep;
    abrdf_ggx_float lobe;
    if (ctx_prepare(ctx, &prep)) return -1;
    if (inlined && abrdf_prepared_ggx_float(&prep, &lobe) != ABRDF_OK) return -1;
    float f[3], acc = 0.0f;
    for (size_t i = 0; i < b->count; ++i) {
        const float wi[3] = {b->wi_x[i], b->wi_y[i], b->wi_z[i]};
        const float wo[3] = {b->wo_x[i], b->wo_y[i], b->wo_z[i]};
        if (inlined)
            abrdf_ggx_float_eval(&lobe, wi, wo, f);
        else
            abrdf_eval_prepared_float(&prep, wi, wo, f);
        acc += f[0] + f[1] + f[2];
    }
    measure_sink = acc;
    return 0;
}

static int run_model_prepared_float(void *ctx, const abrdf_batch *b)
{
    return run_float_pairs(ctx, b, 0);
}

static int run_model_inline_ggx(void *ctx, const abrdf_batch *b)
{
    return run_float_pairs(ctx, b, 1);
}

static int run_model_prepared_unit(void *ctx, const abrdf_batch *b)
{
    return run_prepared(ctx, b, 1);
}

/* The double scalar reference path, one abrdf_eval call (local frame) per pair (the measured
 * model has no unprepared path: abrdf_eval_prepared). */
static int run_model_double(void *ctx, const abrdf_batch *b)
{
    const model_ctx *c = ctx;
    if (c->table) return run_prepared(c, b, 0);
    double f[3], acc = 0.0;
    for (size_t i = 0; i < b->count; ++i) {
        if (abrdf_eval(c->model, &c->params, NULL, c->dir + 6 * i, c->dir + 6 * i + 3, f) !=
            ABRDF_OK)
            return -1;
        acc += f[0];
    }
    measure_sink = (float)acc;
    return 0;
}

static int run_unit(void *ctx, const abrdf_batch *b)
{
    float n = *(const float *)ctx;
    for (size_t i = 0; i < b->count; ++i) {
        float hx = b->wi_x[i] + b->wo_x[i], hy = b->wi_y[i] + b->wo_y[i],
              hz = b->wi_z[i] + b->wo_z[i];
        float c = hz / sqrtf(hx * hx + hy * hy + hz * hz);
        b->f_r[i] = c > 0.0f ? powf(c, n) : 0.0f;
    }
    measure_sink = b->f_r[b->count / 2];
    return 0;
}

/* Median over reps of ns/eval of fn on the first `pairs` pairs of s. */
static double time_batches(measure_set *s, size_t pairs, batch_fn fn, void *ctx,
                           const measure_opts *o)
{
    size_t P = s->pairs;
    float *b = s->buf;
    abrdf_batch batch = {pairs,     b,         b + P,     b + 2 * P, b + 3 * P,
                         b + 4 * P, b + 5 * P, b + 6 * P, b + 7 * P, b + 8 * P};
    if (fn(ctx, &batch) != 0) return -1.0; /* warm-up, and the parameters are valid */
    double t0 = now_seconds();
    fn(ctx, &batch);
    double one = now_seconds() - t0;
    long calls = one > 0.0 ? (long)ceil(o->rep_seconds / one) : 1000;
    if (calls < 1) calls = 1;
    double *ns = malloc(sizeof(double) * (size_t)o->reps);
    if (!ns) return -1.0;
    for (int r = 0; r < o->reps; ++r) {
        double t = now_seconds();
        for (long k = 0; k < calls; ++k) fn(ctx, &batch);
        ns[r] = 1e9 * (now_seconds() - t) / ((double)calls * (double)pairs);
    }
    qsort(ns, (size_t)o->reps, sizeof(double), cmp_double);
    double med = (o->reps % 2) ? ns[o->reps / 2] : 0.5 * (ns[o->reps / 2 - 1] + ns[o->reps / 2]);
    free(ns);
    return med;
}

double measure_model_ns(measure_set *s, abrdf_model model, const measure_opts *o)
{
    abrdf_params p;
    if (abrdf_params_init(model, &p) != ABRDF_OK) return -1.0;
    return measure_model_params_ns(s, model, &p, 0, o);
}

/* The measured model's table for timing: MERL's grid (90 x 90 x 180, 17.5 MB of floats, the
 * memory a renderer's lookups walk) written from lambert kd = 0.5 + disney_specular r = 0.3,
 * a glossy plastic; cells below the horizon not measured, as the generator writes them. */
static const abrdf_prepared *bench_table(measure_set *s)
{
    measured_table *t = &s->table;
    if (t->data) return &s->measured;
    char err[256];
    if (measured_table_alloc(t, 90, 90, 180, err, sizeof err) != 0) return NULL;
    abrdf_params p;
    abrdf_params_init(ABRDF_DISNEY_SPECULAR, &p);
    p.r = 0.3;
    for (int c = 0; c < 3; ++c) p.kd[c] = 0.5;
    for (int ih = 0; ih < t->n_theta_h; ++ih)
        for (int id = 0; id < t->n_theta_d; ++id)
            for (int ip = 0; ip < t->n_phi_d; ++ip) {
                double wi[3], wo[3], fd[3], fs[3];
                measured_table_directions(t, ih, id, ip, wi, wo);
                if (!(wi[2] > 0.0 && wo[2] > 0.0)) continue;
                abrdf_eval(ABRDF_LAMBERT, &p, NULL, wi, wo, fd);
                abrdf_eval(ABRDF_DISNEY_SPECULAR, &p, NULL, wi, wo, fs);
                float *v = t->data + measured_table_cell(t, ih, id, ip);
                for (int c = 0; c < 3; ++c) v[c] = (float)(fd[c] + fs[c]);
            }
    abrdf_measured desc;
    abrdf_measured_init(&desc);
    desc.n_theta_h = t->n_theta_h, desc.n_theta_d = t->n_theta_d, desc.n_phi_d = t->n_phi_d;
    desc.data = t->data;
    if (abrdf_prepare_measured(&desc, &s->measured) != ABRDF_OK) {
        measured_table_free(t);
        return NULL;
    }
    return &s->measured;
}

double measure_model_params_ns(measure_set *s, abrdf_model model, const abrdf_params *p,
                               int double_path, const measure_opts *o)
{
    const abrdf_model_info *m = abrdf_model_get(model);
    if (!m) return -1.0;
    model_ctx ctx;
    ctx.table = NULL;
    if ((m->needs & ABRDF_NEEDS_TABLE) && !(ctx.table = bench_table(s))) return -1.0;
    ctx.model = model;
    ctx.params = *p;
    ctx.dir = s->dir;
    size_t pairs = s->pairs;
    if ((m->needs & ABRDF_NEEDS_INTEGRATION) && pairs > o->integrating_pairs)
        pairs = o->integrating_pairs;
    batch_fn fn = double_path == 5   ? run_model_inline_ggx
                  : double_path == 4 ? run_model_prepared_float
                  : double_path == 3 ? run_model_prepared_unit
                  : double_path == 2 ? run_model_prepared
                  : double_path      ? run_model_double
                                     : run_model;
    return time_batches(s, pairs, fn, &ctx, o);
}

double measure_shared_view_ns(abrdf_model model, const abrdf_params *p, int lights, int group,
                              const measure_opts *o)
{
    const abrdf_model_info *m = abrdf_model_get(model);
    if (!m || lights < 1 || group < lights) return -1.0;
    size_t total = (m->needs & ABRDF_NEEDS_INTEGRATION) ? o->integrating_pairs : o->pairs;
    size_t views = total / (size_t)group > 0 ? total / (size_t)group : 1;
    size_t pairs = views * (size_t)lights;
    measure_set *s = measure_set_new(views * (size_t)group);
    if (!s) return -1.0;
    /* group g of the set: the view of its first pair and the lights of its first `lights`
     * pairs, packed to the front (the same views and lights whatever `lights` is) */
    float *b = s->buf;
    size_t P = s->pairs;
    for (size_t g = 0; g < views; ++g)
        for (size_t l = 0; l < (size_t)lights; ++l) {
            size_t from = g * (size_t)group + l, to = g * (size_t)lights + l;
            for (int c = 0; c < 3; ++c) {
                b[(size_t)c * P + to] = b[(size_t)c * P + from];
                b[(size_t)(3 + c) * P + to] = b[(size_t)(3 + c) * P + g * (size_t)group];
            }
        }
    model_ctx ctx;
    ctx.table = (m->needs & ABRDF_NEEDS_TABLE) ? bench_table(s) : NULL;
    ctx.model = model;
    ctx.params = *p;
    ctx.dir = s->dir;
    double ns = ctx.table || !(m->needs & ABRDF_NEEDS_TABLE)
                    ? time_batches(s, pairs, run_model, &ctx, o)
                    : -1.0;
    measure_set_free(s);
    return ns;
}

double measure_unit_ns(measure_set *s, const measure_opts *o)
{
    float n = 100.0f;
    return time_batches(s, s->pairs, run_unit, &n, o);
}

int measure_models(const measure_opts *o, const abrdf_model *models, int count, abrdf_costs *out,
                   double *unit_ns, void (*progress)(const char *name))
{
    abrdf_costs_init(out, COSTS_UNIT);
    measure_set *s = measure_set_new(o->pairs);
    if (!s) return -1;
    if (progress) progress(COSTS_UNIT_NAME);
    measure_unit_ns(s, o); /* untimed warm-up: clock frequency, page faults, caches */
    *unit_ns = measure_unit_ns(s, o);
    int n = models ? count : ABRDF_MODEL_COUNT;
    for (int i = 0; i < n; ++i) {
        abrdf_model id = models ? models[i] : (abrdf_model)i;
        const abrdf_model_info *m = abrdf_model_get(id);
        if (!m) continue;
        if (progress) progress(m->name);
        abrdf_costs_set(out, id, measure_model_ns(s, id, o));
    }
    measure_set_free(s);
    return 0;
}
