/* abrdf_web.c - libabrdf for the browser explorer (docs/EXPLORER.md): the functions the page's
 * JavaScript calls (static/abrdf_api.js wraps them), compiled with libabrdf's own sources to
 * WebAssembly by emscripten (CMakeLists.txt beside this file).
 *
 * Models are set into a few numbered slots (A and B of the comparison, the worker's own), each
 * holding a prepared evaluation; every image and plot evaluates through libabrdf's float batch
 * path. The selection and the budget print what `abrdf advise --json` prints (select_json,
 * budget_json), so the page and the command line give the same object. Texts returned to
 * JavaScript stay valid until the next call that returns a text. */
#define _POSIX_C_SOURCE 200809L /* open_memstream */
#ifdef __EMSCRIPTEN__
#include <emscripten.h>
#else /* the host build, which tests these functions under the sanitizers (test_web_glue) */
#define EMSCRIPTEN_KEEPALIVE
#endif
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "abrdf.h"
#include "abrdf_fit.h"
#include "abrdf_select.h"
#include "abrdf_web.h"
#include "budget_run.h"
#include "cli_args.h"
#include "data_path.h"
#include "materials.h"
#include "metrics.h"
#include "select_trace.h"

#define WEB_SLOTS AW_SLOTS
#define WEB_CHUNK 1024 /* direction pairs per batch call */
#define PI 3.14159265358979323846

typedef struct web_slot {
    int set;
    abrdf_model model;
    abrdf_params params;
    abrdf_prepared prep;
    int has_diffuse; /* a diffuse + specular pair (a material's choice): f_r is their sum */
    abrdf_prepared diffuse;
} web_slot;

static web_slot slots[WEB_SLOTS];
static char *text;     /* the last text returned (open_memstream buffer) */
static char err[1024]; /* the last error: one line */
static char err_param[64];
static mat_table table;
static int table_loaded;

/* Structure-of-arrays scratch of one batch call. */
static float sx[6][WEB_CHUNK], sf[3][WEB_CHUNK], sd[3][WEB_CHUNK];

static void fail(const char *param, const char *fmt, const char *a, double v)
{
    snprintf(err, sizeof err, fmt, a, v);
    snprintf(err_param, sizeof err_param, "%s", param ? param : "");
}

/* A refused argument: the message, no parameter named. */
#if defined(__GNUC__)
__attribute__((format(printf, 1, 2)))
#endif
static int
refuse(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err, sizeof err, fmt, ap);
    va_end(ap);
    err_param[0] = '\0';
    return -1;
}

EMSCRIPTEN_KEEPALIVE const char *aw_error(void) { return err; }
EMSCRIPTEN_KEEPALIVE const char *aw_error_param(void) { return err_param; }
EMSCRIPTEN_KEEPALIVE const char *aw_version(void) { return abrdf_version(); }

/* A memory stream for a returned text; aw_text_end closes it and keeps the buffer. */
static FILE *text_begin(size_t *size)
{
    free(text);
    text = NULL;
    return open_memstream(&text, size);
}

static const char *text_end(FILE *f)
{
    if (fclose(f)) {
        free(text);
        text = NULL;
        fail(NULL, "%sout of memory", "", 0.0);
    }
    return text;
}

/* A number as JSON that reads back to the same double (a slider's end must be a value the
 * library takes: pi/2 printed to 10 digits lies past it), or null when not finite. */
static void json_exact(FILE *f, double v)
{
    if (isfinite(v))
        fprintf(f, "%.17g", v);
    else
        fprintf(f, "null");
}

static void json_rgb(FILE *f, const double v[3])
{
    fprintf(f, "[%.17g, %.17g, %.17g]", v[0], v[1], v[2]);
}

/* ---- the registry ----------------------------------------------------------------------- */

static void json_flags(FILE *f, unsigned bits, const unsigned *flag, const char *const *name, int n)
{
    fprintf(f, "[");
    for (int i = 0, k = 0; i < n; ++i)
        if (bits & flag[i]) fprintf(f, "%s\"%s\"", k++ ? ", " : "", name[i]);
    fprintf(f, "]");
}

/* Every model: names, citation, what it needs, its parameters with this model's ranges and
 * defaults, the paper's cycle count and the built-in cost (ns per evaluation). */
