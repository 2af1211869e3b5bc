/* scene.c - parser of the scene format (docs/RENDERER.md, "Scene format"): one directive per
 * line, then KEY=VALUE words. Lines may have any length (a long comment is a comment); a word
 * may not exceed SCENE_WORD_MAX, so every message quotes words whole. Every problem is
 * reported as "FILE:LINE: problem"; malformed input of any kind (binary, huge numbers, long
 * words) gives an error, never a crash (tests/fuzz/fuzz_scene.c). */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_args.h"
#include "in_file.h"
#include "measured_file.h"
#include "out_file.h"
#include "param_effect.h"
#include "path_msg.h"
#include "scene.h"
#include "utf8.h"
#include "budget_run.h"

#define SCENE_WORD_MAX 256 /* characters of a word: far above any valid key or value */
#define MAX_WORDS 64
#define SCENE_MAX_FILE (16u << 20) /* 16 MiB: far above any real scene */

typedef struct parser {
    const char *name;
    int line;
    char *err;
    size_t err_size;
    scene *s;
    int have_camera;
    int object_cap;     /* allocated length of s->objects */
    int materials_only; /* scene_parse_materials: material lines only, no camera or object */
} parser;

static int fail(parser *p, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* "NAME:LINE: problem": the problem whole (words are at most SCENE_WORD_MAX long), the name
 * shortened if the buffer is small (path_msg.h). */
static int fail(parser *p, const char *fmt, ...)
{
    if (p->err && p->err_size) {
        char msg[2048];
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(msg, sizeof msg, fmt, ap);
        va_end(ap);
        path_msg(p->err, p->err_size, p->name, ":%d: %s", p->line, msg);
    }
    return -1;
}

/* ---- values ------------------------------------------------------------------------ */

static int parse_num(const char *s, double *out)
{
    if (!*s) return 0;
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    /* ERANGE with a finite result is an underflow (a subnormal or zero): still a number. */
    if (end == s || *end || !isfinite(v) || fabs(v) > SCENE_MAX_COORD) return 0;
    *out = v;
    return 1;
}

/* "A" or "A,B,C" (count 1 or 3), or exactly n numbers if want > 0. Returns the count. */
static int parse_list(const char *s, double *v, int max)
{
    char buf[SCENE_WORD_MAX + 1];
    size_t len = strlen(s);
    if (len > SCENE_WORD_MAX) return 0;
    memcpy(buf, s, len + 1);
    int n = 0;
    char *q = buf;
    for (;;) {
        char *comma = strchr(q, ',');
        if (comma) *comma = '\0';
        if (n == max || !parse_num(q, &v[n])) return 0;
        ++n;
        if (!comma) break;
        q = comma + 1;
    }
    return n;
}

static int get_vec3(parser *p, const char *key, const char *val, double v[3])
{
    if (parse_list(val, v, 3) != 3)
        return fail(p, "%s needs X,Y,Z (three finite numbers, |x| <= %g), got '%s'", key,
                    SCENE_MAX_COORD, val);
    return 0;
}

/* A colour: one number (grey) or R,G,B; every component >= 0. */
static int get_rgb(parser *p, const char *key, const char *val, double v[3])
{
    int n = parse_list(val, v, 3);
    if (n == 1) v[1] = v[2] = v[0];
    if (n != 1 && n != 3) return fail(p, "%s needs one number or R,G,B, got '%s'", key, val);
    if (v[0] < 0 || v[1] < 0 || v[2] < 0)
        return fail(p, "%s must not be negative, got '%s'", key, val);
    return 0;
}

static int get_num(parser *p, const char *key, const char *val, double lo, double hi, int open_lo,
                   double *out)
{
    double v;
    if (!parse_num(val, &v))
        return fail(p, "%s needs a finite number with |x| <= %g, got '%s'", key, SCENE_MAX_COORD,
                    val);
    if (v < lo || v > hi || (open_lo && v == lo))
        return fail(p, "%s = %s is outside %s%g, %g]", key, val, open_lo ? "(" : "[", lo, hi);
    *out = v;
    return 0;
}

static int nonzero3(const double v[3]) { return v[0] != 0 || v[1] != 0 || v[2] != 0; }

/* ---- words ------------------------------------------------------------------------- */

typedef struct word {
    char *key; /* NUL-terminated */
    char *val; /* after '=', or NULL for a bare word */
    int used;
} word;

/* Split a line (modified in place) into words; '#' starts a comment. */
static int split(parser *p, char *line, word *w, int *count)
{
    char *hash = strchr(line, '#');
    if (hash) *hash = '\0';
    int n = 0;
    char *q = line;
    for (;;) {
        while (*q == ' ' || *q == '\t') ++q;
        if (!*q) break;
        if (n == MAX_WORDS) return fail(p, "more than %d words on one line", MAX_WORDS);
        w[n].key = q;
        w[n].val = NULL;
        w[n].used = 0;
        while (*q && *q != ' ' && *q != '\t') ++q;
        if (q - w[n].key > SCENE_WORD_MAX) {
            char shown[64];
            *q = '\0';
            return fail(p, "a word of %ld characters ('%s'); words have at most %d",
                        (long)(q - w[n].key), path_short(shown, sizeof shown, w[n].key, 40),
                        SCENE_WORD_MAX);
        }
        if (*q) *q++ = '\0';
        char *eq = strchr(w[n].key, '=');
        if (eq) {
            *eq = '\0';
            w[n].val = eq + 1;
            if (!*w[n].key) return fail(p, "'=%s' has no key before '='", w[n].val);
        }
        for (const unsigned char *c = (const unsigned char *)w[n].key; *c; ++c)
            if (*c < 0x20 || *c > 0x7e)
                return fail(p, "unexpected byte 0x%02x (not printable ASCII)", *c);
        ++n;
    }
    /* A key given twice is a mistake worth naming. */
    for (int i = 0; i < n; ++i)
        for (int j = i + 1; j < n; ++j)
            if (w[i].val && w[j].val && !strcmp(w[i].key, w[j].key))
                return fail(p, "'%s' is given twice", w[i].key);
    *count = n;
    return 0;
}

/* Value of key among words[from..], marking it used; NULL if absent. */
static const char *take(word *w, int n, int from, const char *key)
{
    for (int i = from; i < n; ++i)
        if (w[i].val && !strcmp(w[i].key, key)) {
            w[i].used = 1;
            return w[i].val;
        }
    return NULL;
}

/* Every word must have been consumed; name the first stray one and the valid keys. */
static int leftovers(parser *p, word *w, int n, int from, const char *valid)
{
    for (int i = from; i < n; ++i)
        if (!w[i].used) {
            if (!w[i].val)
                return fail(p, "unexpected word '%s' (expected KEY=VALUE; keys: %s)", w[i].key,
                            valid);
            return fail(p, "unknown key '%s'; keys: %s", w[i].key, valid);
        }
    return 0;
}

/* ---- directives -------------------------------------------------------------------- */

static int do_camera(parser *p, word *w, int n)
{
    if (p->have_camera) return fail(p, "second camera (a scene has exactly one)");
    scene_camera *c = &p->s->camera;
    const char *v;
    if (!(v = take(w, n, 1, "position"))) return fail(p, "camera needs position=X,Y,Z");
    if (get_vec3(p, "position", v, c->position)) return -1;
    if (!(v = take(w, n, 1, "look_at"))) return fail(p, "camera needs look_at=X,Y,Z");
    if (get_vec3(p, "look_at", v, c->look_at)) return -1;
    c->up[0] = 0, c->up[1] = 1, c->up[2] = 0;
    if ((v = take(w, n, 1, "up")) && get_vec3(p, "up", v, c->up)) return -1;
    c->fov_deg = 40.0;
    if ((v = take(w, n, 1, "fov")) && get_num(p, "fov", v, 0.0, 179.0, 1, &c->fov_deg)) return -1;
    c->width = c->height = 512;
    if ((v = take(w, n, 1, "resolution"))) {
        double r[2];
        if (parse_list(v, r, 2) != 2 || r[0] != floor(r[0]) || r[1] != floor(r[1]) || r[0] < 1 ||
            r[1] < 1 || r[0] > SCENE_MAX_RESOLUTION || r[1] > SCENE_MAX_RESOLUTION)
            return fail(p, "resolution needs W,H (whole numbers in [1, %d]), got '%s'",
                        SCENE_MAX_RESOLUTION, v);
        c->width = (int)r[0];
        c->height = (int)r[1];
    }
    if (leftovers(p, w, n, 1, "position, look_at, up, fov, resolution")) return -1;
    double d[3] = {c->look_at[0] - c->position[0], c->look_at[1] - c->position[1],
                   c->look_at[2] - c->position[2]};
    if (!nonzero3(d)) return fail(p, "camera look_at equals position");
    double x[3] = {d[1] * c->up[2] - d[2] * c->up[1], d[2] * c->up[0] - d[0] * c->up[2],
                   d[0] * c->up[1] - d[1] * c->up[0]};
    double dl = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    double ul = sqrt(c->up[0] * c->up[0] + c->up[1] * c->up[1] + c->up[2] * c->up[2]);
    /* 1e-9 of |d||up|: the view direction and up must span a plane to define "right". */
    if (!(sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]) > 1e-9 * dl * ul))
        return fail(p, "camera up is zero or parallel to the viewing direction");
    p->have_camera = 1;
    return 0;
}

