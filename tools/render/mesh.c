/* mesh.c - OBJ meshes (mesh.h). tinyobjloader parses (mesh_obj.cpp); it is lenient by
 * design - a word it cannot read as a number becomes 0, words beyond the ones it reads are
 * dropped, statements it does not know are skipped - so every line it hands over is checked
 * here word by word, and a malformed file is an error naming its line instead of a silently
 * different mesh (tests/fuzz/fuzz_mesh.c). */
#define _POSIX_C_SOURCE 200809L /* fileno, fstat */
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "in_file.h"
#include "mesh.h"
#include "mesh_obj.h"
#include "path_msg.h"

typedef struct loader {
    const char *name;
    char *err;
    size_t err_size;
    mesh *m;
    int max_triangles;
    size_t cap_v, cap_n, cap_uv, cap_t;
    int faces;                   /* face statements so far */
    int face_has_n, face_has_uv; /* what the first face gave, for the others to match */
    int first_face_line;
    int max_ref[3], max_ref_line[3]; /* largest positive index per kind (v, vt, vn) */
} loader;

static int fail(loader *ld, int line, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

static int fail(loader *ld, int line, const char *fmt, ...)
{
    if (ld->err && ld->err_size && !ld->err[0]) {
        char msg[512];
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(msg, sizeof msg, fmt, ap);
        va_end(ap);
        snprintf(ld->err, ld->err_size, "%s:%d: %s", ld->name, line, msg);
    }
    return -1;
}

/* ---- words of a line --------------------------------------------------------------- */

typedef struct words {
    const char *p, *end;
} words;

/* Next word (spaces and tabs separate words); 0 at the end of the line. */
static int next_word(words *w, const char **s, size_t *len)
{
    while (w->p < w->end && (*w->p == ' ' || *w->p == '\t')) ++w->p;
    if (w->p >= w->end) return 0;
    *s = w->p;
    while (w->p < w->end && *w->p != ' ' && *w->p != '\t') ++w->p;
    *len = (size_t)(w->p - *s);
    return 1;
}

/* Print at most 24 characters of a word for a message. */
#define WORD_FMT "'%.*s%s'"
#define WORD_ARG(s, len) (int)((len) > 24 ? 24 : (len)), (s), (len) > 24 ? "..." : ""

/* The longest number word read (longer ones are refused by name: no OBJ writer needs them). */
#define MESH_NUMBER_MAX 255

/* A decimal number as tinyobjloader reads it (no hex, inf or nan), finite; a number too small
 * for a double is its subnormal or zero, as in the scene format. */
static int read_number(const char *s, size_t len, double *out)
{
    char buf[MESH_NUMBER_MAX + 1];
    if (len == 0 || len > MESH_NUMBER_MAX) return 0;
    for (size_t i = 0; i < len; ++i) {
        char c = s[i];
        if (!((c >= '0' && c <= '9') || c == '.' || c == '-' || c == '+' || c == 'e' || c == 'E'))
            return 0;
    }
    memcpy(buf, s, len);
    buf[len] = '\0';
    char *end;
    double v = strtod(buf, &end);
    if (*end || !isfinite(v)) return 0;
    *out = v;
    return 1;
}

/* The numbers after the statement's keyword: between lo and hi of them, each finite with
 * |x| <= limit. Returns the count or -1 (message written). */
static int check_numbers(loader *ld, const mesh_obj_line *line, const char *what, int lo, int hi,
                         double limit)
{
    words w = {line->text, line->text + line->len};
    const char *s;
    size_t len;
    next_word(&w, &s, &len); /* the keyword */
    int n = 0;
    while (next_word(&w, &s, &len)) {
        double v;
        if (len > MESH_NUMBER_MAX)
            return fail(ld, line->number, "%s: a number of %zu characters (at most %d)", what, len,
                        MESH_NUMBER_MAX);
        if (!read_number(s, len, &v))
            return fail(ld, line->number, "%s: " WORD_FMT " is not a finite decimal number", what,
                        WORD_ARG(s, len));
        if (fabs(v) > limit)
            return fail(ld, line->number, "%s: %.*s is outside [-%g, %g]", what, (int)len, s, limit,
                        limit);
        ++n;
    }
    if (n < lo || n > hi) {
        if (lo == hi) return fail(ld, line->number, "%s needs %d numbers, got %d", what, lo, n);
        return fail(ld, line->number, "%s needs %d to %d numbers, got %d", what, lo, hi, n);
    }
    return n;
}

/* ---- growing arrays ----------------------------------------------------------------- */

static int grow(void **p, size_t *cap, size_t need, size_t elem)
{
    if (need <= *cap) return 0;
    size_t c = *cap ? *cap : 1024;
    while (c < need) c *= 2;
    void *g = realloc(*p, c * elem);
    if (!g) return -1;
    *p = g;
    *cap = c;
    return 0;
}

static int add_vec(loader *ld, const mesh_obj_line *line, float **arr, int *count, size_t *cap,
                   int dim, const double *v, const char *what)
{
    if (*count >= MESH_MAX_ELEMENTS)
        return fail(ld, line->number, "more than %d %s statements", MESH_MAX_ELEMENTS, what);
    if (grow((void **)arr, cap, (size_t)(*count + 1) * (size_t)dim, sizeof **arr))
        return fail(ld, line->number, "out of memory");
    for (int a = 0; a < dim; ++a) (*arr)[(size_t)*count * (size_t)dim + (size_t)a] = (float)v[a];
    ++*count;
    return 0;
}

/* ---- statements --------------------------------------------------------------------- */

static int on_vertex(void *user, const mesh_obj_line *line, double x, double y, double z)
{
    loader *ld = user;
    /* x y z, x y z w, or x y z r g b (the vertex colour extension); w and colour unused */
    int n = check_numbers(ld, line, "v", 3, 6, MESH_MAX_COORD);
    if (n < 0) return -1;
    if (n == 5) return fail(ld, line->number, "v needs 3, 4 or 6 numbers, got 5");
    double v[3] = {x, y, z};
    return add_vec(ld, line, &ld->m->position, &ld->m->vertex_count, &ld->cap_v, 3, v, "v");
}

static int on_normal(void *user, const mesh_obj_line *line, double x, double y, double z)
{
    loader *ld = user;
    if (check_numbers(ld, line, "vn", 3, 3, MESH_MAX_COORD) < 0) return -1;
    double l = sqrt(x * x + y * y + z * z);
    /* 1e-30: a normal must have a direction; below this its square underflows in float. */
    if (!(l > 1e-30)) return fail(ld, line->number, "vn has zero length");
    double v[3] = {x / l, y / l, z / l};
    return add_vec(ld, line, &ld->m->normal, &ld->m->normal_count, &ld->cap_n, 3, v, "vn");
}

static int on_texcoord(void *user, const mesh_obj_line *line, double u, double v)
{
    loader *ld = user;
    if (check_numbers(ld, line, "vt", 1, 3, MESH_MAX_COORD) < 0) return -1;
    double t[2] = {u, v};
    return add_vec(ld, line, &ld->m->uv, &ld->m->uv_count, &ld->cap_uv, 2, t, "vt");
}

/* Room for `need` triangles in tri and, as the faces give them, tri_uv and tri_normal. */
static int reserve_triangles(loader *ld, size_t need)
{
    if (need <= ld->cap_t) return 0;
    size_t c = ld->cap_t ? ld->cap_t : 1024;
    while (c < need) c *= 2;
    mesh *m = ld->m;
    int **arr[3] = {&m->tri, &m->tri_uv, &m->tri_normal};
    int use[3] = {1, ld->face_has_uv, ld->face_has_n};
    for (int k = 0; k < 3; ++k) {
        if (!use[k]) continue;
        /* tri is Embree's index buffer as it is (accel.c), and Embree may read the last
         * triangle with a 16-byte load: 4 spare ints */
        int *g = realloc(*arr[k], (3 * c + 4) * sizeof *g);
        if (!g) return -1;
        *arr[k] = g;
    }
    ld->cap_t = c;
    return 0;
}

/* A corner word is V, V/T, V//N or V/T/N, each a whole number of at most 9 digits (zero
 * is reported by resolve, which names the kind). */
static int check_corner(const char *s, size_t len)
{
    size_t start = 0;
    int field = 0, empty[3] = {0, 0, 0};
    for (size_t i = 0; i <= len; ++i) {
        if (i < len && s[i] != '/') continue;
        if (field == 3) return 0;
        const char *f = s + start;
        size_t n = i - start, d = n > 0 && f[0] == '-';
        if (n == 0) {
            empty[field] = 1;
        } else {
            if (n == d || n - d > 9) return 0;
            for (size_t k = d; k < n; ++k)
                if (f[k] < '0' || f[k] > '9') return 0;
        }
        ++field;
        start = i + 1;
    }
    return !empty[0] && !empty[2] && !(empty[1] && field != 3);
}

/* Resolve an OBJ index (1-based, or negative relative to the count so far). */
static int resolve(loader *ld, const mesh_obj_line *line, int kind, int idx, int count, int *out)
{
    static const char *const names[3] = {"vertex", "texture coordinate", "normal"};
    if (idx == 0) return fail(ld, line->number, "%s index 0 (OBJ counts from 1)", names[kind]);
    if (idx < 0) {
        if (-idx > count)
            return fail(ld, line->number, "%s index %d reaches before the first of %d so far",
                        names[kind], idx, count);
        *out = count + idx;
        return 0;
    }
    /* Positive indices may point forward; checked once the whole file is read. */
    if (idx > ld->max_ref[kind]) ld->max_ref[kind] = idx, ld->max_ref_line[kind] = line->number;
    *out = idx - 1;
    return 0;
}

static int on_face(void *user, const mesh_obj_line *line, const int *v, const int *vt,
                   const int *vn, int corners)
{
    loader *ld = user;
    mesh *m = ld->m;
    words w = {line->text, line->text + line->len};
    const char *s;
    size_t len;
    next_word(&w, &s, &len);
    int n = 0;
    while (next_word(&w, &s, &len)) {
        if (!check_corner(s, len))
            return fail(ld, line->number,
                        "face corner " WORD_FMT " is not V, V/T, V//N or V/T/N (non-zero whole "
                        "numbers)",
                        WORD_ARG(s, len));
        ++n;
    }
    if (n != corners || corners < 3)
        return fail(ld, line->number, "a face needs at least 3 corners, got %d", n);
    int has_uv = vt[0] != 0, has_n = vn[0] != 0;
    for (int k = 1; k < corners; ++k)
        if ((vt[k] != 0) != has_uv || (vn[k] != 0) != has_n)
            return fail(ld, line->number,
                        "corners of one face differ in what they give (texture coordinate, "
                        "normal)");
    if (ld->faces++ == 0) {
        ld->face_has_uv = has_uv, ld->face_has_n = has_n, ld->first_face_line = line->number;
    } else if (has_n != ld->face_has_n || has_uv != ld->face_has_uv) {
        int n = has_n != ld->face_has_n, mine = n ? has_n : has_uv;
        int first = n ? ld->face_has_n : ld->face_has_uv;
        return fail(ld, line->number,
                    "every face gives %s or none does: this face %s, the first (line %d) %s",
                    n ? "normals" : "texture coordinates", mine ? "does" : "does not",
                    ld->first_face_line, first ? "does" : "does not");
    }
    int added = corners - 2;
    if (m->triangle_count > ld->max_triangles - added)
        return fail(ld, line->number, "more than %d triangles", ld->max_triangles);
    if (reserve_triangles(ld, (size_t)m->triangle_count + (size_t)added))
        return fail(ld, line->number, "out of memory");
    if (corners > 3) m->polygons_split = 1;
    int cnt[3] = {m->vertex_count, m->uv_count, m->normal_count};
    const int *raw[3] = {v, vt, vn};
    int *dst[3] = {m->tri, m->tri_uv, m->tri_normal}, use[3] = {1, has_uv, has_n};
    for (int k = 1; k + 1 < corners; ++k) {
        size_t t = 3 * (size_t)m->triangle_count;
        int c[3] = {0, k, k + 1};
        for (int kind = 0; kind < 3; ++kind)
            for (int a = 0; use[kind] && a < 3; ++a)
                if (resolve(ld, line, kind, raw[kind][c[a]], cnt[kind], &dst[kind][t + (size_t)a]))
                    return -1;
        ++m->triangle_count;
    }
    return 0;
}

static int keyword_is(const char *s, size_t len, const char *k)
{
    return strlen(k) == len && !memcmp(s, k, len);
}

/* Lines without a statement for the sink. */
static int on_other(void *user, const mesh_obj_line *line)
{
    loader *ld = user;
    words w = {line->text, line->text + line->len};
    const char *s;
    size_t len;
    if (!next_word(&w, &s, &len) || s[0] == '#') return 0;
    for (size_t i = 0; i < line->len; ++i) {
        unsigned char c = (unsigned char)line->text[i];
        if ((c < 0x20 && c != '\t') || c == 0x7f)
            return fail(ld, line->number, "unexpected byte 0x%02x (not a text OBJ file)", c);
    }
    /* Names, groups, smoothing groups and materials: the scene gives the material and
     * smooth=; lines (l) and points (p) have no surface to render. */
    static const char *const ignored[] = {"o", "g", "s", "usemtl", "mtllib", "l", "p"};
    for (size_t k = 0; k < sizeof ignored / sizeof *ignored; ++k)
        if (keyword_is(s, len, ignored[k])) return 0;
    /* Statements the library skipped because they are malformed. */
    static const char *const geometry[] = {"v", "vn", "vt", "f"};
    for (size_t k = 0; k < sizeof geometry / sizeof *geometry; ++k)
        if (keyword_is(s, len, geometry[k]))
            return fail(ld, line->number, "'%s' without values", geometry[k]);
    static const char *const freeform[] = {"vp",   "cstype", "deg",  "bmat", "step",
                                           "curv", "curv2",  "surf", "parm", "trim",
                                           "hole", "scrv",   "sp",   "end",  "con"};
    for (size_t k = 0; k < sizeof freeform / sizeof *freeform; ++k)
        if (keyword_is(s, len, freeform[k]))
            return fail(ld, line->number,
                        "free-form geometry ('%s') is not supported; export triangles or "
                        "polygons",
                        freeform[k]);
    return fail(ld, line->number, "unknown OBJ statement " WORD_FMT, WORD_ARG(s, len));
}

/* ---- after the file ---------------------------------------------------------------- */

/* Angle-weighted vertex normals (mesh.h); corners whose vertex gets no direction (every
 * triangle around it degenerate) take their own triangle's normal, or +z if it has none. */
int mesh_compute_normals(mesh *m)
{
    size_t nv = (size_t)m->vertex_count, nt = (size_t)m->triangle_count;
    double *acc = calloc(3 * nv, sizeof *acc);
    m->tri_normal = malloc(3 * nt * sizeof *m->tri_normal);
    if (!acc || !m->tri_normal) {
        free(acc);
        return -1;
    }
    for (size_t t = 0; t < nt; ++t) {
        const int *c = m->tri + 3 * t;
        double p[3][3], fn[3];
        for (int k = 0; k < 3; ++k)
            for (int a = 0; a < 3; ++a) p[k][a] = m->position[3 * (size_t)c[k] + (size_t)a];
        double e1[3], e2[3];
        for (int a = 0; a < 3; ++a) e1[a] = p[1][a] - p[0][a], e2[a] = p[2][a] - p[0][a];
        fn[0] = e1[1] * e2[2] - e1[2] * e2[1];
        fn[1] = e1[2] * e2[0] - e1[0] * e2[2];
        fn[2] = e1[0] * e2[1] - e1[1] * e2[0];
        double l = sqrt(fn[0] * fn[0] + fn[1] * fn[1] + fn[2] * fn[2]);
        if (!(l > 0)) continue; /* degenerate: no direction to give */
        for (int k = 0; k < 3; ++k) {
            const double *a = p[k], *b = p[(k + 1) % 3], *d = p[(k + 2) % 3];
            double u[3], w[3];
            for (int x = 0; x < 3; ++x) u[x] = b[x] - a[x], w[x] = d[x] - a[x];
            double lu = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]),
                   lw = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
            if (!(lu > 0 && lw > 0)) continue;
            double cosang = (u[0] * w[0] + u[1] * w[1] + u[2] * w[2]) / (lu * lw);
            double ang = acos(fmax(-1.0, fmin(1.0, cosang)));
            for (int x = 0; x < 3; ++x) acc[3 * (size_t)c[k] + (size_t)x] += ang * fn[x] / l;
        }
    }
    /* Normals: one per vertex, then extras for corners of vertices without a direction. */
    size_t cap = nv + 16, count = 0;
    float *nrm = malloc(3 * cap * sizeof *nrm);
    if (!nrm) {
        free(acc);
        return -1;
    }
    for (size_t v = 0; v < nv; ++v) {
        double *a = acc + 3 * v, l = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
        /* no direction: +z, unit like every normal (no corner uses it, see below) */
        for (int x = 0; x < 3; ++x) nrm[3 * v + (size_t)x] = l > 0 ? (float)(a[x] / l) : x == 2;
        a[0] = l; /* remembered: has a direction */
    }
    count = nv;
    for (size_t t = 0; t < nt; ++t)
        for (int k = 0; k < 3; ++k) {
            int v = m->tri[3 * t + (size_t)k];
            if (acc[3 * (size_t)v] > 0) {
                m->tri_normal[3 * t + (size_t)k] = v;
                continue;
            }
            if (count == cap) {
                float *g = realloc(nrm, 3 * (cap *= 2) * sizeof *g);
                if (!g) {
                    free(nrm), free(acc);
                    return -1;
                }
                nrm = g;
            }
            const int *c = m->tri + 3 * t;
            double e1[3], e2[3], fn[3];
            for (int a = 0; a < 3; ++a) {
                e1[a] = (double)m->position[3 * (size_t)c[1] + (size_t)a] -
                        m->position[3 * (size_t)c[0] + (size_t)a];
                e2[a] = (double)m->position[3 * (size_t)c[2] + (size_t)a] -
                        m->position[3 * (size_t)c[0] + (size_t)a];
            }
            fn[0] = e1[1] * e2[2] - e1[2] * e2[1];
            fn[1] = e1[2] * e2[0] - e1[0] * e2[2];
            fn[2] = e1[0] * e2[1] - e1[1] * e2[0];
            double l = sqrt(fn[0] * fn[0] + fn[1] * fn[1] + fn[2] * fn[2]);
            if (!(l > 0)) fn[0] = 0, fn[1] = 0, fn[2] = 1, l = 1;
            for (int a = 0; a < 3; ++a) nrm[3 * count + (size_t)a] = (float)(fn[a] / l);
            m->tri_normal[3 * t + (size_t)k] = (int)count++;
        }
    free(acc);
    free(m->normal);
    m->normal = nrm;
    m->normal_count = (int)count;
    return 0;
}