EMSCRIPTEN_KEEPALIVE const char *aw_models(void)
{
    static const unsigned needs[] = {ABRDF_NEEDS_TANGENT, ABRDF_NEEDS_FRESNEL, ABRDF_NEEDS_LAYERS,
                                     ABRDF_NEEDS_INTEGRATION, ABRDF_NEEDS_TABLE};
    static const char *const needs_name[] = {"tangent", "fresnel", "layers", "integration",
                                             "table"};
    static const unsigned props[] = {ABRDF_PROP_RECIPROCAL, ABRDF_PROP_ENERGY_CONSERVING,
                                     ABRDF_PROP_DIFFUSE, ABRDF_PROP_SPECULAR};
    static const char *const props_name[] = {"reciprocal", "energy_conserving", "diffuse",
                                             "specular"};
    static const char *const kind[] = {"scalar", "rgb", "int"};
    abrdf_costs costs;
    abrdf_costs_builtin(&costs);
    size_t size;
    FILE *f = text_begin(&size);
    if (!f) return NULL;
    fprintf(f, "[");
    for (int m = 0, k = 0; m < abrdf_model_count(); ++m) {
        const abrdf_model_info *i = abrdf_model_get((abrdf_model)m);
        if (!i) continue;
        fprintf(f, "%s\n{\"name\": ", k++ ? "," : "");
        cli_json_string(f, i->name);
        fprintf(f, ", \"title\": ");
        cli_json_string(f, i->title);
        fprintf(f, ", \"equation\": ");
        cli_json_string(f, i->equation);
        fprintf(f, ", \"citation\": ");
        cli_json_string(f, i->citation);
        fprintf(f, ", \"needs\": ");
        json_flags(f, i->needs, needs, needs_name, 5);
        fprintf(f, ", \"props\": ");
        json_flags(f, i->props, props, props_name, 4);
        fprintf(f, ", \"paperCycles\": ");
        json_exact(f, i->paper_cycles >= 0 ? i->paper_cycles : NAN);
        double c = abrdf_costs_get(&costs, (abrdf_model)m);
        fprintf(f, ", \"costNs\": ");
        json_exact(f, c >= 0.0 ? c : NAN);
        fprintf(f, ", \"closedForm\": %s, \"params\": [",
                i->needs & (ABRDF_NEEDS_INTEGRATION | ABRDF_NEEDS_TABLE) ? "false" : "true");
        for (int p = 0; p < i->param_count; ++p) {
            const abrdf_param_info *pi = abrdf_param_get(i->params[p].id);
            fprintf(f, "%s{\"name\": ", p ? ", " : "");
            cli_json_string(f, pi->name);
            fprintf(f, ", \"help\": ");
            cli_json_string(f, pi->help);
            fprintf(f, ", \"kind\": \"%s\", \"min\": ", kind[pi->kind]);
            json_exact(f, i->params[p].min);
            fprintf(f, ", \"max\": ");
            json_exact(f, i->params[p].max);
            fprintf(f, ", \"def\": ");
            json_exact(f, i->params[p].def);
            fprintf(f, "}");
        }
        fprintf(f, "]}");
    }
    fprintf(f, "\n]\n");
    return text_end(f);
}

/* ---- the material table ----------------------------------------------------------------- */

/* The material table: embedded into the module at /data (CMakeLists.txt), or the host's
 * data file. */
static int materials_load(void)
{
    if (table_loaded) return 0;
    char e[MAT_ERR_MAX], path[4096];
#ifdef __EMSCRIPTEN__
    snprintf(path, sizeof path, "/data/materials.csv");
#else
    data_path_find("materials.csv", path, sizeof path);
#endif
    if (mat_table_load(&table, path, e, sizeof e)) {
        fail(NULL, "%s", e, 0.0);
        return -1;
    }
    table_loaded = 1;
    return 0;
}

/* The rows of data/materials.csv as the flowchart reads them (n or r -1 when the row leaves
 * it to the other). */
EMSCRIPTEN_KEEPALIVE const char *aw_materials(void)
{
    if (materials_load()) return NULL;
    size_t size;
    FILE *f = text_begin(&size);
    if (!f) return NULL;
    fprintf(f, "[");
    for (int i = 0; i < table.count; ++i) {
        const abrdf_material *m = &table.items[i].m;
        fprintf(f, "%s\n{\"name\": ", i ? "," : "");
        cli_json_string(f, table.items[i].name);
        fprintf(f, ", \"surface\": \"%s\", \"n\": ", abrdf_surface_name(m->type));
        json_exact(f, m->n);
        fprintf(f, ", \"r\": ");
        json_exact(f, m->r);
        fprintf(f, ", \"kd\": ");
        json_rgb(f, m->kd);
        fprintf(f, ", \"ks\": ");
        json_rgb(f, m->ks);
        fprintf(f, ", \"f0\": ");
        json_rgb(f, m->f0);
        fprintf(f, ", \"eta\": ");
        json_exact(f, m->eta);
        fprintf(f, ", \"anisotropy\": ");
        json_exact(f, m->anisotropy);
        fprintf(f, ", \"melanin\": ");
        json_exact(f, m->melanin);
        fprintf(f, ", \"redness\": ");
        json_exact(f, m->redness);
        fprintf(f, ", \"layers\": %d, \"source\": ", m->layer_count);
        cli_json_string(f, table.items[i].source);
        fprintf(f, "}");
    }
    fprintf(f, "\n]\n");
    return text_end(f);
}