static int do_ambient(parser *p, word *w, int n)
{
    if (n != 2 || w[1].val)
        return fail(p, "ambient needs one colour: 'ambient R,G,B' or 'ambient V'");
    return get_rgb(p, "ambient", w[1].key, p->s->ambient);
}

/* The path of a file the scene names (file=PATH): relative to the scene file's directory
 * unless absolute; any UTF-8 text but control characters. Returns the malloc'd path, or NULL
 * after the message. */
static char *named_path(parser *p, const char *file)
{
    if (!*file) {
        fail(p, "file= is empty");
        return NULL;
    }
    for (const char *c = file; *c;) {
        unsigned long cp;
        int len = utf8_decode(c, &cp);
        if (!len || cp < 0x20 || (cp >= 0x7f && cp < 0xa0)) { /* C0, DEL and C1 controls */
            fail(p, "file= holds byte 0x%02x: a path is UTF-8 text without control characters",
                 (unsigned char)*c);
            return NULL;
        }
        c += len;
    }
    const char *slash = strrchr(p->name, '/');
    size_t dir = file[0] == '/' || !slash ? 0 : (size_t)(slash - p->name) + 1;
    size_t flen = strlen(file);
    char *path = malloc(dir + flen + 1);
    if (!path) {
        fail(p, "out of memory");
        return NULL;
    }
    memcpy(path, p->name, dir);
    memcpy(path + dir, file, flen + 1);
    return path;
}

/* The map of `light environment file=PATH`. */
static int load_envmap(parser *p, const char *file, scene_light *l)
{
    char *path = named_path(p, file);
    if (!path) return -1;
    l->env = calloc(1, sizeof *l->env);
    if (!l->env) {
        free(path);
        return fail(p, "out of memory");
    }
    char err[512];
    int st = envmap_load(path, l->env, err, (int)sizeof err);
    free(path);
    if (st) {
        free(l->env);
        l->env = NULL;
        return fail(p, "environment light: %s", err);
    }
    return 0;
}

static int do_light(parser *p, word *w, int n)
{
    if (p->s->light_count == SCENE_MAX_LIGHTS)
        return fail(p, "more than %d lights", SCENE_MAX_LIGHTS);
    scene_light l;
    memset(&l, 0, sizeof l);
    l.line = p->line;
    if (n < 2 || w[1].val)
        return fail(p, "light needs a kind: 'light point ...' or 'light directional ...'");
    const char *v, *env_file = NULL;
    if (!strcmp(w[1].key, "point")) {
        l.kind = SCENE_LIGHT_POINT;
        if (!(v = take(w, n, 2, "position"))) return fail(p, "point light needs position=X,Y,Z");
        if (get_vec3(p, "position", v, l.position)) return -1;
    } else if (!strcmp(w[1].key, "directional")) {
        l.kind = SCENE_LIGHT_DIRECTIONAL;
        if (!(v = take(w, n, 2, "direction")))
            return fail(p, "directional light needs direction=X,Y,Z (toward the light)");
        if (get_vec3(p, "direction", v, l.direction)) return -1;
        if (!nonzero3(l.direction)) return fail(p, "direction must not be zero");
        double len = sqrt(l.direction[0] * l.direction[0] + l.direction[1] * l.direction[1] +
                          l.direction[2] * l.direction[2]);
        for (int c = 0; c < 3; ++c) l.direction[c] /= len;
    } else if (!strcmp(w[1].key, "sphere")) {
        l.kind = SCENE_LIGHT_SPHERE;
        if (!(v = take(w, n, 2, "center"))) return fail(p, "sphere light needs center=X,Y,Z");
        if (get_vec3(p, "center", v, l.position)) return -1;
        if (!(v = take(w, n, 2, "radius"))) return fail(p, "sphere light needs radius=R");
        if (get_num(p, "radius", v, 0.0, SCENE_MAX_COORD, 1, &l.radius)) return -1;
    } else if (!strcmp(w[1].key, "rect")) {
        l.kind = SCENE_LIGHT_RECT;
        if (!(v = take(w, n, 2, "center"))) return fail(p, "rect light needs center=X,Y,Z");
        if (get_vec3(p, "center", v, l.position)) return -1;
        if (!(v = take(w, n, 2, "u")))
            return fail(p, "rect light needs u=X,Y,Z and v=X,Y,Z (its edges)");
        if (get_vec3(p, "u", v, l.edge_u)) return -1;
        if (!(v = take(w, n, 2, "v")))
            return fail(p, "rect light needs u=X,Y,Z and v=X,Y,Z (its edges)");
        if (get_vec3(p, "v", v, l.edge_v)) return -1;
        double uu = 0, vv = 0, uv = 0;
        for (int c = 0; c < 3; ++c)
            uu += l.edge_u[c] * l.edge_u[c], vv += l.edge_v[c] * l.edge_v[c],
                uv += l.edge_u[c] * l.edge_v[c];
        /* 1e-12 of the edges' squared lengths: far below any visible skew */
        if (!(uu > 1e-18 && vv > 1e-18))
            return fail(p,
                        "rect light edges u and v must each be longer than 1e-9 (|u| = %g, "
                        "|v| = %g)",
                        sqrt(uu), sqrt(vv));
        if (fabs(uv) > 1e-6 * sqrt(uu * vv))
            return fail(p, "rect light edges u and v must be orthogonal (u.v = %g)", uv);
    } else if (!strcmp(w[1].key, "environment")) {
        l.kind = SCENE_LIGHT_ENVIRONMENT;
        if (!(env_file = take(w, n, 2, "file")))
            return fail(p, "environment light needs file=PATH (a lat-long EXR)");
    } else {
        return fail(p,
                    "unknown light kind '%s'; kinds: point, directional, sphere, rect, "
                    "environment",
                    w[1].key);
    }
    l.color[0] = l.color[1] = l.color[2] = 1.0;
    if ((v = take(w, n, 2, "color")) && get_rgb(p, "color", v, l.color)) return -1;
    l.intensity = 1.0;
    if ((v = take(w, n, 2, "intensity")) &&
        get_num(p, "intensity", v, 0.0, SCENE_MAX_COORD, 0, &l.intensity))
        return -1;
    static const char *const keys[] = {"position, color, intensity", "direction, color, intensity",
                                       "center, radius, color, intensity",
                                       "center, u, v, color, intensity", "file, color, intensity"};
    if (leftovers(p, w, n, 2, keys[l.kind])) return -1;
    scene_light *grown = realloc(p->s->lights, (size_t)(p->s->light_count + 1) * sizeof *grown);
    if (!grown) return fail(p, "out of memory");
    p->s->lights = grown;
    if (env_file && load_envmap(p, env_file, &l)) return -1; /* last: nothing to undo after */
    grown[p->s->light_count++] = l;
    return 0;
}