/* Centre of the bounding box of every position and the largest distance from it. */
void mesh_bounding_sphere(mesh *m)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t v = 0; v < (size_t)m->vertex_count; ++v)
        for (int a = 0; a < 3; ++a) {
            lo[a] = fmin(lo[a], m->position[3 * v + (size_t)a]);
            hi[a] = fmax(hi[a], m->position[3 * v + (size_t)a]);
        }
    double r2 = 0;
    for (int a = 0; a < 3; ++a) m->center[a] = m->vertex_count ? 0.5 * (lo[a] + hi[a]) : 0.0;
    for (size_t v = 0; v < (size_t)m->vertex_count; ++v) {
        double d2 = 0;
        for (int a = 0; a < 3; ++a) {
            double e = m->position[3 * v + (size_t)a] - m->center[a];
            d2 += e * e;
        }
        r2 = fmax(r2, d2);
    }
    m->radius = sqrt(r2);
}

void mesh_free(mesh *m)
{
    if (!m) return;
    free(m->path);
    free(m->position);
    free(m->normal);
    free(m->uv);
    free(m->tri);
    free(m->tri_normal);
    free(m->tri_uv);
    memset(m, 0, sizeof *m);
}

int mesh_load_text(const char *name, const char *text, size_t len, int max_triangles, mesh *out,
                   char *err, size_t err_size)
{
    if (err && err_size) err[0] = '\0';
    memset(out, 0, sizeof *out);
    if (max_triangles > MESH_MAX_TRIANGLES || max_triangles < 0) max_triangles = MESH_MAX_TRIANGLES;
    loader ld;
    memset(&ld, 0, sizeof ld);
    ld.name = name ? name : "<mesh>";
    ld.err = err, ld.err_size = err_size, ld.m = out, ld.max_triangles = max_triangles;
    const char *nul = text ? memchr(text, '\0', len) : NULL;
    if (!text || nul) {
        int line = 1;
        for (const char *q = text; q && q < nul; ++q) line += *q == '\n';
        fail(&ld, text ? line : 0, "%s", text ? "NUL byte (not a text OBJ file)" : "no text");
        mesh_free(out);
        return -1;
    }
    size_t nlen = strlen(ld.name);
    out->path = malloc(nlen + 1);
    if (!out->path) {
        fail(&ld, 0, "out of memory");
        return -1;
    }
    memcpy(out->path, ld.name, nlen + 1);
    /* A UTF-8 byte-order mark (some editors write one) is not part of the first line. */
    if (len >= 3 && !memcmp(text, "\xEF\xBB\xBF", 3)) text += 3, len -= 3;
    mesh_obj_sink sink = {&ld, on_vertex, on_normal, on_texcoord, on_face, on_other};
    char lib_err[256];
    int st = mesh_obj_parse(text, len, &sink, lib_err, sizeof lib_err);
    if (st == -2) fail(&ld, 0, "%s", lib_err);
    if (st == 0) {
        static const char *const names[3] = {"vertex", "texture coordinate", "normal"};
        int cnt[3] = {out->vertex_count, out->uv_count, out->normal_count};
        for (int kind = 0; kind < 3 && st == 0; ++kind)
            if (ld.max_ref[kind] > cnt[kind])
                st = fail(&ld, ld.max_ref_line[kind], "%s index %d but the file has %d",
                          names[kind], ld.max_ref[kind], cnt[kind]);
        if (st == 0 && out->triangle_count == 0) st = fail(&ld, 0, "no faces (f statements)");
    }
    if (st == 0) {
        out->normals_from_file = ld.face_has_n;
        if (!ld.face_has_n) {
            free(out->tri_normal);
            out->tri_normal = NULL;
            if (mesh_compute_normals(out)) st = fail(&ld, 0, "out of memory");
        }
        if (!ld.face_has_uv) {
            free(out->uv), free(out->tri_uv);
            out->uv = NULL, out->tri_uv = NULL, out->uv_count = 0;
        }
        mesh_bounding_sphere(out);
    }
    if (st != 0) {
        mesh_free(out);
        return -1;
    }
    return 0;
}