/* ---- a model in a slot ------------------------------------------------------------------ */

/* A decimal number at s (no hexadecimal, no inf or nan, no leading space), *end after it;
 * 0, or -1 when there is none. */
static int decimal(const char *s, char **end, double *v)
{
    const char *d = s + (*s == '+' || *s == '-');
    if (!((*d >= '0' && *d <= '9') || (*d == '.' && d[1] >= '0' && d[1] <= '9'))) return -1;
    if (d[0] == '0' && (d[1] == 'x' || d[1] == 'X')) return -1;
    *v = strtod(s, end);
    return *end != s && isfinite(*v) ? 0 : -1;
}

/* 1 if `id` is one of the parameters `model` reads. */
static int model_reads(abrdf_model model, int id)
{
    const abrdf_model_info *i = abrdf_model_get(model);
    for (int k = 0; i && k < i->param_count; ++k)
        if (i->params[k].id == id) return 1;
    return 0;
}

/* The text of "NAME=VALUE;NAME=VALUE;..." blocks, copied to be cut in place. */
#define SPEC_MAX 2048

/* spec copied into buf: 0, or -1 with "WHAT text too long". */
static int spec_copy(char buf[SPEC_MAX], const char *spec, const char *what)
{
    if (strlen(spec) >= SPEC_MAX) {
        fail(NULL, "%s text too long", what, 0.0);
        return -1;
    }
    strcpy(buf, spec);
    return 0;
}

/* The next NAME=VALUE of the copied text at *cursor (empty tokens skipped): 1 with *name and
 * *value cut at the '=', 0 at the end, -1 with the message for a token without '='. */
static int spec_next(char **cursor, char **name, char **value)
{
    char *tok = *cursor;
    while (*tok == ';') ++tok;
    if (!*tok) return 0;
    char *stop = strchr(tok, ';');
    *cursor = stop ? stop + 1 : tok + strlen(tok);
    if (stop) *stop = '\0';
    char *eq = strchr(tok, '=');
    if (!eq) {
        fail(NULL, "'%s' is not NAME=VALUE", tok, 0.0);
        return -1;
    }
    *eq = '\0';
    *name = tok;
    *value = eq + 1;
    return 1;
}

/* "name=v;name=v,v,v;..." onto p for the models m[0..n) (a diffuse + specular pair reads one
 * block): every name one they read, one value (or three for a colour) each, in range; a bad
 * name or value: -1 with the message. */
