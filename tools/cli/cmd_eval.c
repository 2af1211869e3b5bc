/* cmd_eval.c - `abrdf eval MODEL --wi X,Y,Z --wo X,Y,Z [...]`: one f_r evaluation, or
 * `--pairs FILE`: one per line of a file of direction pairs. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "in_file.h"
#include "path_msg.h"

static int usage(void)
{
    printf("usage: abrdf eval MODEL --wi X,Y,Z --wo X,Y,Z [--normal X,Y,Z] [--tangent X,Y,Z]\n"
           "                  [--set NAME=VALUE ...] [--json]\n"
           "       abrdf eval MODEL --pairs FILE|- [--normal ...] [--tangent ...] [--set ...]\n"
           "                  [--json]\n\n"
           "Prints f_r (RGB, 1/sr, without the cosine) for light direction wi and view\n"
           "direction wo, both pointing away from the surface. Vectors need not be unit\n"
           "length, but not zero. The normal defaults to 0,0,1; the tangent to an axis\n"
           "orthogonal to it (1,0,0 for the default normal).\n"
           "--set changes a parameter (R,G,B or one value for colours); see abrdf models.\n"
           "--pairs reads many pairs from FILE (- for standard input), one a line as six\n"
           "numbers 'wix wiy wiz wox woy woz' (blank lines and # comments allowed), and\n"
           "prints one line 'r g b' per pair, or with --json one array of [r, g, b].\n"
           "At most 16777216 pairs a run. A bad line stops the run with FILE:LINE and\n"
           "nothing printed.\n");
    return 0;
}

/* The most pairs one --pairs run takes (their doubles and line numbers: 0.9 GB), so that the
 * memory a file can ask for is bounded before it is allocated. */
#define EVAL_MAX_PAIRS (1 << 24)

/* The direction pairs of a --pairs file, 6 doubles each. */
typedef struct pair_list {
    double *v;  /* 6 per pair: wi, wo */
    long *line; /* the line of each pair */
    size_t count, cap;
} pair_list;

/* A direction of a pairs line scaled by 1 / its largest |component| (as --wi does), or 0 if
 * it is zero. */
static int pairs_dir(double v[3])
{
    double m = fmax(fabs(v[0]), fmax(fabs(v[1]), fabs(v[2])));
    if (!(m > 0.0)) return 0;
    for (int c = 0; c < 3; ++c) v[c] /= m;
    return 1;
}

/* One line of a pairs file (comment removed) into out[6]: 1 for a pair, 0 for a blank line,
 * -1 with the problem in why. */
static int pairs_line(char *line, double out[6], char *why, size_t why_size)
{
    char *hash = strchr(line, '#');
    if (hash) *hash = '\0';
    int n = 0;
    for (char *tok = strtok(line, " \t\r\v\f"); tok; tok = strtok(NULL, " \t\r\v\f")) {
        if (n == 6) {
            snprintf(why, why_size, "more than six numbers (wix wiy wiz wox woy woz)");
            return -1;
        }
        if (!cli_parse_double(tok, &out[n])) {
            char shown[64];
            snprintf(why, why_size, "'%s' is not a finite number (number %d of six)",
                     path_short(shown, sizeof shown, tok, 40), n + 1);
            return -1;
        }
        ++n;
    }
    if (n == 0) return 0;
    if (n < 6) {
        snprintf(why, why_size, "%d number%s, expected six: wix wiy wiz wox woy woz", n,
                 n == 1 ? "" : "s");
        return -1;
    }
    if (!pairs_dir(out)) {
        snprintf(why, why_size, "wi 0,0,0 has zero length; give a direction toward the light");
        return -1;
    }
    if (!pairs_dir(out + 3)) {
        snprintf(why, why_size, "wo 0,0,0 has zero length; give a direction toward the viewer");
        return -1;
    }
    return 1;
}

/* Every pair of the file at path ("-": standard input) into list: 0, or 1 after the message
 * "abrdf eval: FILE:LINE: problem". */