int mesh_load_file(const char *path, int max_triangles, mesh *out, char *err, size_t err_size)
{
    memset(out, 0, sizeof *out);
    char msg[512];
    FILE *f = in_file_open(path, msg, sizeof msg);
    if (!f) {
        if (err && err_size) snprintf(err, err_size, "%s", msg);
        return -2;
    }
    /* The size first: nothing is allocated for a file over the limit. */
    struct stat st;
    if (fstat(fileno(f), &st) != 0) {
        if (err && err_size) path_msg(err, err_size, path, ": %s", strerror(errno));
        fclose(f);
        return -2;
    }
    if ((unsigned long long)st.st_size > MESH_MAX_FILE) {
        if (err && err_size)
            path_msg(err, err_size, path, ": %lld bytes; a mesh file has at most %zu",
                     (long long)st.st_size, MESH_MAX_FILE);
        fclose(f);
        return -2;
    }
    size_t size = (size_t)st.st_size;
    char *buf = malloc(size ? size : 1);
    size_t len = buf ? fread(buf, 1, size, f) : 0;
    /* a file that changes while it is read is read up to its size at the open */
    int bad = !buf || ferror(f) || len != size;
    if (bad && err && err_size)
        path_msg(err, err_size, path, ": %s", !buf ? "out of memory" : "read error");
    fclose(f);
    int rc = bad ? -2 : mesh_load_text(path, buf, len, max_triangles, out, err, err_size);
    free(buf);
    return rc;
}