static int find_material(const scene *s, const char *name)
{
    for (int i = 0; i < s->material_count; ++i)
        if (!strcmp(s->materials[i].name, name)) return i;
    return -1;
}

static int set_model(parser *p, const char *key, const char *val, abrdf_model *out)
{
    if (abrdf_model_find(val, out) != ABRDF_OK)
        return fail(p, "%s: unknown model '%s' (abrdf models lists them)", key, val);
    if (abrdf_model_get(*out)->needs & ABRDF_NEEDS_TABLE)
        return fail(p, "%s=%s: a measured material names its table: measured=FILE", key, val);
    return 0;
}

/* A parameter of the line that changes nothing in the material's reflectance (a layer past
 * layer_count, a term the value of another switches off) is an error: it would silently do
 * nothing. 0, or -1 after the message. */
static int without_effect(parser *p, const scene_material *m)
{
    for (int id = 0; id < 64 && id < abrdf_param_count(); ++id) {
        if (!((m->params_set >> id) & 1u)) continue;
        if (!param_matters(m->lobes, m->lobe_count, &m->params, id))
            return fail(p,
                        "material '%s': %s changes nothing in its reflectance here (at these "
                        "values of the others, e.g. a layer past layer_count); drop it",
                        m->name, abrdf_param_get(id)->name);
    }
    return 0;
}

static int copy_name(parser *p, const char *what, const char *src, char dst[SCENE_NAME_MAX])
{
    size_t len = strlen(src);
    if (len == 0 || len >= SCENE_NAME_MAX)
        return fail(p, "%s must have 1 to %d characters", what, SCENE_NAME_MAX - 1);
    memcpy(dst, src, len + 1);
    return 0;
}

/* The table of `measured=FILE` (docs/MEASURED.md, "In a scene"), read once however many
 * materials name it: m->measured. 0, or -1 after the message. */
static int load_measured(parser *p, const char *file, scene_material *m)
{
    scene *s = p->s;
    char *path = named_path(p, file);
    if (!path) return -1;
    for (int i = 0; i < s->measured_count; ++i)
        if (!strcmp(s->measured[i].path, path)) {
            free(path);
            m->measured = i;
            return 0;
        }
    if (s->measured_count == SCENE_MAX_MEASURED_FILES) {
        free(path);
        return fail(p, "more than %d measured files", SCENE_MAX_MEASURED_FILES);
    }
    char err[512];
    const measured_format *f = measured_file_format(path, 0, err, sizeof err);
    scene_measured *grown =
        f ? realloc(s->measured, (size_t)(s->measured_count + 1) * sizeof *grown) : NULL;
    if (!grown) {
        free(path);
        return f ? fail(p, "out of memory") : fail(p, "measured: %s", err);
    }
    s->measured = grown;
    scene_measured *sm = &grown[s->measured_count];
    if (f->read(path, &sm->table, err, sizeof err)) {
        free(path);
        return fail(p, "measured: %s", err);
    }
    sm->path = path;
    sm->format = f->name;
    m->measured = s->measured_count++;
    return 0;
}

/* How the material chooses its models (adaptive with goal= or budget=, table=, measured=, or
 * model= / diffuse= / specular=) into m; *from: the first word after them. 0, or -1 after
 * the message. */