static int params_apply(const abrdf_model *m, int n, abrdf_params *p, const char *spec)
{
    char buf[SPEC_MAX], *cursor = buf, *tok, *value;
    if (spec_copy(buf, spec, "parameter")) return -1;
    for (int got; (got = spec_next(&cursor, &tok, &value));) {
        if (got < 0) return -1;
        int id, reads = 0;
        if (abrdf_param_find(tok, &id) != ABRDF_OK) {
            fail(tok, "unknown parameter '%s'", tok, 0.0);
            return -1;
        }
        for (int k = 0; k < n; ++k) reads |= model_reads(m[k], id);
        if (!reads) {
            snprintf(err, sizeof err, "%s: not a parameter of %s%s%s", tok,
                     abrdf_model_get(m[0])->name, n > 1 ? " + " : "",
                     n > 1 ? abrdf_model_get(m[1])->name : "");
            snprintf(err_param, sizeof err_param, "%s", tok);
            return -1;
        }
        const abrdf_param_info *pi = abrdf_param_get(id);
        double v[3];
        int count = 0;
        for (char *s = value;;) {
            char *end;
            if (count == 3 || decimal(s, &end, &v[count])) {
                fail(tok,
                     count == 3 ? "%s: at most three values (R,G,B)"
                                : "%s: the value is not a finite decimal number",
                     tok, 0.0);
                return -1;
            }
            ++count;
            if (*end == '\0') break;
            if (*end != ',') {
                fail(tok, "%s: the value is not a finite decimal number", tok, 0.0);
                return -1;
            }
            s = end + 1;
        }
        if (pi->kind == ABRDF_PARAM_RGB ? count == 2 : count != 1) {
            fail(tok,
                 pi->kind == ABRDF_PARAM_RGB ? "%s: one value or three (R,G,B)"
                                             : "%s takes one value",
                 tok, 0.0);
            return -1;
        }
        if (abrdf_param_set(p, id, v, count) != ABRDF_OK) {
            int bad = 0;
            for (int k = 1; k < count; ++k)
                if (!(v[k] >= pi->min && v[k] <= pi->max)) bad = k;
            snprintf(err, sizeof err, "%s = %.17g is outside [%.17g, %.17g]", tok, v[bad], pi->min,
                     pi->max);
            snprintf(err_param, sizeof err_param, "%s", tok);
            return -1;
        }
    }
    for (int k = 0; k < n; ++k) {
        abrdf_model model = m[k];
        char msg[512];
        if (abrdf_params_check(model, p, msg, sizeof msg) != ABRDF_OK) {
            snprintf(err, sizeof err, "%s", msg);
            /* the message names the parameter first ("r = 7 is outside ..."): keep that name */
            size_t len = strcspn(msg, " =:");
            snprintf(err_param, sizeof err_param, "%.*s", (int)(len < 63 ? len : 63), msg);
            return -1;
        }
    }
    return 0;
}

/* Set `slot` to `model` with its defaults and the parameters of `spec`, with the diffuse lobe
 * `diffuse` ("" for none) reading the same block, as abrdf_shade does. On any error the slot
 * keeps what it had and -1 is returned (aw_error, aw_error_param say why). */
EMSCRIPTEN_KEEPALIVE int aw_set_pair(int slot, const char *diffuse, const char *model,
                                     const char *spec)
{
    err[0] = err_param[0] = '\0';
    if (slot < 0 || slot >= WEB_SLOTS) {
        fail(NULL, "%sslot %g does not exist", "", slot);
        return -1;
    }
    abrdf_model m, d = ABRDF_MODEL_NONE;
    if (abrdf_model_find(model, &m) != ABRDF_OK) {
        fail(NULL, "unknown model '%s'", model, 0.0);
        return -1;
    }
    if (*diffuse && abrdf_model_find(diffuse, &d) != ABRDF_OK) {
        fail(NULL, "unknown model '%s'", diffuse, 0.0);
        return -1;
    }
    abrdf_params p;
    abrdf_params_init(m, &p);
    abrdf_model both[2] = {m, d};
    if (params_apply(both, *diffuse ? 2 : 1, &p, spec)) return -1;
    web_slot next;
    memset(&next, 0, sizeof next);
    next.set = 1, next.model = m, next.params = p, next.has_diffuse = *diffuse != '\0';
    if (abrdf_prepare(m, &p, &next.prep) != ABRDF_OK ||
        (next.has_diffuse && abrdf_prepare(d, &p, &next.diffuse) != ABRDF_OK)) {
        fail(NULL, "%s: cannot prepare these parameters", model, 0.0);
        return -1;
    }
    slots[slot] = next;
    return 0;
}

EMSCRIPTEN_KEEPALIVE int aw_set_model(int slot, const char *model, const char *spec)
{
    return aw_set_pair(slot, "", model, spec);
}

/* The slot's model, or NULL with the message; every evaluating call starts here, so the
 * message of an earlier call never stays behind. */
static const web_slot *slot_get(int slot)
{
    err[0] = err_param[0] = '\0';
    if (slot < 0 || slot >= WEB_SLOTS || !slots[slot].set) {
        fail(NULL, "%sno model in slot %g", "", slot);
        return NULL;
    }
    return &slots[slot];
}

/* ---- evaluation ------------------------------------------------------------------------- */

static void unit(float v[3])
{
    float l = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (l > 0.0f && isfinite(l)) v[0] /= l, v[1] /= l, v[2] /= l;
}

/* The pairs held in the scratch arrays, [0, n): f into sf (the diffuse lobe's added). */
static int eval_chunk(const web_slot *s, int n)
{
    abrdf_batch b = {(size_t)n, sx[0], sx[1], sx[2], sx[3], sx[4], sx[5], sf[0], sf[1], sf[2]};
    if (abrdf_eval_prepared_batch(&s->prep, &b) != ABRDF_OK) return -1;
    if (!s->has_diffuse) return 0;
    abrdf_batch bd = {(size_t)n, sx[0], sx[1], sx[2], sx[3], sx[4], sx[5], sd[0], sd[1], sd[2]};
    if (abrdf_eval_prepared_batch(&s->diffuse, &bd) != ABRDF_OK) return -1;
    for (int c = 0; c < 3; ++c)
        for (int k = 0; k < n; ++k) sf[c][k] += sd[c][k];
    return 0;
}

