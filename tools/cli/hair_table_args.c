/* hair_table_args.c - the options of huang tables (hair_table_args.h). */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "abrdf.h"
#include "cli.h"
#include "hair_table_args.h"

static const int sizes_default[4] = ABRDF_HUANG_TABLE_SIZES;

/* NT,NV,NP,SETS into v: 0, or the exit status after the message. */
static int sizes_parse(const char *cmd, const char *val, int v[4])
{
    static const char *name[4] = {"theta nodes NT", "view azimuths NV", "light azimuths NP",
                                  "shift sets SETS"};
    static const long lo[4] = {4, 1, 4, 1}, hi[4] = {256, 256, 256, 64};
    const char *p = val;
    for (int k = 0; k < 4; ++k) {
        size_t len = strspn(p, "0123456789");
        if (len == 0 || (k < 3 && p[len] != ',') || (k == 3 && p[len]))
            return cli_fail(cmd, "--hair-table-sizes '%s' is not NT,NV,NP,SETS (four integers)",
                            val);
        errno = 0;
        long x = strtol(p, NULL, 10);
        if (errno || x < lo[k] || x > hi[k])
            return cli_fail(cmd, "--hair-table-sizes '%s': %s is %.*s, not in [%ld, %ld]", val,
                            name[k], (int)len, p, lo[k], hi[k]);
        v[k] = (int)x;
        p += len + (k < 3);
    }
    double values = 3.0 * v[0] * v[1] * v[0] * v[2] + 8.0;
    if (values > 268435456.0)
        return cli_fail(cmd, "--hair-table-sizes '%s': %.0f values, more than 2^28", val, values);
    return 0;
}

int hair_table_option(hair_table_args *h, const char *cmd, int argc, char **argv, int *i)
{
    const char *a = argv[*i], *val = *i + 1 < argc ? argv[*i + 1] : NULL;
    if (!strcmp(a, "--hair-table")) {
        if (!h->sizes[0]) memcpy(h->sizes, sizes_default, sizeof sizes_default);
        return 1;
    }
    int sizes = !strcmp(a, "--hair-table-sizes");
    if (!sizes && strcmp(a, "--hair-table-cache")) return 0;
    if (!val) return -cli_fail(cmd, "%s needs %s", a, sizes ? "NT,NV,NP,SETS" : "a directory");
    ++*i;
    if (!sizes) {
        h->cache = val;
        return 1;
    }
    int rc = sizes_parse(cmd, val, h->sizes);
    return rc ? -rc : 1;
}

int hair_table_check(hair_table_args *h, const char *cmd)
{
    if (!h->cache) return 0;
    struct stat st;
    if (stat(h->cache, &st) || !S_ISDIR(st.st_mode))
        return cli_fail(cmd, "--hair-table-cache %s: not a directory", h->cache);
    if (!h->sizes[0]) memcpy(h->sizes, sizes_default, sizeof sizes_default);
    return 0;
}
