/* cli.c - shared argument parsing and lookups for the abrdf subcommands. */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "cli_args.h"
#include "utf8.h"

int cli_fail(const char *cmd, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    char *msg = n >= 0 ? malloc((size_t)n + 1) : NULL;
    fprintf(stderr, "abrdf %s: ", cmd);
    if (msg) {
        va_start(ap, fmt);
        vsnprintf(msg, (size_t)n + 1, fmt, ap);
        va_end(ap);
        /* One line, whatever an argument held: its control bytes are shown as \xHH. */
        for (const char *p = msg; *p; ++p)
            if ((unsigned char)*p < 0x20 || *p == 0x7f)
                fprintf(stderr, "\\x%02x", (unsigned char)*p);
            else
                fputc(*p, stderr);
        free(msg);
    } else {
        fputs("(out of memory)", stderr);
    }
    fputc('\n', stderr);
    return CLI_EXIT_USAGE;
}

int cli_is_help(const char *arg) { return !strcmp(arg, "-h") || !strcmp(arg, "--help"); }

int cli_option_take(const char *cmd, const cli_options *o, int argc, char **argv, int *i)
{
    const char *a = argv[*i], *val = *i + 1 < argc ? argv[*i + 1] : NULL;
    for (size_t k = 0; k < o->nflags; ++k)
        if (!strcmp(a, o->flags[k].name)) {
            *o->flags[k].slot = o->flags[k].value;
            return 1;
        }
    for (size_t k = 0; k < o->nstrings; ++k)
        if (!strcmp(a, o->strings[k].name)) {
            if (!val) return cli_fail(cmd, "%s needs a value", a);
            ++*i;
            *o->strings[k].slot = val;
            return 1;
        }
    for (size_t k = 0; k < o->nnumbers; ++k)
        if (!strcmp(a, o->numbers[k].name)) {
            long v;
            if (!cli_parse_int(val, 1, o->numbers[k].max, &v))
                return cli_fail(cmd, "%s needs a whole number in [1, %ld]", a, o->numbers[k].max);
            ++*i;
            *o->numbers[k].slot = (int)v;
            return 1;
        }
    return 0;
}

int cli_parse_double(const char *s, double *out)
{
    if (!s || !*s) return 0;
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    /* ERANGE with a finite result is an underflow: a subnormal (1e-310) or a zero (1e-400)
     * is a finite number all the same; overflow gives HUGE_VAL, which is not. */
    if (end == s || *end || !isfinite(v)) return 0;
    *out = v;
    return 1;
}

int cli_parse_int(const char *s, long lo, long hi, long *out)
{
    if (!s || !*s) return 0;
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (*end || errno || v < lo || v > hi) return 0;
    *out = v;
    return 1;
}

int cli_parse_vec3(const char *s, double v[3])
{
    if (!s) return 0;
    char buf[256];
    if (strlen(s) >= sizeof buf) return 0;
    strcpy(buf, s);
    char *p = buf;
    for (int c = 0; c < 3; ++c) {
        char *comma = strchr(p, ',');
        if ((c < 2) != (comma != NULL)) return 0;
        if (comma) *comma = '\0';
        if (!cli_parse_double(p, &v[c])) return 0;
        p = comma ? comma + 1 : p;
    }
    return 1;
}

int cli_model_reads(abrdf_model model, int id)
{
    const abrdf_model_info *mi = abrdf_model_get(model);
    for (int k = 0; mi && k < mi->param_count; ++k)
        if (mi->params[k].id == id) return 1;
    return 0;
}

int cli_parse_dir3(const char *s, double v[3])
{
    if (!cli_parse_vec3(s, v)) return 0;
    double m = fmax(fabs(v[0]), fmax(fabs(v[1]), fabs(v[2])));
    if (m > 0)
        for (int c = 0; c < 3; ++c) v[c] /= m;
    return 1;
}

static int is_option_word(const char *w)
{
    return (w[0] == '-' && w[1] == '-' && w[2]) || !strcmp(w, "-o") || !strcmp(w, "-n");
}

/* The NAME of --set NAME=VALUE at argv[i], or NULL. */
static const char *set_name(int argc, char **argv, int i, size_t *len)
{
    if (strcmp(argv[i], "--set") || i + 1 >= argc) return NULL;
    *len = strcspn(argv[i + 1], "=");
    return argv[i + 1];
}

const char *cli_repeated_option(int argc, char **argv, const char *const *repeatable)
{
    for (int i = 1; i < argc; ++i) {
        if (!is_option_word(argv[i])) continue;
        size_t len, len_j;
        const char *name = set_name(argc, argv, i, &len), *name_j;
        for (int j = 1; name && j < i; ++j)
            if ((name_j = set_name(argc, argv, j, &len_j)) && len_j == len &&
                !strncmp(name, name_j, len))
                return argv[i + 1];
        int listed = 0;
        for (const char *const *r = repeatable; r && *r; ++r) listed |= !strcmp(*r, argv[i]);
        if (listed) continue;
        for (int j = 1; j < i; ++j)
            if (!strcmp(argv[j], argv[i])) return argv[i];
    }
    return NULL;
}

int cli_edit_distance(const char *a, const char *b)
{
    size_t la = strlen(a), lb = strlen(b);
    if (la > 63 || lb > 63) return 64;
    int d[64][64];
    for (size_t i = 0; i <= la; ++i) d[i][0] = (int)i;
    for (size_t j = 0; j <= lb; ++j) d[0][j] = (int)j;
    for (size_t i = 1; i <= la; ++i)
        for (size_t j = 1; j <= lb; ++j) {
            int sub = d[i - 1][j - 1] + (a[i - 1] != b[j - 1]);
            int del = d[i - 1][j] + 1, ins = d[i][j - 1] + 1;
            d[i][j] = sub < del ? (sub < ins ? sub : ins) : (del < ins ? del : ins);
        }
    return d[la][lb];
}