static int material_kind(parser *p, word *w, int n, scene_material *m, int *from)
{
    *from = 2;
    const char *model = take(w, n, *from, "model"), *dif = take(w, n, *from, "diffuse"),
               *spe = take(w, n, *from, "specular"), *table = take(w, n, *from, "table"),
               *measured = take(w, n, *from, "measured");
    int adaptive = n > 2 && !w[2].val && !strcmp(w[2].key, "adaptive");
    if (adaptive) w[2].used = 1, *from = 3;
    if (adaptive) {
        m->kind = SCENE_MAT_ADAPTIVE;
        const char *goal = take(w, n, *from, "goal"), *budget = take(w, n, *from, "budget");
        if (goal && budget)
            return fail(p, "give goal= or budget=, not both (a budget's reference is the "
                           "photoreal choice)");
        if (!goal && !budget)
            return fail(p, "adaptive material needs goal=photoreal, goal=performance or "
                           "budget=none|slight|noticeable|NMSE");
        if (budget) {
            char err[160];
            m->request.by_budget = 1;
            if (budget_parse(budget, &m->request.max_nmse, err, sizeof err))
                return fail(p, "%s", err);
        } else if (abrdf_goal_find(goal, &m->request.goal) != ABRDF_OK) {
            return fail(p, "unknown goal '%s'; goals: photoreal, performance", goal);
        }
        if (model || dif || spe || measured)
            return fail(p, "an adaptive material chooses its own models; drop "
                           "model=/diffuse=/specular=/measured=");
    } else if (table) {
        m->kind = SCENE_MAT_TABLE;
        if (model || dif || spe || measured)
            return fail(p, "table= names a complete material; drop "
                           "model=/diffuse=/specular=/measured=");
    } else if (measured) {
        /* the table, with an optional diffuse lobe under it (diffuse=MODEL, or kd= alone:
         * Lambert) for data measured without its diffuse part */
        m->kind = SCENE_MAT_MODELS;
        if (model || spe)
            return fail(p, "measured= is the material's specular part; drop model=/specular= "
                           "(diffuse=MODEL or kd= adds a diffuse lobe)");
        if (dif && set_model(p, "diffuse", dif, &m->lobes[m->lobe_count++])) return -1;
        if (!dif)
            for (int i = *from; i < n; ++i)
                if (w[i].val && !strcmp(w[i].key, "kd")) m->lobes[m->lobe_count++] = ABRDF_LAMBERT;
        if (m->lobe_count && (abrdf_model_get(m->lobes[0])->props & ABRDF_PROP_DIFFUSE) == 0)
            return fail(p, "diffuse=%s is not a diffuse model", dif);
        m->lobes[m->lobe_count++] = ABRDF_MEASURED;
        if (load_measured(p, measured, m)) return -1;
    } else {
        m->kind = SCENE_MAT_MODELS;
        if (model && (dif || spe))
            return fail(p, "give either model= or diffuse=/specular=, not both");
        if (model) {
            if (set_model(p, "model", model, &m->lobes[0])) return -1;
            m->lobe_count = 1;
        } else if (dif || spe) {
            if (dif && set_model(p, "diffuse", dif, &m->lobes[m->lobe_count++])) return -1;
            if (spe && set_model(p, "specular", spe, &m->lobes[m->lobe_count++])) return -1;
        } else {
            return fail(
                p,
                "material '%s' needs model=, diffuse=/specular=, measured=, table= or adaptive "
                "goal=|budget=",
                m->name);
        }
    }
    if (table && copy_name(p, "table entry", table, m->table)) return -1;
    return 0;
}

/* The parameters' defaults: the first lobe's, then the second lobe's for what only it uses
 * (Lambert's for a material the selection fills in). */
static void material_defaults(scene_material *m)
{
    if (m->kind != SCENE_MAT_MODELS) {
        abrdf_params_init(ABRDF_LAMBERT, &m->params);
        return;
    }
    abrdf_params_init(m->lobes[0], &m->params);
    if (m->lobe_count != 2) return;
    abrdf_params second;
    abrdf_params_init(m->lobes[1], &second);
    const abrdf_model_info *mi = abrdf_model_get(m->lobes[1]);
    for (int i = 0; i < mi->param_count; ++i) {
        int id = mi->params[i].id;
        double v[3];
        if (cli_model_reads(m->lobes[0], id)) continue;
        int cnt = abrdf_param_read(&second, id, v);
        if (cnt > 0) abrdf_param_set(&m->params, id, v, cnt);
    }
}

/* The line's KEY=VALUE words from `from` on: ka, and the parameters the material's models
 * read; *ka_set: whether ka was given. 0, or -1 after the message. */
static int material_params(parser *p, word *w, int n, int from, scene_material *m, int *ka_set)
{
    *ka_set = 0;
    for (int i = from; i < n; ++i) {
        if (w[i].used) continue;
        if (!w[i].val) return fail(p, "unexpected word '%s' (expected KEY=VALUE)", w[i].key);
        w[i].used = 1;
        if (!strcmp(w[i].key, "ka")) {
            if (get_rgb(p, "ka", w[i].val, m->ka)) return -1;
            *ka_set = 1;
            continue;
        }
        int id;
        if (abrdf_param_find(w[i].key, &id) != ABRDF_OK)
            return fail(p,
                        "unknown key '%s'; keys: model, diffuse, specular, measured, table, goal, "
                        "budget, ka and the models' parameters (abrdf models)",
                        w[i].key);
        int used = m->kind != SCENE_MAT_MODELS;
        for (int l = 0; l < m->lobe_count; ++l) used |= cli_model_reads(m->lobes[l], id);
        if (!used)
            return fail(p, "parameter '%s' is not used by the material's model(s)", w[i].key);
        const abrdf_param_info *pi = abrdf_param_get(id);
        double v[3];
        int cnt = parse_list(w[i].val, v, 3);
        if (cnt != 1 && !(cnt == 3 && pi->kind == ABRDF_PARAM_RGB))
            return fail(p, "%s needs %s, got '%s'", w[i].key,
                        pi->kind == ABRDF_PARAM_RGB ? "one number or R,G,B" : "one number",
                        w[i].val);
        if (abrdf_param_set(&m->params, id, v, cnt) != ABRDF_OK)
            return fail(p, "%s = %s is outside [%g, %g]%s", w[i].key, w[i].val, pi->min, pi->max,
                        pi->kind == ABRDF_PARAM_INT ? " or not a whole number" : "");
        if (id < 64) m->params_set |= 1ull << id;
    }
    return 0;
}

/* ---- pbr materials (glTF metallic-roughness, abrdf_pbr.h) ------------------------------ */

static const char *const map_names[SCENE_MAP_COUNT] = {"base_color", "metallic", "roughness",
                                                       "occlusion", "normal"};

const char *scene_map_name(scene_map_slot slot)
{
    return (unsigned)slot < SCENE_MAP_COUNT ? map_names[slot] : NULL;
}

#define PBR_KEYS                                                                                   \
    "base_color, metallic, roughness, ior, specular, specular_color, clearcoat, "                  \
    "clearcoat_roughness, sheen_color, sheen_roughness, anisotropy, anisotropy_rotation, "         \
    "transmission, base_color_map, base_color_srgb, metallic_map, metallic_channel, "              \
    "roughness_map, roughness_channel, occlusion_map, occlusion_channel, occlusion_strength, "     \
    "normal_map, normal_scale, ka, goal, budget"

void scene_material_free(scene_material *m)
{
    for (int k = 0; k < SCENE_MAP_COUNT; ++k) {
        free(m->maps[k].path), free(m->maps[k].blob);
        m->maps[k].path = NULL, m->maps[k].blob = NULL, m->maps[k].blob_size = 0;
    }
}

void scene_pbr_init(scene_material *m)
{
    abrdf_pbr_init(&m->pbr_in);
    static const int default_channel[SCENE_MAP_COUNT] = {0, 2, 1, 0, 0};
    for (int k = 0; k < SCENE_MAP_COUNT; ++k) {
        m->maps[k].channel = default_channel[k];
        m->maps[k].srgb = k == SCENE_MAP_BASE_COLOR;
        m->maps[k].strength = 1;
        m->maps[k].scale[0] = m->maps[k].scale[1] = 1;
    }
}

