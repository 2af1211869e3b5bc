/* measured_file.c - measured tables' formats by extension (measured_file.h). */
#include <ctype.h>
#include <string.h>

#include "measured_file.h"
#include "merl.h"
#include "path_msg.h"
#include "rgl_bsdf.h"

/* An RGL file resampled onto MERL's grid (90 x 90 x 180), the grid every table of the tools
 * shares, so that fits and renders see one resolution whatever the source. */
static int bsdf_read(const char *path, measured_table *out, char *err, size_t err_size)
{
    return rgl_read(path, out, 90, 90, 180, err, err_size);
}

/* Writing .bsdf: abrdf tabulate calls rgl_write with the model itself (a table cannot be
 * turned back into the file's adaptive parametrisation without a model to sample). */
static const measured_format formats[] = {
    {".binary", "MERL BRDF database", merl_read, merl_write_to},
    {".bsdf", "RGL BSDF (Dupuy-Jakob 2018), resampled to 90 x 90 x 180", bsdf_read, NULL},
};
#define FORMAT_COUNT (sizeof formats / sizeof formats[0])

static int ends_with(const char *s, const char *tail)
{
    size_t n = strlen(s), k = strlen(tail);
    if (n <= k) return 0; /* a name, not only an extension */
    for (size_t i = 0; i < k; ++i)
        if (tolower((unsigned char)s[n - k + i]) != tolower((unsigned char)tail[i])) return 0;
    return 1;
}

const measured_format *measured_file_format(const char *path, int writing, char *err,
                                            size_t err_size)
{
    char known[256] = "";
    for (size_t i = 0; i < FORMAT_COUNT; ++i) {
        const measured_format *m = &formats[i];
        if (!(writing ? m->write_to != NULL : m->read != NULL)) continue;
        if (ends_with(path, m->extension)) return m;
        size_t len = strlen(known);
        snprintf(known + len, sizeof known - len, "%s%s (%s)", len ? ", " : "", m->extension,
                 m->name);
    }
    const char *slash = strrchr(path, '/'), *dot = strrchr(slash ? slash + 1 : path, '.');
    if (!dot) {
        path_msg(err, err_size, path, ": no extension to tell the format by; known: %s", known);
        return NULL;
    }
    char ext[40]; /* shown as path_short shows a name: control bytes as \xHH */
    path_msg(err, err_size, path, ": '%s' is not a measured-BRDF format %s; known: %s",
             path_short(ext, sizeof ext, dot, sizeof ext - 1),
             writing ? "written here" : "read here", known);
    return NULL;
}