/* f_r (RGB) of `count` pairs, wi and wo interleaved xyz in the local frame (normal +z), not
 * necessarily unit length, into out (3 count). */
EMSCRIPTEN_KEEPALIVE int aw_eval(int slot, const float *wi, const float *wo, int count, float *out)
{
    const web_slot *s = slot_get(slot);
    if (!s) return -1;
    if (count < 0 || count > AW_MAX_PAIRS)
        return refuse("eval: %d direction pairs is outside [0, %d]", count, AW_MAX_PAIRS);
    for (int base = 0; base < count; base += WEB_CHUNK) {
        int n = count - base < WEB_CHUNK ? count - base : WEB_CHUNK;
        for (int k = 0; k < n; ++k) {
            float a[3] = {wi[3 * (base + k)], wi[3 * (base + k) + 1], wi[3 * (base + k) + 2]};
            float b[3] = {wo[3 * (base + k)], wo[3 * (base + k) + 1], wo[3 * (base + k) + 2]};
            unit(a), unit(b);
            for (int c = 0; c < 3; ++c) sx[c][k] = a[c], sx[3 + c][k] = b[c];
        }
        if (eval_chunk(s, n)) return -1;
        for (int k = 0; k < n; ++k)
            for (int c = 0; c < 3; ++c) out[3 * (base + k) + c] = sf[c][k];
    }
    return 0;
}

/* The lobe in the plane of incidence: light at theta_i (degrees, azimuth 0), view from -90 to
 * +90 degrees in `count` steps (ends included; the mirror direction is -theta_i). */
EMSCRIPTEN_KEEPALIVE int aw_plane(int slot, double theta_i, int count, double *theta_o, float *out)
{
    const web_slot *s = slot_get(slot);
    if (!s) return -1;
    if (count < 2 || count > WEB_CHUNK)
        return refuse("plane: %d samples is outside [2, %d]", count, WEB_CHUNK);
    if (!isfinite(theta_i)) return refuse("plane: the light's angle is not a finite number");
    double ti = theta_i * PI / 180.0;
    for (int k = 0; k < count; ++k) {
        double to = -90.0 + 180.0 * k / (count - 1);
        theta_o[k] = to;
        to *= PI / 180.0;
        sx[0][k] = (float)sin(ti), sx[1][k] = 0.0f, sx[2][k] = (float)cos(ti);
        sx[3][k] = (float)sin(to), sx[4][k] = 0.0f, sx[5][k] = (float)cos(to);
    }
    if (eval_chunk(s, count)) return -1;
    for (int k = 0; k < count; ++k)
        for (int c = 0; c < 3; ++c) out[3 * k + c] = sf[c][k];
    return 0;
}

/* f_r over the hemisphere of views: theta_j = (j + 0.5)/nt * 90 degrees, phi_k = k/np * 360,
 * entry (j np + k) 3; the light at (theta_i, phi_i) degrees. */
EMSCRIPTEN_KEEPALIVE int aw_hemisphere(int slot, double theta_i, double phi_i, int nt, int np,
                                       float *out)
{
    const web_slot *s = slot_get(slot);
    if (!s) return -1;
    if (nt < 1 || np < 1 || nt > AW_MAX_GRID || np > AW_MAX_GRID || nt * np > AW_MAX_GRID_CELLS)
        return refuse("hemisphere: a %d x %d grid is outside 1 to %d per side and %d views", nt, np,
                      AW_MAX_GRID, AW_MAX_GRID_CELLS);
    if (!isfinite(theta_i) || !isfinite(phi_i))
        return refuse("hemisphere: the light's angles are not finite numbers");
    double ti = theta_i * PI / 180.0, pi = phi_i * PI / 180.0;
    float wi[3] = {(float)(sin(ti) * cos(pi)), (float)(sin(ti) * sin(pi)), (float)cos(ti)};
    int total = nt * np;
    for (int base = 0; base < total; base += WEB_CHUNK) {
        int n = total - base < WEB_CHUNK ? total - base : WEB_CHUNK;
        for (int k = 0; k < n; ++k) {
            int j = (base + k) / np, q = (base + k) % np;
            double t = (j + 0.5) / nt * 0.5 * PI, p = (double)q / np * 2.0 * PI;
            for (int c = 0; c < 3; ++c) sx[c][k] = wi[c];
            sx[3][k] = (float)(sin(t) * cos(p)), sx[4][k] = (float)(sin(t) * sin(p));
            sx[5][k] = (float)cos(t);
        }
        if (eval_chunk(s, n)) return -1;
        for (int k = 0; k < n; ++k)
            for (int c = 0; c < 3; ++c) out[3 * (base + k) + c] = sf[c][k];
    }
    return 0;
}