static int pairs_read(const char *path, pair_list *list)
{
    char err[1024];
    int is_stdin = !strcmp(path, "-");
    const char *shown = is_stdin ? "stdin" : path;
    FILE *f = is_stdin ? stdin : in_file_open(path, err, sizeof err);
    if (!f) {
        fprintf(stderr, "abrdf eval: %s\n", err);
        return 1;
    }
    char *buf = NULL;
    size_t cap = 0;
    long lineno = 0;
    ssize_t len;
    int rc = 0;
    while ((len = in_file_line(f, &buf, &cap)) >= 0) {
        ++lineno;
        double v[6];
        char why[256];
        int got = (size_t)len != strlen(buf) ? (snprintf(why, sizeof why, "a NUL byte"), -1)
                                             : pairs_line(buf, v, why, sizeof why);
        if (got < 0) {
            path_msg(err, sizeof err, shown, ":%ld: %s", lineno, why);
            fprintf(stderr, "abrdf eval: %s\n", err);
            rc = 1;
            break;
        }
        if (got == 0) continue;
        if (list->count == EVAL_MAX_PAIRS) {
            path_msg(err, sizeof err, shown, ":%ld: more than %d direction pairs (split the file)",
                     lineno, EVAL_MAX_PAIRS);
            fprintf(stderr, "abrdf eval: %s\n", err);
            rc = 1;
            break;
        }
        if (list->count == list->cap) {
            size_t ncap = list->cap ? 2 * list->cap : 256;
            double *nv = realloc(list->v, ncap * 6 * sizeof *nv);
            if (nv) list->v = nv;
            long *nl = nv ? realloc(list->line, ncap * sizeof *nl) : NULL;
            if (nl) list->line = nl;
            if (!nl) {
                path_msg(err, sizeof err, shown, ":%ld: out of memory", lineno);
                fprintf(stderr, "abrdf eval: %s\n", err);
                rc = 1;
                break;
            }
            list->cap = ncap;
        }
        list->line[list->count] = lineno;
        memcpy(list->v + 6 * list->count++, v, sizeof v);
    }
    if (!rc && ferror(f)) {
        path_msg(err, sizeof err, shown, ": read error after line %ld", lineno);
        fprintf(stderr, "abrdf eval: %s\n", err);
        rc = 1;
    }
    free(buf);
    if (!is_stdin) fclose(f);
    return rc;
}

/* f_r of every pair of the --pairs file, computed first and printed only when all are: 0, or
 * 1 after the message. */
static int eval_pairs(abrdf_model model, const abrdf_params *p, const abrdf_frame *frame,
                      const char *path, int json)
{
    pair_list list = {NULL, NULL, 0, 0};
    const char *shown = strcmp(path, "-") ? path : "stdin";
    int rc = pairs_read(path, &list);
    double *f = rc ? NULL : malloc((list.count ? list.count : 1) * 3 * sizeof *f);
    if (!rc && !f) {
        fprintf(stderr, "abrdf eval: %s: out of memory for %zu pairs\n", shown, list.count);
        rc = 1;
    }
    for (size_t k = 0; !rc && k < list.count; ++k) {
        int st = abrdf_eval(model, p, frame, list.v + 6 * k, list.v + 6 * k + 3, f + 3 * k);
        if (st != ABRDF_OK) {
            char err[1024];
            path_msg(err, sizeof err, shown, ":%ld: %s", list.line[k], abrdf_strerror(st));
            fprintf(stderr, "abrdf eval: %s\n", err);
            rc = 1;
        }
    }
    if (rc) {
        free(f);
        free(list.v);
        free(list.line);
        return 1;
    }
    if (json) printf("[");
    for (size_t k = 0; k < list.count; ++k) {
        const double *c = f + 3 * k;
        if (json) {
            printf("%s[", k ? ",\n " : "");
            for (int i = 0; i < 3; ++i) {
                if (i) printf(", ");
                if (isfinite(c[i]))
                    printf("%.17g", c[i]);
                else
                    printf("null");
            }
            printf("]");
        } else {
            printf("%.9g %.9g %.9g\n", c[0], c[1], c[2]);
        }
    }
    if (json) printf("]\n");
    free(f);
    free(list.v);
    free(list.line);
    return 0;
}