int scene_pbr_finish(scene_material *m, char *msg, size_t msg_size)
{
    m->pbr = 1;
    if (m->kind != SCENE_MAT_ADAPTIVE) m->kind = SCENE_MAT_MODELS;
    abrdf_params_init(ABRDF_DISNEY_SPECULAR, &m->params);
    if (abrdf_pbr_lobes(&m->pbr_in, m->lobes, &m->lobe_count, &m->params) != ABRDF_OK) {
        abrdf_pbr_check(&m->pbr_in, msg, msg_size);
        return -1;
    }
    m->params_set = 0;
    if (!m->ka_given) memcpy(m->ka, m->params.kd, sizeof m->ka);
    m->textured = 0;
    for (int k = 0; k < SCENE_MAP_COUNT; ++k) m->textured |= m->maps[k].path != NULL;
    return 0;
}

/* The words of `material NAME pbr ...` from index 3: factors, maps, goal= or budget=. The
 * material gets glTF's defaults for what the line omits. 0, or -1 after the message (its
 * map paths freed). */
static int pbr_words(parser *p, word *w, int n, scene_material *m)
{
    abrdf_pbr *q = &m->pbr_in;
    scene_pbr_init(m);
    struct {
        const char *key;
        double *v;
        int rgb;
        double lo, hi;
    } const f[] = {
        {"base_color", q->base_color, 1, 0, 1},
        {"metallic", &q->metallic, 0, 0, 1},
        {"roughness", &q->roughness, 0, 0, 1},
        {"ior", &q->ior, 0, 1, 4},
        {"specular", &q->specular, 0, 0, 1},
        {"specular_color", q->specular_color, 1, 0, 100},
        {"clearcoat", &q->clearcoat, 0, 0, 1},
        {"clearcoat_roughness", &q->clearcoat_roughness, 0, 0, 1},
        {"sheen_color", q->sheen_color, 1, 0, 1},
        {"sheen_roughness", &q->sheen_roughness, 0, 0, 1},
        {"anisotropy", &q->anisotropy, 0, 0, 1},
        {"anisotropy_rotation", &q->anisotropy_rotation, 0, -1e3, 1e3},
        {"transmission", &q->transmission, 0, 0, 1},
        {"occlusion_strength", &m->maps[SCENE_MAP_OCCLUSION].strength, 0, 0, 1},
        {"normal_scale", &m->maps[SCENE_MAP_NORMAL].strength, 0, -100, 100},
    };
    for (size_t i = 0; i < sizeof f / sizeof f[0]; ++i) {
        const char *v = take(w, n, 3, f[i].key);
        if (!v) continue;
        if (f[i].rgb) {
            double c[3];
            if (get_rgb(p, f[i].key, v, c)) return -1;
            for (int k = 0; k < 3; ++k)
                if (c[k] < f[i].lo || c[k] > f[i].hi)
                    return fail(p, "%s = %s is outside [%g, %g]", f[i].key, v, f[i].lo, f[i].hi);
            memcpy(f[i].v, c, sizeof c);
        } else if (get_num(p, f[i].key, v, f[i].lo, f[i].hi, 0, f[i].v)) {
            return -1;
        }
    }
    for (int k = 0; k < SCENE_MAP_COUNT; ++k) {
        char key[40];
        snprintf(key, sizeof key, "%s_map", map_names[k]);
        const char *file = take(w, n, 3, key);
        snprintf(key, sizeof key, "%s_channel", map_names[k]);
        const char *ch = take(w, n, 3, key);
        if (ch) {
            double c;
            if (k == SCENE_MAP_BASE_COLOR || k == SCENE_MAP_NORMAL)
                return fail(p, "%s: the %s map is read as RGB", key, map_names[k]);
            if (get_num(p, key, ch, 0, 3, 0, &c)) return -1;
            if (c != floor(c)) return fail(p, "%s = %s is not a whole number", key, ch);
            m->maps[k].channel = (int)c;
        }
        if (!file) continue;
        if (!*file) return fail(p, "%s_map= is empty", map_names[k]);
        char *path = named_path(p, file);
        if (!path) return -1;
        char err[512];
        if (in_file_check(path, err, sizeof err)) {
            free(path);
            return fail(p, "%s_map: %s", map_names[k], err);
        }
        m->maps[k].path = path;
        m->textured = 1;
    }
    const char *srgb = take(w, n, 3, "base_color_srgb");
    if (srgb) {
        if (strcmp(srgb, "on") && strcmp(srgb, "off"))
            return fail(p, "base_color_srgb=%s: on or off", srgb);
        m->maps[SCENE_MAP_BASE_COLOR].srgb = !strcmp(srgb, "on");
    }
    const char *ka = take(w, n, 3, "ka");
    if (ka) {
        if (get_rgb(p, "ka", ka, m->ka)) return -1;
        m->ka_given = 1;
    }
    const char *goal = take(w, n, 3, "goal"), *budget = take(w, n, 3, "budget");
    if (goal && budget)
        return fail(p, "give goal= or budget=, not both (a budget's reference is the "
                       "photoreal choice)");
    if (budget) {
        char err[160];
        m->kind = SCENE_MAT_ADAPTIVE, m->request.by_budget = 1;
        if (budget_parse(budget, &m->request.max_nmse, err, sizeof err)) return fail(p, "%s", err);
    } else if (goal) {
        m->kind = SCENE_MAT_ADAPTIVE;
        if (abrdf_goal_find(goal, &m->request.goal) != ABRDF_OK)
            return fail(p, "unknown goal '%s'; goals: photoreal, performance", goal);
    }
    if (leftovers(p, w, n, 3, PBR_KEYS)) return -1;
    char msg[256];
    if (scene_pbr_finish(m, msg, sizeof msg)) return fail(p, "material '%s': %s", m->name, msg);
    return 0;
}

