/* data_path.c - data file lookup (data_path.h). The two directories come from CMake. */
#include <stdio.h>
#include <stdlib.h>

#include "data_path.h"

#ifndef ABRDF_SOURCE_DATA_DIR
#define ABRDF_SOURCE_DATA_DIR "data"
#endif
#ifndef ABRDF_INSTALL_DATA_DIR
#define ABRDF_INSTALL_DATA_DIR "share/abrdf"
#endif

static int readable(const char *path)
{
    FILE *f = fopen(path, "r");
    if (!f) return 0;
    fclose(f);
    return 1;
}

int data_path_find(const char *name, char *buf, size_t size)
{
    const char *env = getenv("ABRDF_DATA_DIR");
    const char *dirs[3] = {env, ABRDF_SOURCE_DATA_DIR, ABRDF_INSTALL_DATA_DIR};
    for (int i = 0; i < 3; ++i) {
        if (!dirs[i] || !*dirs[i]) continue;
        int w = snprintf(buf, size, "%s/%s", dirs[i], name);
        if (w > 0 && (size_t)w < size && readable(buf)) return 0;
    }
    snprintf(buf, size, "%s/%s", ABRDF_SOURCE_DATA_DIR, name);
    return -1;
}
