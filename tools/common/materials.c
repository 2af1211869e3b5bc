/* materials.c - loader of the material table (materials.h; format in docs/SELECTION.md, "The
 * material table"). */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_args.h"
#include "in_file.h"
#include "materials.h"
#include "path_msg.h"

const char *const mat_columns[] = {
    "name",       "type",      "n",        "r",          "kd_r",   "kd_g",       "kd_b",
    "ks_r",       "ks_g",      "ks_b",     "f0_r",       "f0_g",   "f0_b",       "eta",
    "anisotropy", "melanin",   "redness",  "coat_eta",   "coat_r", "coat_depth", "coat_sa_r",
    "coat_sa_g",  "coat_sa_b", "base_eta", "base_kappa", "source"};
const int mat_column_count = (int)(sizeof mat_columns / sizeof mat_columns[0]);

enum {
    C_NAME,
    C_TYPE,
    C_N,
    C_R,
    C_KD,
    C_KS = C_KD + 3,
    C_F0 = C_KS + 3,
    C_ETA = C_F0 + 3,
    C_ANISO,
    C_MELANIN,
    C_REDNESS,
    C_COAT_ETA,
    C_COAT_R,
    C_COAT_DEPTH,
    C_COAT_SA,
    C_BASE_ETA = C_COAT_SA + 3,
    C_BASE_KAPPA,
    C_SOURCE
};

typedef struct ctx {
    const char *path;
    int line;
    char *err;
    size_t err_size;
    char quoted[2][72]; /* shown(): fields as messages quote them */
    int next;
} ctx;