/* A name is "near" a model name when it is a prefix of it or within an edit distance that
 * grows with its length (a third of it, at least 1), so short typos do not match everything. */
int cli_is_near(const char *typed, const char *name)
{
    size_t lt = strlen(typed);
    int limit = lt / 3 > 1 ? (int)(lt / 3) : 1;
    return (lt >= 3 && !strncmp(typed, name, lt)) || cli_edit_distance(typed, name) <= limit;
}

int cli_model(const char *cmd, const char *name, abrdf_model *out)
{
    if (name && abrdf_model_find(name, out) == ABRDF_OK) return 0;
    /* One line: the problem, the nearest names if any, then every valid name. */
    char near[512] = "", all[2048] = "";
    for (int i = 0; i < abrdf_model_count(); ++i) {
        const abrdf_model_info *m = abrdf_model_get((abrdf_model)i);
        if (!m) continue;
        if (name && cli_is_near(name, m->name) && strlen(near) + strlen(m->name) + 3 < sizeof near)
            strcat(strcat(near, *near ? ", " : ""), m->name);
        if (strlen(all) + strlen(m->name) + 3 < sizeof all)
            strcat(strcat(all, *all ? ", " : ""), m->name);
    }
    if (!name) return cli_fail(cmd, "missing model name; models: %s", all);
    if (*near)
        return cli_fail(cmd, "unknown model '%s'; did you mean %s? models: %s", name, near, all);
    return cli_fail(cmd, "unknown model '%s'; models: %s", name, all);
}

static void model_param_names(const abrdf_model_info *m, char *buf, size_t size)
{
    buf[0] = '\0';
    for (int i = 0; i < m->param_count; ++i) {
        const char *pn = abrdf_param_get(m->params[i].id)->name;
        if (strlen(buf) + strlen(pn) + 3 < size) strcat(strcat(buf, i ? ", " : ""), pn);
    }
}

int cli_set_param(const char *cmd, abrdf_model model, abrdf_params *p, const char *assign)
{
    const abrdf_model_info *m = abrdf_model_get(model);
    char names[1024];
    model_param_names(m, names, sizeof names);
    const char *eq = strchr(assign, '=');
    if (!eq || eq == assign)
        return cli_fail(cmd, "--set needs NAME=VALUE, got '%s'; %s parameters: %s", assign, m->name,
                        names);
    char key[64];
    size_t kl = (size_t)(eq - assign);
    if (kl >= sizeof key)
        return cli_fail(cmd, "unknown parameter in '%s'; %s parameters: %s", assign, m->name,
                        names);
    memcpy(key, assign, kl);
    key[kl] = '\0';
    int id = -1;
    const abrdf_model_param *mp = NULL;
    if (abrdf_param_find(key, &id) == ABRDF_OK)
        for (int i = 0; i < m->param_count; ++i)
            if (m->params[i].id == id) mp = &m->params[i];
    if (!mp)
        return cli_fail(cmd, "unknown parameter '%s' for %s; parameters: %s", key, m->name, names);
    const abrdf_param_info *pi = abrdf_param_get(id);
    const char *want = pi->kind == ABRDF_PARAM_RGB ? "a number or R,G,B" : "one number";
    double v[3];
    int count = 1;
    if (strchr(eq + 1, ',')) {
        if (pi->kind != ABRDF_PARAM_RGB || !cli_parse_vec3(eq + 1, v))
            return cli_fail(cmd, "parameter '%s' needs %s in [%g, %g], got '%s'", key, want,
                            mp->min, mp->max, eq + 1);
        count = 3;
    } else if (!cli_parse_double(eq + 1, &v[0])) {
        return cli_fail(cmd, "parameter '%s' needs %s in [%g, %g], got '%s' (not a finite number)",
                        key, want, mp->min, mp->max, eq + 1);
    }
    /* The model's range, which may be narrower than the parameter's own (abrdf_model_param). */
    for (int c = 0; c < count; ++c)
        if (!(v[c] >= mp->min && v[c] <= mp->max))
            return cli_fail(cmd, "parameter '%s' = %s is outside %s's range [%g, %g]", key, eq + 1,
                            m->name, mp->min, mp->max);
    if (abrdf_param_set(p, id, v, count) != ABRDF_OK)
        return cli_fail(cmd, "parameter '%s' = %s is outside [%g, %g]%s", key, eq + 1, pi->min,
                        pi->max, pi->kind == ABRDF_PARAM_INT ? " or not a whole number" : "");
    char msg[256];
    if (abrdf_params_check(model, p, msg, sizeof msg) != ABRDF_OK) return cli_fail(cmd, "%s", msg);
    return 0;
}

void cli_json_number(FILE *f, double v)
{
    if (isfinite(v))
        fprintf(f, "%.10g", v);
    else
        fputs("null", f);
}

void cli_json_string(FILE *f, const char *s)
{
    fputc('"', f);
    while (s && *s) {
        unsigned char c = (unsigned char)*s;
        unsigned long cp;
        int len = utf8_decode(s, &cp);
        if (!len) { /* JSON text is UTF-8 (RFC 8259): a stray byte becomes U+FFFD */
            fputs("\\ufffd", f);
            ++s;
            continue;
        }
        if (c == '"' || c == '\\')
            fprintf(f, "\\%c", c);
        else if (c < 0x20)
            fprintf(f, "\\u%04x", c);
        else
            fwrite(s, 1, (size_t)len, f);
        s += len;
    }
    fputc('"', f);
}