/* The normal of the sphere at pixel (x, y) of a size x size image (y down); 0 outside. */
static int sphere_normal(int x, int y, int size, double n[3])
{
    double u = (2.0 * (x + 0.5) / size - 1.0), v = -(2.0 * (y + 0.5) / size - 1.0);
    double r2 = u * u + v * v;
    if (r2 >= 1.0) return 0;
    n[0] = u, n[1] = v, n[2] = sqrt(1.0 - r2);
    return 1;
}

/* Evaluate the n pending pixels of a sphere band and fill each one's step x step block of
 * rows [y0, y1). */
static int sphere_flush(const web_slot *s, int n, const int *idx, const float *cosl, int size,
                        int y0, int y1, int step, float *out)
{
    if (!n) return 0;
    if (eval_chunk(s, n)) return -1;
    for (int k = 0; k < n; ++k) {
        int by = idx[k] / size, bx = idx[k] % size;
        for (int yy = by > y0 ? by : y0; yy < by + step && yy < y1; ++yy)
            for (int xx = bx; xx < bx + step && xx < size; ++xx) {
                float *o = out + 3 * ((size_t)(yy - y0) * size + xx);
                for (int c = 0; c < 3; ++c) o[c] = sf[c][k] * cosl[k];
            }
    }
    return 0;
}

/* Rows [y0, y1) of the lit sphere (radiance RGB, 3 size (y1 - y0) floats): an orthographic
 * unit sphere seen from +z under a directional light from `l` with irradiance pi at normal
 * incidence, L = f_r max(0, n.l) pi. Every step-th pixel of every step-th row is evaluated
 * (at its block's centre) and fills its step x step block (coarse previews). The tangent
 * runs around the +y axis. */
EMSCRIPTEN_KEEPALIVE int aw_sphere_rows(int slot, int size, double lx, double ly, double lz, int y0,
                                        int y1, int step, float *out)
{
    const web_slot *s = slot_get(slot);
    if (!s) return -1;
    if (size < 1 || size > AW_MAX_SIZE)
        return refuse("sphere: size %d is outside [1, %d]", size, AW_MAX_SIZE);
    if (y0 < 0 || y1 > size || y0 >= y1)
        return refuse("sphere: rows [%d, %d) are not within [0, %d)", y0, y1, size);
    if (step < 1 || step > size) return refuse("sphere: step %d is outside [1, %d]", step, size);
    double ll = sqrt(lx * lx + ly * ly + lz * lz);
    if (!(ll > 0.0) || !isfinite(ll))
        return refuse("sphere: the light direction is zero or not finite");
    double l[3] = {lx / ll, ly / ll, lz / ll};
    memset(out, 0, sizeof(float) * 3 * (size_t)size * (size_t)(y1 - y0));
    int idx[WEB_CHUNK], n = 0;
    float cosl[WEB_CHUNK];
    for (int y = y0 - y0 % step; y < y1; y += step)
        for (int x = 0; x < size; x += step) {
            int cx = x + step / 2 < size ? x + step / 2 : size - 1;
            int cy = y + step / 2 < size ? y + step / 2 : size - 1;
            double nn[3];
            if (!sphere_normal(cx, cy, size, nn)) continue;
            double ndl = nn[0] * l[0] + nn[1] * l[1] + nn[2] * l[2];
            if (ndl <= 0.0) continue;
            double tl = sqrt(nn[2] * nn[2] + nn[0] * nn[0]);
            double t[3] = {tl > 1e-9 ? nn[2] / tl : 1.0, 0.0, tl > 1e-9 ? -nn[0] / tl : 0.0};
            double b[3] = {nn[1] * t[2] - nn[2] * t[1], nn[2] * t[0] - nn[0] * t[2],
                           nn[0] * t[1] - nn[1] * t[0]};
            sx[0][n] = (float)(t[0] * l[0] + t[1] * l[1] + t[2] * l[2]);
            sx[1][n] = (float)(b[0] * l[0] + b[1] * l[1] + b[2] * l[2]);
            sx[2][n] = (float)ndl;
            sx[3][n] = (float)t[2], sx[4][n] = (float)b[2], sx[5][n] = (float)nn[2];
            cosl[n] = (float)(ndl * PI);
            idx[n++] = y * size + x;
            if (n == WEB_CHUNK) {
                if (sphere_flush(s, n, idx, cosl, size, y0, y1, step, out)) return -1;
                n = 0;
            }
        }
    return sphere_flush(s, n, idx, cosl, size, y0, y1, step, out);
}