/* "PATH:LINE: problem", the problem whole and the path shortened if need be (path_msg.h). */
static int fail(ctx *c, const char *fmt, ...)
{
    char msg[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    path_msg(c->err, c->err_size, c->path, ":%d: %s", c->line, msg);
    return -1;
}

/* A field as a message quotes it: a long one shortened in its middle (lines have any length). */
static const char *shown(ctx *c, const char *field)
{
    c->next ^= 1;
    return path_short(c->quoted[c->next], sizeof c->quoted[0], field, 64);
}

static char *trim(char *s)
{
    while (*s == ' ' || *s == '\t') ++s;
    size_t n = strlen(s);
    while (n && (s[n - 1] == ' ' || s[n - 1] == '\t' || s[n - 1] == '\r' || s[n - 1] == '\n'))
        s[--n] = '\0';
    return s;
}

/* Split into mat_column_count fields; the last (source) takes the rest of the line. */
static int split(char *line, char **f)
{
    int n = 0;
    char *p = line;
    while (n < mat_column_count - 1) {
        char *comma = strchr(p, ',');
        if (!comma) break;
        *comma = '\0';
        f[n++] = trim(p);
        p = comma + 1;
    }
    f[n++] = trim(p);
    return n;
}

/* A number in [lo, hi]; empty -> *out = def and *given = 0. */
static int number(ctx *c, const char *field, int col, double lo, double hi, double def, double *out,
                  int *given)
{
    if (given) *given = 0;
    if (!*field) {
        *out = def;
        return 0;
    }
    if (!cli_parse_double(field, out))
        return fail(c, "column '%s': '%s' is not a finite number", mat_columns[col],
                    shown(c, field));
    if (!(*out >= lo && *out <= hi))
        return fail(c, "column '%s': %s is outside [%g, %g]", mat_columns[col], shown(c, field), lo,
                    hi);
    if (given) *given = 1;
    return 0;
}

/* Three columns as an RGB triple: all given or all empty. Returns 1 if given, 0 if empty. */
static int rgb(ctx *c, char **f, int col, double lo, double hi, double v[3])
{
    int g[3], any = 0, all = 1;
    for (int k = 0; k < 3; ++k) {
        if (number(c, f[col + k], col + k, lo, hi, 0.0, &v[k], &g[k])) return -1;
        any |= g[k];
        all &= g[k];
    }
    if (any && !all)
        return fail(c, "columns '%s'..'%s': give all three components or none", mat_columns[col],
                    mat_columns[col + 2]);
    return all;
}

static int valid_name(const char *s)
{
    if (!*s || strlen(s) >= MAT_NAME_MAX) return 0;
    for (; *s; ++s)
        if (!((*s >= 'a' && *s <= 'z') || (*s >= '0' && *s <= '9') || *s == '_')) return 0;
    return 1;
}

static int parse_row(ctx *c, char *line, mat_entry *e)
{
    char *f[32];
    int nf = split(line, f);
    if (nf < mat_column_count)
        return fail(c, "%d fields, expected %d (name ... source)", nf, mat_column_count);
    memset(e, 0, sizeof *e);
    abrdf_material *m = &e->m;
    abrdf_material_init(m);
    if (!valid_name(f[C_NAME]))
        return fail(c, "name '%s' must be 1-%d characters of a-z, 0-9, _", shown(c, f[C_NAME]),
                    MAT_NAME_MAX - 1);
    strcpy(e->name, f[C_NAME]);
    if (abrdf_surface_find(f[C_TYPE], &m->type) != ABRDF_OK) {
        char types[256] = "";
        for (int i = 0; i < ABRDF_SURFACE_COUNT; ++i)
            strcat(strcat(types, i ? ", " : ""), abrdf_surface_name((abrdf_surface)i));
        return fail(c, "type '%s' is not one of: %s", shown(c, f[C_TYPE]), types);
    }
    int n_given, r_given, eta_given;
    if (number(c, f[C_N], C_N, 0.0, 1e6, -1.0, &m->n, &n_given)) return -1;
    if (number(c, f[C_R], C_R, 0.0, 1.0, -1.0, &m->r, &r_given)) return -1;
    if (!n_given && !r_given) return fail(c, "give n or r (or both)");
    int st;
    if ((st = rgb(c, f, C_KD, 0.0, 1.0, m->kd)) < 0) return -1;
    if (!st) return fail(c, "columns 'kd_r'..'kd_b' are required");
    if ((st = rgb(c, f, C_KS, 0.0, 1.0, m->ks)) < 0) return -1;
    if (!st) return fail(c, "columns 'ks_r'..'ks_b' are required");
    int f0_given = rgb(c, f, C_F0, 0.0, 1.0, m->f0);
    if (f0_given < 0) return -1;
    if (number(c, f[C_ETA], C_ETA, 1.0, 4.0, -1.0, &m->eta, &eta_given)) return -1;
    if (!f0_given && !eta_given) return fail(c, "give f0_r..f0_b or eta");
    if (f0_given && eta_given) return fail(c, "give f0 or eta, not both (eta determines f0)");
    if (number(c, f[C_ANISO], C_ANISO, 0.0, 1.0, 0.0, &m->anisotropy, NULL)) return -1;
    if (number(c, f[C_MELANIN], C_MELANIN, 0.0, 1.0, 0.3, &m->melanin, NULL)) return -1;
    if (number(c, f[C_REDNESS], C_REDNESS, 0.0, 1.0, 0.0, &m->redness, NULL)) return -1;
    if (m->type == ABRDF_SURFACE_HAIR && !*f[C_MELANIN]) return fail(c, "hair needs 'melanin'");

    /* Coat (layer 0) and, for metals, the base interface (layer 1), relative to the coat. */
    double coat[6];
    int g[6], any = 0, all = 1;
    static const double lo[6] = {1.0, 0.0, 0.0, 0.0, 0.0, 0.0},
                        hi[6] = {4.0, 1.0, 100.0, 1e4, 1e4, 1e4};
    for (int k = 0; k < 6; ++k) {
        if (number(c, f[C_COAT_ETA + k], C_COAT_ETA + k, lo[k], hi[k], 0.0, &coat[k], &g[k]))
            return -1;
        any |= g[k];
        all &= g[k];
    }
    if (any && !all) return fail(c, "coat columns: give all six (coat_eta ... coat_sa_b) or none");
    int layered = m->type >= ABRDF_SURFACE_LAYERED_PLASTIC;
    if (layered && !all) return fail(c, "type %s needs the coat columns", f[C_TYPE]);
    if (!layered && all) return fail(c, "coat columns are only for layered types");
    double be, bk;
    int gbe, gbk;
    if (number(c, f[C_BASE_ETA], C_BASE_ETA, 0.0, 40.0, 0.0, &be, &gbe)) return -1;
    if (number(c, f[C_BASE_KAPPA], C_BASE_KAPPA, 0.0, 40.0, 0.0, &bk, &gbk)) return -1;
    if (gbe != gbk) return fail(c, "give base_eta and base_kappa together");
    if (m->type == ABRDF_SURFACE_LAYERED_METAL && !gbe)
        return fail(c, "layered_metal needs base_eta and base_kappa (the metal's n, k at 550 nm)");
    if (gbe && m->type != ABRDF_SURFACE_LAYERED_METAL)
        return fail(c, "base_eta/base_kappa are only for layered_metal");
    if (all) {
        abrdf_layer *l = &m->layers[0];
        l->eta = coat[0];
        l->r = coat[1];
        l->depth = coat[2];
        for (int k = 0; k < 3; ++k) l->sigma_a[k] = coat[3 + k];
        m->layer_count = 1;
    }
    if (gbe) {
        abrdf_layer *l = &m->layers[1];
        l->eta = be / coat[0];
        l->kappa = bk / coat[0];
        l->r = m->r >= 0.0 ? m->r : abrdf_alpha_g_to_r(abrdf_n_to_alpha_g(m->n));
        if (!(l->eta >= 1.0 && l->eta <= 4.0 && l->kappa <= 10.0))
            return fail(c,
                        "base relative to the coat: eta %g, kappa %g outside libabrdf's layer "
                        "ranges (eta [1, 4], kappa [0, 10])",
                        l->eta, l->kappa);
        m->layer_count = 2;
    }
    if (!*f[C_SOURCE])
        return fail(c, "column 'source' is empty: every row needs the source of its numbers");
    if (strlen(f[C_SOURCE]) >= MAT_SOURCE_MAX)
        return fail(c, "column 'source' is longer than %d characters", MAT_SOURCE_MAX - 1);
    strcpy(e->source, f[C_SOURCE]);
    return 0;
}

static int check_header(ctx *c, char *line)
{
    char *f[32];
    int nf = split(line, f);
    for (int i = 0; i < mat_column_count; ++i)
        if (i >= nf || strcmp(f[i], mat_columns[i]))
            return fail(c,
                        "header: column %d is '%s', expected '%s' (docs/SELECTION.md, \"The "
                        "material table\")",
                        i + 1, i < nf ? shown(c, f[i]) : "", mat_columns[i]);
    return 0;
}

static mat_entry *find_mut(mat_table *t, const char *name, int upto)
{
    for (int i = 0; i < upto; ++i)
        if (!strcmp(t->items[i].name, name)) return &t->items[i];
    return NULL;
}

int mat_table_read(mat_table *t, FILE *fp, const char *path, char *err, size_t err_size)
{
    ctx c = {path, 0, err, err_size, {"", ""}, 0};
    if (err_size) err[0] = '\0';
    /* Parse the whole file first, so a bad file leaves the table as it was. */
    mat_table add = {NULL, 0, 0};
    char *line = NULL;
    size_t cap = 0;
    ssize_t len;
    int header = 0, rc = 0;
    while ((len = in_file_line(fp, &line, &cap)) >= 0) {
        ++c.line;
        if (strlen(line) != (size_t)len) {
            rc = fail(&c, "NUL byte (not a text file)");
            break;
        }
        char *s = trim(line);
        if (!*s || *s == '#') continue;
        if (!header) {
            if ((rc = check_header(&c, s))) break;
            header = 1;
            continue;
        }
        if (add.count == add.cap) {
            int ncap = add.cap ? 2 * add.cap : 64;
            mat_entry *p = realloc(add.items, (size_t)ncap * sizeof *p);
            if (!p) {
                rc = fail(&c, "out of memory");
                break;
            }
            add.items = p;
            add.cap = ncap;
        }
        mat_entry *e = &add.items[add.count];
        if ((rc = parse_row(&c, s, e))) break;
        const mat_entry *dup = find_mut(&add, e->name, add.count);
        if (dup) {
            rc = fail(&c, "material '%s' is already defined at line %d", e->name, dup->line);
            break;
        }
        path_short(e->file, sizeof e->file, path, sizeof e->file - 1);
        e->line = c.line;
        ++add.count;
    }
    free(line);
    if (!rc && ferror(fp)) rc = fail(&c, "read error: %s", strerror(errno));
    if (!rc && !header) rc = fail(&c, "no header line (expected: name,type,n,r,...,source)");
    if (rc) {
        free(add.items);
        return -1;
    }
    for (int i = 0; i < add.count && !rc; ++i) {
        mat_entry *old = find_mut(t, add.items[i].name, t->count);
        if (old) {
            *old = add.items[i];
            continue;
        }
        if (t->count == t->cap) {
            int ncap = t->cap ? 2 * t->cap : 64;
            mat_entry *p = realloc(t->items, (size_t)ncap * sizeof *p);
            if (!p) {
                rc = fail(&c, "out of memory");
                break;
            }
            t->items = p;
            t->cap = ncap;
        }
        t->items[t->count++] = add.items[i];
    }
    free(add.items);
    for (int i = 0; i < t->count; ++i) t->items[i].m.name = t->items[i].name;
    return rc;
}

int mat_table_load(mat_table *t, const char *path, char *err, size_t err_size)
{
    FILE *fp = in_file_open(path, err, err_size);
    if (!fp) return -1;
    int rc = mat_table_read(t, fp, path, err, err_size);
    fclose(fp);
    return rc;
}

void mat_table_free(mat_table *t)
{
    free(t->items);
    t->items = NULL;
    t->count = t->cap = 0;
}

const mat_entry *mat_table_find(const mat_table *t, const char *name)
{
    for (int i = 0; i < t->count; ++i)
        if (!strcmp(t->items[i].name, name)) return &t->items[i];
    return NULL;
}

int mat_table_nearest(const mat_table *t, const char *name, const char **out, int max)
{
    int found = 0;
    for (int d = 0; d <= 3 && found < max; ++d)
        for (int i = 0; i < t->count && found < max; ++i) {
            const char *cand = t->items[i].name;
            /* A prefix ("alumin") is as good a hint as a typo. */
            int dist =
                strncmp(cand, name, strlen(name)) == 0 && *name ? 1 : cli_edit_distance(name, cand);
            if (dist == d) out[found++] = cand;
        }
    return found;
}
