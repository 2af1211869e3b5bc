/* cost_file.c - reading and writing cost files (format in cost_file.h). */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/utsname.h>
#include <time.h>
#include <unistd.h>

#include "cli_args.h"
#include "cost_file.h"
#include "in_file.h"
#include "path_msg.h"

int costs_read(FILE *f, const char *name, abrdf_costs *out, double *unit_ns, char *err,
               size_t err_size)
{
    abrdf_costs_init(out, COSTS_UNIT);
    if (unit_ns) *unit_ns = -1.0;
    char *line = NULL, shown[80];
    size_t cap = 0;
    ssize_t len;
    int lineno = 0, entries = 0, have_unit = 0;
    int rc = 0;
    while ((len = in_file_line(f, &line, &cap)) >= 0) {
        ++lineno;
        if (strlen(line) != (size_t)len) {
            path_msg(err, err_size, name, ":%d: NUL byte (not a text file)", lineno);
            rc = -1;
            break;
        }
        char *hash = strchr(line, '#');
        if (hash) *hash = '\0';
        char *tok[3], *save = NULL;
        int k = 0;
        for (char *t = strtok_r(line, " \t\r\v\f", &save); t && k < 3;
             t = strtok_r(NULL, " \t\r\v\f", &save))
            tok[k++] = t;
        if (k == 0) continue; /* blank or comment */
        double v;
        if (k != 2 || !cli_parse_double(tok[1], &v) || !(v > 0.0)) {
            path_msg(err, err_size, name, ":%d: expected 'NAME NS_PER_EVAL' with a positive number",
                     lineno);
            rc = -1;
            break;
        }
        abrdf_model m;
        if (!strcmp(tok[0], COSTS_UNIT_NAME)) {
            if (have_unit++) {
                path_msg(err, err_size, name, ":%d: %s appears twice", lineno, tok[0]);
                rc = -1;
                break;
            }
            if (unit_ns) *unit_ns = v;
        } else if (abrdf_model_find(tok[0], &m) == ABRDF_OK) {
            if (abrdf_costs_get(out, m) >= 0.0) {
                path_msg(err, err_size, name, ":%d: model %s appears twice", lineno, tok[0]);
                rc = -1;
                break;
            }
            abrdf_costs_set(out, m, v);
            ++entries;
        } else {
            path_msg(err, err_size, name, ":%d: unknown model '%s' (see abrdf models)", lineno,
                     path_short(shown, sizeof shown, tok[0], 64));
            rc = -1;
            break;
        }
    }
    if (rc == 0 && ferror(f)) {
        path_msg(err, err_size, name, ": read error: %s", strerror(errno));
        rc = -1;
    }
    free(line);
    if (rc == 0 && entries == 0) {
        path_msg(err, err_size, name, ": no model costs in the file");
        rc = -1;
    }
    return rc;
}

int costs_load(const char *path, abrdf_costs *out, double *unit_ns, char *err, size_t err_size)
{
    abrdf_costs_init(out, COSTS_UNIT);
    if (unit_ns) *unit_ns = -1.0;
    FILE *f = in_file_open(path, err, err_size);
    if (!f) return -1;
    int rc = costs_read(f, path, out, unit_ns, err, err_size);
    fclose(f);
    return rc;
}

void costs_machine(char *buf, size_t size)
{
    char model[256] = "unknown cpu";
    FILE *f = fopen("/proc/cpuinfo", "r");
    if (f) {
        char *line = NULL;
        size_t cap = 0;
        while (in_file_line(f, &line, &cap) >= 0) {
            char *colon = strchr(line, ':');
            if (!strncmp(line, "model name", 10) && colon && colon[1]) {
                snprintf(model, sizeof model, "%s", colon + 2);
                break;
            }
        }
        free(line);
        fclose(f);
    }
    struct utsname u;
    const char *arch = uname(&u) == 0 ? u.machine : "?";
    snprintf(buf, size, "%s (%s, %ld logical cpus)", model, arch, sysconf(_SC_NPROCESSORS_ONLN));
}

double costs_load_clock(const char *path)
{
    char err[64];
    FILE *f = in_file_open(path, err, sizeof err);
    if (!f) return -1.0;
    char *line = NULL;
    size_t cap = 0;
    double ghz = -1.0;
    while (in_file_line(f, &line, &cap) >= 0) {
        double v;
        if (sscanf(line, "# clock: %lf GHz", &v) == 1 && v > 0.0 && v < 1e3) {
            ghz = v;
            break;
        }
    }
    free(line);
    fclose(f);
    return ghz;
}

void costs_write(FILE *f, const abrdf_costs *c, double unit_ns, const char *command,
                 const char *how, const clock_rate *clock)
{
    char machine[384], date[64];
    costs_machine(machine, sizeof machine);
    time_t now = time(NULL);
    strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", gmtime(&now));
    fprintf(f,
            "# abrdf %s cost file: nanoseconds per evaluation of every model on this machine\n"
            "# machine: %s\n# date: %s\n# command: %s\n# method: %s\n"
            "# format: NAME NS_PER_EVAL; %s is the unit of the ratios in the comments\n",
            abrdf_version(), machine, date, command, how, COSTS_UNIT_NAME);
    if (clock) {
        char text[256];
        clock_rate_text(clock, text, sizeof text);
        fprintf(f, "# clock: %s; cycles = ns x GHz\n", text);
    }
    fprintf(f, "%-24s %10.4f  # 1.00 x unit: powf(N.H, n) with H normalised, no guards\n",
            COSTS_UNIT_NAME, unit_ns);
    for (int i = 0; i < ABRDF_MODEL_COUNT; ++i) {
        const abrdf_model_info *m = abrdf_model_get((abrdf_model)i);
        double cost = abrdf_costs_get(c, (abrdf_model)i);
        if (!m || cost < 0.0) continue;
        fprintf(f, "%-24s %10.4f  # %.2f x unit", m->name, cost,
                unit_ns > 0.0 ? cost / unit_ns : 0.0);
        if (clock) fprintf(f, ", %.3g cycles", cost * clock->ghz);
        fputc('\n', f);
    }
}