int cmd_eval(int argc, char **argv)
{
    const char *cmd = "eval";
    const char *name = NULL, *pairs = NULL;
    double wi[3], wo[3], n[3] = {0, 0, 1}, t[3];
    int have_wi = 0, have_wo = 0, have_t = 0, json = 0;
    const char *sets[64];
    int nsets = 0;
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        if (cli_is_help(a)) return usage();
        int has_val = i + 1 < argc;
        if (!strcmp(a, "--json"))
            json = 1;
        else if (!strcmp(a, "--wi") || !strcmp(a, "--wo") || !strcmp(a, "--normal") ||
                 !strcmp(a, "--tangent")) {
            if (!has_val) return cli_fail(cmd, "%s needs a vector X,Y,Z", a);
            double *dst = a[2] == 'w' ? (a[3] == 'i' ? wi : wo) : (a[2] == 'n' ? n : t);
            if (!cli_parse_dir3(argv[++i], dst))
                return cli_fail(cmd, "%s: '%s' is not a vector X,Y,Z of finite numbers", a,
                                argv[i]);
            if (dst == wi) have_wi = 1;
            if (dst == wo) have_wo = 1;
            if (dst == t) have_t = 1;
        } else if (!strcmp(a, "--pairs")) {
            if (!has_val) return cli_fail(cmd, "--pairs needs a file of direction pairs (or -)");
            pairs = argv[++i];
        } else if (!strcmp(a, "--set")) {
            if (!has_val) return cli_fail(cmd, "--set needs NAME=VALUE");
            if (nsets == 64) return cli_fail(cmd, "too many --set options (64 at most)");
            sets[nsets++] = argv[++i];
        } else if (a[0] == '-' && a[1]) {
            return cli_fail(
                cmd,
                "unknown option '%s'; options: --wi --wo --pairs --normal --tangent --set --json",
                a);
        } else if (!name) {
            name = a;
        } else {
            return cli_fail(cmd, "unexpected argument '%s' (one model only)", a);
        }
    }
    abrdf_model model;
    if (cli_model(cmd, name, &model)) return CLI_EXIT_USAGE;
    if (pairs && (have_wi || have_wo))
        return cli_fail(cmd,
                        "--pairs and %s: give the directions one way (the file or the "
                        "options)",
                        have_wi ? "--wi" : "--wo");
    if (!pairs && (!have_wi || !have_wo))
        return cli_fail(cmd, "missing %s X,Y,Z (direction toward the %s); required: --wi and --wo",
                        have_wi ? "--wo" : "--wi", have_wi ? "viewer" : "light");
    if (!pairs && !(fabs(wi[0]) + fabs(wi[1]) + fabs(wi[2]) > 0.0))
        return cli_fail(cmd, "--wi 0,0,0 has zero length; give a direction toward the light");
    if (!pairs && !(fabs(wo[0]) + fabs(wo[1]) + fabs(wo[2]) > 0.0))
        return cli_fail(cmd, "--wo 0,0,0 has zero length; give a direction toward the viewer");
    if (have_t && !(fabs(t[0]) + fabs(t[1]) + fabs(t[2]) > 0.0))
        return cli_fail(cmd, "--tangent 0,0,0 has zero length; give a direction in the surface "
                             "(or leave --tangent out)");
    abrdf_params p;
    abrdf_params_init(model, &p);
    for (int i = 0; i < nsets; ++i)
        if (cli_set_param(cmd, model, &p, sets[i])) return CLI_EXIT_USAGE;
    abrdf_frame frame;
    if (abrdf_frame_make(n, have_t ? t : NULL, &frame) != ABRDF_OK)
        return cli_fail(cmd, "--normal %g,%g,%g is degenerate (zero length)", n[0], n[1], n[2]);
    if (pairs) return eval_pairs(model, &p, &frame, pairs, json);
    double f[3];
    int st = abrdf_eval(model, &p, &frame, wi, wo, f);
    if (st != ABRDF_OK) return cli_fail(cmd, "%s", abrdf_strerror(st));
    if (json) {
        printf("{\"model\": ");
        cli_json_string(stdout, abrdf_model_get(model)->name);
        printf(", \"f_r\": [%.17g, %.17g, %.17g]}\n", f[0], f[1], f[2]);
    } else {
        printf("%s f_r = %.10g %.10g %.10g\n", abrdf_model_get(model)->name, f[0], f[1], f[2]);
    }
    return 0;
}