/* 1 inside the sphere's disk, 0 outside (size x size). */
EMSCRIPTEN_KEEPALIVE int aw_mask(int size, unsigned char *out)
{
    err[0] = err_param[0] = '\0';
    if (size < 1 || size > AW_MAX_SIZE)
        return refuse("mask: size %d is outside [1, %d]", size, AW_MAX_SIZE);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            double n[3];
            out[y * size + x] = (unsigned char)sphere_normal(x, y, size, n);
        }
    return 0;
}

/* NMSE of img against ref over n floats (metrics.h), its Table-8 class by aw_nmse_class. */
EMSCRIPTEN_KEEPALIVE double aw_nmse(const float *img, const float *ref, int n)
{
    err[0] = err_param[0] = '\0';
    if (n < 0) {
        refuse("nmse: %d values", n);
        return NAN;
    }
    double num = 0.0, den = 0.0;
    for (int i = 0; i < n; ++i) {
        double d = (double)img[i] - ref[i];
        num += d * d;
        den += (double)ref[i] * ref[i];
    }
    return den > 0.0 ? num / den : (num > 0.0 ? INFINITY : 0.0);
}

EMSCRIPTEN_KEEPALIVE const char *aw_nmse_class(double nmse) { return abrdf_nmse_class(nmse); }

/* ---- the selection ---------------------------------------------------------------------- */

static int rgb_value(const char *key, const char *s, double v[3])
{
    int count = 0;
    for (const char *p = s; count < 3;) {
        char *end;
        if (decimal(p, &end, &v[count])) break;
        ++count;
        if (*end == '\0') {
            if (count == 1) v[1] = v[2] = v[0];
            if (count == 2) break;
            for (int c = 0; c < 3; ++c)
                if (!(v[c] >= 0.0 && v[c] <= 1.0)) {
                    snprintf(err, sizeof err, "%s = %.17g is outside [0, 1]", key, v[c]);
                    snprintf(err_param, sizeof err_param, "%s", key);
                    return -1;
                }
            return 0;
        }
        if (*end != ',') break;
        p = end + 1;
    }
    fail(key, "%s: give one number or three (R,G,B)", key, 0.0);
    return -1;
}

/* A material from "name=gold;r=0.1;kd=0.5,0.4,0.3;type=general;..." (a row of the table, then
 * values over it, as `abrdf advise NAME --r ...` takes them). */
static int material_parse(const char *spec, abrdf_material *m, const mat_entry **e)
{
    char buf[SPEC_MAX], *cursor = buf, *tok, *v;
    *e = NULL;
    abrdf_material_init(m);
    if (spec_copy(buf, spec, "material")) return -1;
    int has_value = 0;
    for (int got; (got = spec_next(&cursor, &tok, &v));) {
        if (got < 0) return -1;
        char *end;
        double x = 0.0;
        int number = !decimal(v, &end, &x) && *end == '\0';
        if (!strcmp(tok, "name")) {
            if (materials_load()) return -1;
            *e = mat_table_find(&table, v);
            if (!*e) {
                fail("name", "unknown material '%s'", v, 0.0);
                return -1;
            }
            if (has_value) {
                fail("name", "%s: give the material's name before its values", v, 0.0);
                return -1;
            }
            *m = (*e)->m;
            continue;
        }
        has_value = 1;
        if (!strcmp(tok, "type")) {
            if (abrdf_surface_find(v, &m->type) != ABRDF_OK) {
                fail("type", "unknown surface type '%s'", v, 0.0);
                return -1;
            }
        } else if (!strcmp(tok, "kd") || !strcmp(tok, "ks") || !strcmp(tok, "f0")) {
            double *dst = tok[0] == 'f' ? m->f0 : tok[1] == 'd' ? m->kd : m->ks;
            if (rgb_value(tok, v, dst)) return -1;
            if (tok[0] == 'f') m->eta = -1.0;
        } else if (strcmp(tok, "n") && strcmp(tok, "r") && strcmp(tok, "eta") &&
                   strcmp(tok, "anisotropy") && strcmp(tok, "melanin") && strcmp(tok, "redness")) {
            fail(tok, "unknown material value '%s'", tok, 0.0);
            return -1;
        } else if (!number) {
            fail(tok, "%s: the value is not a finite number", tok, 0.0);
            return -1;
        } else if (!(x >= 0.0 && x <= (!strcmp(tok, "n")     ? 1e6
                                       : !strcmp(tok, "eta") ? 4.0
                                                             : 1.0)) ||
                   (!strcmp(tok, "eta") && x < 1.0)) {
            snprintf(err, sizeof err, "%s = %.17g is outside [%g, %g]", tok, x,
                     !strcmp(tok, "eta") ? 1.0 : 0.0,
                     !strcmp(tok, "n")     ? 1e6
                     : !strcmp(tok, "eta") ? 4.0
                                           : 1.0);
            snprintf(err_param, sizeof err_param, "%s", tok);
            return -1;
        } else if (!strcmp(tok, "n"))
            m->n = x;
        else if (!strcmp(tok, "r"))
            m->r = x;
        else if (!strcmp(tok, "eta"))
            m->eta = x;
        else if (!strcmp(tok, "anisotropy"))
            m->anisotropy = x;
        else if (!strcmp(tok, "melanin"))
            m->melanin = x;
        else
            m->redness = x;
    }
    return 0;
}