int scene_pbr_params(const scene_material *sm, const abrdf_pbr *q, abrdf_params *out)
{
    abrdf_model lobes[ABRDF_PBR_MAX_LOBES];
    int count;
    abrdf_params mapped;
    abrdf_params_init(ABRDF_DISNEY_SPECULAR, &mapped);
    if (abrdf_pbr_lobes(q, lobes, &count, &mapped) != ABRDF_OK) return -1;
    if (sm->fit_count > 0) { /* the budget's fits between the two nearest groups, recoloured */
        int g = 0, n = sm->fit_count;
        while (g + 1 < n && sm->fit_r[g + 1] <= q->roughness) ++g;
        int h = g + 1 < n ? g + 1 : g;
        double t =
            h > g && sm->fit_r[h] > sm->fit_r[g]
                ? fmin(fmax((q->roughness - sm->fit_r[g]) / (sm->fit_r[h] - sm->fit_r[g]), 0.0),
                       1.0)
                : 0.0;
        const abrdf_params *a = &sm->fit_params[g], *b = &sm->fit_params[h];
        *out = *a;
        for (int c = 0; c < 3; ++c) {
            out->kd[c] = a->kd[c] + t * (b->kd[c] - a->kd[c]);
            out->ks[c] = a->ks[c] + t * (b->ks[c] - a->ks[c]);
            out->f0[c] = a->f0[c] + t * (b->f0[c] - a->f0[c]);
        }
        out->r = a->r + t * (b->r - a->r);
        out->anisotropic = a->anisotropic + t * (b->anisotropic - a->anisotropic);
        /* an exponent changes by factors: between them geometrically */
        out->n = a->n > 0 && b->n > 0 ? a->n * pow(b->n / a->n, t) : a->n + t * (b->n - a->n);
        abrdf_pbr at = sm->pbr_in;
        at.roughness = sm->fit_r[g] + t * (sm->fit_r[h] - sm->fit_r[g]);
        abrdf_params base;
        abrdf_params_init(ABRDF_DISNEY_SPECULAR, &base);
        if (abrdf_pbr_lobes(&at, lobes, &count, &base) != ABRDF_OK) return -1;
        for (int c = 0; c < 3; ++c) {
            if (base.kd[c] > 0) out->kd[c] = fmin(out->kd[c] * mapped.kd[c] / base.kd[c], 1.0);
            if (base.f0[c] > 0) out->ks[c] = fmin(out->ks[c] * mapped.f0[c] / base.f0[c], 1.0);
            out->f0[c] = mapped.f0[c];
        }
        return 0;
    }
    *out = sm->params;
    /* No map of the material changes a factor (a normal or occlusion map only), so q is its
     * own factors: its block is the one chosen and predicted for them, a fitted stand-in's fit
     * included. Decided per material (a texel of 1 must not switch blocks), and only for the
     * material's own factors (a caller's other q is mapped). */
    if (!sm->maps[SCENE_MAP_BASE_COLOR].path && !sm->maps[SCENE_MAP_METALLIC].path &&
        !sm->maps[SCENE_MAP_ROUGHNESS].path && q->metallic == sm->pbr_in.metallic &&
        q->roughness == sm->pbr_in.roughness && q->base_color[0] == sm->pbr_in.base_color[0] &&
        q->base_color[1] == sm->pbr_in.base_color[1] &&
        q->base_color[2] == sm->pbr_in.base_color[2])
        return 0;
    memcpy(out->kd, mapped.kd, sizeof out->kd);
    memcpy(out->ks, mapped.ks, sizeof out->ks);
    memcpy(out->f0, mapped.f0, sizeof out->f0);
    out->r = mapped.r;
    out->anisotropic = mapped.anisotropic;
    int n_id;
    abrdf_param_find("n", &n_id);
    for (int l = 0; l < sm->lobe_count; ++l)
        if (cli_model_reads(sm->lobes[l], n_id)) {
            double a = mapped.r * mapped.r;
            out->n = a > 0 ? fmin(abrdf_alpha_g_to_n(a), 1e6) : 1e6;
        }
    return 0;
}

/* `material NAME pbr ...`: into the scene's materials. 0, or -1 after the message. */
static int do_pbr_material(parser *p, word *w, int n, scene_material *m)
{
    w[2].used = 1;
    m->pbr = 1;
    m->kind = SCENE_MAT_MODELS;
    if (pbr_words(p, w, n, m)) {
        scene_material_free(m);
        return -1;
    }
    scene *s = p->s;
    scene_material *grown = realloc(s->materials, (size_t)(s->material_count + 1) * sizeof *grown);
    if (!grown) {
        scene_material_free(m);
        return fail(p, "out of memory");
    }
    s->materials = grown;
    grown[s->material_count++] = *m;
    return 0;
}

static int do_material(parser *p, word *w, int n)
{
    scene *s = p->s;
    if (s->material_count == SCENE_MAX_MATERIALS)
        return fail(p, "more than %d materials", SCENE_MAX_MATERIALS);
    if (n < 2 || w[1].val) return fail(p, "material needs a name: 'material NAME model=...'");
    scene_material m;
    memset(&m, 0, sizeof m);
    m.line = p->line;
    m.measured = -1;
    if (copy_name(p, "material name", w[1].key, m.name)) return -1;
    if (find_material(s, m.name) >= 0) return fail(p, "material '%s' is defined twice", m.name);
    if (n > 2 && !w[2].val && !strcmp(w[2].key, "pbr")) return do_pbr_material(p, w, n, &m);
    int from, ka_set, kd_used = 0;
    if (material_kind(p, w, n, &m, &from)) return -1;
    material_defaults(&m);
    if (material_params(p, w, n, from, &m, &ka_set)) return -1;
    for (int l = 0; l < m.lobe_count; ++l) {
        char msg[256];
        if (m.lobes[l] == ABRDF_MEASURED && m.measured >= 0) continue; /* read and checked */
        if (abrdf_params_check(m.lobes[l], &m.params, msg, sizeof msg) != ABRDF_OK)
            return fail(p, "material '%s': %s", m.name, msg);
        int kd_id;
        kd_used |= abrdf_param_find("kd", &kd_id) == ABRDF_OK && cli_model_reads(m.lobes[l], kd_id);
    }
    if (m.kind == SCENE_MAT_MODELS && without_effect(p, &m)) return -1;
    /* Default ambient reflectance: the diffuse albedo where the material has one. */
    m.ka_given = ka_set;
    if (!ka_set && (kd_used || m.kind != SCENE_MAT_MODELS)) memcpy(m.ka, m.params.kd, sizeof m.ka);
    scene_material *grown = realloc(s->materials, (size_t)(s->material_count + 1) * sizeof *grown);
    if (!grown) return fail(p, "out of memory");
    s->materials = grown;
    grown[s->material_count++] = m;
    return 0;
}

static const char *const shape_names[SCENE_SHAPE_COUNT] = {"sphere", "cylinder", "capsule", "box",
                                                           "mesh"};
static const char *const tangent_names[] = {"u", "v", "radial", "axis", "uv"};

const char *scene_shape_name(scene_shape shape)
{
    return (unsigned)shape < SCENE_SHAPE_COUNT ? shape_names[shape] : "?";
}

const char *scene_tangent_name(scene_tangent t)
{
    return (unsigned)t <= SCENE_TANGENT_UV ? tangent_names[t] : "?";
}

/* Append to a growing array (capacity doubles: a scene of 1e5 objects is not quadratic). */
static int append(parser *p, void **arr, int *count, int *cap, const void *item, size_t size)
{
    if (*count == *cap) {
        int c = *cap ? 2 * *cap : 16;
        void *g = realloc(*arr, (size_t)c * size);
        if (!g) return fail(p, "out of memory");
        *arr = g;
        *cap = c;
    }
    memcpy((char *)*arr + (size_t)*count * size, item, size);
    ++*count;
    return 0;
}

