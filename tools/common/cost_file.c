/* cost_file.c - reading and writing cost files (format in cost_file.h). */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/utsname.h>
#include <time.h>
#include <unistd.h>

#include "cli_args.h"
#include "cost_file.h"

int costs_load(const char *path, abrdf_costs *out, double *unit_ns, char *err, size_t err_size)
{
    abrdf_costs_init(out, COSTS_UNIT);
    if (unit_ns) *unit_ns = -1.0;
    FILE *f = fopen(path, "r");
    if (!f) {
        snprintf(err, err_size, "%s: cannot read the cost file", path);
        return -1;
    }
    char line[512];
    int lineno = 0, entries = 0, have_unit = 0;
    int rc = 0;
    while (fgets(line, sizeof line, f)) {
        ++lineno;
        char *hash = strchr(line, '#');
        if (hash) *hash = '\0';
        char name[64], num[64], extra[8];
        int k = sscanf(line, "%63s %63s %7s", name, num, extra);
        if (k <= 0) continue; /* blank or comment */
        double v;
        if (k != 2 || !cli_parse_double(num, &v) || !(v > 0.0)) {
            snprintf(err, err_size, "%s:%d: expected 'NAME NS_PER_EVAL' with a positive number",
                     path, lineno);
            rc = -1;
            break;
        }
        abrdf_model m;
        if (!strcmp(name, COSTS_UNIT_NAME)) {
            if (have_unit++) {
                snprintf(err, err_size, "%s:%d: %s appears twice", path, lineno, name);
                rc = -1;
                break;
            }
            if (unit_ns) *unit_ns = v;
        } else if (abrdf_model_find(name, &m) == ABRDF_OK) {
            if (abrdf_costs_get(out, m) >= 0.0) {
                snprintf(err, err_size, "%s:%d: model %s appears twice", path, lineno, name);
                rc = -1;
                break;
            }
            abrdf_costs_set(out, m, v);
            ++entries;
        } else {
            snprintf(err, err_size, "%s:%d: unknown model '%s' (see abrdf models)", path, lineno,
                     name);
            rc = -1;
            break;
        }
    }
    fclose(f);
    if (rc == 0 && entries == 0) {
        snprintf(err, err_size, "%s: no model costs in the file", path);
        rc = -1;
    }
    return rc;
}

void costs_machine(char *buf, size_t size)
{
    char model[256] = "unknown cpu";
    FILE *f = fopen("/proc/cpuinfo", "r");
    if (f) {
        char line[512];
        while (fgets(line, sizeof line, f)) {
            char *colon = strchr(line, ':');
            if (!strncmp(line, "model name", 10) && colon) {
                snprintf(model, sizeof model, "%s", colon + 2);
                model[strcspn(model, "\n")] = '\0';
                break;
            }
        }
        fclose(f);
    }
    struct utsname u;
    const char *arch = uname(&u) == 0 ? u.machine : "?";
    snprintf(buf, size, "%s (%s, %ld logical cpus)", model, arch, sysconf(_SC_NPROCESSORS_ONLN));
}

void costs_write(FILE *f, const abrdf_costs *c, double unit_ns, const char *command,
                 const char *how)
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
    fprintf(f, "%-24s %10.4f  # 1.00 x unit: powf(N.H, n) with H normalised, no guards\n",
            COSTS_UNIT_NAME, unit_ns);
    for (int i = 0; i < ABRDF_MODEL_COUNT; ++i) {
        const abrdf_model_info *m = abrdf_model_get((abrdf_model)i);
        double cost = abrdf_costs_get(c, (abrdf_model)i);
        if (!m || cost < 0.0) continue;
        fprintf(f, "%-24s %10.4f  # %.2f x unit\n", m->name, cost,
                unit_ns > 0.0 ? cost / unit_ns : 0.0);
    }
}