/* The flowchart's choice for a material and goal, as `abrdf advise --json` prints it. NULL on
 * a bad material (aw_error). */
EMSCRIPTEN_KEEPALIVE const char *aw_select(const char *spec, const char *goal_name)
{
    err[0] = err_param[0] = '\0';
    abrdf_material m;
    const mat_entry *e;
    abrdf_goal goal;
    if (material_parse(spec, &m, &e)) return NULL;
    if (abrdf_goal_find(goal_name, &goal) != ABRDF_OK) {
        fail("goal", "unknown goal '%s' (performance or photoreal)", goal_name, 0.0);
        return NULL;
    }
    abrdf_tolerance tol;
    abrdf_selection sel;
    abrdf_params params;
    select_trace trace = SELECT_TRACE_INIT;
    abrdf_tolerance_init(&tol);
    abrdf_selection_init(&sel);
    abrdf_params_init(ABRDF_MODEL_NONE, &params);
    const char *out = NULL;
    if (abrdf_select(&m, goal, &tol, NULL, &sel, &params, select_trace_keep, &trace) != ABRDF_OK) {
        fail(NULL, "%s", sel.message, 0.0);
    } else if (trace.lost) {
        fail(NULL, "%sout of memory", "", 0.0);
    } else {
        size_t size;
        FILE *f = text_begin(&size);
        if (f) {
            select_json(f, &sel, &params, &trace, e ? e->name : NULL, e ? e->source : NULL, &tol);
            out = text_end(f);
        }
    }
    select_trace_free(&trace);
    return out;
}

/* The budget mode (pareto 0: the cheapest candidate under max_nmse) or the cost/error front
 * (pareto 1), as `abrdf advise --budget ... --json` / `--pareto --json` print them. */
EMSCRIPTEN_KEEPALIVE const char *aw_budget(const char *spec, double max_nmse, int pareto)
{
    err[0] = err_param[0] = '\0';
    abrdf_material m;
    const mat_entry *e;
    if (material_parse(spec, &m, &e)) return NULL;
    if (!pareto && !(max_nmse > 0.0 && max_nmse <= 1.0)) {
        fail("budget", "%sthe budget %g is not in (0, 1]", "", max_nmse);
        return NULL;
    }
    budget_result r;
    char e2[1024];
    if (budget_run(&m, pareto ? 1.0 : max_nmse, NULL, NULL, &r, e2, sizeof e2)) {
        fail(NULL, "%s", e2, 0.0);
        return NULL;
    }
    enum { MAX_CAND = 256 };
    const abrdf_select_step *cand[MAX_CAND];
    int front[MAX_CAND];
    int n = budget_candidates(&r, cand, MAX_CAND), nf = budget_pareto(cand, n, front);
    size_t size;
    const char *out = NULL;
    FILE *f = text_begin(&size);
    if (f) {
        budget_json(f, &r, e ? e->name : NULL, pareto ? 1.0 : max_nmse, cand, n, front, nf, pareto);
        out = text_end(f);
    }
    budget_result_free(&r);
    return out;
}