/* The mesh file of `mesh file=PATH`; read once however many objects use it. */
static int load_mesh(parser *p, const char *file, scene_object *o)
{
    scene *s = p->s;
    char *path = named_path(p, file);
    if (!path) return -1;
    for (int i = 0; i < s->mesh_count; ++i)
        if (!strcmp(s->meshes[i]->path, path)) {
            free(path);
            o->mesh = i;
            o->mesh_data = s->meshes[i];
            return 0;
        }
    if (s->mesh_count == SCENE_MAX_MESH_FILES) {
        free(path);
        return fail(p, "more than %d mesh files", SCENE_MAX_MESH_FILES);
    }
    mesh *m = malloc(sizeof *m);
    mesh **grown = realloc(s->meshes, (size_t)(s->mesh_count + 1) * sizeof *grown);
    if (!m || !grown) {
        free(m), free(path);
        if (grown) s->meshes = grown;
        return fail(p, "out of memory");
    }
    s->meshes = grown;
    char err[512];
    int st = mesh_load_file(path, MESH_MAX_TRIANGLES, m, err, sizeof err);
    if (st) {
        free(m), free(path);
        if (st != -1) return fail(p, "%s", err); /* the file as a whole: name the scene line */
        /* A problem inside the mesh file: its FILE:LINE first, the scene line after. */
        if (p->err && p->err_size)
            snprintf(p->err, p->err_size, "%.400s (mesh at %s:%d)", err, p->name, p->line);
        return -1;
    }
    free(path);
    s->meshes[s->mesh_count] = m;
    o->mesh = s->mesh_count++;
    o->mesh_data = m;
    return 0;
}

static int do_object(parser *p, scene_shape shape, word *w, int n)
{
    scene *s = p->s;
    if (s->object_count == SCENE_MAX_OBJECTS)
        return fail(p, "more than %d objects", SCENE_MAX_OBJECTS);
    scene_object o;
    memset(&o, 0, sizeof o);
    o.shape = shape;
    o.line = p->line;
    o.mesh = -1;
    o.scale[0] = o.scale[1] = o.scale[2] = 1.0;
    const char *v;
    if (!(v = take(w, n, 1, "material")))
        return fail(p, "%s needs material=NAME", shape_names[shape]);
    if ((o.material = find_material(s, v)) < 0)
        return fail(p, "material '%s' is not defined above", v);
    const char *valid = "material, radius, translate, rotate, scale, tangent";
    if (shape == SCENE_SPHERE || shape == SCENE_CYLINDER || shape == SCENE_CAPSULE) {
        if (!(v = take(w, n, 1, "radius"))) return fail(p, "%s needs radius=R", shape_names[shape]);
        if (get_num(p, "radius", v, 0.0, SCENE_MAX_COORD, 1, &o.radius)) return -1;
    }
    if (shape == SCENE_CYLINDER || shape == SCENE_CAPSULE) {
        valid = "material, radius, height, translate, rotate, scale, tangent";
        if (!(v = take(w, n, 1, "height"))) return fail(p, "%s needs height=H", shape_names[shape]);
        if (get_num(p, "height", v, 0.0, SCENE_MAX_COORD, shape == SCENE_CYLINDER, &o.height))
            return -1;
    }
    if (shape == SCENE_BOX) {
        valid = "material, size, translate, rotate, scale, tangent";
        if (!(v = take(w, n, 1, "size"))) return fail(p, "box needs size=X,Y,Z");
        if (get_vec3(p, "size", v, o.size)) return -1;
        if (!(o.size[0] > 0 && o.size[1] > 0 && o.size[2] > 0))
            return fail(p, "box size must be positive, got '%s'", v);
    }
    const char *file = NULL;
    if (shape == SCENE_MESH) {
        valid = "file, material, smooth, translate, rotate, scale, tangent";
        if (!(file = take(w, n, 1, "file"))) return fail(p, "mesh needs file=PATH");
        o.smooth = 1;
        if ((v = take(w, n, 1, "smooth"))) {
            if (strcmp(v, "on") && strcmp(v, "off"))
                return fail(p, "smooth must be on or off, got '%s'", v);
            o.smooth = !strcmp(v, "on");
        }
    }
    if ((v = take(w, n, 1, "translate")) && get_vec3(p, "translate", v, o.translate)) return -1;
    if ((v = take(w, n, 1, "rotate")) && get_vec3(p, "rotate", v, o.rotate_deg)) return -1;
    if ((v = take(w, n, 1, "scale"))) {
        int cnt = parse_list(v, o.scale, 3);
        if (cnt == 1) o.scale[1] = o.scale[2] = o.scale[0];
        /* 1e-6: a thinner object makes the inverse transform ill-conditioned. */
        if ((cnt != 1 && cnt != 3) ||
            !(o.scale[0] >= 1e-6 && o.scale[1] >= 1e-6 && o.scale[2] >= 1e-6))
            return fail(p, "scale needs S or X,Y,Z, each in [1e-6, %g], got '%s'", SCENE_MAX_COORD,
                        v);
    }
    o.tangent = SCENE_TANGENT_U;
    const char *tangent = take(w, n, 1, "tangent");
    if (tangent) {
        int k;
        for (k = 0; k <= SCENE_TANGENT_UV; ++k)
            if (k != SCENE_TANGENT_AXIS && !strcmp(tangent, tangent_names[k])) break;
        if (k <= SCENE_TANGENT_UV) {
            o.tangent = (scene_tangent)k;
        } else if (parse_list(tangent, o.tangent_axis, 3) == 3 && nonzero3(o.tangent_axis)) {
            o.tangent = SCENE_TANGENT_AXIS;
        } else {
            return fail(p,
                        "tangent must be u, v, radial, uv (meshes) or a non-zero direction "
                        "X,Y,Z, got '%s'",
                        tangent);
        }
        if (o.tangent == SCENE_TANGENT_UV && shape != SCENE_MESH)
            return fail(p, "tangent=uv needs a mesh (a %s has no texture coordinates)",
                        shape_names[shape]);
    }
    if (leftovers(p, w, n, 1, valid)) return -1;
    if (file) {
        if (load_mesh(p, file, &o)) return -1;
        if (o.tangent == SCENE_TANGENT_UV && !o.mesh_data->uv)
            return fail(p, "tangent=uv: %s has no texture coordinates (vt)", o.mesh_data->path);
        long long total = s->triangle_count + o.mesh_data->triangle_count;
        if (total > SCENE_MAX_TRIANGLES)
            return fail(p, "this mesh brings the scene to %lld triangles, more than %d", total,
                        SCENE_MAX_TRIANGLES);
        s->triangle_count = total;
    }
    return append(p, (void **)&s->objects, &s->object_count, &p->object_cap, &o, sizeof o);
}

static int do_line(parser *p, char *line)
{
    word w[MAX_WORDS];
    int n = 0; /* split sets it; gcc -O2 -g cannot see that */
    if (split(p, line, w, &n)) return -1;
    if (n == 0) return 0;
    if (w[0].val) return fail(p, "a line starts with a directive, got '%s=...'", w[0].key);
    const char *d = w[0].key;
    if (p->materials_only && strcmp(d, "material"))
        return fail(p, "'%s': a material list holds material lines only", d);
    if (!strcmp(d, "camera")) return do_camera(p, w, n);
    if (!strcmp(d, "ambient")) return do_ambient(p, w, n);
    if (!strcmp(d, "light")) return do_light(p, w, n);
    if (!strcmp(d, "material")) return do_material(p, w, n);
    for (int k = 0; k < SCENE_SHAPE_COUNT; ++k)
        if (!strcmp(d, shape_names[k])) return do_object(p, (scene_shape)k, w, n);
    return fail(p,
                "unknown directive '%s'; directives: camera, ambient, light, material, "
                "sphere, cylinder, capsule, box, mesh",
                d);
}

void scene_free(scene *s)
{
    if (!s) return;
    for (int i = 0; i < s->light_count; ++i)
        if (s->lights[i].env) envmap_free(s->lights[i].env), free(s->lights[i].env);
    free(s->lights);
    for (int i = 0; i < s->material_count; ++i) scene_material_free(&s->materials[i]);
    free(s->materials);
    free(s->objects);
    for (int i = 0; i < s->mesh_count; ++i) {
        mesh_free(s->meshes[i]);
        free(s->meshes[i]);
    }
    free(s->meshes);
    for (int i = 0; i < s->measured_count; ++i) {
        free(s->measured[i].path);
        measured_table_free(&s->measured[i].table);
    }
    free(s->measured);
    for (int i = 0; i < s->buffer_file_count; ++i) free(s->buffer_files[i]);
    free(s->buffer_files);
    free(s->notes);
    memset(s, 0, sizeof *s);
}

static void name_file(const char **paths, const char **roles, int max, int n, const char *path,
                      const char *role)
{
    if (n >= max) return;
    paths[n] = path;
    if (roles) roles[n] = role;
}

int scene_named_files(const scene *s, const char **paths, const char **roles, int max)
{
    int n = 0;
    for (int i = 0; i < s->mesh_count; ++i)
        if (!s->meshes[i]->in_memory)
            name_file(paths, roles, max, n++, s->meshes[i]->path, "mesh file");
    for (int i = 0; i < s->light_count; ++i)
        if (s->lights[i].env)
            name_file(paths, roles, max, n++, s->lights[i].env->path, "environment map");
    for (int i = 0; i < s->measured_count; ++i)
        name_file(paths, roles, max, n++, s->measured[i].path, "measured file");
    for (int i = 0; i < s->material_count; ++i)
        for (int k = 0; k < SCENE_MAP_COUNT; ++k)
            if (s->materials[i].maps[k].path && !s->materials[i].maps[k].blob)
                name_file(paths, roles, max, n++, s->materials[i].maps[k].path, "texture");
    for (int i = 0; i < s->buffer_file_count; ++i)
        name_file(paths, roles, max, n++, s->buffer_files[i], "buffer file");
    return n;
}

int scene_outputs_distinct(const scene *s, const char *const *outputs,
                           const char *const *output_roles, int nout, char *err, size_t err_size)
{
    int n = scene_named_files(s, NULL, NULL, 0);
    const char **paths = malloc((size_t)(n ? n : 1) * sizeof *paths),
               **roles = malloc((size_t)(n ? n : 1) * sizeof *roles);
    int rc = -1;
    if (!paths || !roles)
        snprintf(err, err_size, "out of memory");
    else {
        scene_named_files(s, paths, roles, n);
        rc = out_files_distinct(outputs, output_roles, nout, paths, roles, n, err, err_size);
    }
    free(paths), free(roles);
    return rc;
}

static int parse_text(const char *name, const char *text, size_t len, int materials_only,
                      scene *out, char *err, size_t err_size)
{
    if (err && err_size) err[0] = '\0';
    if (!out) return -1;
    memset(out, 0, sizeof *out);
    parser p = {name ? name : "<scene>", 0, err, err_size, out, 0, 0, materials_only};
    if (!text) return fail(&p, "no text");
    /* Lines are split in a copy of the text, in place: any length is fine. */
    char *copy = malloc(len + 1);
    if (!copy) return fail(&p, "out of memory");
    memcpy(copy, text, len);
    copy[len] = '\0';
    size_t i = 0;
    while (i < len) {
        ++p.line;
        char *line = copy + i;
        for (; i < len && copy[i] != '\n'; ++i) {
            if (copy[i] == '\0') {
                fail(&p, "NUL byte in the file (not a text scene)");
                free(copy);
                goto bad;
            }
            if (copy[i] == '\r') copy[i] = ' ';
        }
        copy[i++] = '\0'; /* the '\n' (or the terminator) */
        if (do_line(&p, line)) {
            free(copy);
            goto bad;
        }
    }
    free(copy);
    ++p.line;
    if (materials_only) {
        if (out->material_count) return 0;
        p.line = 0;
        fail(&p, "no materials");
        goto bad;
    }
    if (!p.have_camera) {
        p.line = 0;
        fail(&p, "no camera (a scene needs 'camera position=... look_at=...')");
        goto bad;
    }
    if (out->object_count == 0) {
        p.line = 0;
        fail(&p, "no objects (sphere, cylinder, capsule, box or mesh)");
        goto bad;
    }
    return 0;
bad:
    scene_free(out);
    return -1;
}

int scene_parse_text(const char *name, const char *text, size_t len, scene *out, char *err,
                     size_t err_size)
{
    return parse_text(name, text, len, 0, out, err, err_size);
}

int scene_parse_materials(const char *name, const char *text, size_t len, scene *out, char *err,
                          size_t err_size)
{
    return parse_text(name, text, len, 1, out, err, err_size);
}

int scene_parse_file(const char *path, scene *out, char *err, size_t err_size)
{
    if (out) memset(out, 0, sizeof *out);
    char tmp[2];
    FILE *f = in_file_open(path, err && err_size ? err : tmp, err && err_size ? err_size : 1);
    if (!f) return -1;
    char *buf = NULL;
    size_t len = 0, cap = 0;
    for (;;) {
        if (len == cap) {
            if (cap >= SCENE_MAX_FILE) {
                if (err && err_size)
                    path_msg(err, err_size, path, ": larger than %u bytes", SCENE_MAX_FILE);
                free(buf);
                fclose(f);
                return -1;
            }
            cap = cap ? 2 * cap : 65536;
            char *g = realloc(buf, cap);
            if (!g) {
                free(buf);
                fclose(f);
                if (err && err_size) path_msg(err, err_size, path, ": out of memory");
                return -1;
            }
            buf = g;
        }
        size_t got = fread(buf + len, 1, cap - len, f);
        len += got;
        if (got == 0) break;
    }
    int bad = ferror(f), code = errno;
    fclose(f);
    if (bad) {
        free(buf);
        if (err && err_size) path_msg(err, err_size, path, ": read error: %s", strerror(code));
        return -1;
    }
    int st = scene_parse_text(path, buf, len, out, err, err_size);
    free(buf);
    return st;
}
